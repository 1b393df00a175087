"""core2d.planner.lid_lines: the lid question solved sample by sample gives
the passes of the whole list (the nearest free sample per position)."""
from __future__ import annotations

import numpy as np
import pytest

from core2d.planner.known import KnownContour
from core2d.visibility import free_gaps


def _map(seed):
    """A map of random short pieces around a lid from A = (0, 0) to B = (4, 0)."""
    rng = np.random.default_rng(seed)
    known = KnownContour(join=0.05)
    for _ in range(int(rng.integers(3, 25))):
        start = rng.uniform([-2.0, -3.0], [6.0, 3.0])
        steps = rng.normal(scale=0.4, size=(int(rng.integers(2, 6)), 2))
        known.add(np.vstack([start, start + np.cumsum(steps, axis=0)]))
    return known


def _whole_list(known, a, b, spacing, margin, min_gap):
    """Every free line, from one batch of every sample (what the lazy answer replaces)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    n = float(np.hypot(*(b - a)))
    k = int(min(512, max(2, np.ceil((n - 2 * margin) / spacing) + 1)))
    s = np.linspace(margin, n - margin, k)
    pts = a + (s / n)[:, None] * (b - a)
    width, angle = free_gaps(pts, np.broadcast_to(-(b - a) / n, pts.shape), *known.segments())
    ok = width > min_gap
    return pts[ok], width[ok], angle[ok], (s / n)[ok]


@pytest.mark.parametrize("seed", range(30))
def test_nearest_free_sample_is_that_of_the_whole_list(seed):
    known = _map(seed)
    a, b, args = [0.0, 0.0], [4.0, 0.0], dict(spacing=0.05, margin=0.1, min_gap=0.2)
    pts, width, angle, along = _whole_list(known, a, b, **args)
    lines = known.free_lines(a, b, **args)
    positions = np.r_[np.linspace(0.0, 1.0, 23), 0.5, 0.5 + 1e-3]
    got = lines.nearest_many(positions)
    assert bool(lines) == bool(len(pts))
    for pos, ln in zip(positions, got):
        if not len(pts):
            assert ln is None
            continue
        i = int(np.argmin(np.abs(along - pos)))
        np.testing.assert_array_equal(ln.point, pts[i])
        np.testing.assert_array_equal(ln.direction, -np.array([np.cos(angle[i]), np.sin(angle[i])]))
        assert (ln.gap, ln.along) == (float(width[i]), float(along[i]))
        one = lines.nearest(pos)
        assert (one.gap, one.along) == (ln.gap, ln.along)
    full = list(known.free_lines(a, b, **args))
    assert [ln.along for ln in full] == along.tolist()


def test_blocked_samples_are_skipped_and_few_are_solved():
    """A wall in front of the lid's left half (on F's side, above it: the lid
    runs B -> A with F on its right) blocks the samples there: a pass planned
    there goes to the nearest free sample, found without solving the whole lid."""
    known = KnownContour(join=0.05)
    known.add([[-1.0, 0.05], [2.0, 0.05]])  # just above the left half
    a, b, args = [0.0, 0.0], [4.0, 0.0], dict(spacing=0.02, margin=0.1, min_gap=0.3)
    pts, width, angle, along = _whole_list(known, a, b, **args)
    lines = known.free_lines(a, b, **args)
    assert 0 < len(pts) < len(lines.points)  # some samples blocked, some free
    ln = lines.nearest(0.1)
    assert ln.along == float(along[0]) > 0.4  # the first free sample, past the wall
    assert lines._solved.sum() < len(lines.points)  # the far end was never asked


def test_ties_go_to_the_first_sample():
    """Samples at 1/8, 3/8, 5/8, 7/8 of the lid, nothing recorded: 1/2 lies
    exactly between two free samples, and argmin over the list takes the first."""
    known = KnownContour(join=0.05)
    lines = known.free_lines([0.0, 0.0], [4.0, 0.0], spacing=1.0, margin=0.5, min_gap=0.1)
    assert lines.along.tolist() == [0.125, 0.375, 0.625, 0.875]
    assert lines.nearest(0.5).along == 0.375
    assert [ln.along for ln in lines.nearest_many([0.5, 0.25, 0.75])] == [0.375, 0.125, 0.625]


def test_joined_segments_once_per_lid(monkeypatch):
    """The recorded segments' joins (``free_gaps``'s ``joined``, 40 % of a one-sample
    solve against ~2,000 segments) are found once per lid, not once per solve."""
    import core2d.planner.lid_lines as lid_lines

    calls = []
    real = lid_lines.joined_segments
    monkeypatch.setattr(lid_lines, "joined_segments", lambda a, b: calls.append(1) or real(a, b))
    lines = _map(3).free_lines([0.0, 0.0], [4.0, 0.0], spacing=0.05, margin=0.1, min_gap=0.2)
    for pos in (0.5, 0.1, 0.9, 0.3):
        lines.nearest(pos)
    lines.nearest_many([0.2, 0.4, 0.6])
    assert len(calls) == 1


def _clear_of(line, centre, radius, reach=100.0):
    """Does the pass along ``line`` (from F, ``reach`` long up to the lid) keep
    farther than ``radius`` from ``centre``?"""
    end = line.point
    start = end - reach * line.direction
    t = np.clip((centre - start) @ (end - start) / ((end - start) @ (end - start)), 0.0, 1.0)
    return float(np.hypot(*(start + t * (end - start) - centre))) > radius


def test_a_blocker_turns_the_line_out_of_its_disc():
    """Nothing recorded: the line through the lid's middle runs straight down from F.
    A pass stopped 5 above it (:class:`~core2d.planner.grazing.Blockers`) blocks a
    disc there; the middle's line then runs clear of it, every sample solved again."""
    known = KnownContour(join=0.05)
    lines = known.free_lines([0.0, 0.0], [4.0, 0.0], spacing=0.5, margin=0.5, min_gap=0.1)
    centre, radius = np.array([2.0, 5.0]), 0.5
    before = lines.nearest(0.5)
    assert not _clear_of(before, centre, radius)
    lines.block(centre, radius)
    assert not lines._solved.any()
    after = lines.nearest(0.5)
    assert after.along == before.along and _clear_of(after, centre, radius)
    assert after.gap < before.gap


