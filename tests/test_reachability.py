"""Exact reachability (core2d.truth.reachability) against closed forms and brute force."""
from __future__ import annotations

import numpy as np
import pytest
import shapely
from shapely.geometry import box
from shapely.geometry.polygon import orient
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from core2d.truth.reachability import (contour_edges, free_angle, loop_is_hole, reachable,
                                 reachable_samples, sample_contour)

try:
    from polygen import (keyhole, loops_from_shapely, polygons_with_holes, polygons_with_islands,
                         simple_polygons, slotted_box)
except ImportError:  # tests/ imported as a package
    from tests.polygen import (keyhole, loops_from_shapely, polygons_with_holes,
                               polygons_with_islands, simple_polygons, slotted_box)

SETTINGS = dict(deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])


def rotate(loops, angle, centre=(0.3, -0.2)):
    c, s = np.cos(angle), np.sin(angle)
    rot = np.array([[c, -s], [s, c]])
    return [(lp - centre) @ rot.T + centre for lp in loops], lambda p: (p - centre) @ rot.T + centre


def brute_free(loops, points, edge_ids, k=20_000):
    """Independent reference: cast ``k`` rays per point with shapely.

    Returns the longest circular run of free directions (rad) and the
    direction step. A ray starts 1e-7 off the point (so it does not touch
    the point's own edge) and ends far outside; touching an edge blocks it.
    """
    a, b, _ = contour_edges(loops)
    tree = shapely.STRtree(shapely.linestrings(np.stack([a, b], axis=1)))
    lo, hi = a.min(axis=0), a.max(axis=0)
    th = 2 * np.pi * (np.arange(k) + 0.5) / k
    d = np.c_[np.cos(th), np.sin(th)]
    runs = np.zeros(len(points))
    for i, p in enumerate(points):
        far = np.hypot(*np.maximum(np.abs(lo - p), np.abs(hi - p))) + 1.0  # leaves the bounding box
        rays = shapely.linestrings(np.stack([p + 1e-7 * d, p + far * d], axis=1))
        hit = np.zeros(k, dtype=bool)
        hit[tree.query(rays, predicate="intersects")[0]] = True
        if not hit.any():
            runs[i] = k
            continue
        free = np.roll(~hit, -int(np.argmax(hit)))  # starts blocked: no run crosses the end
        edges = np.diff(np.r_[0, free.astype(np.int8), 0])
        lengths = np.flatnonzero(edges == -1) - np.flatnonzero(edges == 1)
        runs[i] = lengths.max() if len(lengths) else 0
    return runs * (2 * np.pi / k), 2 * np.pi / k


# --- closed forms --------------------------------------------------------------------------

CONVEX = {
    "triangle": [[0, 0], [10, 0], [3, 7]],
    "square": [[-5, -5], [5, -5], [5, 5], [-5, 5]],
    "heptagon": [[40 * np.cos(t), 40 * np.sin(t)] for t in np.linspace(0, 2 * np.pi, 7, endpoint=False)],
    "circle64": [[50 * np.cos(t), 30 * np.sin(t)] for t in np.linspace(0, 2 * np.pi, 64, endpoint=False)],
    "hull": np.random.default_rng(1).normal(size=(40, 2)) * 20,
}


@pytest.mark.parametrize("name", sorted(CONVEX))
@pytest.mark.parametrize("angle", [0.0, 2.0, np.pi])
def test_convex_everything_reachable_with_half_plane_free(name, angle):
    pts = np.asarray(CONVEX[name], dtype=float)
    hull = orient(shapely.convex_hull(shapely.multipoints(pts)))  # CCW, no collinear points
    loops, _ = rotate([np.asarray(hull.exterior.coords)[:-1]], angle)
    s, ok = reachable_samples(loops, 0.7)
    assert ok.all()
    # from a convex contour the whole outward half-plane is free
    np.testing.assert_allclose(free_angle(loops, s.points, s.edge), np.pi, atol=1e-9)


