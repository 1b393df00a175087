"""Plain data shared by the rooms of recon3d: a run, its families and slices.

Imports no room of recon3d, only :mod:`recon3d.config` (like core2d's shared
modules): sensing fills these records, surface/, score/, io/ and viz/ read them.

* :class:`SliceRun` -- one sensed slice (what a worker sends back, picklable);
* :class:`Family` -- the slices cut by one plane normal;
* :class:`MeshRun` -- a whole run over the families of one mesh;
* the integer codes of the pictures and the surface (:data:`LABELS`,
  :data:`CURVE_CLASSES`, :data:`COVERAGE_CLASSES`);
* :func:`robot_time`, the robot's time model.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import trimesh

import core2d
import slicer
from core2d.truth.metrics import total_metrics
from recon3d.config import RunConfig, diagonal

__all__ = ["ContourTruth", "SliceRun", "Family", "MeshRun", "robot_time",
           "LABELS", "CURVE_CLASSES", "COVERAGE_CLASSES"]

LABELS = {1: "W1 traced", 2: "W2 approximated", 3: "W3 lid", 4: "between slices", 5: "cap"}
"""Surface face label codes and their names."""

CURVE_CLASSES = {1: "W1", 2: "W2", 3: "W3", 4: "unknown"}
"""Codes of the ``class`` array of the curves block of ``scene.vtm``."""

COVERAGE_CLASSES = {0: "outside the slab", 1: "touched", 2: "reachable, missed",
                    3: "unreachable", 4: "inside a hole", 5: "in an opening narrower than eps"}
"""Ground-truth coverage classes (:func:`recon3d.score.evaluate.coverage_mesh`)."""


def robot_time(stats: dict, probe_speed: float, motion_overhead: float,
               read_time: float = 0.0) -> float:
    """Seconds: joint path / probe speed + motions x overhead + sensor reads x read time
    (a real sensor's reads, ``sensor_reads`` of the stats; none with perfect sensing).

    >>> robot_time({"joint_path": 100.0, "motions": 10}, 20.0, 0.2)
    7.0
    >>> robot_time({"joint_path": 100.0, "motions": 10, "sensor_reads": 3000}, 20.0, 0.2, 0.001)
    10.0
    """
    return float(stats["joint_path"] / probe_speed + stats["motions"] * motion_overhead
                 + stats.get("sensor_reads", 0) * read_time)


@dataclass
class ContourTruth:
    """Reference contour samples of one slice, for the 3D evaluation.

    points : (m, 2) float -- sample points in the slice frame.
    lengths : (m,) float -- contour length each sample stands for.
    reachable : (m,) bool -- exact 2D reachability.
    covered : (m,) bool -- reachable and within ``metric_tol`` of W1 u W2.
    in_hole : (m,) bool or None -- nearest a hole loop of the section
        (:func:`recon3d.score.evaluate.on_holes`, made by the worker that sensed the slice;
        None: computed where needed).
    resolvable : (m,) bool or None -- not inside an opening narrower than eps
        (:func:`core2d.truth.resolvable.resolvable`; None: computed where needed).
    """

    points: np.ndarray
    lengths: np.ndarray
    reachable: np.ndarray
    covered: np.ndarray
    in_hole: np.ndarray | None = None
    resolvable: np.ndarray | None = None

    @classmethod
    def empty(cls) -> ContourTruth:
        z = np.zeros(0, dtype=bool)
        return cls(np.zeros((0, 2)), np.zeros(0), z, z.copy(), z.copy(), z.copy())


@dataclass
class SliceRun:
    """One sensed slice: its geometry, the sensing result, its metrics and reference samples.

    slice : slicer.Slice -- plane, reference contour (``None`` while a worker
        sends it back: the parent fills in its own slice).
    family, index : int -- family and plane index.
    result : core2d.SliceResult
    metrics : dict -- core2d's slice metrics (+ ``robot_time_s``).
    workspace : ((2,) float, float) -- centre and radius the robot knows.
    truth : ContourTruth
    motion_rows : str or None -- this slice's rows of ``motions.csv``, made by the worker
        that sensed it (:func:`recon3d.io.motions.slice_rows`; None: made when written).
    document : dict or None -- this slice's entry of ``sensing.json``, made by the worker
        that sensed it (:func:`recon3d.io.documents.slice_document`; None: made when written).
    """

    slice: slicer.Slice | None
    family: int
    index: int
    result: core2d.SliceResult
    metrics: dict
    workspace: tuple
    truth: ContourTruth
    motion_rows: str | None = None
    document: dict | None = None

    @property
    def has_reference(self) -> bool:
        """The reference section is closed loops only (not empty, no open chain)."""
        return len(self.slice.loops) > 0 and not self.slice.open_chains

    @property
    def outer_loops(self) -> int:
        """Closed reference loops that are not holes (> 1: several objects, §3.2)."""
        return int((~np.asarray(self.slice.holes, dtype=bool)).sum())


@dataclass
class Family:
    """The slices cut by one plane normal.

    normal : (3,) float; slices : list of SliceRun in plane order.
    """

    normal: np.ndarray
    slices: list[SliceRun] = field(default_factory=list)

    @property
    def label(self) -> str:
        """Short name of the normal: 'x', '-z' or 'nx,ny,nz'."""
        for k, name in enumerate("xyz"):
            for sign, pre in ((1.0, ""), (-1.0, "-")):
                e = np.zeros(3)
                e[k] = sign
                if np.allclose(self.normal, e, atol=1e-12):
                    return pre + name
        return ",".join(f"{c:.4g}" for c in self.normal)


@dataclass
class MeshRun:
    """A whole run over the slice families of one mesh.

    eps, tol : float -- the finest eps sensed and its contact resolution.
    probe_length : float -- link length (4 x (largest slice radius + first eps)).
    adaptive : dict or None -- what ``--slices auto`` decided (metrics.json ``adaptive``).
    reads : int -- sensor reads averaged at each reading point (``--reads`` resolved).
    """

    name: str
    mesh: trimesh.Trimesh
    config: RunConfig
    eps: float
    tol: float
    probe_length: float
    families: list[Family] = field(default_factory=list)
    seconds: float = 0.0
    jobs: int = 1
    adaptive: dict | None = None
    reads: int = 1

    @property
    def slices(self) -> list[SliceRun]:
        """Every SliceRun, family by family."""
        return [s for fam in self.families for s in fam.slices]

    @property
    def read_noise(self) -> float:
        """The sensor noise of the readings the planner saw, in eps: the stated noise over
        sqrt(reads), the scatter of the means averaged at each reading point."""
        return float(self.config.noise) / float(self.reads) ** 0.5

    @property
    def totals(self) -> dict:
        """2D totals: accuracy over the slices with a reference, cost over all."""
        ref = [s.metrics for s in self.slices if s.has_reference]
        out = total_metrics(ref)
        cost = [dict(s.result.stats.as_dict(), robot_time_s=s.metrics["robot_time_s"])
                for s in self.slices]
        out.update(total_metrics(cost))
        out["slices_without_reference"] = sum(not s.has_reference for s in self.slices)
        return out

    @property
    def nudge_notes(self) -> list[str]:
        """One line per family whose degenerate planes were moved (slicer.degenerate)."""
        out = []
        scale = diagonal(self.mesh)
        for fam in self.families:
            moved = [s.slice.plane for s in fam.slices if s.slice.plane.nudge != 0.0]
            if moved:
                worst = max(abs(p.nudge) for p in moved) / scale
                out.append(f"axis {fam.label}: moved {len(moved)} of {len(fam.slices)} planes "
                           f"off mesh vertices (planes {_index_runs([p.index for p in moved])}; "
                           f"at most {worst:.1e} x diagonal)")
        return out


def _index_runs(indices) -> str:
    """Integer ``indices`` (sorted here) as runs of consecutive values, for a one-line note:
    a run of three or more as ``first-last``, shorter ones value by value.

    Examples
    --------
    >>> _index_runs([0, 1, 2, 3, 5, 7, 8, 9, 11, 12])
    '0-3, 5, 7-9, 11, 12'
    >>> _index_runs([])
    ''
    """
    out, values = [], sorted(int(i) for i in indices)
    start = 0
    for k in range(1, len(values) + 1):
        if k < len(values) and values[k] == values[k - 1] + 1:
            continue
        run = values[start:k]
        out += [f"{run[0]}-{run[-1]}"] if len(run) >= 3 else [str(v) for v in run]
        start = k
    return ", ".join(out)
