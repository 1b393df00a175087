"""The last look: contour that no area holds any more.

Every piece the robot records runs with the material on its right
(:class:`~core2d.planner.known.KnownContour`), so on a closed contour the
unknown parts are exactly the stretches from a *loose end* (a piece ends and
nothing recorded continues it) to a *loose start* (a piece starts and
nothing recorded leads into it). On one object the areas A_iB_i of the paper
hold those stretches; with several objects in a slice (islands, §3.2) the
bootstrap pairs contacts across objects, and a stretch can end up in no
area's C_A^B at all.

When nothing else is left, :func:`audit` pairs every loose end E with the
nearest loose start S whose pair (E, S) the robot has not registered yet,
and registers (E, S) as an unknown area (rule ``"audit"``) with the
postures that touched E and S: it goes through the paper's flow like any
other. The robot uses only its own records.

**Behind a lid that opened to F.** An area whose lid is a gap between two
separate objects ends ``open`` (:mod:`core2d.planner.revisit`, step 5):
a pass left through the gap without contact. Its A_i and B_i lie on two
objects, and the contour that goes on from A_i round A_i's own object
(C_{A_i} onward), and the contour that leads round B_i's object into B_i,
face away from the gap: no pass through that lid reaches them (§3.2's
single object does not hold). The robot's map says whether they are
recorded: at A_i the recorded contour may stop, and at B_i begin. The
coarse test of :meth:`~core2d.planner.known.KnownContour.loose_ends` (any
piece passing within ``join`` continues an end) misses that where a W2
chord a hair long lies at A_i, or the same stretch was recorded twice, so
the audit asks the finer one there
(:func:`core2d.planner.loose_ends.recorded_stops`: recorded contour must
move on beyond ``join``) and adds what it finds to the loose ends and
starts it pairs. The stretch behind each end then goes through the paper's
flow like any A_iB_i.

What stays untraced behind such a lid is never dropped:
:func:`report_leftovers` reports it as an unknown chord from the loose end
to the nearest loose start (rule ``"loose"``), as the chords of areas left
unknown are reported.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from core2d.planner.areas import Area
from core2d.planner.loose_ends import recorded_stops

if TYPE_CHECKING:  # the planner state that drives this module; typing only
    from core2d.planner.run import Exploration

__all__ = ["audit", "behind_open_lids", "report_leftovers", "MAX_AUDITS"]

#: rounds of the audit in one run
MAX_AUDITS = 4


def _registered(run: Exploration, e, s) -> bool:
    same = run.res.tip_zone
    return any(np.hypot(*(rec.a - e)) <= same and np.hypot(*(rec.b - s)) <= same
               for rec in run.result.areas)


def _near(p, points, r) -> bool:
    """Does any of ``points`` lie within ``r`` of ``p``?"""
    return any(np.hypot(*(np.asarray(q) - p)) <= r for q in points)


def behind_open_lids(run: Exploration):
    """The stretches behind the ends of lids that opened to F.

    Loose ends at the A_i, and loose starts at the B_i, of the areas that
    ended ``open`` (within ``join``), by the finer test
    :func:`~core2d.planner.loose_ends.recorded_stops`, each with its
    partner: the nearest loose start (loose end) of that test anywhere.

    Returns
    -------
    list of ((2,) E, Posture, (2,) S, Posture) -- a stretch from loose end E
    to loose start S.
    """
    opened = [rec for rec in run.result.areas if rec.outcome == "open"]
    if not opened:
        return []
    ends, starts = recorded_stops(run.known)
    r = run.known.join
    out = []
    if starts:
        for e, pose, _ in ends:
            if _near(e, [rec.a for rec in opened], r):
                out.append((e, pose, *_nearest(starts, e)))
    if ends:
        for s, pose, _ in starts:
            if _near(s, [rec.b for rec in opened], r):
                out.append((*_nearest(ends, s), s, pose))
    return out


def audit(run: Exploration) -> int:
    """Register an area for every loose end of the map and every stretch
    behind the ends of a lid that opened to F; returns how many."""
    if run.audits >= MAX_AUDITS:
        return 0
    run.audits += 1
    ends, starts = run.known.loose_ends()
    used, added = set(), 0
    for e, pose_e, _ in ends:
        if pose_e is None:
            continue
        order = np.argsort([np.hypot(*(s - e)) for s, _, _ in starts]) if starts else []
        for m in order:
            s, pose_s, _ = starts[m]
            if m in used or pose_s is None or _registered(run, e, s):
                continue
            used.add(m)
            run.add(Area(np.asarray(e, float), np.asarray(s, float), pose_e, pose_s,
                         rule="audit"))
            added += 1
            break
    for e, pose_e, s, pose_s in behind_open_lids(run):
        if pose_e is not None and pose_s is not None and not _registered(run, e, s):
            run.add(Area(np.asarray(e, float), np.asarray(s, float), pose_e, pose_s,
                         rule="audit"))
            added += 1
    return added


def _reported(run: Exploration, p) -> bool:
    """Does an unknown chord already end (within eps/2) at ``p``?"""
    same = run.res.tip_zone
    return any(min(np.hypot(*(u[0] - p)), np.hypot(*(u[1] - p))) <= same
               for u in run.result.unknown)


def _nearest(found, p):
    """The (point, Posture) of ``found`` nearest to ``p``."""
    q, pose, _ = min(found, key=lambda f: np.hypot(*(f[0] - p)))
    return np.asarray(q, float), pose


def report_leftovers(run: Exploration) -> int:
    """Report the contour left untraced behind the ends of lids that opened
    to F (:func:`behind_open_lids`) that no unknown chord holds yet: an
    unknown area (E, S) each (rule ``"loose"``). Returns how many."""
    added = 0
    for e, pose_e, s, pose_s in behind_open_lids(run):
        if _reported(run, e) and _reported(run, s):
            continue
        area = Area(np.asarray(e, float), np.asarray(s, float), pose_e, pose_s, rule="loose")
        run.add(area)
        run.queue.remove(area)
        run.close(area, "unknown", "the recorded contour stops at the end of a lid that "
                                   "opened to F, and no area traced on from it")
        added += 1
    return added
