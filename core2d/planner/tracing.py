"""Tracing motion planning (§4.3) from the local concave point D_i.

Theorem 4 picks the joint direction v_i in K (Definition 6) from the final
state (Y1, Y2, Face) of the bisection, with tau = tau0 sgn(v_i, t*):

(A) (1, 0): K1 -- both sides, K1 cap K2 then K1 cap not-K2;
(B) (1, -1): K1 cap K2;  (C) (1, 1): K1 cap not-K2;
(D) (2, 0) with Face(left): K1 cap K2;  (E) (2, 0) with Face(right): K1 cap not-K2.

P_fin (Definition 8) is A_i for sgn(v_i, t*) > 0 and B_i otherwise. The
events of §4.3.2 end a trace: Case 1 (reached P_fin), Case 2-1 / 2-2 / 2-3
(contact point jump onto Int, onto Ext, or into F), Case 3 (v.t > 0) and
Case 4 (joint blocked). Non-traced parts are registered by the rule of §4.3.3.
"""
from __future__ import annotations

import numpy as np

from core2d.planner.areas import pivot_G, register
from core2d.planner.regions import Posture, T_contains, contains, in_V, near_probe, trace_direction
from core2d.planner.robot import Robot
from core2d.readings import LEFT, RIGHT, TIP

__all__ = ["plan_sides", "split_contact", "trace_side", "attach_pivot_G", "is_internal"]


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


def trace_side(probe: Robot, area, G, joint_i, local, toward_B, budget):
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
            pieces.append(np.asarray(p_fin)[None])
            break
        if r.event == "jump":
            p2 = r.contacts[0].point
            pose2 = Posture(r.joint, r.direction)
            if is_internal(p2, area, G, joint_i):
                cases.append("case2-1")
                kid = register(p1, pose1, p2, pose2, fin_is_A, area.index, "case2-1", depth)
                if r.contacts[0].face != TIP and _on_probe(p1, probe):
                    attach_pivot_G(kid, probe, r.contacts[0].face)  # Fig. 6
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
    keep = [k for k, p in enumerate(polylines) if len(p) >= 2]
    lines = [polylines[k] if toward_B else polylines[k][::-1] for k in keep]
    ends = [poses[k] if toward_B else poses[k][::-1] for k in keep]
    return lines, new, cases, ends
