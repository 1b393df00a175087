"""Tracing motion planning (§4.3) from the local concave point D_i.

Theorem 4 picks the joint direction v_i in K (Definition 6) from the final
state (Y1, Y2, Face) of the bisection, with tau = tau0 sgn(v_i, t*):

(A) (1, 0): K1 -- both sides, K1 cap K2 then K1 cap not-K2;
(B) (1, -1): K1 cap K2;  (C) (1, 1): K1 cap not-K2;
(D) (2, 0) with Face(left): K1 cap K2;  (E) (2, 0) with Face(right): K1 cap not-K2.

P_fin (Definition 8) is A_i for sgn(v_i, t*) > 0 and B_i otherwise. The
events of §4.3.2 end a trace: Case 1 (reached P_fin), Case 2-1 / 2-2 / 2-3
(contact point jump onto Int, onto Ext, or into F), Case 3 (v.t > 0) and
Case 4 (joint blocked). Non-traced parts are registered by the rule of §4.3.3,
and so is a hop of the tip over a gap the controller took as continuous
(:func:`_split_hops`: the mouth of a slender wedge is not traced contour).
"""
from __future__ import annotations

import numpy as np

from core2d.planner.areas import pivot_G, register
from core2d.planner.grazing import resolves_half_eps
from core2d.planner.regions import Posture, T_contains, contains, in_V, near_probe, trace_direction
from core2d.planner.robot import Robot
from core2d.readings import LEFT, RIGHT, TIP

__all__ = ["plan_sides", "split_contact", "trace_side", "attach_pivot_G", "is_internal",
           "reread_jump", "reread_pass"]

#: a W1 step longer than eps / 4 turning left (concave) by more than this hides contour
HOP_TURN = np.pi / 4


def plan_sides(local):
    """Theorem 4: which sides to trace from D_i.

    Returns ``(sides, other)``: the list of ``toward_B`` flags to execute and,
    for one-sided cases, the contact Q of Fig. 12(c) (or None).
    """
    Y1, Y2, r = local.Y1, local.Y2, local.reading
    if Y1 == 1:
        if Y2 == 0:
            return [True, False], None  # (A)
        return ([True] if Y2 == -1 else [False]), None  # (B) / (C)
    left, right = r.contact(LEFT), r.contact(RIGHT)
    if left is not None:
        return [True], left  # (D)
    if right is not None:
        return [False], right  # (E)
    return [True, False], None


def split_contact(q, area, G, joint_i):
    """Fig. 12(c): the contact Q of a one-sided start splits A_iB_i into
    (D_i, Q) and (Q, P_fin) only when Q lies on Int(A_iB_i) (Fig. 13's test,
    :func:`is_internal`). A Q on Ext (the probe's side resting on contour
    outside the area, e.g. a neighbouring island) says nothing about
    C_{A_i}^{B_i}: no split, returns None.

    q : Contact or None -- from :func:`plan_sides`.
    """
    if q is None or not is_internal(q.point, area, G, joint_i):
        return None
    return q


