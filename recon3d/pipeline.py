"""Run the 2D algorithm on every slice of every family (meshes -> slicer -> core2d).

Each slice gets its own contact backend, probe, planner and budget, so a
run always ends; slices run in parallel processes
(:mod:`recon3d.parallel`). Metrics against the reference contour are
computed after sensing and never fed back to the planner.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from core2d.truth.metrics import total_metrics
from recon3d.sensing import ContourTruth, SenseSettings, family_slices

__all__ = ["RunConfig", "SliceRun", "Family", "MeshRun", "sense_mesh", "default_eps",
           "robot_time"]


@dataclass(frozen=True)
class RunConfig:
    """Parameters of one run (the flags of ``recon3d run``).

    axes : tuple -- one slice normal per family ('x', 'y', 'z', '-x', 'nx,ny,nz'
        or a (3,) vector).
    slices : int or 'auto' -- evenly spaced planes per family, strictly inside
        the mesh; 'auto': adaptive slicing (:mod:`recon3d.adaptive`).
    eps : float or None -- the paper's epsilon; default bbox diagonal / 200.
    backend : str -- 'embree' or 'exact' contact backend.
    tol : float or None -- contact resolution, default eps / 20.
    max_motions : int -- motion budget per slice.
    bootstrap : int -- initial insertions around each slice.
    jobs : int or None -- worker processes, default the number of cores.
    probe_speed : float -- joint speed, mesh units per second (scenes: mm/s).
    motion_overhead : float -- seconds per motion (stop, sense, plan).
    max_slices : int -- 'auto': candidate planes per family (the uniform run it replaces).
    slice_tol : float -- 'auto': neighbouring sensed regions differing by more
        than this share of the diagonal get a slice between them.
    """

    axes: tuple = ("z",)
    slices: int = 8
    eps: float | None = None
    backend: str = "embree"
    tol: float | None = None
    max_motions: int = 20000
    bootstrap: int = 12
    jobs: int | None = None
    probe_speed: float = 20.0
    motion_overhead: float = 0.2
    max_slices: int = 32
    slice_tol: float = 0.005


@dataclass
class SliceRun:
    """One slice: its geometry, the sensing result, its metrics and reference samples."""

    slice: object
    family: int
    result: object
    metrics: dict
    workspace: tuple
    truth: ContourTruth

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
    """The slices cut by one plane normal."""

    normal: np.ndarray
    slices: list = field(default_factory=list)

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
    """A whole run over the slice families of one mesh."""

    name: str
    mesh: object
    config: RunConfig
    eps: float
    tol: float
    probe_length: float
    families: list = field(default_factory=list)
    seconds: float = 0.0
    jobs: int = 1
    adaptive: dict | None = None

    @property
    def slices(self) -> list:
        """Every SliceRun, family by family."""
        return [s for fam in self.families for s in fam.slices]

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
        scale = float(np.linalg.norm(np.ptp(self.mesh.bounds, axis=0)))
        for fam in self.families:
            moved = [s.slice.plane for s in fam.slices if s.slice.plane.nudge != 0.0]
            if moved:
                worst = max(abs(p.nudge) for p in moved) / scale
                out.append(f"axis {fam.label}: moved {len(moved)} of {len(fam.slices)} planes "
                           f"off mesh vertices (planes {', '.join(str(p.index) for p in moved)}; "
                           f"at most {worst:.1e} x diagonal)")
        return out


def default_eps(mesh) -> float:
    """eps = 1/200 of the bounding-box diagonal."""
    return float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)) / 200.0)


def robot_time(stats: dict, probe_speed: float, motion_overhead: float) -> float:
    """Seconds: joint path / probe speed + motions x overhead.

    >>> robot_time({"joint_path": 100.0, "motions": 10}, 20.0, 0.2)
    7.0
    """
    return float(stats["joint_path"] / probe_speed + stats["motions"] * motion_overhead)


def sense_mesh(mesh, name, config: RunConfig, progress=None) -> MeshRun:
    """Slice ``mesh`` along every axis of ``config`` and sense every slice.

    Parameters
    ----------
    mesh : trimesh.Trimesh
    name : str -- label written to the output.
    config : RunConfig
    progress : callable(SliceOutcome) or None -- called as each slice finishes.

    Returns
    -------
    MeshRun -- families in ``config.axes`` order, slices in plane order.
    """
    from recon3d.parallel import default_jobs, sense_all
    from slicer import parse_axis

    t0 = time.perf_counter()
    eps = float(config.eps) if config.eps is not None else default_eps(mesh)
    tol = float(config.tol) if config.tol is not None else eps / 20.0
    normals = tuple(parse_axis(a) for a in config.axes)
    cuts = [family_slices(mesh, n, config.slices) for n in normals]
    radius = max((s.bounding_circle()[1] for fam in cuts for s in fam if not s.is_empty),
                 default=1.0)
    jobs = default_jobs() if config.jobs is None else int(config.jobs)
    run = MeshRun(name, mesh, config, eps, tol, probe_length=4.0 * (radius + eps), jobs=jobs,
                  families=[Family(n) for n in normals])
    settings = SenseSettings(normals, config.slices, eps, tol, config.backend,
                             config.max_motions, config.bootstrap)
    tasks = [(f, i) for f, fam in enumerate(cuts) for i in range(len(fam))]

    outcomes = sense_all(mesh, settings, tasks, jobs, progress=progress)
    for out in outcomes:
        out.metrics["robot_time_s"] = robot_time(out.result.stats.as_dict(), config.probe_speed,
                                                 config.motion_overhead)
        run.families[out.family].slices.append(SliceRun(
            cuts[out.family][out.index], out.family, out.result, out.metrics, out.workspace,
            out.truth))
    run.seconds = time.perf_counter() - t0
    return run
