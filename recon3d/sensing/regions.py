"""The slices' filled regions, closed as the slices come back from the sensing (internal).

The main process only waits while the workers sense; each slice's filled region
(:func:`recon3d.surface.closure.result_region`: snap, bridge, fill of its W1 / W2 / W3
pieces and unknown chords, emptied where the probe was, the first step of
:func:`recon3d.surface.reconstruct`) needs
that slice alone, so it is computed there, slice by slice, as the pool hands the slices
back, and the reconstruction takes them as they are (its ``regions``). The same call on
the same pieces: the same regions (tested ``==``).

The snap distance (twice the contact tolerance) of a uniform plan is known before the
sensing; an adaptive plan settles its tolerance only at the end, so nothing is precomputed
there (``snap`` None), and a region computed with another snap than the run's is never used.
"""
from __future__ import annotations

from recon3d.records import MeshRun, SliceRun
from recon3d.surface.closure import SliceRegion, closure_lengths, result_region

__all__ = ["RegionsAsSensed"]


def _region(srun: SliceRun, snap: float, noise: float, jitter: float) -> SliceRegion:
    return result_region(srun.result, snap, noise, jitter)


class RegionsAsSensed:
    """Slice regions computed as the slices are sensed (module doc).

    snap : float or None -- the run's snap distance (``2 * tol``) when known before the
        sensing; None: :meth:`add` does nothing.
    noise, jitter : float -- the sensor's standard deviation and its readings' jitter
        (lengths, :func:`recon3d.surface.closure.closure_lengths`; 0: a perfect sensor).
    """

    def __init__(self, snap: float | None, noise: float = 0.0, jitter: float = 0.0):
        self.snap, self.noise, self.jitter = snap, noise, jitter
        self._got: dict[int, tuple[object, SliceRegion]] = {}

    def add(self, srun: SliceRun) -> None:
        """Close the region of a slice just sensed (the sensing's ``progress`` call)."""
        if self.snap is not None:
            self._got[id(srun.result)] = (srun.result, _region(srun, self.snap, self.noise,
                                                               self.jitter))

    def for_run(self, run: MeshRun) -> list[list[SliceRegion]] | None:
        """The regions of every slice of ``run``, per family, in its slice order (what
        :func:`recon3d.surface.reconstruct` takes as ``regions``); a slice not seen by
        :meth:`add` is closed here. None when the run's snap is not the one used."""
        snap, noise, jitter = closure_lengths(run.eps, run.tol, run.config.noise,
                                              run.config.taxel)
        if self.snap is None or (snap, noise, jitter) != (self.snap, self.noise, self.jitter):
            return None
        out = []
        for fam in run.families:
            regs = []
            for s in fam.slices:
                got = self._got.get(id(s.result))
                regs.append(got[1] if got is not None and got[0] is s.result
                            else _region(s, snap, noise, jitter))
            out.append(regs)
        return out
