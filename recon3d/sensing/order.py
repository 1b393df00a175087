"""The order in which worker processes are handed the slices: longest first (internal).

A pool hands out one task at a time per worker, so the run ends when the last task
does. Handed out in plane order, the costly planes of a mesh whose section grows busy
towards one end (more loops, longer contour) come last, and one worker senses the
last of them while the other waits. Handed out longest first (the classic longest
processing time rule), the short tasks fill the tail.

The cost of a slice is not known before it is sensed; its proxy is known from the
reference section the parent already holds (never shown to the planner, which only
senses): the contour length in units of the slice's eps (the paper's tracing advances
about eps per motion, so the W1 motions grow with it) plus :data:`LOOP_WEIGHT` per
closed loop (every loop adds its own bootstrap, lids and revisits, whatever its
length). Only the dispatch order changes: results come back in task order, every slice
is sensed by the same code with its own noise stream, so the outputs do not depend on
it.
"""
from __future__ import annotations

import numpy as np

__all__ = ["LOOP_WEIGHT", "slice_cost", "dispatch_order"]

LOOP_WEIGHT = 100.0
"""Cost of one closed loop in eps of contour length: the least-squares fit of the CPU
seconds of the 64 z-slices of the 176k-face mesh (``bench.run_timeline``, per slice)
on contour length and loop count gave 0.05 s a loop and 0.0054 s a mesh unit at
eps = 0.088, i.e. about 100 eps a loop."""


def slice_cost(cut, eps: float) -> float:
    """The cost proxy of sensing slice ``cut`` (a :class:`slicer.Slice`) at ``eps``:
    contour length / eps + :data:`LOOP_WEIGHT` x loops (0 for an empty slice)."""
    parts = [np.asarray(p, dtype=np.float64) for p in cut.loops]
    closed = [np.vstack([p, p[:1]]) for p in parts]
    chains = [np.asarray(p, dtype=np.float64) for p in cut.open_chains]
    length = sum(float(np.hypot(*np.diff(p, axis=0).T).sum()) for p in (*closed, *chains)
                 if len(p) > 1)
    return length / float(eps) + LOOP_WEIGHT * len(parts)


def dispatch_order(families: list, tasks: list, eps: float) -> list[int]:
    """Indices of ``tasks`` in the order a pool hands them out: costliest first
    (:func:`slice_cost`; ties in task order).

    Parameters
    ----------
    families : list of list of slicer.Slice
    tasks : list of (family, index) or (family, index, eps) -- ``eps`` of the run when
        a task has none.
    eps : float

    Returns
    -------
    list of int -- a permutation of ``range(len(tasks))``.
    """
    cost = [slice_cost(families[t[0]][t[1]], t[2] if len(t) > 2 else eps) for t in tasks]
    return sorted(range(len(tasks)), key=lambda k: -cost[k])
