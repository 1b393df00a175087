"""Constructed slices for the events of a trace (§4.3.2), Theorem 1's
common-point aim (Fig. 5(c)) and the Fig. 12(c) split, each built so that the decision under test
changes the outcome.

A trace is started from a chosen final state of the bisection (a probe
inserted along a chosen line: the reading at D_i), so every case is met on
purpose rather than by chance. Scenes are blocks about 100 units wide
(tests/figure_scenes.py), eps = 1.
"""
from __future__ import annotations

import numpy as np
import pytest

from core2d.planner.areas import Area
from core2d.planner.local_search import LocalResult, definition5, initial_pass
from core2d.planner.regions import G_region, Posture, common_point, trace_direction
from core2d.planner.tracing import plan_sides, split_contact, trace_side
from core2d.readings import LEFT, TIP, Contact, Reading
from figure_scenes import (DOWN, EPS, V_POCKET, block, make_probe, on_int, place, pose_to,
                           posture_touches, vertical_area)


def always():
    return True


def _started(top, at, direction, a, b, length=None, pose_b=None):
    """Probe inserted along ``direction`` through ``at``: its reading is the
    final state D_i of a bisection for the area (a, b)."""
    loops = block(top)
    probe = make_probe(loops, length=length)
    r = place(probe, at, np.asarray(direction, float) / np.linalg.norm(direction))
    area = vertical_area(probe, a, b)
    if pose_b is not None:
        area.pose_b = pose_to(probe, area.b, pose_b)
    local = LocalResult(r, r.tip_contact.point, *definition5(r), 0)
    G = G_region(area.a, area.b, area.pose_a, area.pose_b)
    return loops, probe, area, G, r.joint.copy(), local


def test_case2_3_the_probe_enters_F_without_contact():
    """Case 2-3: tracing along a flat top toward B_i on the side wall, the
    tip passes the convex edge and the probe swings into F without any
    contact: the trace stops and (P_1st, P_fin) is registered, P_1st at the
    edge where contact was lost (rule (ii), P_fin = B_i)."""
    top = [(0, 60), (100, 60)]
    loops, probe, area, G, joint_i, local = _started(
        top, (50, 60), (-1, -1), (10, 60), (100, 30), pose_b=(-1, 0))  # tip trails the joint
    lines, new, cases, _ = trace_side(probe, area, G, joint_i, local, True, always)
    assert cases == ["case2-3"] and len(new) == 1
    kid = new[0]
    assert kid.rule == "case2-3"
    assert np.linalg.norm(kid.a - [100.0, 60.0]) < EPS  # P_1st: the edge
    np.testing.assert_allclose(kid.b, area.b)  # P_fin = B_i
    assert lines and lines[0][-1][0] > 99 - EPS  # the top was traced up to the edge
    assert probe.stats.pushes == 0


def test_case3_the_guard_stops_a_pushing_step_and_counts_it():
    """Case 3: with a short probe (20) the tip climbs the step and the probe
    turns until the commanded v_i would push (v.t > 0): the guard stops the
    trace before that step, counts one push attempt, executes no push, and
    registers (P_1st, P_fin) with P_1st replaced by the point where v.t > 0
    was detected."""
    top = [(0, 30), (50, 30), (50, 70), (100, 70)]
    loops, probe, area, G, joint_i, local = _started(
        top, (45, 75), (-0.5, -np.sqrt(3) / 2), (5, 30), (95, 70), length=20)
    v, _ = trace_direction(local.reading.direction, True)
    lines, new, cases, _ = trace_side(probe, area, G, joint_i, local, True, always)
    assert "case3" in cases and probe.stats.push_attempts == 1 and probe.stats.pushes == 0
    kid = next(k for k in new if k.rule == "case3")
    np.testing.assert_allclose(kid.b, area.b)  # P_fin = B_i
    assert v @ probe.direction > 0  # stopped where the next step would push
    assert np.linalg.norm(kid.a - probe.tip) < 2 * probe.tol  # P_1st: that point


def test_case4_the_joint_loses_its_freedom_along_v():
    """Case 4: in a cave the probe, traced toward A_i, gets wedged (no free
    angle against the torque): the trace stops and (P_fin, P_1st) is
    registered by rule (i), P_1st replaced by the point where the freedom
    was lost."""
    top = [(0, 60), (40, 60), (40, 30), (70, 30), (70, 45), (55, 45), (55, 55), (100, 55)]
    loops, probe, area, G, joint_i, local = _started(
        top, (45, 75), (np.sin(np.radians(60)), -np.cos(np.radians(60))), (5, 60), (95, 55),
        length=20)
    lines, new, cases, _ = trace_side(probe, area, G, joint_i, local, False, always)
    assert cases == ["case4"] and len(new) == 1
    kid = new[0]
    np.testing.assert_allclose(kid.a, area.a)  # (A_j, B_j) = (P_fin, P_1st), P_fin = A_i
    assert np.linalg.norm(kid.b - probe.tip) < 2 * probe.tol
    assert probe.stats.pushes == 0


