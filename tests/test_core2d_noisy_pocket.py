"""Pockets one to three eps wide under a fine noisy sensor (sigma = 0.1 eps,
exact backend, eps 1): a pass's contact against the lid's ends
(:func:`core2d.planner.grazing.end_radius`) and the pass's contact read
again where the probe stopped (:func:`core2d.planner.tracing.reread_pass`, tested in
``tests/test_core2d_noisy_jump.py`` beside :func:`~core2d.planner.tracing.reread_jump`).

A lid laid along a pocket's wall is crossed by every line from F at a few
degrees, so a pass lands on the wall about offset / tan(alpha) from where
it crossed the lid (the offset: how far the lid's noisy ends lie off the
wall). With the same-contact radius eps/2 + jitter as the test of a new
contact, such landings were discarded and the wall's lids ended unknown:
on the ``comb`` and ``star`` outlines of ``tests/outlines.py`` that was the
largest share of what sigma = 0.1 eps lost against the noiseless run.
"""
from __future__ import annotations

import numpy as np

from core2d.planner.grazing import end_radius
from core2d.planner.other_side import back_at
from core2d.resolution import Resolution
from noisy_runs import coverages
from outlines import slotted_block

SLOTS = (1.3, 1.8, 2.5)
NOISE = 0.1
SEEDS = range(6)
#: mean reachable coverage within eps/2 + 2 sigma over SEEDS; measured 0.906
#: with the same-contact radius and one reading of each pass's contact, 0.977
#: with end_radius and reread_pass (noiseless 0.998)
THRESHOLD = 0.95


def _pockets():
    """A block with pockets ``SLOTS`` wide and 25 deep (eps 1), and its workspace."""
    return slotted_block(SLOTS, tooth=6.0, depth=25.0, base=8.0)


def test_pocket_walls_at_sigma_01_eps():
    covs = coverages(*_pockets(), NOISE, SEEDS)
    assert np.mean(covs) >= THRESHOLD, np.round(covs, 4)


def test_end_radius_is_the_papers_while_the_sensor_resolves_half_eps():
    assert end_radius(Resolution.of(1.0)) == 0.5  # perfect sensing: eps/2
    assert end_radius(Resolution.of(1.0, noise=0.1)) == 0.5  # jitter 0.42 <= eps/2 - tol
    coarse = Resolution.of(1.0, noise=0.3, taxel=0.25)  # jitter 1.52: the same-contact radius
    assert end_radius(coarse) == coarse.tip_zone > 0.5


def _tip_at(point):
    """A reading whose tip contact is at ``point`` (None: no tip contact)."""
    from types import SimpleNamespace
    return SimpleNamespace(tip_contact=None if point is None else SimpleNamespace(
        point=np.asarray(point, float)))


def test_back_at_d_i_before_tracing_the_other_side():
    fine, d_i = Resolution.of(1.0, noise=0.1), np.zeros(2)  # same-contact radius 0.92
    assert back_at(fine, _tip_at([0.3, 0.3]), d_i)
    assert not back_at(fine, _tip_at([40.0, 34.0]), d_i)  # stopped on a grazed corner
    assert not back_at(fine, _tip_at(None), d_i)
    for res in (Resolution.of(1.0), Resolution.of(1.0, noise=0.3, taxel=0.25)):
        assert back_at(res, _tip_at([40.0, 34.0]), d_i)  # as before: any tip contact


def test_textured_pocket_slice_at_sigma_01_eps_lays_no_w1_through_material():
    """``textured_pocket`` z0 (of 8), the sensor study's settings: a W1 segment
    53 eps long through material (precision 0.922) when the second side's
    trace started on the corner the posture at D_i grazed."""
    from noisy_runs import scene_slice

    _, m = scene_slice("textured_pocket", 0, NOISE, 0.0, 0)
    assert m["precision_sensor"] >= 0.98
