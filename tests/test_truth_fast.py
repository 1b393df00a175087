"""The ground truth's fast paths answer as the code they replace, bit for bit.

* :func:`core2d.truth.nearest.segment_distances` against shapely's
  ``STRtree.query_nearest`` distances (GEOS), on random segments and real slices;
* :func:`core2d.truth.reachability.reachable` (a free cone proves most points,
  :mod:`core2d.truth.free_ray`) against the exact arcs alone, on real slices of
  built-in scenes and random polygons with holes and islands.
"""
from __future__ import annotations

import math

import numba
import numpy as np
import pytest
import shapely
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import meshes
import slicer
from core2d.truth import reachability as R
from core2d.truth import free_ray as FR
from core2d.truth.free_ray import normal_cone_free
from core2d.truth.nearest import polyline_segments, segment_distances

try:
    from polygen import keyhole, polygons_with_holes, polygons_with_islands, slotted_box
except ImportError:  # tests/ imported as a package
    from tests.polygen import keyhole, polygons_with_holes, polygons_with_islands, slotted_box

SETTINGS = dict(deadline=None, derandomize=True, max_examples=40,
                suppress_health_check=[HealthCheck.too_slow])
SCENES = ("comb", "cup_handle", "knurled_pocket", "fig18_overhangs", "twin_posts")


def geos_distances(points, a, b) -> np.ndarray:
    """The replaced code: nearest-segment distance by shapely's STRtree (inf: no segment)."""
    tree = shapely.STRtree(shapely.linestrings(np.stack([a, b], axis=1)))
    idx, dist = tree.query_nearest(shapely.points(points), all_matches=False,
                                   return_distance=True)
    out = np.full(len(points), np.inf)
    out[idx[0]] = dist
    return out


def exact_reachable(loops, points, edge_ids, angle_tol=1e-9) -> np.ndarray:
    """The replaced code: on the hull, or the exact arcs leave a gap > angle_tol."""
    a, b, _ = R.contour_edges(loops)
    atol = 1e-9 * max(float(np.ptp(a, axis=0).max()), 1e-300)
    hull = shapely.convex_hull(shapely.multipoints(a)).boundary
    ok = shapely.distance(shapely.points(points), hull) <= atol
    todo = np.flatnonzero(~ok)
    ok[todo] = R.free_angle(loops, points[todo], edge_ids[todo]) > angle_tol
    return ok


def real_slices(count=5):
    """(scene, loops) of the closed sections of a few built-in scenes."""
    out = []
    for name in SCENES:
        for cut in slicer.slice_mesh(meshes.load(name), axis="z", count=count):
            if cut.loops and not cut.open_chains:
                out.append((name, [np.asarray(lp) for lp in cut.loops]))
    return out


@pytest.fixture(scope="module")
def slices():
    return real_slices()


# --- nearest-segment distances --------------------------------------------------------------

@pytest.mark.parametrize("seed", range(40))
def test_segment_distances_are_geos_bits_on_random_segments(seed):
    rng = np.random.default_rng(seed)
    n, m = int(rng.integers(1, 400)), int(rng.integers(1, 400))
    scale = 10.0 ** rng.uniform(-3, 3)
    off = rng.uniform(-1e3, 1e3, 2) * (seed % 2)  # far from the origin on odd seeds
    a = rng.normal(size=(n, 2)) * scale + off
    b = a + rng.normal(size=(n, 2)) * scale * 10.0 ** rng.uniform(-4, 0.5)
    zero = rng.random(n) < 0.05
    b[zero] = a[zero]  # zero-length segments: points
    p = rng.normal(size=(m, 2)) * scale * rng.uniform(0.1, 5.0) + off
    k = m // 3
    p[:k] = a[rng.integers(0, n, k)] + rng.normal(size=(k, 2)) * scale * 1e-6  # near vertices
    got = segment_distances(p, a, b)
    assert got.shape == (m,)
    assert np.array_equal(got, geos_distances(p, a, b))


def test_segment_distances_are_geos_bits_on_real_slices(slices):
    """Samples of each slice against the edges of the next (the true-to-detected shape of
    the metrics: near, crossing, far), and the edges' pieces against their own slice."""
    for (_, loops), (_, other) in zip(slices, slices[1:] + slices[:1]):
        samp = R.sample_contour(loops, 0.01 * float(np.ptp(np.concatenate(loops), axis=0).max()))
        a, b, _ = R.contour_edges(other)
        assert np.array_equal(segment_distances(samp.points, a, b),
                              geos_distances(samp.points, a, b))
        a, b, _ = R.contour_edges(loops)
        mids = 0.5 * (a + b) + 1e-3 * (b - a)[:, ::-1]
        assert np.array_equal(segment_distances(mids, a, b), geos_distances(mids, a, b))


