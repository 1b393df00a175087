"""The planner with a noisy sensor (sigma = 0.3 eps, taxels 0.25 eps) on
constructed slices: the blocks of the paper's figures (tests/figure_scenes.py),
exact backend, ten noise seeds each.

On every seed it finishes within the budget, and what it reports holds at the
tolerance the sensor allows (eps / 2 + 2 sigma): precision at least 0.98, every
W3 lid sound. Reachable coverage at that tolerance is at least 0.98 **on average
over the ten seeds**: one seed's coverage is a lottery at +-0.01 around the
planner's level (one generator draws every reading, so any change in the number
of motions re-draws all later readings; README, "Where it breaks"), and a test
of three fixed seeds passed or failed by that draw. Measured over seeds 0-9:
every block's worst seed is 0.959 - 0.986 and HILL's seed 9 is 0.978 whatever
the bootstrap does; OVERHANG_LEFT's mean is 0.9723 (seed 4: 0.869) when the
bootstrap decides Def. 3's orientation of its coin-toss pair from one noisy
reading, 0.9843 when it reads that pair again
(``core2d.planner.bootstrap.undecided``). (The issue's motion target -- at most
2 x the noiseless run -- is measured by ``bench/sensor_study.py``, not asserted.)
"""
from __future__ import annotations

import numpy as np
import pytest

import figure_scenes as F
from core2d import SensorModel, sense_slice
from core2d.truth.metrics import sensor_metrics
from slicer.contact.exact import ExactContact

SCENES = ("V_POCKET", "SLOPE_RIGHT", "OVERHANG_LEFT", "OVERHANG_RIGHT", "HILL")


@pytest.mark.parametrize("name", SCENES)
def test_planner_at_sigma_03_eps_holds_at_the_sensor_tolerance(name):
    loops = F.block(getattr(F, name))
    coverage = []
    for seed in range(10):
        res = sense_slice(ExactContact(loops), F.WORKSPACE, F.EPS,
                          sensor=SensorModel.of_eps(F.EPS, 0.3, 0.25, seed))
        m = sensor_metrics(loops, res, F.EPS, 0.3 * F.EPS)
        where = f"{name} seed {seed}"
        assert not res.stats.budget_hit, where
        assert m["precision_sensor"] >= 0.98, f"{where}: precision {m['precision_sensor']:.4f}"
        assert m["w3_unsound_count_sensor"] == 0, f"{where}: unsound W3 lids"
        assert res.stats.pushes == 0
        coverage.append(m["coverage_sensor"])
    assert np.mean(coverage) >= 0.98, f"{name}: coverage per seed {np.round(coverage, 4)}"


def test_sensor_soundness_forgives_a_lid_on_the_contour_only():
    """The sensor-tolerance soundness: a lid lying within eps/2 + 2 sigma of
    the contour it covers hides nothing; a lid across a pocket does."""
    from core2d.result import SliceResult

    loops = F.block(F.V_POCKET)  # pocket from (30, 60) down to (40, 30) and up to (70, 60)
    on_top = SliceResult(w3=[np.array([[2.0, 60.3], [9.0, 60.3]])])
    across = SliceResult(w3=[np.array([[30.0, 60.0], [70.0, 60.0]])])
    m = sensor_metrics(loops, on_top, 1.0, 0.3)
    assert m["w3_unsound_count_sensor"] == 0 and m["w3_soundness_sensor"] == 1.0
    assert sensor_metrics(loops, across, 1.0, 0.3)["w3_unsound_count_sensor"] == 1
