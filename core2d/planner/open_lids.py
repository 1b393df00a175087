"""The lids of the other open areas steer a revisit's passes (a noisy sensor only).

The region behind an open lid L_j -- between the chord A_jB_j and the
unknown contour C_{A_j}^{B_j} -- is closed by contour when A_j and B_j lie on
one object (§3.2). A straight line from F that crosses L_j from V_j is inside
that region until it meets C_{A_j}^{B_j}, and it cannot leave through L_j
again: it reaches no other area's lid. The open areas partition the contour
still unknown (the paper's recursion splits an area into children whose arcs
are disjoint), so for the revisit of A_iB_i every other open lid is contour
as far as a pass is concerned.

Why it matters with a noisy sensor: the record has holes. A trace breaks at
noisy events, a corner's two faces are recorded as pieces that do not join,
and each hole is an open lid. :meth:`~core2d.planner.known.KnownContour.free_lines`
lets a line through every hole and takes the widest free gap at each lid
sample, and the widest gap of a lid deep in a slot ran through a hole at a
corner of the outer contour and across the object's inside, not out through
the slot's mouth. Measured on the ``undercut`` outline seed 3 of
``tests/outlines.py`` at sigma 0.3, taxel 0.25 eps: the 21 revisit passes of
a lid along a slot wall 2.5 eps wide all landed on the bottom face 60 eps
away, through the unrecorded corner below; and on ``deep_slot`` z7 at sensor
seed 1007, 19 - 33 passes per lid of the slot's walls landed on the box's
outer corners.

**Rule.** The revisit plans its passes as before, from the lines free past
the record. A planned pass whose line from F crosses the lid of another
open area (pending, deferred, or ended unknown; :func:`open_lids`) farther
than the same-contact radius from that lid's ends (:func:`crossing`) is made
along the line free past the record *and* the other open lids nearest the
same place on the lid, when there is one (:func:`steer`). The other passes
stay as they were. It only chooses passes: the W3 proof still asks the
record alone (:func:`~core2d.planner.revisit.proof_lines`) -- a lid may
span two objects (islands: the bootstrap pairs contacts across them) and
bounds nothing there, and a line it would block is a line the proof must
see. For the same reason a lid whose passes were steered is not proven W3 by
its passes all ending at its touched ends: the lines they left out were not
tried. Perfect sensing (jitter 0) leaves the paper's flow as it is: its
record has no such holes.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from core2d.planner.segments import cross2

if TYPE_CHECKING:  # the planner state that drives this module; typing only
    from core2d.planner.run import Exploration

__all__ = ["open_lids", "crossing", "steer", "OPEN"]

#: outcomes of an area whose lid is still open (``AreaRecord.outcome``)
OPEN = ("pending", "deferred", "unknown")


def open_lids(run: Exploration, area) -> np.ndarray:
    """(m, 2, 2) float: A_j and B_j of every area of ``run`` still open (:data:`OPEN`)
    but ``area``."""
    lids = [(rec.a, rec.b) for rec in run.result.areas
            if rec.outcome in OPEN and rec.index != area.index]
    return np.asarray(lids, dtype=np.float64).reshape(-1, 2, 2)


def crossing(lids, starts, ends, margin: float) -> np.ndarray:
    """(k,) bool: does segment ``starts[i]`` -> ``ends[i]`` ((k, 2) float each) cross
    any of ``lids`` ((m, 2, 2) float) farther than ``margin`` from both of its ends?

    >>> lid = np.array([[[0.0, 0.0], [4.0, 0.0]]])
    >>> crossing(lid, np.array([[2.0, 3.0], [0.2, 3.0]]), np.array([[2.0, -3.0], [0.2, -3.0]]),
    ...          0.5).tolist()
    [True, False]
    """
    lids = np.asarray(lids, dtype=np.float64).reshape(-1, 2, 2)
    p = np.asarray(starts, dtype=np.float64).reshape(-1, 1, 2)
    q = np.asarray(ends, dtype=np.float64).reshape(-1, 1, 2)
    a, b = lids[None, :, 0], lids[None, :, 1]
    pq, ab = q - p, b - a
    den = cross2(ab, pq)
    with np.errstate(divide="ignore", invalid="ignore"):
        s = cross2(p - a, pq) / den  # along the lid
        t = cross2(p - a, ab) / den  # along the pass
    length = np.hypot(ab[..., 0], ab[..., 1])
    inner = (s * length > margin) & ((1.0 - s) * length > margin)
    return ((den != 0) & inner & (t >= 0.0) & (t <= 1.0)).any(axis=1)


def steer(plan, lids, lines, a, b, reach: float, margin: float):
    """The passes of ``plan`` (``(point, direction)`` pairs: a lid sample and the
    direction from F) with each one whose line (from ``reach`` before its point)
    crosses one of ``lids`` (:func:`crossing`) replaced by the free line of
    ``lines`` (:class:`~core2d.planner.lid_lines.FreeLines` past the record and
    ``lids``) nearest its place along the lid A -> B, when there is one;
    and whether any was replaced."""
    if not plan or not len(lids):
        return plan, False
    pts = np.array([p for p, _ in plan], dtype=np.float64)
    dirs = np.array([d for _, d in plan], dtype=np.float64)
    hit = crossing(lids, pts - reach * dirs, pts, margin)
    if not hit.any():
        return plan, False
    ab = np.asarray(b, float) - a
    along = (pts - a) @ ab / max(float(ab @ ab), 1e-300)
    found = lines.nearest_many(along[hit].tolist())
    out, k = list(plan), np.flatnonzero(hit)
    for i, ln in zip(k.tolist(), found):
        if ln is not None:
            out[i] = (ln.point, ln.direction)
    return out, any(ln is not None for ln in found)
