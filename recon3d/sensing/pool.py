"""Sense the slices of a run, in this process or in parallel processes (internal).

The slices are cut once, in the parent (:func:`recon3d.sensing.mesh.sense_mesh`).
``jobs == 1`` senses them in this process. Otherwise a
``ProcessPoolExecutor`` with ``jobs`` workers: forked workers (where the
platform can fork) inherit the parent's slices through the module-level
state set before the pool starts -- nothing is cut again and the caller's
script is not re-imported, so no ``if __name__ == "__main__"`` guard is
needed; spawned workers (elsewhere) cut them again from the mesh arrays
(Embree scenes do not pickle). Every path runs the same code on the same
slices, so the results are identical; they come back in task order
whatever the completion order.
"""
from __future__ import annotations

import dataclasses
import multiprocessing
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor, as_completed

import numpy as np
import trimesh

from recon3d.records import SliceRun
from recon3d.sensing.worker import SenseSettings, WorkerState

__all__ = ["sense_all"]

_STATE: WorkerState | None = None
"""The slices a worker senses: set in the parent before a fork (inherited), or by
the initializer of a spawned worker."""


def _rebuild(vertices, faces, settings) -> None:
    global _STATE
    _STATE = WorkerState.rebuild(vertices, faces, settings)


def _sense(task):
    return _STATE.sense(*task)


def _own_contacts(families: list) -> list:
    """The same slices (geometry shared, not cut again) with empty contact caches, so
    the contact models built while sensing go when sensing ends, as in a worker."""
    return [[dataclasses.replace(s) for s in fam] for fam in families]


def sense_all(mesh: trimesh.Trimesh, families: list, settings: SenseSettings, tasks: list,
              jobs: int, progress: Callable[[SliceRun], None] | None = None) -> list[SliceRun]:
    """Sense ``tasks``; return their SliceRuns (``slice`` None) in task order.

    Parameters
    ----------
    mesh : trimesh.Trimesh -- what ``families`` were cut from (spawned workers cut it again).
    families : list of list of slicer.Slice -- ``settings.slices`` planes per axis of ``settings``.
    settings : SenseSettings
    tasks : list of (family, index) or (family, index, eps)
    jobs : int -- worker processes (1: in this process).
    progress : callable(SliceRun) or None -- called as slices finish.
    """
    global _STATE
    jobs = max(1, min(int(jobs), len(tasks)))
    out: list = [None] * len(tasks)
    if jobs == 1:
        state = WorkerState(settings, _own_contacts(families))
        for k, task in enumerate(tasks):
            out[k] = state.sense(*task)
            if progress is not None:
                progress(out[k])
        return out
    if "fork" in multiprocessing.get_all_start_methods():
        ctx, init, args = multiprocessing.get_context("fork"), None, ()
        _STATE = WorkerState(settings, families)  # inherited by the forked workers
    else:  # pragma: no cover - no fork on this platform
        ctx, init = multiprocessing.get_context("spawn"), _rebuild
        args = (np.asarray(mesh.vertices, dtype=np.float64),
                np.asarray(mesh.faces, dtype=np.int64), settings)
    try:
        with ProcessPoolExecutor(jobs, mp_context=ctx, initializer=init,
                                 initargs=args) as pool:
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
    finally:
        _STATE = None
    return out
