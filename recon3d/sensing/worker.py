"""Sense one slice and score it: the unit of work of a run (internal).

A :class:`WorkerState` holds the slices of every family -- the parent's own
(``jobs=1``, or inherited by forked workers) or rebuilt from the mesh arrays
in a spawned worker (Embree scenes do not pickle) -- senses the slices it is
given with :func:`core2d.sense_slice` and scores them with
:func:`core2d.truth.metrics.slice_metrics`. The same code runs in every
process, so results do not depend on ``jobs``.

Slices of an open mesh whose reference section is not made of closed loops
alone (no loop, or open chains beside the loops) have no reference: every
metric that needs one is ``None`` and the slice is left out of the accuracy
totals; its cost counters still count.
"""
from __future__ import annotations

import logging
from dataclasses import dataclass, replace

import numpy as np
import trimesh
from threadpoolctl import ThreadpoolController

import core2d
import slicer
from core2d.resolution import repeated_reads
from core2d.sim.sensor import SensorModel
from core2d.truth.metrics import sensor_metrics, slice_metrics
from core2d.truth.nearest import polyline_segments, segment_distances
from core2d.truth.reachability import reachable_samples
from core2d.truth.resolvable import resolvable
from recon3d.io.documents import slice_document
from recon3d.io.motions import slice_rows
from recon3d.records import ContourTruth, SliceRun
from recon3d.score.evaluate import on_holes

__all__ = ["SenseSettings", "WorkerState", "family_slices", "resolved_reads", "no_reference_metrics",
           "own_contacts", "built_contacts"]


@dataclass(frozen=True)
class SenseSettings:
    """What every slice of a run shares.

    axes : tuple of (3,) float -- one unit normal per family.
    slices : int -- planes per family.
    eps, tol : float -- the paper's eps and the contact resolution.
    backend : str -- one of ``slicer.BACKENDS`` ('embree', 'exact', 'trimesh').
    max_motions, bootstrap : int -- per-slice budget and bootstrap insertions.
    method : str -- ``'pulling'``, ``'paper'`` or ``'follow'`` (:func:`core2d.sense_slice`).
    noise, taxel : float -- the sensor's noise and taxel spacing, in eps
        (:mod:`core2d.sim.sensor`; 0: perfect sensing).
    seed : int -- seed of the noise; slice (family, plane) draws from its own stream.
    friction : float -- Coulomb mu at the tip (:mod:`core2d.sim.friction`; 0: none).
    torque_threshold, torque_noise : float -- the torque sensor's, in eps.
    keyed : bool -- keyed noise draws (:class:`core2d.SensorModel`'s ``keyed``).
    reads : int -- reads averaged at each reading point (:class:`core2d.SensorModel`'s).
    """

    axes: tuple
    slices: int
    eps: float
    tol: float
    backend: str
    max_motions: int
    bootstrap: int
    method: str = "pulling"
    noise: float = 0.0
    taxel: float = 0.0
    seed: int = 0
    friction: float = 0.0
    torque_threshold: float = 0.0
    torque_noise: float = 0.0
    keyed: bool = False
    reads: int = 1

    def sensor(self, family: int, index: int) -> SensorModel | None:
        """The sensor model of slice ``index`` of ``family`` at this eps (None: perfect)."""
        if not (self.noise or self.taxel or self.torque_threshold or self.torque_noise):
            return None
        return SensorModel.of_eps(self.eps, self.noise, self.taxel, self.seed,
                                  self.torque_threshold, self.torque_noise, self.keyed,
                                  self.reads).reseeded(
            family, index)

    @property
    def metric_tol(self) -> float:
        """Distance tolerance of the metrics: eps / 2 (see core2d.truth.metrics)."""
        return 0.5 * self.eps

    @property
    def spacing(self) -> float:
        """Reference contour sampling step: eps / 4."""
        return 0.25 * self.eps


def resolved_reads(config, tol_share: float) -> int:
    """``config.reads`` (a :class:`~recon3d.config.RunConfig`'s) as a number: 'auto' asks
    :func:`core2d.resolution.repeated_reads` for the stated noise and taxels (in eps) and
    ``tol_share`` = tol / eps."""
    if config.reads != "auto":
        return int(config.reads)
    return repeated_reads(1.0, float(config.noise), float(config.taxel), float(tol_share))


def family_slices(mesh, axis, count):
    """``slicer.slice_mesh`` with its degenerate-plane log silenced (reported by the caller)."""
    log = logging.getLogger("slicer.degenerate")
    level = log.level
    log.setLevel(logging.ERROR)
    try:
        return slicer.slice_mesh(mesh, axis=axis, count=count)
    finally:
        log.setLevel(level)


def no_reference_metrics(result, settings: SenseSettings) -> dict:
    """The metrics of a slice without reference: the keys of ``slice_metrics``,
    every value None except the cost counters of ``result.stats``."""
    st = settings
    keys = slice_metrics([], core2d.SliceResult(), st.eps, tol=st.metric_tol, spacing=st.spacing)
    if st.sensor(0, 0) is not None:
        keys = {**keys, **sensor_metrics([], core2d.SliceResult(), st.eps, 0.0, spacing=st.spacing)}
    out = {k: None for k in keys}
    out.update(result.stats.as_dict())
    return out