def test_left_a_trace_that_passes_the_other_end_registers_what_it_skipped():
    """The 'left' rule: Definition 8 assumes the K2 side leads to B_i. Here
    A_i and B_i are swapped (A_i on the right rim, B_i on the left), so the
    trace toward B_i climbs the right wall and passes A_i: the part toward
    P_fin = B_i is still unknown and is registered as (D_i, P_fin)."""
    loops, probe, area, G, joint_i, local = _started(
        V_POCKET, (40, 60), DOWN, (70, 60), (30, 60))
    lines, new, cases, _ = trace_side(probe, area, G, joint_i, local, True, always)
    assert cases == ["left"] and len(new) == 1
    kid = new[0]
    assert kid.rule == "left"
    np.testing.assert_allclose(kid.a, local.point)  # D_i
    np.testing.assert_allclose(kid.b, area.b)  # P_fin = B_i
    assert lines and np.linalg.norm(lines[0][-1] - area.a) < EPS / 2  # traced up to A_i


# Fig. 5(c), asymmetric: the postures cross at X off the chord's bisector, and
# a shelf of the same object reaches into the region beside X that lies
# outside G_i. Theorem 1's pass through X reaches Int; a pass aimed at the
# centre of L_{A_i}^{B_i} from the same start point leaves G_i and touches the
# shelf (Ext).
SHELF = [(0, 60), (0, 93), (60.0, 93), (60.0, 92), (8, 92), (8, 60), (30, 60), (40, 30),
         (70, 60), (100, 60)]


def _asymmetric_5c():
    loops = block(SHELF)
    probe = make_probe(loops)
    a, b = np.array([30.0, 60.0]), np.array([70.0, 60.0])
    area = Area(a, b, pose_to(probe, a, (-1.0, -1.0)), pose_to(probe, b, (0.3, -1.0)))
    assert posture_touches(probe, area.pose_a, a) and posture_touches(probe, area.pose_b, b)
    return loops, probe, area


def test_fig5c_asymmetric_pass_through_the_common_point_reaches_Int():
    loops, probe, area = _asymmetric_5c()
    x = common_point(area.a, area.b, area.pose_a, area.pose_b)
    assert x is not None and abs(x[0] - 50.0) > 5  # off the chord's bisector
    r, G, _ = initial_pass(probe, area)
    assert r is not None and on_int(loops, area.a, area.b, r.tip_contact.point)
    w = x - r.joint  # the pass goes through X
    assert abs(w[0] * r.direction[1] - w[1] * r.direction[0]) < 1e-6 and w @ r.direction > 0


def test_fig5c_asymmetric_chord_centre_aim_would_touch_Ext(monkeypatch):
    """The same pass aimed at the centre of L_{A_i}^{B_i}: it leaves G_i and
    the tip stops on the shelf -- what the common point of Theorem 1 avoids."""
    import core2d.planner.local_search as ls

    loops, probe, area = _asymmetric_5c()
    monkeypatch.setattr(ls, "common_point", lambda *a: None)
    r, _, _ = initial_pass(probe, area)
    assert r is not None and not on_int(loops, area.a, area.b, r.tip_contact.point)
    assert r.tip_contact.point[1] > 90  # on the shelf


@pytest.mark.parametrize("lip, splits", [
    ((40.0, 55.0), True),   # over the chord, inside G_i: Int
    ((40.0, 10.0), True),   # under the chord, inside T_i and out of V_i: Int
    ((5.0, 55.0), False),   # beside the area, out of G_i and T_i: Ext
    ((90.0, 20.0), False),  # past B_i, under the chord but out of T_i: Ext
])
def test_fig12c_splits_only_at_a_Q_on_Int(lip, splits):
    """Fig. 12(c) / Fig. 13: a one-sided start (Theorem 4 (D)) splits A_iB_i
    at the side contact Q only when Q is on Int(A_iB_i); a Q on Ext (contour
    outside the area, e.g. another island under the probe's side) must not
    become an end of an unknown area."""
    a, b = np.array([10.0, 30.0]), np.array([70.0, 30.0])
    area = Area(a, b, Posture(np.array([10.0, 350.0]), DOWN), Posture(np.array([70.0, 350.0]), DOWN))
    G = G_region(area.a, area.b, area.pose_a, area.pose_b)
    joint_i = np.array([40.0, 350.0])
    contacts = (Contact(np.array([40.0, 30.0]), TIP, 320.0), Contact(np.array(lip), LEFT, 290.0))
    local = LocalResult(Reading(joint_i, DOWN, contacts), contacts[0].point, 2, 0, 1)
    sides, q = plan_sides(local)
    assert sides == [True] and q.face == LEFT  # (D): Q proposed by Theorem 4
    got = split_contact(q, area, G, joint_i)
    assert (got is q) if splits else (got is None)
