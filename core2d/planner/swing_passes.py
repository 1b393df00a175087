"""Swing passes: touching the contour behind a lid no straight pass from F crosses (noisy sensor).

The revisit's passes are straight insertions from F (Theorem 1's pass, §4.2). A lid laid
along a wall -- a noisy trace of a deep slot's wall leaves such lids, A_i and B_i read a
fraction of eps off the wall, the wall between them never recorded -- is crossed by no
line from F past the recorded contour: every line that could reach the wall behind it
comes down the slot at a grazing angle. The W3 proof then holds, but the probe cannot
hold the lid (:func:`~core2d.planner.w3_checks.holds_lid`: inserted along the lid, its
tip meets nothing at the far end), and the lid ended ``unknown`` with the wall behind it
untouched (``deep_slot`` at sigma 0.3 eps with taxels 0.25 eps: 120 eps of the scenes'
missed contour, a quarter of it, lay behind such lids on the study's own seeds).

The probe reaches such a wall the way the bisection does (§4.2.2 (i)): it is inserted
along a line parallel to the lid (or tilted a few degrees), the same-contact radius beside
it, until its tip is abreast of a point of the lid, and swung about its joint towards the
lid until it touches (or the tip has passed the lid by the W2 distance). Each contact,
the tip's or the rod's, goes to the lid's :class:`~core2d.planner.touched.Touches`, as a
straight pass's would; none splits the lid (splitting at new ones, measured in an earlier
form, gained nothing over six sensor seeds: docs/notes/noise.md). The points aimed at are the middles of the widest gaps the touches leave
(A_i and B_i included), as :class:`~core2d.planner.touched.Fill` aims.

The same swings serve a lid whose straight passes did cross it but found nothing new
(:func:`swing_gaps`, after the revisit's passes and the Fill): they reach the gaps near
its ends that grazing straight passes leave.
"""
from __future__ import annotations

import numpy as np

from core2d.planner.grazing import resolves_half_eps
from core2d.planner.pass_plan import MAX_SWEEP
from core2d.planner.short_lids import lid_end_radius
from core2d.planner.touched import Touches, applies, gap_key

__all__ = ["swing_lid", "swing_gaps", "swing_fill", "swing_targets", "swing_pass"]


def swing_targets(touches, limit: int):
    """Fractions along A_i -> B_i to swing at: the middle of the widest open gap of
    ``touches`` each time, each gap at most twice, at most ``limit`` in all (a generator:
    the gaps are read again after every pass)."""
    tried: dict[tuple[float, float], int] = {}
    for _ in range(limit):
        gap = touches.widest_untried(tried)
        if gap is None:
            return
        key = gap_key(*gap)
        tried[key] = tried.get(key, 0) + 1
        yield (gap[0] + gap[1]) / 2


TILTS = np.radians([0.0, 2.0, -2.0, 4.0, -4.0, 8.0, -8.0])
"""Directions tried about the lid's, in turn: the lid is a pair of readings, tilted against
the wall it lies along by up to jitter / length (3 degrees on ``deep_slot``'s walls at sigma
0.3 eps), and a line parallel to it drifts into that wall over the way in from F."""


def _directions(u):
    """Unit directions along the lid (both ways) tilted by :data:`TILTS`."""
    for sign in (1.0, -1.0):
        base = np.arctan2(sign * u[1], sign * u[0])
        for tilt in TILTS:
            yield np.array([np.cos(base + tilt), np.sin(base + tilt)])


