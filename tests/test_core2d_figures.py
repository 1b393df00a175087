"""The paper's regions, signs and local search, figure by figure.

Kaneko & Tsuji, "Pulling Motion Based Tactile Sensing" (WAFR 2000): sign
conventions (eq. 1, Defs. 3, 4, 6, Theorem 4), the registration rule of
§4.3.3, G_i of Fig. 5 and Theorem 1, Theorem 3 against Fig. 9 (single
probe detection, Fig. 6, is in ``test_core2d_fig6.py``). The scenes are in
``figure_scenes.py``; geometry is checked against the ground-truth contour
with shapely and hand-worked coordinates, never with the planner's own view.
"""
from __future__ import annotations

import numpy as np
import pytest
from shapely.geometry import Point, Polygon, box

from core2d.planner.areas import Area, register
from core2d.planner.local_search import LocalResult, bisection, initial_pass
from core2d.planar import unit
from core2d.readings import LEFT, RIGHT, TIP, Contact, Reading
from core2d.planner.regions import (G_region, Posture, T_contains, common_point, contains, in_V, sgn,
                            trace_direction)
from core2d.planner.tracing import is_internal, plan_sides
from figure_scenes import (DOWN, FIG9, FIG9_A, FIG9_B, FIG9_DIR_B, FIG9_EXT, FIG9_H, V_CORNER,
                           V_POCKET, block, chain, dist_to_contour, make_probe, on_int, place,
                           pose_to, posture_touches, seg_param, vertical_area)

rng = np.random.default_rng(20000316)
EPS = 1.0
EPS_TOL = EPS / 20  # the probe's default contact resolution tol


# ------------------------------------------------------------ signs (§4.2-4.3)
@pytest.mark.parametrize("x, y, want", [((1, 0), (0, 1), 1), ((0, 1), (1, 0), -1),
                                        ((3, 4), (-8, 6), 1), ((2, 0), (5, 0), 0),
                                        ((0, -1), (-1, 1), -1)])
def test_sgn_is_the_sign_of_the_vector_product(x, y, want):
    assert sgn(x, y) == want  # eq. (1): x1 y2 - x2 y1, normalised


def test_V_is_the_right_hand_side_from_B_to_A():
    """Def. 3 / 'V_i: half plane on the right hand side when moving from B_i to A_i'."""
    a, b = np.array([30.0, 60.0]), np.array([70.0, 60.0])
    assert in_V([50.0, 90.0], a, b) and not in_V([50.0, 30.0], a, b)
    assert not in_V([100.0, 60.0], a, b)  # on the line: sgn = 0
    for _ in range(5):
        a, b = rng.uniform(-50, 50, 2), rng.uniform(-50, 50, 2)
        q = rng.uniform(-100, 100, (200, 2))
        d = a - b  # moving from B to A; its right-hand normal is (d_y, -d_x)
        right = (q - b) @ np.array([d[1], -d[0]]) > 0
        np.testing.assert_array_equal(in_V(q, a, b), right)


@pytest.mark.parametrize("q, want", [((50, 60), True), ((50, -500), True), ((35, 100), True),
                                     ((20, 60), False), ((50, 400), False), ((75, 55), False)])
def test_T_is_the_wedge_at_the_joint_through_A_and_B(q, want):
    """Def. 4: semi-infinite region sandwiched by P_iA_i and P_iB_i."""
    p, a, b = np.array([50.0, 380.0]), np.array([30.0, 60.0]), np.array([70.0, 60.0])
    assert T_contains(p, a, b, q) is want
    assert T_contains(p, b, a, q) is want


@pytest.mark.parametrize("theta", np.linspace(-np.pi, np.pi, 12, endpoint=False))
@pytest.mark.parametrize("toward_B", [True, False])
def test_theorem4_direction_in_K_and_torque_eq2(theta, toward_B):
    """Def. 6 / Theorem 4: v in K1 (v.t* < 0); toward B -> K1 cap K2
    (sgn(v, t*) < 0, so P_fin = B by Def. 8), toward A -> K1 cap not-K2;
    tau = tau0 sgn(v, t*), clockwise positive."""
    t = unit(theta)
    v, tau = trace_direction(t, toward_B)
    assert np.isclose(np.linalg.norm(v), 1.0)
    assert v @ t < 0  # K1: pulling, never pushing
    assert sgn(v, t) == (-1 if toward_B else 1)
    assert tau == sgn(v, t)


