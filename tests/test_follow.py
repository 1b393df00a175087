"""The pushing contour follower (core2d.planner.follow, ``--method follow``).

Fig. 2(a) of the paper: traced from an arbitrary first contact, a pocket's
inner side is pushed. On a pocket whose flanks carry fine teeth the
follower pushes without friction, and with friction it jams and covers
less; the pulling planner covers the same pocket without one push, and
friction changes nothing for it.
"""
import numpy as np
import pytest

from core2d import sense_slice
from core2d.truth.metrics import slice_metrics
from meshes.scenes_textured import teeth
from slicer.contact.exact import ExactContact
from test_core2d_walls import SIMULATOR, _Guarded

POCKET = np.array([[75.0, 50.0], [62.0, 30.0], [38.0, 30.0], [25.0, 50.0]])
LOOP = np.vstack([[[0.0, 0.0], [100.0, 0.0], [100.0, 50.0]], teeth(POCKET, 0.5, 0.12, 0.2),
                  [[0.0, 50.0]]])
WORKSPACE = (np.array([50.0, 25.0]), 57.0)
EPS = 0.6


def _run(method, mu, contact=None):
    contact = ExactContact([LOOP]) if contact is None else contact
    res = sense_slice(contact, WORKSPACE, EPS, method=method, friction=mu)
    return res, slice_metrics([LOOP], res, EPS)["coverage"]


@pytest.fixture(scope="module")
def follow_runs():
    return {mu: _run("follow", mu) for mu in (0.0, 1.0)}


def test_the_follower_pushes_on_the_pocket_without_friction(follow_runs):
    res, cov = follow_runs[0.0]
    assert res.stats.pushes > 0 and res.stats.jams == 0 and res.stats.push_attempts == 0
    assert res.w1 and not res.w3 and not res.unknown
    assert 0.3 < cov < 0.99  # it traces much, and not all: dead ends end a direction


def test_with_friction_the_follower_jams_and_covers_less(follow_runs):
    (free, cov0), (rough, cov1) = follow_runs[0.0], follow_runs[1.0]
    assert rough.stats.jams > 0
    assert rough.stats.pushes < free.stats.pushes
    assert cov1 < cov0


@pytest.mark.parametrize("mu", [0.0, 1.0])
def test_the_pulling_planner_covers_the_pocket_without_a_push(mu):
    res, cov = _run("pulling", mu)
    assert res.stats.pushes == 0 and res.stats.jams == 0
    assert cov >= 0.99


def test_the_follower_queries_geometry_only_through_the_simulator():
    guarded = _Guarded([LOOP])
    res, _ = _run("follow", 0.0, guarded)
    assert guarded.callers and guarded.callers <= SIMULATOR and res.w1
