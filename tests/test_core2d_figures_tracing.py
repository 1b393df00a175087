"""Tracing motion planning and the flowchart, figure by figure.

Kaneko & Tsuji (WAFR 2000): the outline of Fig. 4 (local concave point,
pulling traces to both sides), contact point jumps over a hill (Fig. 12(b),
Cases 2-1 / 2-2 with the registration rule of §4.3.3), the one-sided start
of Fig. 12(c), the infinite loop escape of Fig. 15 (§4.4), and one whole run
of the flowchart (Fig. 16); and the final states of the bisection that
select the tracing sides (Fig. 10, Definition 5, Theorem 4 (A)-(E)).
Scenes are in ``figure_scenes.py``.
"""
from __future__ import annotations

import numpy as np
import pytest
from shapely.geometry import LineString, Point
from shapely.ops import unary_union

from core2d import sense_slice
from core2d.planner.detection import reestablish
from core2d.planner.local_search import bisection, initial_pass
from core2d.planner.run import STALE
from core2d.readings import LEFT, RIGHT, TIP
from core2d.planner.regions import G_region, Posture, in_V, trace_direction
from core2d.planner.tracing import is_internal, plan_sides, trace_side
from figure_scenes import (DOWN, EPS, HILL, HILL_MIRROR, HILL_TOP, LIP_LEFT, LIP_RIGHT,
                           OVERHANG_LEFT, OVERHANG_RIGHT, SLOPE_LEFT, SLOPE_RIGHT, V_BOTTOM,
                           V_POCKET, WORKSPACE, block, chain, dist_to_contour, make_probe, new_run,
                           on_int, place, run_one, vertical_area)
from slicer.contact.exact import ExactContact

TOL = EPS / 20  # the probe's default contact resolution


def always():
    return True


def _uncovered(target, lines, width):
    """Length of ``target`` farther than ``width`` from every polyline."""
    cover = unary_union([LineString(p).buffer(width) for p in lines if len(p) >= 2])
    return target.difference(cover).length


def _on_contour(loops, lines):
    return max(dist_to_contour(loops, p) for line in lines for p in line)


# ---------------------------------------------------------------- Fig. 4
# A_0, B_0 on the walls of the V pocket (Fig. 4(b)) or at its rim corners.
FIG4_AREAS = {"walls": ((100 / 3, 50.0), (60.0, 50.0)), "rim": ((30.0, 60.0), (70.0, 60.0))}


def _fig4(which):
    loops = block(V_POCKET)
    probe = make_probe(loops)
    area = vertical_area(probe, *FIG4_AREAS[which])
    r, G, _ = initial_pass(probe, area)
    local = bisection(probe, area, G, r)
    return loops, probe, area, G, r.joint.copy(), local


@pytest.mark.parametrize("which", sorted(FIG4_AREAS))
def test_fig4a_bisection_reaches_the_local_concave_point(which):
    loops, probe, area, G, joint_i, local = _fig4(which)
    assert np.linalg.norm(local.point - V_BOTTOM) < 0.1
    assert (local.Y1, local.Y2) == (1, 0)
    assert local.iterations > 1  # the first contact was on the wall, not at D_0
    assert plan_sides(local) == ([True, False], None)  # Theorem 4 (A): both sides


@pytest.mark.parametrize("which", sorted(FIG4_AREAS))
@pytest.mark.parametrize("toward_B", [False, True])
def test_fig4b_pulling_traces_to_A_and_B(which, toward_B):
    """Fig. 4(b): from D_0 the probe is pulled outward, clockwise torque toward
    A_0 and counter-clockwise toward B_0; the smooth wall is traced to P_fin
    (Case 1) without any push."""
    loops, probe, area, G, joint_i, local = _fig4(which)
    t_star = local.reading.direction
    v, tau = trace_direction(t_star, toward_B)
    assert tau == (-1 if toward_B else +1)
    joint0 = probe.joint.copy()
    lines, new, cases, _ = trace_side(probe, area, G, joint_i, local, toward_B, always)
    assert cases == ["case1"] and new == []
    assert probe.stats.pushes == 0
    moved = probe.joint - joint0
    assert moved @ v > 0.99 * np.linalg.norm(moved)  # the joint went along v_i
    assert _on_contour(loops, lines) < 2 * TOL
    p_fin = area.b if toward_B else area.a
    wall = chain(loops, local.point, p_fin) if toward_B else chain(loops, p_fin, local.point)
    assert wall.length > 20
    assert _uncovered(wall, lines, EPS / 2) < 1e-6