def test_segment_distances_without_segments_or_points():
    assert np.array_equal(segment_distances(np.zeros((3, 2)), np.zeros((0, 2)), np.zeros((0, 2))),
                          np.full(3, np.inf))
    assert segment_distances(np.zeros((0, 2)), np.ones((2, 2)), np.ones((2, 2))).shape == (0,)


def test_polyline_segments_skip_lone_vertices():
    a, b = polyline_segments([np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 2.0]]),
                              np.array([[5.0, 5.0]])])
    assert a.tolist() == [[0.0, 0.0], [1.0, 0.0]]
    assert b.tolist() == [[1.0, 0.0], [1.0, 2.0]]
    assert polyline_segments([])[0].shape == (0, 2)


# --- reachability: the free cone --------------------------------------------------------------

def test_reachable_is_the_exact_test_on_real_slices(slices, monkeypatch):
    """Same answers; and the cone proves most samples (the exact arcs get few)."""
    asked = []
    exact = R.free_angle

    def counting(loops, points, *args, **kwargs):
        asked.append(len(points))
        return exact(loops, points, *args, **kwargs)

    total = 0
    for name, loops in slices:
        spacing = 0.005 * float(np.ptp(np.concatenate(loops), axis=0).max())
        samp = R.sample_contour(loops, spacing)
        want = exact_reachable(loops, samp.points, samp.edge)
        monkeypatch.setattr(R, "free_angle", counting)
        got = R.reachable(loops, samp.points, samp.edge)
        monkeypatch.setattr(R, "free_angle", exact)
        assert np.array_equal(got, want), name
        total += len(samp.points)
    assert sum(asked) < 0.25 * total  # the exact arcs for a quarter of the samples at most


def test_the_exact_arcs_run_whatever_the_cone_proves(monkeypatch):
    """An L-shaped section: every sample reachable, those of the inner corner's walls off
    the hull and proved by the cone; the exact arcs still check one of them (so a run
    compiles the same kernels on any contour: the first-compile notice depends on it)."""
    loops = [np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 1.0], [1.0, 1.0], [1.0, 4.0], [0.0, 4.0]])]
    samp = R.sample_contour(loops, 0.1)
    asked = []
    exact = R.free_angle
    monkeypatch.setattr(R, "free_angle",
                        lambda lp, pts, *a, **k: asked.append(len(pts)) or exact(lp, pts, *a, **k))
    assert R.reachable(loops, samp.points, samp.edge).all()
    assert asked == [1]


def test_cone_never_proves_an_unreachable_point(slices):
    """Wherever the exact test says unreachable, the cone proves nothing (slots, holes)."""
    cases = [lp for _, lp in slices] + [keyhole(2.0), slotted_box(1.0, 6.0), slotted_box(0.2, 3.0)]
    blocked = 0
    for loops in cases:
        samp = R.sample_contour(loops, 0.003 * float(np.ptp(np.concatenate(loops), axis=0).max()))
        ok = exact_reachable(loops, samp.points, samp.edge)
        a, b, _ = R.contour_edges(loops)
        own = samp.edge[~ok]
        t = (b - a)[own] / np.hypot(*(b - a)[own].T)[:, None]
        proved = normal_cone_free(samp.points[~ok], t, a, b, own, 1e-9, center=a.mean(axis=0))
        assert not proved.any()
        blocked += int((~ok).sum())
    assert blocked > 100  # the cases do have unreachable samples


@settings(**SETTINGS)
@given(loops=st.one_of(polygons_with_holes(), polygons_with_islands()))
def test_reachable_is_the_exact_test_with_holes_and_islands(loops):
    samp = R.sample_contour(loops, 0.25)
    assert np.array_equal(R.reachable(loops, samp.points, samp.edge),
                          exact_reachable(loops, samp.points, samp.edge))


def _bored_square(hole):
    """A square 10 across with a hole (clockwise) of the given corners."""
    outer = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])
    return [outer, np.asarray(hole, float)[::-1]]


