"""Hops: steps of a traced polyline that are not contour the tip slid along (§3.1, §4.3.2).

:func:`trace <core2d.planner.tracing.trace_side>` records W1 as the contacts of the
compliant trace. A step longer than the trace's sampling that turns concave, a step at a
polyline's end onto the free side of the contour's line, a trace's first step farther than
the same-point radius from D_i, and Case 1 reaching P_fin across a gap are hops: the
stretch between their two contacts is registered as an unknown area (rule ``"hop"``).
:func:`across_wall` tells Case 1's P_fin reached across a wall thinner than eps/2 (a
needle's far face) from one reached across a gap: the trace slides on past the former.
"""
from __future__ import annotations

import numba
import numpy as np

from core2d.planner.areas import register

__all__ = ["split_hops", "hop_to", "across_wall", "face_line", "HOP_TURN"]

#: a W1 step longer than eps / 4 turning left (concave) by more than this hides contour
HOP_TURN = np.pi / 4


def _reach_back(pl, k, step, hop):
    """Index of the first point at least ``hop`` from ``pl[k]`` walking by
    ``step`` (-1 backward, +1 forward), or None: the direction of the
    contour slid along is read over that stretch, not over single
    micro-steps (whose contacts scatter by the contact resolution)."""
    m = _walk_to(np.ascontiguousarray(pl, dtype=np.float64), int(k), int(step), float(hop))
    return None if m < 0 else m


@numba.njit(cache=True, nogil=True)
def _walk_to(pl, k, step, hop):  # pragma: no cover - compiled
    """:func:`_reach_back`'s walk (-1: none), stopping at the first point found; its
    distances are numpy's ``np.hypot(*(pl[m] - pl[k]))``, the same to the bit."""
    m = k + step
    while 0 <= m < pl.shape[0]:
        if np.hypot(pl[m, 0] - pl[k, 0], pl[m, 1] - pl[k, 1]) >= hop:
            return m
        m += step
    return -1


def _turn(u, w) -> float:
    """Signed angle (left positive) from direction ``u`` to ``w``."""
    return float(np.arctan2(u[0] * w[1] - u[1] * w[0], u @ w))


def hop_to(pieces, last, p_fin, hop):
    """Case 1 at the paper's resolution: the controller reports P_fin
    reached when the tip's step passed within eps / 2 of it. When the last
    contact lies farther than ``hop`` from P_fin and the step to P_fin does
    not continue the contour slid along (it turns by more than
    :data:`HOP_TURN`), the tip passed P_fin across a gap (the mouth of a
    slit): the stretch is still unknown (:func:`split_hops`)."""
    if np.linalg.norm(last - p_fin) <= hop:
        return False
    pts = np.concatenate(pieces)[:-1]
    m = _reach_back(pts, len(pts) - 1, -1, hop)
    if m is None:
        return False
    return abs(_turn(last - pts[m], np.asarray(p_fin) - last)) > HOP_TURN