def swing_pass(run, area, fraction: float):
    """One swing pass at ``fraction`` of the lid; the reading after the swing, or None
    when no free line along the lid (tilted by :data:`TILTS`) leads abreast of that
    point, or the insertion met contour before it got there.

    The line runs ``off`` = the same-contact radius in front of the lid, on F's side
    first, then (a lid read a hair inside the wall, V_i facing the free side) on V_i's;
    it is entered from whichever end's side reaches it through F without crossing the
    recorded contour. The swing turns the tip towards the lid, by an angle that carries
    it ``off`` + the W2 distance sideways (less when the probe is shorter)."""
    probe, res, known = run.probe, run.res, run.known
    a, b = np.asarray(area.a, float), np.asarray(area.b, float)
    u = (b - a) / area.dist
    left = np.array([-u[1], u[0]])  # towards V_i (Definition 3)
    off = res.tip_zone
    lateral = min(off + res.w2_dist, 0.9 * probe.length)
    for side in (1, -1):  # F's side, then V_i's
        q = a + fraction * (b - a) - side * off * left
        for t in _directions(u):
            if known.crosses(q - (2.0 * probe.radius) * t, q, res.tol):
                continue
            probe.approach(q, t)
            reach = float((q - probe.tip) @ t)
            if reach <= 0:
                continue
            r = probe.insert(reach)
            if r.contacts:
                return None  # met contour on the way
            rot = side * (1 if float(t @ u) > 0 else -1)  # the tip turns towards the lid
            return probe.swing(rot, float(np.arcsin(lateral / probe.length)))
    return None


def swing_fill(run, area, touches):
    """Swing passes into the widest gaps of ``touches`` (:func:`swing_targets`: each gap
    at most twice, at most 2 ceil(Dist / W2 distance) in all), every contact of each swing
    added to ``touches``; how many were made, or None when the budget ran out."""
    limit = min(MAX_SWEEP, 2 * int(np.ceil(area.dist / run.res.w2_dist)))
    made = 0
    for fraction in swing_targets(touches, limit):
        if not run.budget():
            return None
        r = swing_pass(run, area, fraction)
        made += 1
        for c in (r.contacts if r is not None else ()):  # the tip's or the rod's
            touches.add(r.joint, c.point)
    return made


def swing_gaps(run, area, touches):
    """After a lid's straight passes found nothing new (the revisit's passes and the
    :class:`~core2d.planner.touched.Fill`'s): swing passes into the gaps their touches
    left, under a sensor that does not resolve eps/2; the lid's pieces then
    (:meth:`~core2d.planner.touched.Touches.pieces`), or None when nothing of it is W2.

    Straight passes meet a wall the lid lies along where a grazing line meets it, not
    where they cross the lid, so their touches leave gaps wider than the W2 distance
    near the ends; a swing from beside the lid reaches them. Measured at sigma 0.3 eps
    with taxels 0.25 eps (8 slices, six keyed sensor seeds, docs/notes/noise.md): 144
    slice runs up, 1 down, coverage +0.0003 / +0.0009 / +0.0015 (meshes, outlines,
    scenes), motions +1.6 / +2.4 / +4.0 %; kept with the coarse sensor's sweep spacing
    (:func:`~core2d.planner.grazing.sweep_length`), which pays for it."""
    if not resolves_half_eps(run.res):
        swing_fill(run, area, touches)
    return touches.pieces() if touches.points else None


def swing_lid(run, area) -> bool:
    """Swing passes at a lid no straight pass crosses and the probe cannot hold (a coarse
    noisy sensor; ``run`` an :class:`~core2d.planner.run.Exploration`): True when their
    touches closed it -- W2 along them, or unknown with W2 where they lie within the W2
    distance (:meth:`~core2d.planner.touched.Touches.pieces`); False when nothing was
    touched, the sensor resolves eps/2 (a fine sensor gained nothing from them: σ 0.1 eps
    over six seeds, case runs 192 -> 191) or the budget ran out."""
    if not applies(run.res) or resolves_half_eps(run.res):
        return False
    touches = Touches(run.res, np.asarray(area.a, float), np.asarray(area.b, float),
                      lid_end_radius(run.res, area.dist))
    made = swing_fill(run, area, touches)
    if made is None:
        return False
    part = touches.pieces() if touches.points else None
    if part is None:
        return False
    if "unknown" not in part:
        run.close(area, "W2", f"{made} swing passes touched C_A^B along the lid, every "
                              "neighbour within eps + the sensor's jitter", pieces=part)
    else:
        run.close(area, "unknown", f"no line from F crosses the lid and the probe cannot hold "
                                   f"it; {made} swing passes: W2 where they touched C_A^B",
                  pieces=part)
    return True
