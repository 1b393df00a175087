"""Sense the slices of a run in parallel processes.

``jobs == 1`` runs every slice in this process; otherwise a
``ProcessPoolExecutor`` with ``jobs`` workers, each of which rebuilds the
slices once from the mesh arrays (:class:`recon3d.sensing.WorkerState`:
Embree scenes do not pickle). Workers are forked where the platform can
(the caller's script is not re-imported, so no ``if __name__ ==
"__main__"`` guard is needed) and spawned elsewhere. Both paths run the
same code on the same inputs, so the results are identical; they come back
in task order whatever the completion order.
"""
from __future__ import annotations

import os
from concurrent.futures import ProcessPoolExecutor, as_completed
import multiprocessing

import numpy as np

from recon3d.sensing import WorkerState

__all__ = ["default_jobs", "sense_all"]

_STATE: WorkerState | None = None
"""The worker process's slices (set once by the pool initializer, only in workers)."""


def default_jobs() -> int:
    """Number of cores this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not on Linux
        return max(1, os.cpu_count() or 1)


def _init(vertices, faces, settings) -> None:
    global _STATE
    _STATE = WorkerState(vertices, faces, settings)


def _sense(task):
    return _STATE.sense(*task)


def sense_all(mesh, settings, tasks, jobs: int, progress=None) -> list:
    """Sense ``tasks`` ((family, index) pairs); return their outcomes in task order.

    Parameters
    ----------
    mesh : trimesh.Trimesh
    settings : recon3d.sensing.SenseSettings
    tasks : list of (int, int)
    jobs : int -- worker processes (1: in this process).
    progress : callable(SliceOutcome) or None -- called as slices finish.
    """
    vertices = np.asarray(mesh.vertices, dtype=np.float64)
    faces = np.asarray(mesh.faces, dtype=np.int64)
    jobs = max(1, min(int(jobs), len(tasks)))
    out: list = [None] * len(tasks)
    if jobs == 1:
        state = WorkerState(vertices, faces, settings)
        for k, task in enumerate(tasks):
            out[k] = state.sense(*task)
            if progress is not None:
                progress(out[k])
        return out
    methods = multiprocessing.get_all_start_methods()
    ctx = multiprocessing.get_context("fork" if "fork" in methods else "spawn")
    with ProcessPoolExecutor(jobs, mp_context=ctx, initializer=_init,
                             initargs=(vertices, faces, settings)) as pool:
        futures = {pool.submit(_sense, task): k for k, task in enumerate(tasks)}
        try:
            for fut in as_completed(futures):
                k = futures[fut]
                out[k] = fut.result()
                if progress is not None:
                    progress(out[k])
        except BaseException:
            for fut in futures:
                fut.cancel()
            raise
    return out
