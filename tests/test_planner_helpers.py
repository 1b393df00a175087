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
            for hop in (0.05, 0.3, 2.0):
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