def test_fig4_both_sides_cover_the_pocket():
    """Both traces of case (A), the second from D_0 re-established."""
    loops, probe, area, G, joint_i, local = _fig4("walls")
    lines = []
    for k, toward_B in enumerate(plan_sides(local)[0]):
        if k:
            assert reestablish(probe, Posture(local.reading.joint,
                                              local.reading.direction)).tip_contact
        more, new, cases, _ = trace_side(probe, area, G, joint_i, local, toward_B, always)
        assert cases == ["case1"]
        lines += more
    target = chain(loops, area.a, area.b)
    assert _uncovered(target, lines, EPS / 2) < 1e-6


def test_fig4_sliding_along_a_straight_edge_is_not_a_jump():
    loops = block(V_POCKET)
    probe = make_probe(loops)
    area = vertical_area(probe, (20, 60), (80, 60))
    r, G, _ = initial_pass(probe, area)
    local = bisection(probe, area, G, r)
    _, new, cases, _ = trace_side(probe, area, G, r.joint.copy(), local, True, always)
    jumps = [kid for kid in new if kid.rule == "case2-1"]  # (P_1st, P_2nd), rule (ii)
    for kid in jumps:  # a jump skips contour: the contour is not the chord
        skipped = chain(loops, kid.a, kid.b)
        assert skipped.length > np.linalg.norm(kid.b - kid.a) + TOL


# ------------------------------------------- Fig. 10: final states (Y1, Y2)
def _final(top, a, b):
    loops = block(top)
    probe = make_probe(loops)
    area = vertical_area(probe, a, b)
    r, G, _ = initial_pass(probe, area)
    assert on_int(loops, area.a, area.b, r.tip_contact.point)
    local = bisection(probe, area, G, r)
    assert local is not None and dist_to_contour(loops, local.point) < 1e-6
    return loops, area, local, (probe, G, r.joint.copy())


def test_fig10a_local_concave_point():
    loops, area, local, _ = _final(V_POCKET, (30, 60), (70, 60))
    assert (local.Y1, local.Y2) == (1, 0)
    assert np.linalg.norm(local.point - V_BOTTOM) < 0.1
    r = local.reading
    assert r.blocked_cw and r.blocked_ccw  # 'loses any rotational degree of freedom'
    assert {c.face for c in r.contacts} == {TIP}
    assert plan_sides(local) == ([True, False], None)  # Theorem 4 (A)


@pytest.mark.parametrize("top, a, b, Y2, sides", [
    (SLOPE_RIGHT, (30, 65), (70, 45), 1, [False]),   # cw held by the slope -> (C)
    (SLOPE_LEFT, (30, 45), (70, 65), -1, [True]),    # ccw held by the slope -> (B)
])
def test_fig10b_stop_at_the_T_boundary(top, a, b, Y2, sides):
    """Fig. 10(b): no local concave point inside the area; the tip slides down
    to where the surface meets the boundary of T^(n) -- here the end the slope
    falls to -- with a single constraint: Y2 = 1 (cw) or -1 (ccw)."""
    loops, area, local, (probe, G, joint_i) = _final(top, a, b)
    low = area.b if Y2 == 1 else area.a
    assert (local.Y1, local.Y2) == (1, Y2)
    assert np.linalg.norm(local.point - low) < EPS / 2
    r = local.reading
    assert (r.blocked_cw, r.blocked_ccw) == (Y2 == 1, Y2 == -1)
    assert plan_sides(local) == (sides, None)
    # Theorem 4 (B)/(C): one pulling trace up the slope, to the other end
    lines, new, cases, _ = trace_side(probe, area, G, joint_i, local, sides[0], always)
    assert cases == ["case1"] and probe.stats.pushes == 0
    assert _uncovered(chain(loops, area.a, area.b), lines, EPS / 2) < EPS / 2


