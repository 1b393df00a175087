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
(:func:`core2d.planner.hops.split_hops`: the mouth of a slender wedge is not
traced contour; where the probe's end hangs in a slot narrower than eps / 2 that
it stepped over, the controller itself reports the jump:
:func:`core2d.sim.compliance.overhangs`). Case 1 is the tip reaching P_fin along
the contour: a P_fin the controller's radius (eps/2) reports across a wall thinner than that -- a
needle's far face -- is slid on past (:func:`core2d.planner.hops.across_wall`):
one trace without P_fin as long as the same-point radius on both sides (2 tip_zone:
eps with perfect sensing, so the tip ends outside the radius round P_fin), then the
controller watches for it again, so the contour round the wall's end is traced, or
registered by the rule of §4.3.3 where the trace ends there. A slide that ends within
that length by any event (the face ended: a convex corner, not a wall) is Case 1 where
the controller stopped. (A slide of eps left a noisy tip within the radius, 0.86 eps
from P_fin on ``numerics`` seed 0 at sigma 0.3 eps, taxels 0.25 eps, sensor seed 5000:
the controller reported the same P_fin again at once, a slide more for the same wall, and
where that second reading failed the needle was lost.) With a noisy sensor a trace that met
P_fin before it read ``hop`` of the face (from a pass's contact near P_fin) is read through
the controller's stopping contact and answered by the map's faces alone (``through_stop``).

The controller also stops when the probe's body comes within the contact noise of P_fin
before the tip's path passes it (``reached-body``, registered as Case 2-2 from P_1st to
P_fin). With a noisy sensor that is how a probe lying along a needle thinner than the
jitter meets a P_fin read on the needle's far face just ahead of the tip: the area (P_1st,
P_fin), shorter than eps + the jitter, is W2 at once and the needle's end is never touched
(``numerics`` seed 0 at sigma 0.3 eps, taxels 0.25 eps, sensor seed 1000: P_fin 0.51 eps
ahead, the needle's outer 16 eps lost, 0.889 covered). When that area would be W2 and
:func:`~core2d.planner.hops.across_wall` (P_1st as the last contact, the map's faces)
reads P_fin across a wall, the trace slides on past it as after Case 1 (0.997); a slide
that ends within its length is Case 2-2 where the controller stopped. A longer area is
explored as any other, so the rule asks nothing there (asked of every such stop, it cost
``comb`` seed 4 at sigma 0.1 eps, sensor seed 2004, 4,427 -> 5,362 motions for the same
coverage). Perfect sensing is left as it was: there the rule changed motions only
(``islands`` seed 3 +68, ``numerics`` seed 5 -11, coverage equal).
"""
from __future__ import annotations

from functools import partial

import numpy as np

from core2d.planner.areas import pivot_G, register
from core2d.planner.grazing import resolves_half_eps
from core2d.planner.hops import across_wall, hop_to, split_hops
from core2d.planner.regions import Posture, T_contains, contains, in_V, near_probe, trace_direction
from core2d.planner.robot import Robot
from core2d.planner.thin_walls import far_face_means
from core2d.readings import LEFT, RIGHT, TIP

__all__ = ["plan_sides", "split_contact", "trace_side", "attach_pivot_G", "is_internal",
           "reread_jump", "reread_pass"]

#: P_fin reached across a wall at most this many times in one trace (each costs a motion)
_MAX_WALLS = 4


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
    probe stopped (the jump's own and :meth:`Robot.reread`, no motion), else
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
    got = probe.reread(k - 1)
    with np.errstate(invalid="ignore"):  # a read without a tip contact: NaN, left out
        same = np.hypot(*(got.tip - c.point).T) <= probe.resolution.tip_zone
    pts = np.vstack((c.point, got.tip[same]))
    joints = np.vstack((r.joint, got.joint[same]))
    d = np.sum(np.vstack((r.direction, got.direction[same])), axis=0)
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


def trace_side(probe: Robot, area, G, joint_i, local, toward_B, budget, flow=None, known=None):
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
    res, sign, walls = probe.resolution, 1.0 if toward_B else -1.0, 0
    held = None  # (pieces, pose, event) where the controller reported P_fin across a wall
    against = None if known is None else partial(far_face_means, known, res, p_fin,
                                                  radius=res.tip_zone)
    while budget():
        r = probe.trace(v, tau, 2 * res.tip_zone if held else 4 * probe.radius,
                        stop_at=None if held else p_fin, leave_at=p_other)
        if len(r.trace):
            pieces.append(r.trace)
        p1 = pieces[-1][-1]
        pose1 = Posture(r.before_joint, r.before_direction)
        back, event = False, r.event  # back: the held stop (Case 1 or 2-2) stands, after all
        if held is not None:
            if r.event == "done":
                held = None
                continue  # the wall goes on: the controller watches for P_fin again
            (pieces, pose1, event), held, back = held, None, True  # it ended within the slide
            p1 = pieces[-1][-1]
        if event == "reached-body" and not back and walls < _MAX_WALLS and _body_across(
                res, pieces, p1, r.tip_contact, p_fin, pose_fin, sign, against):
            held = (list(pieces), pose1, event)  # the body over a needle's far face
            walls += 1
            continue
        if event == "reached" or (back and event != "reached-body"):
            last = _before_fin(pieces)
            now = r.tip_contact
            if not back and last is not None and now is not None and walls < _MAX_WALLS \
                    and across_wall(pieces, last, now.point, p_fin, pose_fin, sign, res.hop,
                                    res.near, 2 * res.tip_zone, against, res.face_span,
                                    res.jitter > 0):
                held = (list(pieces), pose1, event)
                pieces[-1] = pieces[-1][:-1]  # P_fin lies across a wall, not slid to
                walls += 1
                continue  # the contour goes on round the wall's end
            cases.append("case1")
            if last is not None and hop_to(pieces, last, p_fin, res.hop):
                pieces[-1] = pieces[-1][:-1]  # P_fin was passed, not slid over
                new.append(register(last, pose1, p_fin, pose_fin, fin_is_A, area.index,
                                    "hop", depth))
            else:
                pieces.append(np.asarray(p_fin)[None])
            break
        if event == "reached-body":  # P_fin reached by the body, not the tip
            cases.append("case2-2")
            new.append(register(p1, pose1, p_fin, pose_fin, fin_is_A, area.index,
                                "case2-2", depth))
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
    polylines, poses = split_hops(polylines, poses, probe.resolution.hop,
                                   1.0 if toward_B else -1.0, new, fin_is_A, area.index, depth,
                                   probe.resolution.near, appended, probe.resolution.tip_zone)
    keep = [k for k, p in enumerate(polylines) if len(p) >= 2]
    lines = [polylines[k] if toward_B else polylines[k][::-1] for k in keep]
    ends = [poses[k] if toward_B else poses[k][::-1] for k in keep]
    return lines, new, cases, ends


def _body_across(res, pieces, p1, now, p_fin, pose_fin, sign, against) -> bool:
    """Did the controller stop on the body reaching P_fin across a wall whose area (P_1st,
    P_fin) would be W2 at once (module doc)? With a noisy sensor only; P_1st = ``p1``, the
    last contact, the tip's ``now`` (a Contact or None), ``against`` the map's faces."""
    return (res.jitter > 0 and against is not None and now is not None
            and float(np.hypot(*(p1 - p_fin))) < res.w2_dist
            and across_wall(pieces + [np.asarray(p_fin)[None]], p1, now.point, p_fin, pose_fin,
                            sign, res.hop, res.near, 2 * res.tip_zone, against,
                            res.face_span))


def _before_fin(pieces):
    """The last tip contact before the P_fin that the controller appended
    on Case 1 (None when the trace holds no contact before it)."""
    pts = np.concatenate(pieces)
    return pts[-2] if len(pts) >= 2 else None
