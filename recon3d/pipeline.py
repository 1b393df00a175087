"""Run the 2D algorithm on every slice of a mesh (meshes -> slicer -> core2d).

The pipeline owns the loop over slices; each slice gets its own contact
backend (Embree or exact), its own probe and planner, and its own budget, so
a run always ends. Metrics against the reference contour are computed after
sensing and never fed back to the planner.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

import core2d
import slicer
from core2d.truth.metrics import slice_metrics, total_metrics

__all__ = ["RunConfig", "SliceRun", "MeshRun", "sense_mesh"]


@dataclass(frozen=True)
class RunConfig:
    """Parameters of one run (CLI flags of ``recon3d run``).

    axis : str or (3,) float -- slice normal ('x', 'y', 'z' or a vector).
    slices : int -- number of evenly spaced planes strictly inside the mesh.
    eps : float or None -- the paper's epsilon; default bbox diagonal / 200.
    backend : str -- 'embree' or 'exact' contact backend.
    tol : float or None -- contact resolution, default eps / 20.
    max_motions : int -- motion budget per slice.
    bootstrap : int -- initial insertions around each slice.
    """

    axis: object = "z"
    slices: int = 8
    eps: float | None = None
    backend: str = "embree"
    tol: float | None = None
    max_motions: int = 20000
    bootstrap: int = 12


@dataclass
class SliceRun:
    """One slice: its geometry, the sensing result and its metrics."""

    slice: object
    result: object
    metrics: dict
    workspace: tuple


@dataclass
class MeshRun:
    """A whole run over the slices of one mesh."""

    name: str
    mesh: object
    config: RunConfig
    eps: float
    probe_length: float
    slices: list = field(default_factory=list)
    seconds: float = 0.0

    @property
    def totals(self) -> dict:
        return total_metrics([s.metrics for s in self.slices])


def default_eps(mesh) -> float:
    """eps = 1/200 of the bounding-box diagonal (issue default)."""
    return float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)) / 200.0)


def sense_mesh(mesh, name, config: RunConfig, progress=None) -> MeshRun:
    """Slice ``mesh`` and sense every slice.

    Parameters
    ----------
    mesh : trimesh.Trimesh
    name : str -- label written to the output.
    config : RunConfig
    progress : callable(SliceRun) or None -- called after each slice.
    """
    t0 = time.perf_counter()
    eps = config.eps if config.eps is not None else default_eps(mesh)
    cuts = slicer.slice_mesh(mesh, axis=config.axis, count=config.slices)
    radius = max((s.bounding_circle()[1] for s in cuts if not s.is_empty), default=1.0)
    run = MeshRun(name, mesh, config, eps, probe_length=4.0 * (radius + eps))
    for cut in cuts:
        run.slices.append(_sense_one(cut, config, eps))
        if progress is not None:
            progress(run.slices[-1])
    run.seconds = time.perf_counter() - t0
    return run


def _sense_one(cut, config, eps) -> SliceRun:
    if cut.is_empty:
        result = core2d.SliceResult()
        return SliceRun(cut, result, slice_metrics([], result, eps), (np.zeros(2), 0.0))
    center, radius = cut.bounding_circle()
    workspace = (np.asarray(center, float), float(radius) + eps)
    result = core2d.sense_slice(
        cut.contact(config.backend), workspace, eps, tol=config.tol,
        max_motions=config.max_motions, bootstrap_count=config.bootstrap,
    )
    metrics = slice_metrics([np.asarray(l) for l in cut.loops], result, eps)
    return SliceRun(cut, result, metrics, workspace)
