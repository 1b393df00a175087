"""Property tests: random outlines with narrow pockets, combs, undercuts,
islands and holes (tests/outlines.py, seeds drawn by hypothesis).

On every outline the run ends within its budget, no push is executed, every
W3 lid is sound by the per-lid definition of core2d.truth.metrics, the
reachable contour is covered, and detections lie on the contour. The
``numerics`` kind (spikes thinner than the contact resolution) is measured
by bench/bench_planner.py, not promised here.
"""
import numpy as np
import pytest
import shapely
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from core2d import sense_slice
from core2d.truth.metrics import slice_metrics
from outlines import outline
from polygen import polygons_with_holes
from slicer.contact.exact import ExactContact

EPS = 1.0
SETTINGS = settings(max_examples=3, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])
KINDS = ["star", "comb", "undercut", "islands", "holes"]


def _sense(loops, budget=20000):
    pts = np.concatenate(loops)
    lo, hi = pts.min(0), pts.max(0)
    ws = ((lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2 + EPS))
    res = sense_slice(ExactContact(loops), ws, EPS, max_motions=budget)
    return res, slice_metrics(loops, res, EPS)


def _check(loops):
    res, m = _sense(loops)
    assert not res.stats.budget_hit
    assert res.stats.pushes == 0 and res.stats.push_attempts >= 0
    assert m["w3_unsound_count"] == 0 and m["w3_cross_loop"] == 0, "a W3 lid hides reachable contour"
    assert m["coverage"] >= 0.99, f"coverage {m['coverage']:.4f}"
    assert m["precision"] >= 0.99
    contour = shapely.MultiLineString([np.vstack([lp, lp[:1]]) for lp in loops])
    for line in res.w1:  # W1 points are tip contacts: on the contour
        assert shapely.distance(shapely.points(line), contour).max() <= 2 * EPS / 20
    for seg in res.w2 + res.w3:  # the ends of approximations and lids were touched
        assert shapely.distance(shapely.points(seg), contour).max() <= 2 * EPS / 20
    for seg in res.w2:
        assert np.linalg.norm(seg[1] - seg[0]) < EPS
    return res, m


@pytest.mark.parametrize("kind", KINDS)
@SETTINGS
@given(seed=st.integers(0, 10_000))
def test_random_outlines(kind, seed):
    _check(outline(kind, np.random.default_rng(seed), EPS))


@settings(max_examples=3, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(polygons_with_holes())
def test_holes_are_never_touched(loops):
    res, _ = _check(loops)
    holes = [lp for lp in loops if shapely.LinearRing(lp).is_ccw is False]
    for hole in holes:  # nothing can be detected on an enclosed hole
        ring = shapely.LinearRing(hole)
        for line in res.w1:
            assert shapely.distance(shapely.points(line), ring).min() > EPS / 20


def test_a_tiny_budget_ends_the_run_and_reports_what_is_unknown():
    loop = np.array([[0, 0], [100, 0], [100, 50], [60, 50], [50, 20], [40, 50], [0, 50]], float)
    res = sense_slice(ExactContact([loop]), (np.array([50.0, 25.0]), 57.0), EPS, max_motions=150)
    assert res.stats.budget_hit and res.unknown
    assert res.stats.motions < 150 + 100  # the motion in flight finishes, nothing more
    outcomes = {a.outcome for a in res.areas}
    assert "unknown" in outcomes and "pending" not in outcomes and "deferred" not in outcomes