def test_theorem4_probe_pointing_down_hand_values():
    """Fig. 4: clockwise torque from D_0 to A_0 (left), ccw from D_0 to B_0."""
    v, tau = trace_direction(DOWN, toward_B=False)
    np.testing.assert_allclose(v, np.array([-1.0, 1.0]) / np.sqrt(2))
    assert tau == +1
    v, tau = trace_direction(DOWN, toward_B=True)
    np.testing.assert_allclose(v, np.array([1.0, 1.0]) / np.sqrt(2))
    assert tau == -1


def _local(Y1, Y2, *faces):
    contacts = [Contact(np.array([40.0, 30.0]), TIP, 320.0)]
    contacts += [Contact(np.array([40.0, 55.0]), f, 290.0) for f in faces]
    r = Reading(np.array([40.0, 350.0]), DOWN, tuple(contacts))
    return LocalResult(r, contacts[0].point, Y1, Y2, 1)


@pytest.mark.parametrize("Y1, Y2, faces, sides, q_face", [
    (1, 0, (), [True, False], None),   # (A) K1: both sides
    (1, -1, (), [True], None),          # (B) K1 cap K2 -> toward B
    (1, 1, (), [False], None),          # (C) K1 cap not-K2 -> toward A
    (2, 0, (LEFT,), [True], LEFT),      # (D) Face(left)
    (2, 0, (RIGHT,), [False], RIGHT),   # (E) Face(right)
])
def test_theorem4_cases_A_to_E(Y1, Y2, faces, sides, q_face):
    got, q = plan_sides(_local(Y1, Y2, *faces))
    assert got == sides
    assert (q is None) if q_face is None else (q.face == q_face)
    for toward_B in got:  # K2 <=> sgn(v, t*) < 0 <=> P_fin = B
        assert (sgn(trace_direction(DOWN, toward_B)[0], DOWN) < 0) == toward_B


# --------------------------------------------------- registration rule §4.3.3
@pytest.mark.parametrize("fin_is_A", [True, False])
def test_registration_rule(fin_is_A):
    p1, p2 = np.array([50.0, 55.0]), np.array([76.9, 54.9])
    pose1, pose2 = Posture(np.zeros(2), DOWN), Posture(np.ones(2), DOWN)
    kid = register(p1, pose1, p2, pose2, fin_is_A, 4, "case2-1", 2)
    if fin_is_A:  # (i): (A_j, B_j) = (P_2nd or P_fin, P_1st)
        np.testing.assert_array_equal(np.stack([kid.a, kid.b]), [p2, p1])
        assert kid.pose_a is pose2 and kid.pose_b is pose1
    else:  # (ii): (A_j, B_j) = (P_1st, P_2nd or P_fin)
        np.testing.assert_array_equal(np.stack([kid.a, kid.b]), [p1, p2])
        assert kid.pose_a is pose1 and kid.pose_b is pose2
    assert (kid.parent, kid.rule, kid.depth) == (4, "case2-1", 2)


@pytest.mark.parametrize("fin_is_A", [True, False])
def test_registration_rule_keeps_V_on_the_free_side(fin_is_A):
    """'This rule is for keeping the characteristics of V_i': after a jump
    over a hill (Fig. 12(b)) the new V_j holds the probe, not the valley."""
    hill, landing, valley = np.array([50.0, 55.0]), np.array([76.9, 54.9]), np.array([65.0, 35.0])
    if fin_is_A:  # tracing right to left: P_1st on the right
        hill, landing, valley = [np.array([100 - p[0], p[1]]) for p in (hill, landing, valley)]
    joint = np.array([60.0, 370.0])
    kid = register(hill, None, landing, None, fin_is_A, 0, "case2-1", 1)
    assert in_V(joint, kid.a, kid.b) and not in_V(valley, kid.a, kid.b)


