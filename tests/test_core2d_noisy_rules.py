"""The planner's rules for a noisy sensor (sigma = 0.3 eps, taxels 0.25 eps),
each on a constructed slice where removing it shows.

* the bisection (§4.2.2) converges within tol + the sensor's jitter: on a
  convex polygon -- no concave point inside any area -- the noisy run then
  needs no more motions than the noiseless one, covers the contour within
  eps/2 + 2 sigma and stays within the budget (with the paper's tol the
  readings' scatter never converges, D_i drifts to an area's end and the
  run takes 1.1 - 1.2 x the noiseless motions);
* a lid that is not W2 keeps lid samples between the margins its free lines
  are searched within (:attr:`Resolution.lid_margin`): its W3 proof is
  never vacuous.
"""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from core2d import SensorModel, sense_slice
from core2d.planner.known import KnownContour
from core2d.planner.revisit import proof_lines
from core2d.resolution import Resolution
from core2d.truth.metrics import sensor_metrics
from slicer.contact.exact import ExactContact

EPS = 1.0
_A = np.linspace(0.0, 2 * np.pi, 12, endpoint=False)
POLYGON = [40.0 * np.c_[np.cos(_A), np.sin(_A)]]  # 12-gon, edges 20.7 eps, CCW
WORKSPACE = (np.zeros(2), 41.0)


def test_bisection_converges_at_the_sensor_resolution_on_a_convex_polygon():
    base = sense_slice(ExactContact(POLYGON), WORKSPACE, EPS).stats.motions
    for seed in range(3):
        sensor = SensorModel.of_eps(EPS, 0.3, 0.25, seed)
        res = sense_slice(ExactContact(POLYGON), WORKSPACE, EPS, sensor=sensor)
        m = sensor_metrics(POLYGON, res, EPS, sensor.noise)
        where = f"seed {seed}"
        assert not res.stats.budget_hit, where
        assert m["coverage_sensor"] >= 0.98, f"{where}: coverage {m['coverage_sensor']:.4f}"
        assert m["precision_sensor"] >= 0.98, f"{where}: precision {m['precision_sensor']:.4f}"
        assert res.stats.motions <= base, f"{where}: {res.stats.motions} motions, noiseless {base}"


@pytest.mark.parametrize("noise,taxel", [(0.0, 0.0), (0.1, 0.0), (0.3, 0.25), (1.0, 0.0)])
def test_every_lid_wider_than_w2_has_free_lines(noise, taxel):
    """A lid just wider than the W2 distance, over nothing recorded: free
    lines cross it (the proof of step 2 of the revisit is not vacuous)."""
    res = Resolution.of(EPS, noise=noise * EPS, taxel=taxel * EPS)
    a, b = np.zeros(2), np.array([1.02 * res.w2_dist, 0.0])
    run = SimpleNamespace(known=KnownContour(join=res.w2_dist), eps=EPS, res=res,
                          angle_tol=res.angle_tol(100.0))
    area = SimpleNamespace(a=a, b=b)
    assert proof_lines(run, area)
    assert res.lid_margin <= res.tip_zone  # equal for perfect sensing: the paper's eps/2
    assert (res.lid_margin == res.tip_zone) == (noise == 0 and taxel == 0)