def reread_jump(probe: Robot, r):
    """P_2nd of a Case 2 jump (§4.3.2) and the posture that touched it:
    with a noisy contact sensor the means of
    :attr:`~core2d.resolution.Resolution.contact_reads` readings where the
    probe stopped (the jump's own and :meth:`Robot.sense`, no motion), else
    the one reading.

    Parameters
    ----------
    probe : Robot -- standing where the trace stopped on the jump.
    r : Reading -- the trace's reading, event ``"jump"``, P_2nd first in
        ``r.contacts``.

    Returns
    -------
    ((2,) float P_2nd, Posture)

    Notes
    -----
    Why: (P_1st, P_2nd) is the mouth of the gap the contact jumped over,
    and Case 2-1 registers it as an area: W2 at once when Dist < eps (§3.1,
    the chord standing for C_{P_1st}^{P_2nd}, the gap behind it). One
    reading of P_2nd scatters by sqrt(3) sigma per axis (contact, joint and
    direction noise; :func:`core2d.planner.bootstrap.undecided`); across a
    mouth narrower than eps that can put P_2nd on the near side of the gap,
    and the chord then stands for no gap at all (the ``comb`` outline of
    ``tests/outlines.py``, seed 0, sigma 0.1 eps: P_2nd at a slot 0.51 eps
    wide and 35 deep read 0.43 eps off, beside P_1st on the near corner;
    the slot's far wall was never recorded). The probe still stands on
    P_2nd, so reading it again is free, and the mean of 25 readings
    scatters a fifth as much. Only a tip contact is read again (the tactile
    skin of :meth:`Robot.sense` finds the tip's contact by its tip ray; a
    re-read whose tip contact lies farther than the same-contact radius from
    the first reading is left out); a body contact is kept as read.

    Only while :func:`~core2d.planner.grazing.resolves_half_eps` (two
    readings of one point within eps/2 - tol: sigma <= 0.106 eps without
    taxels). Beyond it, measured on the ``star`` outline, seed 0, sigma
    0.3 eps, taxels 0.25 eps, seeds 0-11: the re-read raised coverage on
    seeds 0-2 (0.861 -> 0.929 on average) but quadrupled the reported lids
    lying deeper than eps inside material (633 -> 2,486 eps, mostly the
    audit's areas between loose ends of the record and their children);
    why is not known, so it is off there."""
    c = r.contacts[0]
    k = probe.resolution.contact_reads
    if k <= 1 or c.face != TIP or not resolves_half_eps(probe.resolution):
        return c.point, Posture(r.joint, r.direction)
    same = probe.resolution.tip_zone
    pts, joints, dirs = [c.point], [r.joint], [r.direction]
    for _ in range(k - 1):
        x = probe.sense()
        tip = x.tip_contact
        if tip is not None and np.hypot(*(tip.point - c.point)) <= same:
            pts.append(tip.point)
            joints.append(x.joint)
            dirs.append(x.direction)
    d = np.sum(dirs, axis=0)
    return np.mean(pts, axis=0), Posture(np.mean(joints, axis=0), d / np.hypot(*d))


def reread_pass(probe: Robot, r):
    """The tip contact C of a pass (Theorem 1's pass, the §4.4 escape, a
    revisit pass) and the posture that touched it, read again where the
    probe stopped like P_2nd (:func:`reread_jump`: the means of
    :attr:`~core2d.resolution.Resolution.contact_reads` readings, only while
    the sensor resolves eps/2; else the one reading). Returns
    ``((2,) float C, Posture)``; ``r`` must hold a tip contact.

    Why: C becomes an end of the children A_iC and CB_i, and with a fine
    noisy sensor the next pass through such a lid, laid along a pocket's
    wall and crossed at a few degrees, meets the wall about
    offset / tan(alpha) from where it crossed, the offset being how far the
    lid's ends are read off the wall: a fifth of it (the mean of 25
    readings) keeps the §4.4 escape's halving going as with a perfect
    sensor. Measured with :func:`~core2d.planner.grazing.end_radius`, see it."""
    tip = r.tip_contact
    if r.contacts[0] is tip:
        return reread_jump(probe, r)
    return tip.point, Posture(r.joint, r.direction)


def _on_probe(point, probe: Robot) -> bool:
    """Single probe detection test (Def. 9): is ``point`` on the probe now?"""
    return near_probe(point, probe.joint, probe.direction, probe.length, probe.resolution.tip_zone)


def attach_pivot_G(area, probe: Robot, body_face):
    """Generate G_i of a single probe detection now, while the probe is there."""
    G = pivot_G(probe, body_face)
    area.G, area.zero_G = G, G is None


def is_internal(p2, area, G, joint_i):
    """Case 2-1 test (Fig. 13): P_2nd in G_i cup (T_i cap not-V_i)."""
    q = np.asarray(p2, float)
    if contains(G, q):
        return True
    return T_contains(joint_i, area.a, area.b, q) and not in_V(q, area.a, area.b)