@pytest.mark.parametrize("top, lip, face, sides", [
    (OVERHANG_LEFT, LIP_LEFT, LEFT, [True]),     # (D)
    (OVERHANG_RIGHT, LIP_RIGHT, RIGHT, [False]),  # (E)
])
def test_fig10c_multiple_contacts(top, lip, face, sides):
    """Fig. 10(c): the floor falls toward an overhang lip; the tip ends on
    the floor with the probe side on the lip: (Y1, Y2) = (2, 0)."""
    loops, area, local, _ = _final(top, (20, 60), (80, 60))
    assert (local.Y1, local.Y2) == (2, 0)
    r = local.reading
    other = r.contact(face)
    assert other is not None and np.linalg.norm(other.point - lip) < 0.2
    assert r.blocked_cw if face == LEFT else r.blocked_ccw  # Face(left) blocks cw
    assert local.point[1] < 30 and on_int(loops, area.a, area.b, local.point)
    got, q = plan_sides(local)
    assert got == sides and q.face == face


# ------------------------------------------------------------- Fig. 12(b)
def _hill(top, a, b, start, toward_B):
    loops = block(top)
    probe = make_probe(loops)
    area = vertical_area(probe, a, b)
    G = G_region(area.a, area.b, area.pose_a, area.pose_b)
    r = place(probe, start, DOWN)  # an initial contact in the first pocket
    local = bisection(probe, area, G, r)
    assert (local.Y1, local.Y2) == (1, 0) and local.point[1] < 36
    joint_i = r.joint.copy()
    lines, new, cases, _ = trace_side(probe, area, G, joint_i, local, toward_B, always)
    return loops, area, G, joint_i, lines, new, cases


@pytest.mark.parametrize("mirror", [False, True])
def test_fig12b_jump_over_a_hill_onto_Int_case2_1(mirror):
    """The tip leaves the surface at the hill top (P_1st) and lands on the far
    wall of the next pocket (P_2nd on Int): Case 2-1 registers (P_1st, P_2nd)
    by rule (ii) toward B, (P_2nd, P_1st) by rule (i) toward A, and the
    tracing continues from P_2nd."""
    top = HILL_MIRROR if mirror else HILL
    start = (60, 60) if mirror else (40, 60)
    loops, area, G, joint_i, lines, new, cases = _hill(top, (10, 60), (90, 60), start,
                                                       toward_B=not mirror)
    assert cases[0] == "case2-1"
    kid = new[0]
    p1st, p2nd = (kid.b, kid.a) if mirror else (kid.a, kid.b)
    assert np.linalg.norm(p1st - HILL_TOP) < 0.3
    far_wall = LineString([(35, 35), (20, 60)] if mirror else [(65, 35), (80, 60)])
    assert far_wall.distance(Point(*p2nd)) < 1e-6 and abs(p2nd[1] - HILL_TOP[1]) < 1
    assert on_int(loops, area.a, area.b, p2nd) and is_internal(p2nd, area, G, joint_i)
    valley = np.array([35.0, 35.0] if mirror else [65.0, 35.0])
    assert chain(loops, kid.a, kid.b).distance(Point(*valley)) < 1e-9  # what was skipped
    assert in_V(joint_i, kid.a, kid.b) and not in_V(valley, kid.a, kid.b)
    # continued from P_2nd; W1 runs with the material on the right, so a
    # trace toward A_i is stored reversed and P_2nd is its last point
    start_of_second = lines[1][-1] if mirror else lines[1][0]
    assert len(lines) >= 2 and np.linalg.norm(start_of_second - p2nd) < 1e-9
    assert _on_contour(loops, lines) < 2 * TOL


def test_fig12b_jump_onto_Ext_case2_2():
    """B_i on the far flank of the hill: P_2nd lands beyond B_i (Ext), the
    trace stops and (P_1st, P_fin = B_i) is registered."""
    b = np.array([57.5, 45.0])  # on the hill's right flank
    loops, area, G, joint_i, lines, new, cases = _hill(HILL, (10, 60), b, (40, 60), True)
    assert cases == ["case2-2"] and len(new) == 1
    kid = new[0]
    assert kid.rule == "case2-2"
    assert np.linalg.norm(kid.a - HILL_TOP) < 0.3
    np.testing.assert_allclose(kid.b, b)
    assert len(lines) == 1  # no tracing after Case 2-2