def across_wall(pieces, last, now, p_fin, pose_fin, sign, hop, near, gap, against=None,
                span=None, through_stop=False) -> bool:
    """Did Case 1 report P_fin reached across a wall (not along the contour, nor across a gap)?

    The controller's radius (the same-point radius eps / 2) takes P_fin as
    reached across anything narrower: the mouth of a slit (:func:`hop_to`:
    the slit behind is registered as an area) or a wall thinner than eps / 2
    -- a needle, whose P_fin was touched on its far face. Across a wall the
    contour from the tip to P_fin runs round the wall's end, however far:
    registered as a hop its lid, shorter than eps, is W2 at once (§3.1) and
    the wall's end is never touched (``numerics`` seed 0: a needle 0.56 eps
    wide at its base and 39 eps long, its outer 33 eps on both faces lost,
    0.882 of the reachable contour covered noiselessly). Read from what the
    probe sensed: the tip still touches the face slid along where the
    controller stopped (on its line over the last ``hop`` of contour, or
    ``span``, within ``near``: the step that passed P_fin slid along it), P_fin lies behind
    that face (on its material side by more than ``near``), and the probe
    that touched P_fin (``pose_fin``: its joint to P_fin is free space) did
    not come through a gap beside the tip -- its segment from the joint to
    P_fin crosses that line nowhere within ``gap`` of the tip, or not at
    all. A slit's probe came in through its mouth beside the tip; a wall's
    probe lay on its far side. A P_fin just round a convex corner, touched
    on the next face, reads the same; there the face slid along ends within
    the stretch the trace slides on (:func:`~core2d.planner.tracing.trace_side`
    then keeps Case 1 where the controller stopped), or the corner is traced.

    A wall thinner than ``near`` (the sensor's jitter + 2 tol) has no depth the
    sensor resolves: its P_fin reads on the face's line. ``against`` (a
    callable of the face slid along, a unit direction with the material on
    its right; :func:`core2d.planner.thin_walls.far_face` over the robot's
    map) tells it by direction instead: P_fin was recorded on a face running
    against this one, turned by more than 135 degrees over as much of its
    recorded contour as reads a direction -- a turn far above any jitter.
    Then P_fin behind the face by any depth will do (on its free side it is
    a slit's far wall, which runs against the face too), and the probe's crossing is not
    asked: read off the face's line over ``hop``, whose direction a noisy
    sensor gives to several degrees, it lies anywhere for a probe along a
    needle (within a degree of its faces), and a probe that came through a
    mouth beside the tip touched the mouth's wall, turned from the face, not
    running against it. ``numerics`` seed 0 at sigma 0.3 eps, taxels 0.25 eps
    (``near`` 0.54 eps): the needle is 0.3 eps thick where the trace stops,
    and 0.886 - 0.889 of the reachable contour within eps/2 + 2 sigma was
    covered; with the map's reading 0.994 - 0.996 (``tests/test_core2d_needles.py``;
    keyed sensor seed 5000 only without the crossing: 0.888 with it, the
    crossing read 1.35 eps from the tip). A P_fin read on the free side is one
    reading; the far face's record near it, averaged over its local lines (the
    mean points ``against`` returns), tells the side to the jitter over the square
    root of its readings: every mean behind the face is a wall's far face, whatever
    side P_fin read on. ``numerics`` seed 2 at sigma 0.3 eps, taxels 0.25 eps, sensor
    seed 1002: P_fin, a jump's P_2nd on a needle 0.07 eps thick, read 0.20 eps in front
    of the face, the far face's record 0.087 eps behind it; the needle's last 5 eps
    on both faces were lost (0.976 covered).

    A trace that began less than ``hop`` before the stop (at a pass's contact near P_fin)
    holds no line of its own. ``through_stop`` (a noisy sensor, the map's faces given)
    reads it through the stop's contact ``now`` too -- the step that passed P_fin slid
    along the face, as the check on ``now`` asks of a longer trace -- and then answers by
    the map's faces alone, whatever P_fin's depth: a line read over so few readings says
    little about where the probe crossed it (where the face ends within the slide that
    follows, a convex corner, Case 1 stands where the controller stopped:
    :func:`~core2d.planner.tracing.trace_side`). ``numerics``
    seed 2 at sigma 0.3 eps, taxels 0.25 eps, sensor seed 2002: the trace from a pass's
    contact met P_fin (on a needle 0.07 eps thick) after three contacts, the first 0.36
    eps from the last; with ``now`` (0.96 eps from the farthest) P_fin read 0.25 eps and
    the far face's record 0.11 eps behind the line of the four; without it the needle's
    last 5 eps on both faces were lost (0.9715 covered; 1.000 with it).

    Parameters
    ----------
    pieces : list of (k, 2) float -- the trace so far, P_fin appended last.
    last : (2,) float -- the last tip contact before P_fin.
    now : (2,) float -- the tip's contact where the controller stopped.
    p_fin : (2,) float -- P_fin.
    pose_fin : Posture -- the probe posture that touched P_fin.
    sign : float -- +1 when the material lies right of the trace, -1 left.
    hop, near, gap : float -- the lengths of
        :class:`~core2d.resolution.Resolution`: the stretch the face's line is
        read over, the contact noise, how far from the tip a gap can open.
    against : callable (2,) float -> (k, 2) float, optional -- where P_fin was
        recorded on a face running against the one given, that face's record near it
        (the mean points of its local lines; none: not such a face; None: no map,
        depth only; :func:`~core2d.planner.thin_walls.far_face_means`).
    span : float, optional -- the stretch the face's line is read over
        (:attr:`~core2d.resolution.Resolution.face_span`, :func:`face_line`;
        None: ``hop``, the line through its two ends).
    through_stop : bool -- a trace shorter than ``hop`` is read through ``now`` and
        answered by ``against`` alone (above); False: such a trace is not across a wall.

    Examples
    --------
    >>> from core2d.planner.regions import Posture
    >>> face = [np.array([[x, 0.0] for x in np.arange(0.0, 2.01, 0.25)])]
    >>> under = Posture(np.array([50.0, -0.5]), np.array([-1.0, 0.0]))  # the far face's probe
    >>> last, now = np.array([2.0, 0.0]), np.array([2.2, 0.0])
    >>> across_wall(face, last, now, [2.1, -0.3], under, 1.0, 0.25, 0.02, 1.0)
    True
    >>> slit = Posture(np.array([2.1, 50.0]), np.array([0.0, -1.0]))  # down through a mouth
    >>> across_wall(face, last, now, [2.1, -0.3], slit, 1.0, 0.25, 0.02, 1.0)
    False
    >>> across_wall(face, last, [2.1, -0.5], [2.1, -0.3], under, 1.0, 0.25, 0.02, 1.0)
    False
    """
    pts = np.concatenate(pieces)[:-1]
    m = _reach_back(pts, len(pts) - 1, -1, hop)
    short = m is None
    if short:  # no line of its own: through the stop's contact, by the map's faces
        if not through_stop or against is None:
            return False
        pts = np.concatenate([pts, np.asarray(now, dtype=np.float64)[None]])
        last = pts[-1]
        m = _reach_back(pts, len(pts) - 1, -1, hop)
        if m is None:
            return False
    origin, u = face_line(pts, last, m, hop if span is None else span)
    if abs(_off_line(origin, u, now)) > near:
        return False  # the stopping step left the face: not a slide past P_fin
    behind = sign * _off_line(origin, u, p_fin)
    if short or behind >= -near:  # within the jitter of the face's line: by the map's faces
        far = np.zeros((0, 2)) if against is None else against(sign * u / np.hypot(*u))
        if not len(far):
            return False
        return behind < 0.0 or all(sign * _off_line(origin, u, m) < 0.0 for m in far)
    joint = sign * _off_line(origin, u, pose_fin.joint)
    if joint <= 0.0:
        return True  # the whole probe behind the face: it touched P_fin from the far side
    cross = np.asarray(p_fin, float) + (pose_fin.joint - p_fin) * (behind / (behind - joint))
    return bool(np.hypot(*(cross - last)) > gap)


