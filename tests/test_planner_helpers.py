"""Small helpers of the planner's per-motion path, rewritten for speed: the
same answers, bit for bit, as the plain numpy they replace."""
from __future__ import annotations

import numpy as np
import pytest

from core2d.planar import magnitude
from core2d.planner.segments import turns
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


def _turns_numpy(d, e):
    """The turn test as numpy asks it: cos(d, e) > -0.5, nan (a zero length) turns."""
    n = np.hypot(e[:, 0], e[:, 1]) * np.hypot(*d)
    with np.errstate(invalid="ignore", divide="ignore"):
        return ~((e[:, 0] * d[0] + e[:, 1] * d[1]) / n <= -0.5)


def test_turns_is_the_division_it_replaces():
    rng = np.random.default_rng(1)
    e = rng.normal(size=(500, 2))
    e[:20] = 0.0  # zero-length directions turn
    e[20:40] = [-1.0, 0.0]  # straight back: cos -1
    for d in (rng.normal(size=2), np.zeros(2), np.array([1.0, 0.0])):
        got = turns(d, e)
        np.testing.assert_array_equal(got, _turns_numpy(d, e))
        assert got.all() == (not d.any())  # some directions turn back unless d has no length


def _continuations_numpy(pieces, join):
    """``KnownContour._next`` as the map made it with numpy: for each piece, the pieces
    passing within ``join`` of its end and turning by less than 120 degrees there, each with
    its first such segment; pieces added later that pass an earlier end are appended."""
    from core2d.planner.known import _end_direction
    from core2d.planner.segments import point_segment_distances

    nxt, dirs = [], []
    for i, pl in enumerate(pieces):
        d = _end_direction(pl, join)
        row = []
        for j, old in enumerate(pieces[:i]):  # old pieces continuing the new one
            ok = point_segment_distances(pl[-1], old[:-1], old[1:]) <= join
            ok &= _turns_numpy(d, old[1:] - old[:-1])
            if ok.any():
                row.append((j, int(np.argmax(ok))))
        for j, old in enumerate(pieces[:i]):  # the new piece continuing old ones
            ok = point_segment_distances(old[-1], pl[:-1], pl[1:]) <= join
            ok &= _turns_numpy(dirs[j], pl[1:] - pl[:-1])
            if ok.any():
                nxt[j].append((i, int(np.argmax(ok))))
        nxt.append(row)
        dirs.append(d)
    return nxt


@pytest.mark.parametrize("seed", range(6))
def test_the_maps_continuations_are_numpys(seed):
    """``KnownContour.add``'s compiled continuation search (which pieces pass a piece's end,
    turning by less than 120 degrees, and at which segment) against the plain numpy
    search over every piece, on random maps with zero-length segments at scales
    1e-2 .. 1e3, and on a map whose pieces meet end to start exactly."""
    from core2d.planner.known import KnownContour

    rng = np.random.default_rng(seed)
    scale = 10.0 ** rng.uniform(-2, 3)
    walk = np.cumsum(rng.normal(0, 0.3, (240, 2)), axis=0)  # cut into pieces that chain
    cuts = np.sort(rng.choice(np.arange(2, 238), 30, replace=False))
    pieces = []
    for lo, hi in zip(np.r_[0, cuts], np.r_[cuts, 240]):
        pl = walk[lo:hi + 1] + rng.normal(0, 0.1, 2)  # a start a little off the last end
        if rng.random() < 0.2:
            pl = pl[::-1]  # runs the other way: no continuation
        if rng.random() < 0.2 and len(pl) > 2:
            pl[1] = pl[0]  # a zero-length segment
        pieces.append(np.ascontiguousarray(pl * scale))
    order = rng.permutation(len(pieces))  # added in any order
    known = KnownContour(join=0.3 * scale)
    for i in order:
        known.add(pieces[i])
    assert known._next == _continuations_numpy([pieces[i] for i in order], known.join)
    assert sum(map(len, known._next)) > 10  # pieces were continued
    square = [np.array([[0.0, 0.0], [1.0, 0.0]]), np.array([[1.0, 0.0], [1.0, 1.0]]),
              np.array([[1.0, 1.0], [0.0, 1.0]]), np.array([[0.0, 1.0], [0.0, 0.0]]),
              np.array([[0.0, 0.0], [0.0, 1.0]])]  # the last turns straight back
    k = KnownContour(join=0.1)
    for pl in square:
        k.add(pl)
    assert k._next == _continuations_numpy(square, 0.1)
    assert k._next[0] == [(1, 0)] and k._next[3] == [(0, 0)]  # not (4, 0): it turns back


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
