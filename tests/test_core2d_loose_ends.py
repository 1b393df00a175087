"""Where the recorded contour stops (core2d.planner.loose_ends): the walk
that asks each start point's passing pieces once per audit, and places the
meeting point in float arithmetic, answers exactly as the plain walk that
asks ``known.passing`` again at every step with numpy's (2,) vector algebra
(kept here as the reference)."""
from __future__ import annotations

import numpy as np
import pytest

from core2d.planner import loose_ends
from core2d.planner.known import KnownContour
from core2d.planner.loose_ends import recorded_stops


def _ref_meets(known, j, k, q):
    a, b = known.pieces[j][k], known.pieces[j][k + 1]
    ab = b - a
    t = float(np.clip((q - a) @ ab / max(float(ab @ ab), 1e-300), 0.0, 1.0))
    return a + t * ab


def _ref_onward(points, p, e, r):
    return bool(len(points)) and bool(
        (np.hypot(*(points - e).T) > max(r, float(np.hypot(*(p - e))))).any())


def _ref_end(known, i):
    pl, r = known.pieces[i], known.join
    e = pl[-1]
    todo = [(j, k, e) for j, k in known.successors(i)]
    if not (np.hypot(*(pl - e).T) > r).any():
        todo += [(j, k, e) for j, k in known.passing(e, r)]
    seen, last, far = {i}, i, 0.0
    while todo:
        j, k, q = todo.pop()
        p = _ref_meets(known, j, k, q)
        if j in seen or np.hypot(*(p - e)) > 2 * r:
            continue
        seen.add(j)
        if _ref_onward(known.pieces[j][k + 1:], p, e, r):
            return None
        d = float(np.hypot(*(known.pieces[j][-1] - e)))
        if d > max(far, float(np.hypot(*(p - e)))):
            last, far = j, d
        todo += [(m, n, known.pieces[j][-1]) for m, n in known.successors(j)]
    return last


def _ref_start(known, i):
    s, r = known.pieces[i][0], known.join
    seen, todo, first, far = {i}, [s], i, 0.0
    while todo:
        q = todo.pop()
        for j, k in known.passing(q, r):
            p = _ref_meets(known, j, k, q)
            if j in seen or np.hypot(*(p - s)) > 2 * r:
                continue
            seen.add(j)
            if _ref_onward(known.pieces[j][:k + 1], p, s, r):
                return None
            d = float(np.hypot(*(known.pieces[j][0] - s)))
            if d > max(far, float(np.hypot(*(p - s)))):
                first, far = j, d
            todo.append(known.pieces[j][0])
    return first


def _ref_stops(known):
    ends, starts = [], []
    for i in range(len(known.pieces)):
        if (j := _ref_end(known, i)) is not None:
            ends.append((known.pieces[j][-1], known.poses[j][1], j))
        if (j := _ref_start(known, i)) is not None:
            starts.append((known.pieces[j][0], known.poses[j][0], j))
    return loose_ends._one_each(ends, known.join), loose_ends._one_each(starts, known.join)


def _map(seed) -> KnownContour:
    """A circle recorded in ragged pieces: gaps, overlaps, stretches recorded
    twice, short stubs and jitter, added in a shuffled order."""
    rng = np.random.default_rng(seed)
    known = KnownContour(join=0.5)
    cuts = np.sort(rng.uniform(0, 2 * np.pi, rng.integers(4, 30)))
    pieces = []
    for a0, a1 in zip(cuts, np.roll(cuts, -1) + np.r_[np.zeros(len(cuts) - 1), 2 * np.pi]):
        a0 += rng.choice([0.0, rng.normal(0, 0.05)])  # a gap or an overlap at the start
        a1 += rng.choice([0.0, rng.normal(0, 0.05)])
        n = max(2, int((a1 - a0) * 20))
        ang = -np.linspace(a0, a1, n)  # material on the right: clockwise round it
        pl = 10 * np.column_stack([np.cos(ang), np.sin(ang)]) + rng.normal(0, 0.02, (n, 2))
        pieces.append(pl)
        if rng.random() < 0.2:  # the same stretch recorded again, or a stub
            pieces.append(pl[: rng.integers(2, n + 1)] + rng.normal(0, 0.05, 2))
    for m in rng.permutation(len(pieces)):
        known.add(pieces[m])
    return known


def _same(found, want):
    assert len(found) == len(want)
    for (p, pose, j), (q, pose_q, m) in zip(found, want):
        assert j == m and pose is pose_q
        assert np.array_equal(p, q)


@pytest.mark.parametrize("seed", range(12))
def test_stops_are_the_plain_walks(seed):
    known = _map(seed)
    ends, starts = recorded_stops(known)
    want_ends, want_starts = _ref_stops(known)
    _same(ends, want_ends)
    _same(starts, want_starts)


def test_every_chain_is_the_plain_walks():
    """Piece by piece (most chains stop at no loose point: the lists above
    alone would not see a chain that ends on another piece)."""
    kinds = set()
    for seed in range(12):
        known = _map(seed)
        found = {}

        def passing(m):
            if m not in found:
                found[m] = known.passing(known.pieces[m][0], known.join)
            return found[m]

        for i in range(len(known.pieces)):
            end, start = loose_ends._end_chain(known, i), loose_ends._start_chain(known, i, passing)
            assert end == _ref_end(known, i) and start == _ref_start(known, i)
            kinds |= {end is None, end == i, start is None, start == i}
    assert kinds == {True, False}  # continued, stopping on itself and on another piece


def test_meeting_point_rounds_as_numpy():
    rng = np.random.default_rng(7)
    known = KnownContour(join=0.5)
    pl = rng.normal(0, 1, (400, 2)) * rng.choice([1e-3, 1.0, 1e3], (400, 1))
    pl[50] = pl[49]  # a zero-length segment
    known.add(pl)
    for k in range(len(pl) - 1):
        q = pl[k] + rng.normal(0, 2, 2) * np.abs(pl[k + 1] - pl[k]).max()
        assert np.array_equal(loose_ends._meets(known, 0, k, q), _ref_meets(known, 0, k, q))


def test_the_answer_is_remembered_while_the_map_stays_the_same(monkeypatch):
    """The audit asks again about an unchanged map: the walk is not made again; a piece
    added (a new version of the map) gets a new walk, equal to the plain one."""
    walks = []
    real = loose_ends._walk_stops
    monkeypatch.setattr(loose_ends, "_walk_stops", lambda k: walks.append(1) or real(k))
    known = _map(3)
    first = recorded_stops(known)
    assert recorded_stops(known) is first and len(walks) == 1
    copy = known.with_pieces([])  # a copy remembers nothing
    assert recorded_stops(copy) is not first and len(walks) == 2
    end = known.pieces[0][-1]
    known.add(end + [[0.0, 0.0], [0.1, 5.0]])  # a new loose end, 5 away
    ends, starts = recorded_stops(known)
    assert len(walks) == 3
    want_ends, want_starts = _ref_stops(known)
    _same(ends, want_ends)
    _same(starts, want_starts)
    assert len(ends) != len(first[0]) or len(starts) != len(first[1])