def face_line(pts, last, m, span):
    """The line of the face slid along up to ``last`` (``pts[-1]``): a point on it and its
    direction (along the trace), for :func:`across_wall`.

    ``pts[m]`` is the first contact at least ``hop`` back (:func:`_reach_back`). With
    ``span`` no longer than that stretch, the line through ``pts[m]`` and ``last`` (the
    perfect sensor's reading: :attr:`~core2d.resolution.Resolution.face_span`). A longer
    ``span`` fits every contact within it (or the whole trace, if shorter) by least
    squares: readings ``hop`` apart scatter by the sensor's jitter, so their line tilts by
    up to atan(jitter / hop) -- 16 degrees on ``numerics`` seed 0, keyed sensor seed 3000
    at sigma 0.3 eps, taxels 0.25 eps, where P_fin on a needle 0.29 eps thick read 0.155
    eps in front of the face (a slit's far wall) and lay 0.14 eps behind the fit over
    twice the same-point radius.

    Parameters
    ----------
    pts : (k, 2) float -- the trace's contacts, ``last`` the final one.
    last : (2,) float
    m : int -- the index :func:`_reach_back` gave for ``hop``.
    span : float -- the stretch read.

    Returns
    -------
    origin : (2,) float
    direction : (2,) float -- not normalised.

    Examples
    --------
    >>> pts = np.array([[0.0, 0.0], [0.5, 0.1], [1.0, -0.1], [1.5, 0.1], [2.0, 0.0]])
    >>> face_line(pts, pts[-1], 3, 0.4)[1]  # two readings: tilted by their scatter
    array([ 0.5, -0.1])
    >>> o, d = face_line(pts, pts[-1], 3, 2.0)
    >>> bool(abs(d[1] / d[0]) < 0.05)
    True
    """
    if np.hypot(*(last - pts[m])) >= span:
        return last, last - pts[m]
    k = _reach_back(pts, len(pts) - 1, -1, span)
    stretch = pts[0 if k is None else k:]
    origin = stretch.mean(axis=0)
    direction = np.linalg.svd(stretch - origin)[2][0]
    return origin, direction if direction @ (last - stretch[0]) >= 0 else -direction


def _off_line(origin, direction, point) -> float:
    """Signed distance of ``point`` from the line through ``origin`` along
    ``direction`` (positive on its left)."""
    d = np.asarray(direction, float) / np.hypot(*direction)
    q = np.asarray(point, float) - origin
    return float(d[0] * q[1] - d[1] * q[0])


