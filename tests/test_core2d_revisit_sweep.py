"""The revisit's sweep (:mod:`core2d.planner.revisit`, step 3) is planned only once the
spread passes of that look at the lid found nothing: its one pass every eps/2 solves
the lid question at up to ``MAX_SWEEP`` lid samples, wasted on a lid that one of the
first passes splits (most of them). Noiseless, exact backend, eps 1."""
from __future__ import annotations

import numpy as np

from core2d import sense_slice
from core2d.planner import revisit as rv
from outlines import outline
from slicer.contact.exact import ExactContact


def test_sweep_planned_after_the_spread_passes(monkeypatch):
    looks = []  # per look at a lid: [area, its tries at the start, tries when swept]
    one, sweep = rv.revisit_one, rv._sweep

    def revisit_one(run, area):
        looks.append([area, area.tries, None])
        return one(run, area)

    def swept(lines, length, eps):
        looks[-1][2] = looks[-1][0].tries
        return sweep(lines, length, eps)

    monkeypatch.setattr(rv, "revisit_one", revisit_one)
    monkeypatch.setattr(rv, "_sweep", swept)
    loops = outline("undercut", np.random.default_rng(0), 1.0)
    pts = np.concatenate(loops)
    lo, hi = pts.min(0), pts.max(0)
    res = sense_slice(ExactContact(loops), ((lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2 + 1)),
                      1.0)
    assert res.stats.motions > 0
    swept_looks = [(start, at) for _, start, at in looks if at is not None]
    assert swept_looks, "no lid was swept: the case no longer tests the sweep"
    # every pass of the spread plan was made (and found nothing) before the sweep was planned
    assert all(at - start >= len(rv._PLAN) for start, at in swept_looks), swept_looks
    # and lids were split by a spread pass with no sweep planned for them
    assert len(swept_looks) < len(looks)
