"""Small helpers of the planner's per-motion path, rewritten for speed: the
same answers, bit for bit, as the plain numpy they replace."""
from __future__ import annotations

import numpy as np
import pytest

from core2d.planar import magnitude
from core2d.planner.known import _turns
from core2d.planner.hops import _reach_back


def test_magnitude_is_numpys_norm_bit_for_bit():
    rng = np.random.default_rng(0)
    v = rng.normal(size=(20000, 2)) * 10.0 ** rng.integers(-8, 8, size=(20000, 1))
    got = np.array([magnitude(x) for x in v])
    want = np.array([np.linalg.norm(x) for x in v])
    np.testing.assert_array_equal(got, want)


def _reach_back_walk(pl, k, step, hop):
    """The walk point by point that :func:`_reach_back` replaces."""
    far = np.hypot(*(pl - pl[k]).T) >= hop
    idx = range(k - 1, -1, -1) if step < 0 else range(k + 1, len(pl))
    return next((m for m in idx if far[m]), None)


@pytest.mark.parametrize("seed", range(5))
def test_reach_back_is_the_walk(seed):
    rng = np.random.default_rng(seed)
    pl = np.cumsum(rng.normal(scale=0.1, size=(60, 2)), axis=0)
    answers = set()
    for k in range(len(pl)):
        for step in (-1, 1):
            tie = float(np.hypot(*(pl[(k + 7) % len(pl)] - pl[k])))  # a point exactly at hop
            for hop in (0.05, 0.3, 2.0, tie):
                got, want = _reach_back(pl, k, step, hop), _reach_back_walk(pl, k, step, hop)
                assert got == want
                answers.add(want is None)
    assert answers == {True, False}  # both found and not found were asked


def test_turns_is_the_division_it_replaces():
    rng = np.random.default_rng(1)
    e = rng.normal(size=(500, 2))
    e[:20] = 0.0  # zero-length directions turn
    for d in (rng.normal(size=2), np.zeros(2), np.array([1.0, 0.0])):
        n = np.hypot(e[:, 0], e[:, 1]) * np.hypot(*d)
        with np.errstate(invalid="ignore", divide="ignore"):
            want = ~((e @ d) / n <= -0.5)
        np.testing.assert_array_equal(_turns(d, e), want)


def _random_map(rng, join=0.2):
    from core2d.planner.known import KnownContour

    known = KnownContour(join=join)
    scale = 10.0 ** rng.uniform(-2, 3)
    for _ in range(int(rng.integers(1, 30))):
        pts = (rng.uniform(-3, 3, 2) + np.cumsum(rng.normal(0, 0.3, (int(rng.integers(2, 12)), 2)),
                                                 axis=0)) * scale
        if rng.random() < 0.2:
            pts[1] = pts[0]  # a zero-length segment
        known.add(pts)
    return known, scale


def _within_numpy(known, p, r):
    """The map's segments within ``r`` of ``p`` as plain numpy asks: box culling, then
    the distances."""
    from core2d.planner.segments import point_segment_distances

    g = known._near(p, r)
    return g[point_segment_distances(p, known._a[g], known._b[g]) <= r]


@pytest.mark.parametrize("seed", range(4))
def test_the_maps_compiled_queries_are_numpys(seed):
    """``passing``, ``_within`` and ``distance`` of the map against the numpy expressions
    they replace, on random maps (zero-length segments, scales 1e-2 .. 1e3), at random
    points, at piece starts (distance 0) and at radii equal to a segment's distance."""
    from core2d.planner.segments import point_segment_distances

    rng = np.random.default_rng(seed)
    found = set()
    for _ in range(40):
        known, scale = _random_map(rng)
        for _ in range(15):
            p = rng.uniform(-4, 4, 2) * scale
            if rng.random() < 0.2:
                p = known._starts[rng.integers(len(known._starts))].copy()
            d = point_segment_distances(p, known._a, known._b)
            r = float(rng.choice(d)) if rng.random() < 0.3 else float(rng.uniform(0, 1.5) * scale)
            g = _within_numpy(known, p, r)
            np.testing.assert_array_equal(known._within(p, r), g)
            pieces = known._piece[g]
            want = [(int(j), int(g[np.argmax(pieces == j)]) - known._first[j])
                    for j in np.unique(pieces)]
            assert known.passing(p, r) == want
            found.add(len(want) > 1)
            bound = float(np.hypot(*(known._starts - p).T).min())
            near = known._near(p, bound)
            assert known.distance(p) == float(
                point_segment_distances(p, known._a[near], known._b[near]).min())
    assert found == {True, False}  # one piece and several passing were both asked