def test_a_blocker_in_the_only_opening_leaves_no_line_and_no_spread_pass():
    """A wall above the lid with one slit 0.6 wide over its middle: every free line goes
    through the slit. A blocker filling the slit leaves none, and the spread plans no
    pass (it used to ask a line of ``None``)."""
    from core2d.planner.pass_plan import spread, sweep

    known = KnownContour(join=0.05)
    known.add([[-10.0, 1.0], [1.7, 1.0]])
    known.add([[2.3, 1.0], [14.0, 1.0]])
    a, b = np.array([0.0, 0.0]), np.array([4.0, 0.0])
    lines = known.free_lines(a, b, spacing=0.1, margin=0.1, min_gap=0.3)
    assert lines and len(list(spread(lines, a, b))) == 6
    lines.block([2.0, 1.0], 0.5)
    assert not lines
    assert list(spread(lines, a, b)) == [] and list(sweep(lines, 4.0, 1.0)) == []


def test_a_distinct_spread_takes_other_free_samples_when_one_end_is_blocked():
    """A wall in front of the lid's left two thirds: positions 0.5, 0.1 and 0.3 of
    the spread all fall on the first free sample. With ``distinct`` (a noisy sensor)
    each steer takes a sample once while free ones are left, so the passes go down
    the free third instead of three times down its edge."""
    from core2d.planner.pass_plan import PLAN, spread

    known = KnownContour(join=0.05)
    known.add([[-1.0, 0.05], [2.7, 0.05]])
    a, b = np.array([0.0, 0.0]), np.array([4.0, 0.0])
    args = dict(spacing=0.2, margin=0.1, min_gap=0.3)
    plain = list(spread(known.free_lines(a, b, **args), a, b))
    apart = list(spread(known.free_lines(a, b, **args), a, b, distinct=True))
    assert len(plain) == len(apart) == len(PLAN)
    middle = [k for k, (_, steer) in enumerate(PLAN) if steer == 0]  # positions 0.5, 0.3, 0.7
    xs = lambda passes: [round(float(passes[k][0][0]), 6) for k in middle]  # noqa: E731
    assert len(set(xs(plain))) < len(middle)  # one sample taken twice
    assert len(set(xs(apart))) == len(middle)
