"""The sweep through a lid that can no longer be W3 -- a pass left through it or ended
anywhere but at a touched end -- with a noisy sensor
(:func:`core2d.planner.pass_plan.sweep`'s ``sparse``, :mod:`core2d.planner.revisit`)."""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from core2d import SensorModel, sense_slice
from core2d.planner.pass_plan import sweep
from core2d.truth.metrics import sensor_metrics
from outlines import outline
from slicer.contact.exact import ExactContact


class _Lines:
    """FreeLines' sweep interface; records the positions it was asked to solve."""

    def __init__(self):
        self.solved = []

    def nearest_many(self, positions):
        self.solved.extend(positions.tolist())
        return [SimpleNamespace(point=p, turned=lambda f: f) for p in positions]


def test_a_sparse_sweep_takes_and_solves_every_other_position():
    fine, sparse = _Lines(), _Lines()
    every = list(sweep(fine, 10.0, 1.0))
    half = list(sweep(sparse, 10.0, 1.0, sparse=lambda: True))
    assert len(every) == 20 and len(half) == 10
    assert [p for p, _ in half] == [p for p, _ in every[::2]]
    assert sparse.solved == [p for p, _ in half]  # the positions left out are not solved
    assert {t for _, t in half} == {0.25, 0.75}  # both steers kept


def test_the_sweep_turns_sparse_when_asked():
    """``sparse`` is asked before each pass: the sweep halves from the pass after it turns."""
    state = {"escaped": False}
    passes = sweep(_Lines(), 10.0, 1.0, sparse=lambda: state["escaped"])
    first = [next(passes) for _ in range(3)]
    state["escaped"] = True
    rest = list(passes)
    assert len(first) == 3 and len(rest) == 8  # positions 4, 6, ..., 18 of 20


def _outline(kind, seed):
    """The outline ``kind`` of ``seed`` (eps 1) and a workspace circle around it."""
    loops = outline(kind, np.random.default_rng(seed), 1.0)
    pts = np.concatenate(loops)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    return loops, ((lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2 + 1.0))


def test_open_lids_between_islands_cost_at_most_twice_the_noiseless_motions():
    """``islands`` outline seed 1 at sigma 0.1 eps with its own sensor seed (the README's
    one-stream study): lids across the gaps between the islands, each an opening to F
    whose passes left through it, made a sweep of up to 48 passes each; 3,664 motions
    against 1,769 noiseless (2.07 x). With one sweep pass every eps once a pass has
    left, 3,433 (1.94 x), coverage 1.000 both ways."""
    loops, ws = _outline("islands", 1)
    base = sense_slice(ExactContact(loops), ws, 1.0)
    res = sense_slice(ExactContact(loops), ws, 1.0, sensor=SensorModel.of_eps(1.0, 0.1, 0.0, 1))
    assert sum(r.outcome == "open" for r in res.areas) >= 3
    assert res.stats.motions <= 2.0 * base.stats.motions, (res.stats.motions, base.stats.motions)
    assert sensor_metrics(loops, res, 1.0, 0.1)["coverage_sensor"] >= 0.99


def test_lids_across_slots_that_cannot_be_w3_cost_at_most_twice_the_noiseless_motions():
    """``comb`` outline seed 4 at sigma 0.3 eps, taxels 0.25 eps, 16 reads, sensor seed 2004
    (the unseen-outline study's repeat 2): lids across its slots 1.6 - 3 eps wide and
    along their walls, whose walls the noisy trace recorded in pieces. Their passes landed
    on recorded contour behind the lid, so none could be W3, yet each was swept one pass
    every eps/2: 5,479 motions against 2,649 noiseless (2.07 x). Swept at eps once a pass
    ends anywhere but at a touched end: 5,207 (1.97 x), coverage 1.000 both ways."""
    from core2d.resolution import repeated_reads

    loops, ws = _outline("comb", 4)
    base = sense_slice(ExactContact(loops), ws, 1.0)
    sensor = SensorModel.of_eps(1.0, 0.3, 0.25, 2004, reads=repeated_reads(1.0, 0.3, 0.25))
    res = sense_slice(ExactContact(loops), ws, 1.0, sensor=sensor)
    assert res.stats.motions <= 2.0 * base.stats.motions, (res.stats.motions, base.stats.motions)
    m = sensor_metrics(loops, res, 1.0, 0.3, spacing=0.25)
    assert m["coverage_sensor"] >= 0.98 and m["precision_sensor"] >= 0.98
    assert m["w3_unsound_count_sensor"] == 0
