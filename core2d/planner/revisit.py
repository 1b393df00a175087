"""A second look at dead ends, with everything the robot has recorded.

An area that reached a dead end in the paper's flow (no Theorem 1 pass into
G_i cap V_i, or a pass that found no new contact) is *deferred*, never W3:
those dead ends say that the two recorded postures leave no pass, not that
none exists. Once nothing else is left, every deferred area A_iB_i is looked
at again against the robot's own map (:class:`KnownContour`):

1. C_A^B has meanwhile been traced through other areas -> closed as traced.
2. No straight line from F crosses the open lid L_A^B past the recorded
   contour (:meth:`KnownContour.free_lines`) and the lid crosses no recorded
   contour -> **W3, proven**: the contour behind a lid is reachable only
   through the lid, and every line through it is blocked by real contour
   the robot has touched. This extends Area(G_i) = 0 (§4.2.1) from one
   posture to all lines through the lid.
3. Otherwise a free line is a pass to try (another pass, another side; it
   plays the role of Theorem 1's pass through L_{A0}^{B0} cap G_i cap V_i):
   the probe is inserted along it from F. A new contact C (farther than
   2 tol from everything recorded and than eps/2 from A and B) splits the
   area into (A_i, C) and (C, B_i), which go back to the paper's flow.
   The passes are spread over the lid and over the free directions
   (:func:`passes`): the middle of the lid along the middle of its free
   gap, then near each end steered towards that end (where the unknown
   contour continues from the touched end), then the quarter points.
4. After ``MAX_TRIES`` passes that found nothing new:

   * a pass left without any contact -> ``open``: the lid is an opening
     to F (a gap between separate objects, §3.2); nothing is written;
   * the area was pinched (single probe detection with Area(G_i) = 0,
     Fig. 6(b)) and every pass ended at a touched end of the lid (within
     eps/2 of A or B) -> **W3**: the paper's Area(G_i) = 0, confirmed by
     passes through the lid -- the lines the robot's map still allows
     through a slit narrower than eps touch nothing beyond the lid's ends;
   * otherwise -> ``unknown``, reported with the lid in the result.
"""
from __future__ import annotations

import numpy as np

from core2d.planner.areas import Area
from core2d.planner.regions import Posture

__all__ = ["revisit", "MAX_TRIES"]

#: passes through one lid that may find nothing new before it is called open
MAX_TRIES = 6
#: (position along the lid A -> B, which way to steer in the free gap)
_PLAN = ((0.5, 0.0), (0.9, 1.0), (0.1, -1.0), (0.3, 0.0), (0.7, 0.0), (0.5, 1.0), (0.5, -1.0))


def passes(lines, a, b):
    """Candidate passes ``(point, direction)`` through the lid, in the order
    of ``_PLAN``: for each planned position the nearest free lid sample, its
    direction at the middle of the free gap (steer 0) or at 0.1 / 0.9 of it,
    whichever edge leans towards B (steer +1) or A (steer -1)."""
    out = []
    ab = np.asarray(b, float) - a
    along = np.array([ln.along for ln in lines])
    for pos, steer in _PLAN:
        ln = lines[int(np.argmin(np.abs(along - pos)))]
        if steer == 0:
            out.append((ln.point, ln.direction))
            continue
        d0, d1 = ln.turned(0.1), ln.turned(0.9)
        toward_b = d0 if d0 @ ab > d1 @ ab else d1
        out.append((ln.point, toward_b if steer > 0 else (d1 if toward_b is d0 else d0)))
    return out


def _near_end(probe, area, point) -> bool:
    """Within eps/2 of A_i or B_i: the same contact at the paper's resolution."""
    return min(np.hypot(*(point - area.a)), np.hypot(*(point - area.b))) <= probe.tip_zone


def _new_contact(run, area, point) -> bool:
    """Farther than eps/2 from A_i and B_i and than 2 tol from the map."""
    return not _near_end(run.probe, area, point) and run.known.distance(point) > 2 * run.probe.tol


def revisit_one(run, area) -> None:
    """Look at one deferred area again; see the module doc."""
    probe, known = run.probe, run.known
    if known.covers(area.a, area.b, 2 * probe.tol):
        return run.close(area, "traced", "C_A^B traced through other areas")
    crossing = known.crosses(area.a, area.b, probe.tip_zone)
    lines = known.free_lines(area.a, area.b, spacing=run.eps / 2, margin=probe.tol,
                             min_gap=probe.ang_tol)
    if not lines:
        if crossing:
            return run.close(area, "open", "the lid crosses recorded contour")
        return run.close(area, "W3", "no line from F crosses the lid past the recorded contour")
    plan = passes(lines, area.a, area.b)[area.tries:MAX_TRIES]
    ends_only, escaped = True, False
    for point, direction in plan:
        if not run.budget():
            return run.deferred.append(area)  # the budget ran out: still unknown
        probe.approach(point, direction)
        r = probe.insert(2.5 * probe.radius)
        c = r.tip_contact
        if c is not None and _new_contact(run, area, c.point):
            pose_c = Posture(r.joint, r.direction)
            d = area.depth + 1
            kids = [Area(area.a, c.point, area.pose_a, pose_c, area.index, "revisit", d),
                    Area(c.point, area.b, pose_c, area.pose_b, area.index, "revisit", d)]
            return run.children(area, kids)
        area.tries += 1
        escaped |= c is None
        ends_only &= c is not None and _near_end(probe, area, c.point)
    note = f"{area.tries} passes through the lid found nothing new"
    if escaped:
        return run.close(area, "open", note + "; one left through it: an opening to F")
    if area.pinched and ends_only:
        return run.close(area, "W3", "single probe detection, Area(G) = 0; every pass through "
                                     "the lid ended at its touched ends")
    run.close(area, "unknown", note)


def revisit(run) -> None:
    """Look at every deferred area of ``run`` again (see the module doc)."""
    todo, run.deferred = run.deferred, []
    for area in todo:
        revisit_one(run, area)
