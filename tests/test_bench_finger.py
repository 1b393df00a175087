"""Dense finger probing (core2d.planner.finger): the baseline of ``recon3d bench``.

Checked against the true contour with shapely (an independent computation):
every touch lies on the contour, every W2 segment joins touches closer than
eps with the material on its right, the probe only approaches and inserts,
a denser grid covers more, and the motion budget holds.
"""
import numpy as np
import pytest
import shapely
from shapely.geometry import Polygon

from core2d import sense_slice
from core2d.planner.finger import finger_probe, probe_lines
from core2d.sim.probe import Probe
from core2d.truth.metrics import slice_metrics
from slicer import ExactContact

# a block with a pocket 10 wide and 40 deep (reachable from above only)
POCKET = np.array([[0, 0], [100, 0], [100, 50], [55, 50], [55, 10], [45, 10], [45, 50],
                   [0, 50]], float)
WORKSPACE = (np.array([50.0, 25.0]), 57.0)


class _OnlyProbing:
    """Forwards approach / insert to a Probe; any other motion fails the test."""

    def __init__(self, probe):
        self._probe, self.calls = probe, set()

    def __getattr__(self, name):
        if name in ("center", "radius", "motions", "costs"):  # stated constants, counters
            return getattr(self._probe, name)
        assert name in ("approach", "insert"), f"finger probing used {name}"
        self.calls.add(name)
        return getattr(self._probe, name)


def _touches(res):
    """(m, 2) float: every touch point of a finger-probing result."""
    return np.concatenate([np.zeros((0, 2))] + [np.asarray(p) for p in (*res.w1, *res.w2)])


def _run(directions, spacing, max_motions=100000):
    return sense_slice(ExactContact([POCKET]), WORKSPACE, 1.0, method="finger",
                       directions=directions, spacing=spacing, max_motions=max_motions)


def test_probe_lines_cover_the_workspace_in_sweeps():
    pts, dirs, sweep = probe_lines(np.zeros(2), 10.0, 4, 1.0)
    assert len(pts) == 4 * 21 and set(sweep) == {0, 1, 2, 3}
    assert np.allclose(np.linalg.norm(dirs, axis=1), 1.0)
    first = pts[sweep == 0]
    assert np.allclose(np.diff(first[:, 1]), 1.0)  # ordered along the sweep, spacing apart
    with pytest.raises(ValueError):
        probe_lines(np.zeros(2), 10.0, 0, 1.0)


def test_only_approach_and_insert_are_commanded():
    proxy = _OnlyProbing(Probe(ExactContact([POCKET]), WORKSPACE, 1.0))
    res = finger_probe(proxy, 1.0, directions=4, spacing=2.0)
    assert proxy.calls == {"approach", "insert"}
    assert res.stats.motions == 2 * len(probe_lines(*WORKSPACE, 4, 2.0)[0])
    assert not res.w3 and not res.unknown


def test_touches_lie_on_the_contour_and_w2_joins_close_touches_material_right():
    res = _run(16, 0.5)
    poly = Polygon(POCKET)
    touches = _touches(res)
    dist = shapely.distance(poly.exterior, shapely.points(touches))
    assert dist.max() <= 1.0 / 20 + 1e-9  # within the contact resolution tol
    assert res.w2
    for a, b in res.w2:
        assert np.linalg.norm(b - a) < 1.0
        e = b - a
        right = np.array([e[1], -e[0]]) / np.linalg.norm(e)
        mid = (a + b) / 2
        assert poly.contains(shapely.Point(mid + 0.2 * right)) or \
            poly.exterior.distance(shapely.Point(mid + 0.2 * right)) < 0.05


def test_denser_grids_cover_more_and_reach_the_pocket_floor():
    cov = [slice_metrics([POCKET], _run(d, s), 1.0)["coverage"]
           for d, s in ((4, 4.0), (8, 1.0), (32, 0.5))]
    assert cov[0] < cov[1] < cov[2]
    assert cov[2] >= 0.9  # the deep pocket's walls need directions within 14 deg of its axis
    res = _run(4, 0.5)  # straight down into the 10-wide pocket: its floor is touched
    floor = [p for p in _touches(res)
             if abs(p[1] - 10) < 0.1 and 45 < p[0] < 55]
    assert floor


def test_motion_budget_is_kept_and_reported():
    res = _run(32, 0.5, max_motions=300)
    assert res.stats.budget_hit and res.stats.motions <= 300
    assert not _run(4, 4.0).stats.budget_hit


def test_unknown_method_is_a_clear_error():
    with pytest.raises(ValueError, match="method"):
        sense_slice(ExactContact([POCKET]), WORKSPACE, 1.0, method="poke")