# ------------------------------------------------------------- Fig. 12(c)
@pytest.mark.parametrize("top, lip, face", [(OVERHANG_LEFT, LIP_LEFT, LEFT),
                                            (OVERHANG_RIGHT, LIP_RIGHT, RIGHT)])
def test_fig12c_one_sided_start_registers_D_Q_and_Q_A(top, lip, face):
    """(Y1, Y2) = (2, 0) with Face(left): Theorem 4 (D) traces toward B only;
    'we register (D_i, Q) and (Q, A_i)' by rule (i); mirrored for Face(right)
    ((E): (D_i, Q), (Q, B_i) by rule (ii))."""
    loops = block(top)
    probe = make_probe(loops)
    area = vertical_area(probe, (20, 60), (80, 60))
    run = run_one(probe, area)
    assert run.result.areas[0].outcome == "split"
    kids = [a for a in run.queue if a.rule == "fig12c"]
    assert len(kids) == 2
    if face == LEFT:  # contour order A -> Q -> D
        (q1, d), (a, q2) = [(k.a, k.b) for k in kids]
        np.testing.assert_allclose(a, area.a)
    else:  # contour order D -> Q -> B
        (d, q1), (q2, b) = [(k.a, k.b) for k in kids]
        np.testing.assert_allclose(b, area.b)
    np.testing.assert_allclose(q1, q2)
    assert np.linalg.norm(q1 - lip) < 0.2
    assert d[1] < 30 and dist_to_contour(loops, d) < 1e-6  # D_i: the tip on the floor
    for k in kids:  # sub-areas of A_iB_i, each oriented like it (V_j on the free side)
        c = chain(loops, area.a, area.b)
        assert c.distance(Point(*k.a)) < 1e-6 and c.distance(Point(*k.b)) < 1e-6
        assert chain(loops, k.a, k.b).length < c.length
    dq = kids[0]  # (D_i, Q) is a single probe detection: G_j made at once (Def. 1)
    assert dq.G is not None or dq.zero_G
    # traced from D_i; W1 runs with the material on the right, so the trace
    # toward A_i (Face(right), case (E)) is stored reversed and ends at D_i
    start = run.result.w1[0][0] if face == LEFT else run.result.w1[0][-1]
    assert run.result.w1 and np.linalg.norm(start - d) < 1e-6
    assert probe.stats.pushes == 0


# ---------------------------------------------------------------- Fig. 15
def test_fig15_escape_splits_the_area_at_the_new_contact():
    """§4.4: the probe searches a new contact 'by the same way taken in the
    initial pass planning' and A_iB_i is separated into two new areas."""
    loops = block(V_POCKET)
    probe = make_probe(loops)
    area = vertical_area(probe, (30, 60), (70, 60), escape=True)
    run = run_one(probe, area)
    assert run.counters.escapes == 1
    assert run.result.areas[0].outcome == "split"
    kids = list(run.queue)
    assert [k.rule for k in kids] == ["escape", "escape"]
    (a1, c1), (c2, b2) = [(k.a, k.b) for k in kids]
    np.testing.assert_allclose([a1, b2], [area.a, area.b])
    np.testing.assert_allclose(c1, c2)
    assert on_int(loops, area.a, area.b, c1)  # Theorem 1: a new contact on Int
    assert all(k.parent == 0 and k.depth == 1 and not k.escape for k in kids)


def test_fig15_same_area_again_requests_the_escape():
    """'called upon request when the same contact point is detected
    repeatedly': registering A_iB_i again flags it for the escape."""
    probe = make_probe(block(V_POCKET))
    run = new_run(probe)
    parent = vertical_area(probe, (30, 60), (70, 60))
    run.add(parent)
    run.queue.popleft()
    same = vertical_area(probe, (30, 60 + TOL / 2), (70, 60))
    other = vertical_area(probe, (30, 60), (60, 50))
    run.children(parent, [same, other])
    assert same.escape and not other.escape
    run.queue.popleft()
    run.process(same)
    assert run.counters.escapes == 1
    assert [r.rule for r in run.result.areas[-2:]] == ["escape", "escape"]


