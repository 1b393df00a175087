"""The slices' filled regions, closed as the slices come back from the sensing (internal).

The main process only waits while the workers sense; each slice's filled region
(:func:`recon3d.surface.closure.result_region`: snap, bridge, fill of its W1 / W2 / W3
pieces and unknown chords, emptied where the probe was, the first step of
:func:`recon3d.surface.reconstruct`) needs
that slice alone, so it is computed there, slice by slice, as the pool hands the slices
back, and the reconstruction takes them as they are (its ``regions``). The same call on
the same pieces: the same regions (tested ``==``).

The closure's lengths (the snap distance, twice the contact tolerance, and the sensor's) of a
uniform plan are known before the sensing; an adaptive plan settles its tolerance only at
the end, so nothing is precomputed there (``lengths`` None), and a region computed with other
lengths than the run's is never used.
"""
from __future__ import annotations

from recon3d.records import MeshRun, SliceRun
from recon3d.surface.closure import ClosureLengths, SliceRegion, closure_lengths, result_region

__all__ = ["RegionsAsSensed"]


def _region(srun: SliceRun, lengths: ClosureLengths) -> SliceRegion:
    return result_region(srun.result, lengths.snap, lengths.noise, lengths.jitter,
                         lengths.close)


class RegionsAsSensed:
    """Slice regions computed as the slices are sensed (module doc).

    lengths : ClosureLengths or None -- the run's closure lengths
        (:func:`recon3d.surface.closure.closure_lengths`: the snap distance ``2 * tol``, the
        sensor's noise and jitter) when known before the sensing; None: :meth:`add` does
        nothing.
    """

    def __init__(self, lengths: ClosureLengths | None):
        self.lengths = lengths
        self._got: dict[int, tuple[object, SliceRegion]] = {}

    def add(self, srun: SliceRun) -> None:
        """Close the region of a slice just sensed (the sensing's ``progress`` call)."""
        if self.lengths is not None:
            self._got[id(srun.result)] = (srun.result, _region(srun, self.lengths))

    def for_run(self, run: MeshRun) -> list[list[SliceRegion]] | None:
        """The regions of every slice of ``run``, per family, in its slice order (what
        :func:`recon3d.surface.reconstruct` takes as ``regions``); a slice not seen by
        :meth:`add` is closed here. None when the run's closure lengths are not the ones
        used."""
        lengths = closure_lengths(run.eps, run.tol, run.read_noise, run.config.taxel)
        if self.lengths is None or lengths != self.lengths:
            return None
        out = []
        for fam in run.families:
            regs = []
            for s in fam.slices:
                got = self._got.get(id(s.result))
                regs.append(got[1] if got is not None and got[0] is s.result
                            else _region(s, lengths))
            out.append(regs)
        return out
