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

What the audit leaves -- a loose end whose stretch went through the flow
and came back untraced (its area ended ``open``: the pass left through a
gap to F without reaching the contour behind; §3.2's single object does not
hold), or one left when the rounds ran out -- is never dropped:
:func:`report_leftovers` reports each as an unknown chord from the loose
end to the nearest loose start (rule ``"loose"``), as the chords of areas
left unknown are reported.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from core2d.planner.areas import Area

if TYPE_CHECKING:  # the planner state that drives this module; typing only
    from core2d.planner.run import Exploration

__all__ = ["audit", "report_leftovers", "MAX_AUDITS"]

#: rounds of the audit in one run
MAX_AUDITS = 4


def _registered(run: Exploration, e, s) -> bool:
    same = run.res.tip_zone
    return any(np.hypot(*(rec.a - e)) <= same and np.hypot(*(rec.b - s)) <= same
               for rec in run.result.areas)


def audit(run: Exploration) -> int:
    """Register an area for every loose end of the map; returns how many."""
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
    """Report every loose end and loose start of the map that no unknown
    chord holds yet as an unknown area (E, S): E a loose end, S the
    nearest loose start (for a start no such chord reaches, the nearest
    loose end leads to it). An end that any recorded piece continues,
    whichever way it turns (the tip of a slit, where the contour turns
    back), is not loose here; nor, with no loose start anywhere, is a lone
    end (nor a lone start): the recorded contour stops there without
    beginning again anywhere, as at the tip of a spike narrower than eps
    whose other side was recorded within eps of the side traced.
    Returns how many were reported."""
    ends, starts = run.known.loose_ends(turn=False)
    if not ends or not starts:
        return 0
    added = 0
    for (p, pose, _), is_end in [(e, True) for e in ends] + [(s, False) for s in starts]:
        if _reported(run, p):
            continue
        q, pose_q = _nearest(starts if is_end else ends, p)
        a, b, pose_a, pose_b = (p, q, pose, pose_q) if is_end else (q, p, pose_q, pose)
        area = Area(np.asarray(a, float), np.asarray(b, float), pose_a, pose_b, rule="loose")
        run.add(area)
        run.queue.remove(area)
        run.close(area, "unknown", "the recorded contour stops here and no area traced on "
                                   "(a loose end the audit left)")
        added += 1
    return added
