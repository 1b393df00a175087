"""Property tests (hypothesis): random polygons with pockets, islands, holes."""
import numpy as np
import shapely
from hypothesis import HealthCheck, given, settings

from slicer.exact import ExactContact
from core2d import sense_slice
from polygen import polygons_with_holes, polygons_with_islands, simple_polygons

EPS = 1.0
BUDGET = 2500
SETTINGS = settings(max_examples=8, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])


def _check(loops):
    pts = np.concatenate(loops)
    lo, hi = pts.min(0), pts.max(0)
    center, radius = (lo + hi) / 2, np.linalg.norm(hi - lo) / 2 + EPS
    res = sense_slice(ExactContact(loops), (center, radius), EPS, max_motions=BUDGET)
    st = res.stats
    assert st.pushes == 0
    assert st.motions <= BUDGET + 200  # one area in flight may finish its motion
    assert st.budget_hit or not res.unknown
    contour = shapely.MultiLineString([np.vstack([l, l[:1]]) for l in loops])
    tol = EPS / 20
    for line in res.w1:  # W1 points are tip contacts: on the contour
        d = shapely.distance(shapely.points(line), contour)
        assert d.max() <= 2 * tol
    for seg in res.w2 + res.w3:  # lid / approximation end points were touched
        d = shapely.distance(shapely.points(seg), contour)
        assert d.max() <= 2 * tol
    for seg in res.w2:
        assert np.linalg.norm(seg[1] - seg[0]) < EPS
    return res


@SETTINGS
@given(simple_polygons())
def test_random_polygons(loops):
    _check(loops)


@SETTINGS
@given(polygons_with_islands())
def test_random_polygons_with_islands(loops):
    _check(loops)


@SETTINGS
@given(polygons_with_holes())
def test_random_polygons_with_holes(loops):
    res = _check(loops)
    holes = [l for l in loops if shapely.LinearRing(l).is_ccw is False]
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
    assert "unknown" in outcomes and "pending" not in outcomes