def trace_side(probe: Robot, area, G, joint_i, local, toward_B, budget, flow=None):
    """Trace one side from D_i; returns (w1 polylines, new areas, cases, ends).

    The polylines are oriented like C_{A_i}^{B_i} (material on the right);
    ``ends`` holds, per polyline, the postures (Posture, Posture) that touched
    its first and its last point.

    Parameters
    ----------
    probe : Probe -- its tip is at D_i with direction t*.
    area : Area -- A_iB_i being processed.
    G : shapely geometry -- G_i.
    joint_i : (2,) float -- P_i, the joint of the initial pass (T_i).
    local : LocalResult -- final bisection state at D_i.
    toward_B : bool -- side to trace.
    budget : callable -> bool -- True while motions remain.
    flow : Flow, optional -- ``flow.pair`` False drops Case 2-1's
        (P_1st, P_2nd) (bench.ablation and tests only).
    """
    t_star = local.reading.direction
    v, tau = trace_direction(t_star, toward_B)
    fin_is_A = not toward_B  # Definition 8
    p_fin = area.a if fin_is_A else area.b
    pose_fin = area.pose_a if fin_is_A else area.pose_b
    p_other = area.b if fin_is_A else area.a
    polylines, new, cases, poses = [], [], [], []
    depth = area.depth + 1
    pieces = [local.point[None]]
    first = Posture(local.reading.joint, t_star)  # the posture at the polyline's first point
    while budget():
        r = probe.trace(v, tau, 4 * probe.radius, stop_at=p_fin, leave_at=p_other)
        if len(r.trace):
            pieces.append(r.trace)
        p1 = pieces[-1][-1]
        pose1 = Posture(r.before_joint, r.before_direction)
        if r.event == "reached":
            cases.append("case1")
            last = _before_fin(pieces)
            if last is not None and _hop_to(pieces, last, p_fin, probe.resolution.hop):
                pieces[-1] = pieces[-1][:-1]  # P_fin was passed, not slid over
                new.append(register(last, pose1, p_fin, pose_fin, fin_is_A, area.index,
                                    "hop", depth))
            else:
                pieces.append(np.asarray(p_fin)[None])
            break
        if r.event == "jump":
            p2, pose2 = reread_jump(probe, r)
            if is_internal(p2, area, G, joint_i):
                cases.append("case2-1")
                kid = register(p1, pose1, p2, pose2, fin_is_A, area.index, "case2-1", depth)
                if (r.contacts[0].face != TIP and _on_probe(p1, probe)
                        and (flow is None or flow.detection)):
                    attach_pivot_G(kid, probe, r.contacts[0].face)  # Fig. 6
                if flow is None or flow.pair:
                    new.append(kid)
                if r.contacts[0].face == TIP:
                    polylines.append(np.concatenate(pieces))
                    poses.append((first, pose1))
                    pieces, first = [p2[None]], pose2
                    continue  # tracing continues for the remaining area
                new.append(register(p2, pose2, p_fin, pose_fin, fin_is_A, area.index,
                                    "case2-1", depth))
                break
            cases.append("case2-2")
            new.append(register(p1, pose1, p_fin, pose_fin, fin_is_A, area.index,
                                "case2-2", depth))
            break
        if r.event == "left":
            # Traced out through the other end of A_iB_i: Definition 8 assumes
            # the K2 side leads to B_i, which a deep D_i can invert. The part
            # toward P_fin is still unknown.
            cases.append("left")
            new.append(register(local.point, Posture(local.reading.joint, t_star),
                                p_fin, pose_fin, fin_is_A, area.index, "left", depth))
            break
        if r.event == "reached-body":  # P_fin reached by the body, not the tip
            cases.append("case2-2")
            new.append(register(p1, pose1, p_fin, pose_fin, fin_is_A, area.index,
                                "case2-2", depth))
            break
        rule = {"lost": "case2-3", "pushing": "case3", "blocked": "case4"}.get(r.event, "limit")
        cases.append(rule)
        tip = r.tip_contact
        if rule in ("case3", "case4") and tip is not None:
            p1, pose1 = tip.point, Posture(r.joint, r.direction)  # P_1st replaced
        new.append(register(p1, pose1, p_fin, pose_fin, fin_is_A, area.index, rule, depth))
        break
    else:  # the motion budget ran out: what is left stays unknown, reported
        cases.append("limit")
        new.append(register(pieces[-1][-1], Posture(probe.joint.copy(), probe.direction),
                            p_fin, pose_fin, fin_is_A, area.index, "limit", depth))
    polylines.append(np.concatenate(pieces))
    poses.append((first, Posture(probe.joint.copy(), probe.direction)))
    # W1 runs like C_A^B, material on the right: from D_i towards B_i as
    # traced, towards A_i reversed (and so do the postures at its two ends)
    appended = cases[-1:] == ["case1"] and np.array_equal(polylines[-1][-1], p_fin)
    polylines, poses = _split_hops(polylines, poses, probe.resolution.hop,
                                   1.0 if toward_B else -1.0, new, fin_is_A, area.index, depth,
                                   probe.resolution.near, appended, probe.resolution.tip_zone)
    keep = [k for k, p in enumerate(polylines) if len(p) >= 2]
    lines = [polylines[k] if toward_B else polylines[k][::-1] for k in keep]
    ends = [poses[k] if toward_B else poses[k][::-1] for k in keep]
    return lines, new, cases, ends