def test_fig13_case2_1_or_2_2_test():
    """Fig. 13: P_2nd in G_i cup (T_i cap not-V_i) -> Int (Case 2-1), else Ext."""
    probe = make_probe(block(V_POCKET))
    area = vertical_area(probe, (20, 60), (80, 60))
    G = G_region(area.a, area.b, area.pose_a, area.pose_b)
    joint_i = np.array([50.0, 380.0])
    assert is_internal(np.array([50.0, 70.0]), area, G, joint_i)       # in G_i
    assert is_internal(np.array([60.0, 40.0]), area, G, joint_i)       # T_i cap not-V_i
    assert not is_internal(np.array([90.0, 70.0]), area, G, joint_i)   # V_i, outside G_i
    assert not is_internal(np.array([95.0, 40.0]), area, G, joint_i)   # outside T_i


# ------------------------------------------------------------ Fig. 5, Thm. 1
def _shoelace(pts):
    x, y = np.asarray(pts, float).T
    return 0.5 * abs(x @ np.roll(y, -1) - y @ np.roll(x, -1))


def _V(a, b, far=1e4):
    a, b = np.asarray(a, float), np.asarray(b, float)
    d = (b - a) / np.linalg.norm(b - a)
    n = np.array([-d[1], d[0]])  # left of A->B = right of B->A
    return Polygon([a - far * d, b + far * d, b + far * d + far * n, a - far * d + far * n])


# name: (top edge, A, B, direction of posture A, direction of posture B)
FIG5 = {
    "a": (V_POCKET, (30, 60), (70, 60), (0, -1), (0, -1)),
    "b": (V_CORNER, (30, 60), (70, 60), (0, -1), (-1, 0.25)),
    "c": (V_POCKET, (30, 60), (70, 60), (-3, -2), (3, -2)),
    "d": (V_POCKET, (20, 60), (80, 60), (-1, -3), (1, -3)),
}


def _fig5(name):
    top, a, b, da, db = FIG5[name]
    loops = block(top)
    probe = make_probe(loops)
    a, b = np.array(a, float), np.array(b, float)
    area = Area(a, b, pose_to(probe, a, da), pose_to(probe, b, db))
    assert posture_touches(probe, area.pose_a, a) and posture_touches(probe, area.pose_b, b)
    return loops, probe, area


def test_fig5a_convex_quadrangle():
    _, probe, area = _fig5("a")
    G = G_region(area.a, area.b, area.pose_a, area.pose_b)
    assert G.geom_type == "Polygon"
    assert np.isclose(G.area, 40 * probe.length)  # 40 wide, L tall
    assert np.isclose(G.convex_hull.area, G.area)
    assert np.isclose(G.intersection(_V(area.a, area.b)).area, G.area)  # G cap V = G
    assert common_point(area.a, area.b, area.pose_a, area.pose_b) is None


def test_fig5b_concave_quadrangle_cut_convex_by_V():
    _, probe, area = _fig5("b")
    G = G_region(area.a, area.b, area.pose_a, area.pose_b)
    ring = [area.pose_a.joint, area.a, area.b, area.pose_b.joint]
    assert G.geom_type == "Polygon" and np.isclose(G.area, _shoelace(ring))
    assert G.convex_hull.area > G.area + 1  # concave at B
    GV = G.intersection(_V(area.a, area.b))
    assert GV.area < G.area - 1  # G cap V != G (the joint of B is below L_AB)
    assert np.isclose(GV.convex_hull.area, GV.area)  # ... and G cap V is convex
    assert common_point(area.a, area.b, area.pose_a, area.pose_b) is None


@pytest.mark.parametrize("name", ["c", "d"])
def test_fig5cd_two_triangles_with_a_common_point(name):
    _, probe, area = _fig5(name)
    a, b, ja, jb = area.a, area.b, area.pose_a.joint, area.pose_b.joint
    x = common_point(a, b, area.pose_a, area.pose_b)
    want = {"c": (50.0, 60 + 20 * 2 / 3), "d": (50.0, 150.0)}[name]  # hand-worked
    np.testing.assert_allclose(x, want, atol=1e-9)
    G = G_region(a, b, area.pose_a, area.pose_b)
    assert G.geom_type == "MultiPolygon" and len(G.geoms) == 2
    assert np.isclose(G.area, _shoelace([x, a, b]) + _shoelace([x, ja, jb]))
    for tri in G.geoms:
        assert len(tri.exterior.coords) == 4
        assert min(Point(*c).distance(Point(*x)) for c in tri.exterior.coords) < 1e-9
    GV = G.intersection(_V(a, b))
    assert np.isclose(GV.area, G.area)  # G cap V = G, still two triangles
    inside = Point(*probe.center).buffer(probe.radius, 256)
    GVF = GV.intersection(inside)  # G cap V cap not-F
    # (c): concave (the known free circle crosses the joints' triangle);
    # (d): the circle crosses the A_iB_i triangle, G cap V cap not-F is convex
    convex = np.isclose(GVF.convex_hull.area, GVF.area)
    assert convex == (name == "d")