@pytest.mark.parametrize("neck", [1.5, 3.0, 5.0])
@pytest.mark.parametrize("angle", [0.0, 0.7, np.pi / 2, np.pi, -2.2, np.pi - 1e-3])
def test_keyhole_exact(neck, angle):
    base = keyhole(neck)
    s = sample_contour(base, 0.25)
    x, y = s.points.T
    loops, rot = rotate(base, angle)
    ok = reachable(loops, rot(s.points), s.edge)
    fa = free_angle(loops, rot(s.points), s.edge)
    ceiling = np.isclose(y, 20) & (np.abs(x) > neck)
    side = np.isclose(np.abs(x), 30) & (np.abs(y) < 20)
    neck_wall = np.isclose(np.abs(x), neck) & (y > 20)
    floor = np.isclose(y, -20)
    outside = (np.abs(x) > 49.9) | (np.abs(y) > 49.9)
    assert not ok[ceiling | side].any() and (fa[ceiling | side] == 0).all()
    assert ok[neck_wall | outside].all()
    x_max = 11 * neck / 3
    clear = np.abs(np.abs(x) - x_max) > 1e-5
    np.testing.assert_array_equal(ok[floor & clear], np.abs(x[floor & clear]) < x_max)
    # the free angle of a floor point is the cone through both neck openings
    p = s.points[floor]
    ang = lambda cx, cy: np.arctan2(cy - p[:, 1], cx - p[:, 0])  # noqa: E731
    cone = np.minimum(ang(-neck, 20), ang(-neck, 50)) - np.maximum(ang(neck, 20), ang(neck, 50))
    np.testing.assert_allclose(fa[floor], np.maximum(cone, 0), atol=1e-9)


@pytest.mark.parametrize("lip", [0.05, 0.5])
def test_thin_lip_next_to_the_hull(lip):
    """A chamber just under the top: its ceiling is within ``lip`` of the hull, yet unreachable."""
    cut = box(-3, 50 - lip, 3, 50).union(box(-30, 0, 30, 50 - lip))
    loops = loops_from_shapely(box(-50, -50, 50, 50).difference(cut))
    s, ok = reachable_samples(loops, 0.25)
    x, y = s.points.T
    ceiling = np.isclose(y, 50 - lip) & (np.abs(x) > 3)
    assert ceiling.sum() > 100 and not ok[ceiling].any()
    np.testing.assert_array_equal(ok, free_angle(loops, s.points, s.edge) > 1e-9)


@pytest.mark.parametrize("width,depth", [(4.0, 10.0), (1.0, 90.0), (0.2, 60.0)])
def test_straight_slot_walls_reachable_with_exact_angle(width, depth):
    loops = slotted_box(width, depth)
    s, ok = reachable_samples(loops, 0.5)
    assert ok.all()
    x, y = s.points.T
    wall = np.isclose(np.abs(x), width / 2) & (y > 50 - depth)
    bottom = np.isclose(y, 50 - depth) & (np.abs(x) < width / 2)
    fa = free_angle(loops, s.points, s.edge)
    # a wall point sees out between the wall and the opposite lip
    np.testing.assert_allclose(fa[wall], np.arctan2(width, 50 - y[wall]), rtol=1e-9)
    h = 50 - y[bottom]
    mouth = np.arctan2(h, x[bottom] - width / 2) - np.arctan2(h, x[bottom] + width / 2)
    np.testing.assert_allclose(fa[bottom], mouth, rtol=1e-9)


@pytest.mark.parametrize("angle", [0.0, 1.0, np.pi])
def test_vertices(angle):
    """Points at vertices take the full-circle path (edge_ids given or found)."""
    loops, rot = rotate(keyhole(3.0), angle)
    pts = rot(np.array([[50.0, 50.0], [3.0, 50.0], [30.0, 20.0], [-30.0, -20.0], [-3.0, 20.0]]))
    expect = [1.5 * np.pi, np.pi, 0.0, 0.0, np.arctan2(6, 30)]  # last: up through the neck
    np.testing.assert_allclose(free_angle(loops, pts), expect, atol=1e-9)
    a, b, _ = contour_edges(loops)
    for i, p in enumerate(pts):  # either incident edge gives the same answer
        for e in np.flatnonzero(np.all(np.isclose(a, p), axis=1) | np.all(np.isclose(b, p), axis=1)):
            assert np.isclose(free_angle(loops, p[None], [e])[0], expect[i], atol=1e-9)
    np.testing.assert_array_equal(reachable(loops, pts), np.array(expect) > 0)


@pytest.mark.parametrize("angle", [0.0, 0.5, np.pi])
def test_square_hole_unreachable(angle):
    outer = np.array([[-50, -50], [50, -50], [50, 50], [-50, 50]], dtype=float)
    hole = np.array([[-10, -10], [-10, 10], [10, 10], [10, -10]], dtype=float)  # CW
    loops, _ = rotate([outer, hole], angle)
    s, ok = reachable_samples(loops, 0.5)
    np.testing.assert_array_equal(loop_is_hole(loops), [False, True])
    np.testing.assert_array_equal(ok, ~s.is_hole)
    assert (free_angle(loops, s.points[s.is_hole], s.edge[s.is_hole]) == 0).all()


