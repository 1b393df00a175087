"""The planner with a noisy sensor (sigma = 0.3 eps, taxels 0.25 eps) on
constructed slices besides the figure blocks: a convex 12-gon (no concave
point inside any area: the bisection of §4.2.2 ends at an area's end) and a
wobbly 24-gon, three noise seeds each. It finishes within the budget, covers
the contour within eps/2 + 2 sigma, is precise there, and needs at most the
issue's 2 x the noiseless motions.
"""
from __future__ import annotations

import numpy as np
import pytest

from core2d import SensorModel, sense_slice
from core2d.truth.metrics import sensor_metrics
from slicer.contact.exact import ExactContact

EPS = 1.0
_A12 = np.linspace(0.0, 2 * np.pi, 12, endpoint=False)
_A24 = np.linspace(0.0, 2 * np.pi, 24, endpoint=False)
_R24 = 35.0 * (1 + 0.08 * np.random.default_rng(1).uniform(-1, 1, 24))
SHAPES = {"12-gon": [40.0 * np.c_[np.cos(_A12), np.sin(_A12)]],  # edges 20.7 eps, CCW
          "wobbly 24-gon": [np.c_[_R24 * np.cos(_A24), _R24 * np.sin(_A24)]]}
WORKSPACE = (np.zeros(2), 41.0)


@pytest.mark.parametrize("name", sorted(SHAPES))
def test_planner_at_sigma_03_eps_on_convex_outlines(name):
    loops = SHAPES[name]
    base = sense_slice(ExactContact(loops), WORKSPACE, EPS).stats.motions
    for seed in range(3):
        sensor = SensorModel.of_eps(EPS, 0.3, 0.25, seed)
        res = sense_slice(ExactContact(loops), WORKSPACE, EPS, sensor=sensor)
        m = sensor_metrics(loops, res, EPS, sensor.noise)
        where = f"{name} seed {seed}"
        assert not res.stats.budget_hit, where
        assert m["coverage_sensor"] >= 0.98, f"{where}: coverage {m['coverage_sensor']:.4f}"
        assert m["precision_sensor"] >= 0.98, f"{where}: precision {m['precision_sensor']:.4f}"
        assert m["w3_unsound_count_sensor"] == 0, where
        assert res.stats.motions <= 2 * base, f"{where}: {res.stats.motions} vs {base}"