def test_fig15_a_loop_over_several_generations_requests_the_escape():
    """§4.4 over the whole ancestry: a creeping loop -- a grandchild that
    registers its grandparent's A and B again, whatever came in between --
    is a loop the direct-parent test cannot see."""
    probe = make_probe(block(V_POCKET))
    run = new_run(probe)
    root = vertical_area(probe, (30, 60), (70, 60))
    run.add(root)
    run.queue.popleft()
    mid = vertical_area(probe, (30, 60), (60, 50))  # a new area: no escape
    run.children(root, [mid], traced=5 * EPS)
    run.queue.popleft()
    assert not mid.escape
    again = vertical_area(probe, (30, 60 + TOL / 2), (70, 60))  # the root again
    fresh = vertical_area(probe, (35, 55), (60, 50))
    run.children(mid, [again, fresh], traced=5 * EPS)
    assert again.escape and not fresh.escape


def test_fig15_generations_that_trace_nothing_request_the_escape():
    """§4.4: 'the tip can find the same point repeatedly' -- STALE generations
    in a row that trace less than eps of new contour request the escape,
    even with A and B creeping (no pair repeats)."""
    probe = make_probe(block(V_POCKET))
    run = new_run(probe)
    area = vertical_area(probe, (30, 60), (70, 60))
    run.add(area)
    run.queue.popleft()
    for k in range(STALE):
        assert not area.escape
        kid = vertical_area(probe, (31 + k, 60), (69 - k, 60))  # creeping, never the same
        run.children(area, [kid], traced=0.5 * EPS)
        run.queue.popleft()
        area = kid
    assert area.escape and area.stale == STALE
    fresh = vertical_area(probe, (40, 60), (60, 60))
    run.children(area, [fresh], traced=2 * EPS)  # new contour traced: counting restarts
    assert fresh.stale == 0 and not fresh.escape


def test_fig15_endless_escapes_still_bring_the_shape_in_relief():
    """Fig. 15(a): if an infinite mode appeared after every initial pass, the
    areas would be split again and again until Dist(A_j, B_j) < eps gives W2:
    the W2 segments then approximate C_A^B."""
    loops = block(V_POCKET)
    probe = make_probe(loops)
    run = new_run(probe)
    run.add(vertical_area(probe, (30, 60), (70, 60)))
    for _ in range(1000):
        if not run.queue:
            break
        area = run.queue.popleft()
        area.escape = True
        run.process(area)
    assert not run.queue
    leaves = [r for r in run.result.areas if r.outcome != "split"]
    assert leaves and all(r.outcome == "W2" and r.note.startswith("Dist") for r in leaves)
    assert run.counters.escapes == len(run.result.areas) - len(leaves)
    segs = run.result.w2
    assert all(np.linalg.norm(s[1] - s[0]) < EPS for s in segs)
    assert _on_contour(loops, segs) < 1e-9
    target = chain(loops, (30, 60), (70, 60))
    relief = unary_union([LineString(s) for s in segs])
    assert target.hausdorff_distance(relief) < EPS / 2


# --------------------------------------------------- Fig. 16, a whole slice
def test_fig16_whole_slice_of_the_fig4_block():
    """The flowchart from the bootstrap on: every area ends (W1/W2/W3 or
    split), no push, and W1 cup W2 covers the pocket and the top."""
    loops = block(V_POCKET)
    res = sense_slice(ExactContact(loops), WORKSPACE, EPS)
    assert not res.stats.budget_hit and not res.unknown
    assert res.stats.pushes == 0
    assert all(r.outcome in ("traced", "split", "W2", "W3") for r in res.areas)
    assert {r.rule for r in res.areas} >= {"bootstrap"}
    assert _on_contour(loops, res.w1) < 2 * TOL
    target = chain(loops, (5, 60), (95, 60))  # top edge with the pocket
    assert _uncovered(target, list(res.w1) + list(res.w2), EPS / 2) < EPS