def test_sample_contour_bookkeeping():
    loops = keyhole(3.0) + [np.array([[-5, -5], [-5, 5], [5, 5], [5, -5]], dtype=float)]
    s = sample_contour(loops, 0.3)
    a, b, loop = contour_edges(loops)
    assert (s.lengths <= 0.3 + 1e-12).all()
    np.testing.assert_allclose(s.loop_lengths, [np.hypot(*(b - a)[loop == i].T).sum() for i in (0, 1)])
    np.testing.assert_allclose(np.bincount(s.loop, s.lengths), s.loop_lengths)
    # every sample lies on its edge, at arc length s from vertex 0 of its loop
    ea, eb = a[s.edge], b[s.edge]
    cross = (eb - ea)[:, 0] * (s.points - ea)[:, 1] - (eb - ea)[:, 1] * (s.points - ea)[:, 0]
    assert np.abs(cross).max() < 1e-9
    assert ((s.s > 0) & (s.s < s.loop_lengths[s.loop])).all()
    assert np.all(np.diff(s.s[s.loop == 0]) > 0)
    np.testing.assert_array_equal(s.is_hole, s.loop == 1)


# --- random polygons -----------------------------------------------------------------------

ANY_POLYGON = st.one_of(simple_polygons(), polygons_with_islands(), polygons_with_holes(),
                        simple_polygons(rounded=True), polygons_with_holes(rounded=True))


def pick_points(loops, seed, k=50, delta=1e-3):
    """``k`` contour points: up to 5 visibility events, located by bisection on an
    edge between a reachable and an unreachable sample, each with a point ``delta``
    to either side; the rest random samples off the convex hull (points on it
    are trivially reachable)."""
    s = sample_contour(loops, 1.0)
    ok = free_angle(loops, s.points, s.edge) > 1e-9
    flip = np.flatnonzero((ok[1:] != ok[:-1]) & (s.edge[1:] == s.edge[:-1]))
    rng = np.random.default_rng(seed)
    flip = rng.permutation(flip)[:5]
    yes = np.where(ok[flip, None], s.points[flip], s.points[flip + 1])  # reachable end
    no = np.where(ok[flip, None], s.points[flip + 1], s.points[flip])
    for _ in range(40):
        mid = 0.5 * (yes + no)
        m_ok = free_angle(loops, mid, s.edge[flip]) > 1e-9
        yes, no = np.where(m_ok[:, None], mid, yes), np.where(m_ok[:, None], no, mid)
    unit = (yes - no) / np.linalg.norm(yes - no + 1e-300, axis=1, keepdims=True)
    event = np.r_[no + delta * unit, no - delta * unit]
    hull = shapely.convex_hull(shapely.multipoints(np.concatenate(loops))).boundary
    inside = np.flatnonzero(shapely.distance(shapely.points(s.points), hull) > 1e-6)
    pick = rng.choice(inside, size=min(k - len(event), len(inside)), replace=False)
    return np.r_[event, s.points[pick]], np.r_[s.edge[flip], s.edge[flip], s.edge[pick]], len(event)


@settings(max_examples=4, **SETTINGS)
@given(loops=ANY_POLYGON, seed=st.integers(0, 2**32 - 1))
def test_agrees_with_brute_force(loops, seed):
    p, e, _ = pick_points(loops, seed)
    if len(p) == 0:  # convex: nothing off the hull
        return
    exact = free_angle(loops, p, e)
    brute, step = brute_free(loops, p, e)
    # a free interval of width g holds between g/step - 1 and g/step + 1 directions
    assert np.all(np.abs(exact - brute) <= step * 1.001 + 1e-9)
    ok = reachable(loops, p, e)
    disagree = ok != (brute > 0)
    assert np.all(exact[disagree] < 2 * step)  # only right at a visibility event
    assert disagree.mean() <= 0.1  # the 5 points right next to an event may differ


@settings(max_examples=15, **SETTINGS)
@given(loops=ANY_POLYGON, angle=st.floats(-np.pi, np.pi))
def test_invariants(loops, angle):
    s, ok = reachable_samples(loops, 1.0)
    # holes never, convex-hull points always
    assert not ok[s.is_hole].any()
    a = np.concatenate(loops)
    on_hull = shapely.distance(shapely.points(s.points),
                               shapely.convex_hull(shapely.multipoints(a)).boundary) < 1e-9
    fa = free_angle(loops, s.points, s.edge)
    assert (fa[on_hull] > 1e-9).all()
    np.testing.assert_array_equal(ok, fa > 1e-9)  # the hull shortcut changes nothing
    # rigid motions change nothing (the +-pi cut moves over other edges)
    moved, rot = rotate(loops, angle, centre=(7.0, -3.0))
    fm = free_angle(moved, rot(s.points), s.edge)
    np.testing.assert_allclose(fm, fa, atol=1e-7)
