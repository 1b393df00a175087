"""Lids read again with a noisy sensor (:mod:`core2d.planner.repeats`)."""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from core2d import SensorModel, sense_slice
from core2d.planner import revisit
from core2d.planner.repeats import repeats_opening
from core2d.resolution import Resolution
from core2d.truth.metrics import sensor_metrics
from outlines import outline
from slicer.contact.exact import ExactContact


def _lid(a, b):
    return SimpleNamespace(a=np.array(a, float), b=np.array(b, float))


OPENINGS = [(np.array([0.0, 0.0]), np.array([20.0, 0.0]))]


@pytest.mark.parametrize("a, b, repeat", [
    ([0.5, 0.4], [19.4, -0.3], True),  # each end within eps/2 + jitter = 0.92 of its own
    ([20.0, 0.0], [0.0, 0.0], False),  # the reversed lid: V_i on the other side
    ([0.5, 0.4], [18.5, 0.0], False),  # B_i 1.5 away: another lid
    ([0.0, 1.0], [20.0, 1.0], False),  # both ends 1 away
])
def test_a_repeat_has_both_ends_within_the_same_contact_radius(a, b, repeat):
    run = SimpleNamespace(res=Resolution.of(1.0, noise=0.1), openings=OPENINGS)
    assert repeats_opening(run, _lid(a, b)) == repeat


def test_perfect_sensing_is_left_as_it_is():
    run = SimpleNamespace(res=Resolution.of(1.0), openings=OPENINGS)
    assert not repeats_opening(run, _lid([0.0, 0.0], [20.0, 0.0]))


def test_the_gaps_between_islands_are_probed_once_at_sigma_01(monkeypatch):
    """``islands`` outline seed 1, keyed sensor seed 2001 (the keyed sensor study's
    repeat 2): lids across the gaps between the islands came back with their ends read
    again and were probed again, 3,326 motions against 1,769 noiseless (1.88 x) at
    a84c8f6; with the repeats closed as the openings they are, 3,004 (1.70 x). Since
    the sweep through an open lid takes one pass every eps, the repeats cost less:
    2,724 without the rule, 2,684 with it (1.52 x), coverage 1.000 each way."""
    loops = outline("islands", np.random.default_rng(1), 1.0)
    pts = np.concatenate(loops)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    ws = ((lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2 + 1.0))
    base = sense_slice(ExactContact(loops), ws, 1.0)

    def noisy():
        return sense_slice(ExactContact(loops), ws, 1.0,
                           sensor=SensorModel.of_eps(1.0, 0.1, 0.0, 2001, keyed=True))

    res = noisy()
    monkeypatch.setattr(revisit, "repeats_opening", lambda run, area: False)
    without = noisy()
    assert any(r.note == "the lid repeats an opening to F found before" for r in res.areas)
    assert res.stats.motions < without.stats.motions, (res.stats.motions, without.stats.motions)
    assert res.stats.motions <= 1.8 * base.stats.motions, (res.stats.motions, base.stats.motions)
    assert sensor_metrics(loops, res, 1.0, 0.1)["coverage_sensor"] >= 0.99