def _theorem1(name):
    loops, probe, area = _fig5(name)
    r, G, _ = initial_pass(probe, area)
    assert r is not None
    return loops, area, r


@pytest.mark.parametrize("name", ["a", "b", "c", "d"])
def test_theorem1_initial_pass_reaches_Int(name):
    """Theorem 1: the pass through L_A0B0 cap G cap V and a point of L_AiBi
    (the common point for the concave two-triangle G of Fig. 5(c)) ends on
    Int(A_iB_i)."""
    loops, area, r = _theorem1(name)
    c = r.tip_contact.point
    assert on_int(loops, area.a, area.b, c)
    if name == "c":  # the line passes the common point of both triangles
        x = common_point(area.a, area.b, area.pose_a, area.pose_b)
        w = x - r.joint
        assert abs(w[0] * r.direction[1] - w[1] * r.direction[0]) < 1e-6
        assert w @ r.direction > 0
    else:  # ... or crosses L_AiBi strictly inside, going from V to not-V
        s = seg_param(r.joint, r.direction, area.a, area.b)
        assert 0.0 < s < 1.0
        assert in_V(r.joint, area.a, area.b)


# ------------------------------------------------- Fig. 9: Theorem 3 vs 2
def _fig9(big_G):
    loops = block(FIG9)
    probe = make_probe(loops)
    area = Area(FIG9_A.copy(), FIG9_B.copy(), pose_to(probe, FIG9_A, DOWN),
                pose_to(probe, FIG9_B, FIG9_DIR_B))
    assert posture_touches(probe, area.pose_a, FIG9_A)
    assert posture_touches(probe, area.pose_b, FIG9_B)
    G = G_region(area.a, area.b, area.pose_a, area.pose_b)
    r = place(probe, FIG9_H, DOWN)  # 'the initial contact at the top of the hill'
    np.testing.assert_allclose(r.tip_contact.point, FIG9_H, atol=1e-6)
    local = bisection(probe, area, box(-1e4, -1e4, 1e4, 1e4) if big_G else G, r)
    return loops, area, G, r.joint.copy(), local


def test_fig9_scene_has_Ext_inside_T1_cap_V():
    loops, area, G, joint1, _ = _fig9(big_G=False)
    assert dist_to_contour(loops, FIG9_EXT) < 1e-9
    assert not on_int(loops, area.a, area.b, FIG9_EXT)  # Ext(A_iB_i)
    assert T_contains(joint1, area.a, area.b, FIG9_EXT) and in_V(FIG9_EXT, area.a, area.b)
    assert not contains(G, FIG9_EXT)
    assert chain(loops, area.a, area.b).distance(Point(*FIG9_H)) < 1e-9  # hill on Int


def test_fig9a_T_bound_alone_converges_on_Ext():
    """Theorem 2's premise fails here: within T cap V only, the bisection
    ends in the external local concave point (Fig. 9(a))."""
    loops, area, _, _, local = _fig9(big_G=True)
    assert np.linalg.norm(local.point - FIG9_EXT) < 0.1
    assert not on_int(loops, area.a, area.b, local.point)


def test_fig9b_theorem3_G_bound_converges_on_Int():
    """Theorem 3: keeping the tip inside T cap V cap G_i (Fig. 9(b)) makes it
    converge on Int(A_iB_i)."""
    loops, area, G, _, local = _fig9(big_G=False)
    assert local is not None
    assert on_int(loops, area.a, area.b, local.point)
    assert np.linalg.norm(local.point - FIG9_EXT) > 2