def test_hole_samples_skip_the_arcs(monkeypatch):
    """Samples inside a hole's edges are unreachable without the arcs (every ray leaves the
    hole through its loop): the exact arcs are asked only for the rest, and the answer is
    the exact test's."""
    loops = _bored_square([[3.0, 3.0], [7.0, 3.0], [7.0, 6.0], [3.0, 6.0]])
    samp = R.sample_contour(loops, 0.1)
    on_hole = R.loop_is_hole(loops)[R.contour_edges(loops)[2][samp.edge]]
    assert on_hole.sum() == 140
    asked = []
    exact = R.free_angle
    monkeypatch.setattr(R, "free_angle",
                        lambda lp, pts, *a, **k: asked.append(np.asarray(pts)) or exact(lp, pts, *a, **k))
    got = R.reachable(loops, samp.points, samp.edge)
    monkeypatch.setattr(R, "free_angle", exact)
    assert np.array_equal(got, exact_reachable(loops, samp.points, samp.edge))
    assert not got[on_hole].any() and got[~on_hole].all()
    assert sum(len(p) for p in asked) == 1  # the one the exact arcs always check
    # a smaller angle_tol than SEALED_TOL: the hole's samples go to the arcs again
    asked.clear()
    monkeypatch.setattr(R, "free_angle",
                        lambda lp, pts, *a, **k: asked.append(np.asarray(pts)) or exact(lp, pts, *a, **k))
    R.reachable(loops, samp.points, samp.edge, angle_tol=1e-12)
    assert sum(len(p) for p in asked) >= 140


def test_hole_samples_near_other_edges_go_to_the_arcs(monkeypatch):
    """Two square holes joined by a channel 5e-7 wide (the margin is 1e-6 of the size,
    1e-5 here) and a point 5e-6 from a hole's corner: the channel's samples lie within the
    margin of the other channel wall, the point within it of the neighbouring edge -- all
    are left to the exact arcs, which agree; the squares' other samples are not."""
    w = 2.5e-7
    dumbbell = _bored_square([[2, 2], [4, 2], [4, 5 - w], [6, 5 - w], [6, 2], [8, 2], [8, 8],
                              [6, 8], [6, 5 + w], [4, 5 + w], [4, 8], [2, 8]])
    assert R.loop_is_hole(dumbbell).tolist() == [False, True]
    samp = R.sample_contour(dumbbell, 0.1)
    a, b, _ = R.contour_edges(dumbbell)
    corner = 4 + 11  # the hole's edge (2, 2) -> (2, 8) after the reversal
    assert np.array_equal(a[corner], [2.0, 2.0]) and np.array_equal(b[corner], [2.0, 8.0])
    points = np.vstack([samp.points, [[2.0, 2.0 + 5e-6]]])
    edges = np.append(samp.edge, corner)
    channel = (points[:, 0] > 4.0) & (points[:, 0] < 6.0) & (np.abs(points[:, 1] - 5.0) < 2 * w)
    assert channel.sum() == 40
    asked = []
    exact = R.free_angle
    monkeypatch.setattr(R, "free_angle",
                        lambda lp, pts, *a, **k: asked.append(np.asarray(pts)) or exact(lp, pts, *a, **k))
    got = R.reachable(dumbbell, points, edges)
    monkeypatch.setattr(R, "free_angle", exact)
    assert np.array_equal(got, exact_reachable(dumbbell, points, edges))
    sent = {tuple(p) for p in np.vstack(asked)}
    assert all(tuple(p) in sent for p in points[channel]) and tuple(points[-1]) in sent
    on_hole = R.loop_is_hole(dumbbell)[R.contour_edges(dumbbell)[2][edges]]
    assert len(sent) < 0.2 * on_hole.sum()


def test_segment_distances_with_non_finite_input():
    """Non-finite coordinates (one cell holds every segment): finite points get their
    distance to the finite segments, a NaN point inf."""
    a = np.array([[0.0, 0.0], [np.nan, 1.0], [5.0, 5.0]])
    b = np.array([[1.0, 0.0], [2.0, 2.0], [6.0, 5.0]])
    p = np.array([[0.5, 2.0], [5.5, 4.0], [np.nan, 0.0]])
    got = segment_distances(p, a, b)
    assert got[:2].tolist() == [2.0, 1.0]
    assert got[2] == np.inf


def test_a_wide_angle_tol_skips_the_cone():
    """The cone proves a gap of 2e-5 rad only: a larger angle_tol asks the arcs alone."""
    loops = slotted_box(1.0, 6.0)
    samp = R.sample_contour(loops, 0.1)
    for tol in (1e-9, 0.3, 1.0):
        assert np.array_equal(R.reachable(loops, samp.points, samp.edge, angle_tol=tol),
                              exact_reachable(loops, samp.points, samp.edge, angle_tol=tol))


