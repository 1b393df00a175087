"""The revisit's passes through a lid, each planned when it is next
(:mod:`core2d.planner.pass_plan`): a spread pass solves its lid samples only when it is
the next pass, the sweep only once the spread passes found nothing, eight positions at a
time -- and the passes are those of a plan made at once. Noiseless, exact backend, eps 1."""
from __future__ import annotations

import numpy as np
import pytest

from core2d import sense_slice
from core2d.planner import pass_plan
from core2d.planner import revisit as rv
from core2d.planner.lid_lines import FreeLines
from outlines import outline
from slicer.contact.exact import ExactContact


def _lid_lines(rng):
    """A lid from (0, 0) to (20, 0), V_i above it, behind a comb of recorded walls."""
    k = 41
    s = np.linspace(0.0, 1.0, k)
    points = np.column_stack([20 * s, np.zeros(k)])
    tangent = np.broadcast_to([-1.0, 0.0], points.shape)
    x = rng.uniform(-5, 25, 30)
    seg_a = np.column_stack([x, rng.uniform(1, 8, 30)])
    seg_b = seg_a + rng.normal(0, 2, (30, 2))
    return lambda: FreeLines(points, tangent, s, seg_a, seg_b, 1e-3)


class _Asked:
    """FreeLines that logs the positions each ``nearest_many`` call asks for."""

    def __init__(self, lines):
        self.lines, self.asked = lines, []

    def nearest(self, pos):
        return self.nearest_many([pos])[0]

    def nearest_many(self, positions):
        self.asked.append(len(positions))
        return self.lines.nearest_many(positions)


@pytest.mark.parametrize("seed", range(4))
def test_passes_are_those_of_a_plan_made_at_once(seed):
    make = _lid_lines(np.random.default_rng(seed))
    assert make(), "no free line: the case tests nothing"
    lines = make()
    ab = np.array([20.0, 0.0])
    eager = []
    for (pos, steer), ln in zip(pass_plan.PLAN, lines.nearest_many([p for p, _ in pass_plan.PLAN])):
        d0, d1 = ln.turned(0.1), ln.turned(0.9)
        toward_b, toward_a = (d0, d1) if d0 @ ab > d1 @ ab else (d1, d0)
        eager.append((ln.point, ln.direction if steer == 0 else
                      (toward_b if steer > 0 else toward_a)))
    k = 40  # Dist 20, one pass every eps/2
    picks = lines.nearest_many((np.arange(k) + 0.5) / k)
    eager += [(ln.point, ln.turned(0.25 + 0.5 * (n % 2))) for n, ln in enumerate(picks)]
    lazy = make()  # a fresh one: its samples solved in the lazy order only
    got = list(pass_plan.spread(lazy, np.zeros(2), ab)) + list(pass_plan.sweep(lazy, 20.0, 1.0))
    assert len(got) == len(eager) == pass_plan.MAX_TRIES + k
    for (p, d), (q, e) in zip(got, eager):
        assert np.array_equal(p, q) and np.array_equal(d, e)


def test_each_pass_solved_when_it_is_next():
    asked = _Asked(_lid_lines(np.random.default_rng(0))())
    spread = pass_plan.spread(asked, np.zeros(2), np.array([20.0, 0.0]))
    next(spread)
    assert asked.asked == [1]  # the first spread pass alone
    sweep = pass_plan.sweep(asked, 20.0, 1.0)
    assert asked.asked == [1]  # nothing solved before the sweep's first pass is asked for
    for _ in range(pass_plan.SWEEP_CHUNK + 1):
        next(sweep)
    assert asked.asked == [1, pass_plan.SWEEP_CHUNK, pass_plan.SWEEP_CHUNK]


def test_sweep_comes_after_the_spread_passes(monkeypatch):
    looks = []  # per look at a lid: [area, its tries at the start, tries at the first sweep pass]
    one, sweep = rv.revisit_one, rv.sweep

    def revisit_one(run, area):
        looks.append([area, area.tries, None])
        return one(run, area)

    def swept(lines, length, eps, **kw):
        for n, item in enumerate(sweep(lines, length, eps, **kw)):
            if n == 0:
                looks[-1][2] = looks[-1][0].tries
            yield item

    monkeypatch.setattr(rv, "revisit_one", revisit_one)
    monkeypatch.setattr(rv, "sweep", swept)
    loops = outline("undercut", np.random.default_rng(0), 1.0)
    pts = np.concatenate(loops)
    lo, hi = pts.min(0), pts.max(0)
    res = sense_slice(ExactContact(loops), ((lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2 + 1)),
                      1.0)
    assert res.stats.motions > 0
    swept_looks = [(start, at) for _, start, at in looks if at is not None]
    assert swept_looks, "no lid was swept: the case no longer tests the sweep"
    # every spread pass was made, and found nothing, before the sweep's first pass
    assert all(at - start >= pass_plan.MAX_TRIES for start, at in swept_looks), swept_looks
    assert len(swept_looks) < len(looks)  # lids split by a spread pass: never swept