def _is_hop(pl, k, hop, sign, near) -> bool:
    """Is the step ``pl[k] -> pl[k + 1]`` (longer than ``hop``) a hop by its
    turns, or at a polyline's end by its side of the contour's line
    (:func:`split_hops`)?"""
    before, after = _reach_back(pl, k, -1, hop), _reach_back(pl, k + 1, 1, hop)
    if before is None and after is None:
        return False  # a lone step: no contour slid along on either side
    step = pl[k + 1] - pl[k]
    if before is None:  # concave: the free side is left of a line, material right
        return sign * _off_line(pl[k + 1], pl[after] - pl[k + 1], pl[k]) > near
    if after is None:
        return sign * _off_line(pl[k], pl[k] - pl[before], pl[k + 1]) > near
    return max(sign * _turn(pl[k] - pl[before], step),
               sign * _turn(step, pl[after] - pl[k + 1])) > HOP_TURN


def split_hops(polylines, poses, hop, sign, new, fin_is_A, parent, depth, near,
                appended=False, jump=np.inf):
    """W1 is contour the tip slid along. Cut the traced polylines (in trace
    order; ``sign`` +1 when the material lies on their right, -1 on their
    left) at a step longer than the trace's sampling step ``hop`` (eps / 4,
    :attr:`~core2d.resolution.Resolution.hop`, + the sensor's jitter) that turns concave by
    more than :data:`HOP_TURN` at either end, and register the stretch
    between its two contacts as an unknown area (rule ``"hop"``). The turns
    are read over at least ``hop`` of contour on either side
    (:func:`_reach_back`).

    Why (the slender wedges): the controller takes a contact that
    moves up to eps / 2 in one micro-step as continuous (the same-point
    radius), so the tip sliding on one wall of a slit narrower than that can
    hop over the slit's mouth onto the next contour; the wedge behind the
    hop, however deep, was recorded as traced and never probed nor
    approximated. The paper counts as traced only what the tip slid along
    (W1, §3.1); a discontinuous move of the contact point is Case 2 of
    §4.3.2, whose stretch (P_1st, P_2nd) is registered by the rule of
    §4.3.3. Its Dist(A, B) < eps makes it W2 at once (§3.1: approximated by
    the chord; no motion spent), a wider one goes through Fig. 16 like any
    other area. A long step that turns convex at both ends is the chord of
    a convex corner (the controller's ``_passes``), a straight one a fast
    slide along a wall: nothing can hide behind them, and they stay W1.
    A long step at an end of a polyline, where the contour slid along is
    readable on one side only, is read against that side's line: a hop when
    its other contact lies on the free side of the line by more than
    ``near`` (2 tol, the contact noise; :func:`_off_line`). That is the tip
    of a trace in a slit narrower than eps / 2 stepping from one wall onto
    the other (both within the same-point radius) with the slit's bottom
    behind the step: the walls are nearly parallel, so the turn is small,
    but the step's contact lies a slit's width off the wall's line. A fast
    slide along a wall lies on its line, a convex corner's chord on the
    material side. Such an area has Dist < eps / 2 and is W2 at once, so
    nothing is probed for it; the step onto the P_fin that Case 1 appends
    (``appended``) is left to :func:`hop_to`.
    The first step of a polyline, from D_i (the local search's contact) to
    the trace's first contact, longer than ``jump`` (the same-point radius
    eps/2 + jitter, :attr:`~core2d.resolution.Resolution.tip_zone`) is a
    hop whatever its turn: the controller reports any later step that long
    as a jump (Case 2), but the trace starts at whatever the probe touches
    when it starts, and a noisy D_i at the bottom of a slot 9 eps wide with
    the probe's body on the slot's corner made a W1 step 100 eps long down
    the slot (``deep_slot`` z1, sigma 0.3 eps, taxels 0.25 eps, sensor seed
    1001: precision 0.858); the step's far end lay on the material side of
    the top face's line, so the end test above took it for a corner's chord.
    The pieces keep the postures recorded at their polyline's ends (the
    trace keeps none in between); the new areas carry them too.
    """
    out, out_poses = [], []
    for j, (pl, (pose_first, pose_last)) in enumerate(zip(polylines, poses)):
        n = np.hypot(*np.diff(pl, axis=0).T)
        if appended and j == len(polylines) - 1 and len(n):
            n[-1] = 0.0  # Case 1's step onto P_fin: decided by hop_to
        start = 0
        for k in np.flatnonzero(n > hop).tolist():
            if not (k == 0 and n[0] > jump) and not _is_hop(pl, k, hop, sign, near):
                continue
            out.append(pl[start:k + 1])
            out_poses.append((pose_first, pose_last))
            new.append(register(pl[k], pose_first, pl[k + 1], pose_last, fin_is_A, parent,
                                "hop", depth))
            start = k + 1
        out.append(pl[start:])
        out_poses.append((pose_first, pose_last))
    return out, out_poses