def _covered(points, result, tol) -> np.ndarray:
    """(m,) bool: within ``tol`` of the W1 polylines and W2 segments."""
    return segment_distances(points, *polyline_segments((*result.w1, *result.w2))) <= tol


class WorkerState:
    """The slices of every family of one mesh, in the process that senses them.

    Parameters
    ----------
    settings : SenseSettings
    families : list of list of slicer.Slice -- the parent's slices (not copied).
    """

    def __init__(self, settings: SenseSettings, families: list):
        self.settings = settings
        self.families = families
        self._blas = None  # threadpoolctl's view of this process's BLAS, made on first use

    @classmethod
    def rebuild(cls, vertices, faces, settings: SenseSettings) -> WorkerState:
        """Cut the families again from (v, 3) vertices and (f, 3) faces (a spawned worker)."""
        mesh = trimesh.Trimesh(vertices, faces, process=False)
        return cls(settings, [family_slices(mesh, axis, settings.slices)
                              for axis in settings.axes])

    def sense(self, family: int, index: int, eps: float | None = None) -> SliceRun:
        """Sense slice ``index`` of ``family`` and score it against its reference
        (at ``eps`` instead of the run's, tol scaled alike, when given).

        The returned SliceRun has ``slice=None`` (the parent holds the slices), its rows
        of ``motions.csv`` (``motion_rows``) and its entry of ``sensing.json``
        (``document``), both made here, beside the other workers.

        BLAS runs one thread meanwhile (restored after): a slice's arrays are small, and
        OpenBLAS's threads, idle-spinning beside the other workers, cost more CPU than
        they save (measured: cutting the mesh at a plane, 22 ms of CPU with two
        threads, 1.4 ms with one). Outputs compared identical on the built-in scenes
        and the large mesh (``bench.compare_commits``, ``bench.bench_large --before``)."""
        if self._blas is None:
            self._blas = ThreadpoolController()
        with self._blas.limit(limits=1, user_api="blas"):
            srun = self._sense(family, index, eps)
            cut = self.families[family][index]
            srun.motion_rows = slice_rows(srun, cut.plane)
            srun.document = slice_document(srun, cut)
        return srun

    def _sense(self, family: int, index: int, eps: float | None) -> SliceRun:
        """:meth:`sense` without the motion rows."""
        st = self.settings
        if eps is not None:
            st = replace(st, eps=float(eps), tol=st.tol * float(eps) / st.eps)
        cut = self.families[family][index]
        if cut.is_empty:
            result = core2d.SliceResult()
            return SliceRun(None, family, index, result, no_reference_metrics(result, st),
                            (np.zeros(2), 0.0), ContourTruth.empty())
        center, radius = cut.bounding_circle()
        workspace = (np.asarray(center, float), float(radius) + st.eps)
        sensor = st.sensor(family, index)
        result = core2d.sense_slice(cut.contact(st.backend), workspace, st.eps, tol=st.tol,
                                    max_motions=st.max_motions, bootstrap_count=st.bootstrap,
                                    method=st.method, sensor=sensor, friction=st.friction)
        if not cut.loops or cut.open_chains:
            return SliceRun(None, family, index, result, no_reference_metrics(result, st),
                            workspace, ContourTruth.empty())
        loops = [np.asarray(lp) for lp in cut.loops]
        samples = reachable_samples(loops, st.spacing)
        samp, reach = samples
        resolved = resolvable(loops, samp.points, st.eps)
        metrics = slice_metrics(loops, result, st.eps, tol=st.metric_tol, spacing=st.spacing,
                                samples=samples, resolved=resolved)
        if sensor is not None:  # beside the noiseless ones: within eps/2 + 2 sigma
            metrics.update(sensor_metrics(loops, result, st.eps, sensor.noise,
                                          spacing=st.spacing, samples=samples,
                                          resolved=resolved))
        covered = reach & _covered(samp.points, result, st.metric_tol)
        truth = ContourTruth(samp.points, samp.lengths, reach, covered,
                             on_holes(cut, samp.points), resolved)
        return SliceRun(None, family, index, result, metrics, workspace, truth)


def own_contacts(families: list) -> list:
    """The same slices (geometry shared, not cut again) with empty contact caches, so
    the contact models built while sensing go when sensing ends, as in a worker."""
    return [[replace(s) for s in fam] for fam in families]


def built_contacts(families: list, tasks: list, backend: str) -> list:
    """:func:`own_contacts` with the contact model of every task's slice built here, before
    the workers are forked: they inherit the models and only cast rays.

    Building an Embree scene runs TBB tasks. TBB's worker threads of this process (any
    Embree scene built here before, e.g. by an earlier run in the same process) may hold
    one of TBB's locks at the instant of a fork, and a child that then builds a scene waits
    on that lock forever: a sensing worker of the test suite hung so in
    ``tbb::detail::r1::private_server::wake_some``, under ``rtcCommitScene``. Built here,
    nothing in a worker calls TBB. The models go with the pool (fresh caches, as in
    :func:`own_contacts`). ``tasks``: (family, index, eps) each."""
    own = own_contacts(families)
    for task in tasks:
        cut = own[task[0]][task[1]]
        if not cut.is_empty:
            getattr(cut.contact(backend), "ray_kernel", None)  # Embree: its direct scene too
    return own