@numba.njit
def _plain_scan(p, dirs, a, b, own, margin, cos_h, sin_h, out):  # pragma: no cover
    """The replaced scan: every segment against every candidate cone, by the kernel's own
    segment test, without its boxes (compiled here, not cached)."""
    for r in range(p.shape[0]):
        free = False
        for k in range(dirs.shape[1]):
            nx, ny = dirs[r, k, 0], dirs[r, k, 1]
            lx, ly = nx * cos_h - ny * sin_h, nx * sin_h + ny * cos_h
            rx, ry = nx * cos_h + ny * sin_h, -nx * sin_h + ny * cos_h
            free = FR._segments_free(lx, ly, rx, ry, p[r, 0], p[r, 1], a, b, 0, a.shape[0],
                                     own[r], margin)
            if free:
                break
        out[r] = free


def _plain_cone_free(p, dirs, a, b, own, margin):
    out = np.zeros(len(p), dtype=np.bool_)
    _plain_scan(p, dirs, a, b, own, margin, math.cos(FR.HALF_ANGLE), math.sin(FR.HALF_ANGLE),
                out)
    return out


def test_the_cone_skips_boxes_as_the_plain_scan_skips_their_segments(slices):
    """The boxes of consecutive segments change nothing: on real slices (every sample,
    several margins), on contours with NaN and on one edge, the same answers."""
    cases = [lp for _, lp in slices] + [keyhole(2.0), slotted_box(0.2, 3.0)]
    proved = unproved = 0
    for loops in cases:
        samp = R.sample_contour(loops, 0.004 * float(np.ptp(np.concatenate(loops), axis=0).max()))
        a, b, _ = R.contour_edges(loops)
        own = samp.edge
        t = (b - a)[own] / np.hypot(*(b - a)[own].T)[:, None]
        center = a.mean(axis=0)
        for margin in (1e-9, 1e-3):
            dirs = FR.candidate_directions(samp.points, t, center)
            want = _plain_cone_free(samp.points, dirs, a, b, own, margin)
            got = normal_cone_free(samp.points, t, a, b, own, margin, center=center)
            assert np.array_equal(got, want)
            proved, unproved = proved + int(want.sum()), unproved + int((~want).sum())
    assert proved > 1000 and unproved > 1000
    a, b, _ = R.contour_edges(slotted_box(1.0, 6.0))
    p = 0.5 * (a + b)
    t = (b - a) / np.hypot(*(b - a).T)[:, None]
    own = np.arange(len(a))
    a_nan = a.copy()
    a_nan[3] = np.nan
    for aa in (a, a_nan, a[:1]):
        bb, pp, tt, oo = b[:len(aa)], p[:len(aa)], t[:len(aa)], own[:len(aa)]
        dirs = FR.candidate_directions(pp, tt)
        assert np.array_equal(normal_cone_free(pp, tt, aa, bb, oo, 1e-9),
                              _plain_cone_free(pp, dirs, aa, bb, oo, 1e-9))


def test_a_box_is_skipped_only_wholly_outside_a_boundary():
    """Cone along +x from the origin (half-angle 1e-5): a box beside it is skipped, one
    it crosses, one it reaches within the slack, and one with NaN are not."""
    c, s = np.cos(FR.HALF_ANGLE), np.sin(FR.HALF_ANGLE)
    left, right = (c, s), (c, -s)

    def outside(x0, y0, x1, y1, slack=1e-12):
        return FR._box_outside(*left, *right, x0, y0, x1, y1, 1e-9, slack)

    assert outside(1.0, 1.0, 2.0, 2.0) and outside(1.0, -2.0, 2.0, -1.0)
    assert not outside(1.0, -1.0, 2.0, 1.0)  # across the cone
    assert not outside(-2.0, -1.0, -1.0, 1.0)  # behind the apex, across the axis
    y = (s + 1e-9 + 5e-13) / c  # a box at x = 1 outside by 5e-13: less than the slack
    assert not outside(1.0, y, 1.0, 1.0 + y) and outside(1.0, y, 1.0, 1.0 + y, slack=1e-13)
    assert not outside(1.0, np.nan, 2.0, 2.0)
    lo, hi = FR.chunk_boxes(np.arange(40.0).reshape(20, 2), np.arange(40.0).reshape(20, 2) + 1)
    assert lo.tolist() == [[0.0, 1.0], [32.0, 33.0]] and hi.tolist() == [[31.0, 32.0], [39.0, 40.0]]
