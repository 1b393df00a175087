"""Which contacts of a revisit pass split A_iB_i with a noisy sensor
(:mod:`core2d.planner.pass_contacts`): :func:`splits_across_record` keeps a
coarse sensor's contact met in front of a lid from splitting it when a child's
lid would cross recorded contour.
"""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from core2d.planner import revisit as rv
from core2d.planner.known import KnownContour
from core2d.planner.pass_contacts import splits_across_record
from core2d.resolution import Resolution
from noisy_runs import coverages
from outlines import outline

COARSE = Resolution.of(1.0, noise=0.3, taxel=0.25)


def _wall_and_lid():
    """A wall recorded up x = 3 (y 1 - 30) beside a lid from (10, 0) to (30, 0), and a
    piece recorded behind the lid down x = 12 (y -1 to -8); the probe comes from above
    (y > 0 is F)."""
    known = KnownContour(join=1.0)
    known.add(np.stack([np.full(30, 3.0), np.linspace(1.0, 30.0, 30)], axis=1))
    known.add(np.stack([np.full(8, 12.0), np.linspace(-1.0, -8.0, 8)], axis=1))
    area = SimpleNamespace(a=np.array([10.0, 0.0]), b=np.array([30.0, 0.0]), dist=20.0)
    return known, area


@pytest.mark.parametrize("joint, point, expected", [
    ((0.0, 25.0), (0.0, 5.0), True),    # in front, beyond the wall: A_iC crosses it
    ((8.0, 25.0), (8.0, 6.0), False),   # in front, on this side of the wall: no crossing
    ((20.0, 25.0), (20.0, -8.0), False),  # behind the lid (A_iC crosses x = 12 there)
    ((2.5, 25.0), (2.5, 2.0), False),   # the crossings within `near` of C: C's own wall
])
def test_a_child_lid_across_the_record_is_refused(joint, point, expected):
    known, area = _wall_and_lid()
    got = splits_across_record(COARSE, known, area, np.array(joint), np.array(point))
    assert got is expected


@pytest.mark.parametrize("res", [Resolution.of(1.0), Resolution.of(1.0, noise=0.1),
                                 Resolution.of(1.0, taxel=0.25)])
def test_perfect_and_fine_sensors_keep_the_paper_flow(res):
    known, area = _wall_and_lid()
    assert not splits_across_record(res, known, area, np.array([0.0, 25.0]),
                                    np.array([0.0, 5.0]))


def test_in_reach_is_still_the_revisit_name():
    from core2d.planner import pass_contacts
    assert rv.in_reach is pass_contacts.in_reach


def test_undercut_neck_wall_is_reached_at_sigma_03_taxel_025():
    """``undercut-1`` at sigma 0.3 eps, taxels 0.25 eps: a pass into a 3-eps neck
    stopped on the other neck's wall, 17 eps in front of a lid 45 eps long;
    splitting there laid both children's lids across two traced walls and the
    neck's far wall (22 eps) was never touched. Coverage within eps/2 + 2 sigma
    on the sensor seeds 1, 1001, 2001: 0.935, 0.970, 0.976 without the rule,
    0.992, 0.987, 0.989 with it (each run also meets the per-slice targets:
    :func:`noisy_runs.coverages`)."""
    loops = outline("undercut", np.random.default_rng(1), 1.0)
    pts = np.concatenate(loops)
    lo, hi = pts.min(0), pts.max(0)
    ws = ((lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2 + 1.0))
    covs = coverages(loops, ws, 0.3, [1, 1001, 2001], taxel=0.25)
    assert covs.min() >= 0.98, covs