def _before_fin(pieces):
    """The last tip contact before the P_fin that the controller appended
    on Case 1 (None when the trace holds no contact before it)."""
    pts = np.concatenate(pieces)
    return pts[-2] if len(pts) >= 2 else None


def _reach_back(pl, k, step, hop):
    """Index of the first point at least ``hop`` from ``pl[k]`` walking by
    ``step`` (-1 backward, +1 forward), or None: the direction of the
    contour slid along is read over that stretch, not over single
    micro-steps (whose contacts scatter by the contact resolution)."""
    side = pl[:k] if step < 0 else pl[k + 1:]
    far = np.flatnonzero(np.hypot(*(side - pl[k]).T) >= hop)
    if not len(far):
        return None
    return int(far[-1]) if step < 0 else k + 1 + int(far[0])


def _turn(u, w) -> float:
    """Signed angle (left positive) from direction ``u`` to ``w``."""
    return float(np.arctan2(u[0] * w[1] - u[1] * w[0], u @ w))


def _hop_to(pieces, last, p_fin, hop):
    """Case 1 at the paper's resolution: the controller reports P_fin
    reached when the tip's step passed within eps / 2 of it. When the last
    contact lies farther than ``hop`` from P_fin and the step to P_fin does
    not continue the contour slid along (it turns by more than
    :data:`HOP_TURN`), the tip passed P_fin across a gap (the mouth of a
    slit): the stretch is still unknown (:func:`_split_hops`)."""
    if np.linalg.norm(last - p_fin) <= hop:
        return False
    pts = np.concatenate(pieces)[:-1]
    m = _reach_back(pts, len(pts) - 1, -1, hop)
    if m is None:
        return False
    return abs(_turn(last - pts[m], np.asarray(p_fin) - last)) > HOP_TURN


def _off_line(origin, direction, point) -> float:
    """Signed distance of ``point`` from the line through ``origin`` along
    ``direction`` (positive on its left)."""
    d = np.asarray(direction, float) / np.hypot(*direction)
    q = np.asarray(point, float) - origin
    return float(d[0] * q[1] - d[1] * q[0])


def _is_hop(pl, k, hop, sign, near) -> bool:
    """Is the step ``pl[k] -> pl[k + 1]`` (longer than ``hop``) a hop by its
    turns, or at a polyline's end by its side of the contour's line
    (:func:`_split_hops`)?"""
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


def _split_hops(polylines, poses, hop, sign, new, fin_is_A, parent, depth, near,
                appended=False, jump=np.inf):
    """W1 is contour the tip slid along. Cut the traced polylines (in trace
    order; ``sign`` +1 when the material lies on their right, -1 on their
    left) at a step longer than the trace's sampling step ``hop`` (eps / 4,
    :attr:`~core2d.resolution.Resolution.hop`, + the sensor's jitter) that turns concave by
    more than :data:`HOP_TURN` at either end, and register the stretch
    between its two contacts as an unknown area (rule ``"hop"``). The turns
    are read over at least ``hop`` of contour on either side
    (:func:`_reach_back`).

    Why (issue 17, the slender wedges): the controller takes a contact that
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
    (``appended``) is left to :func:`_hop_to`.
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
            n[-1] = 0.0  # Case 1's step onto P_fin: decided by _hop_to
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
