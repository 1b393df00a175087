"""Pockets one to three eps wide under a fine noisy sensor (sigma = 0.1 eps,
exact backend, eps 1): a pass's contact against the lid's ends
(:func:`core2d.planner.grazing.end_radius`) and the pass's contact read
again where the probe stopped (:func:`core2d.planner.tracing.reread_pass`).

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

from core2d import SensorModel, sense_slice
from core2d.planner.grazing import end_radius
from core2d.planner.tracing import reread_pass
from core2d.resolution import Resolution
from core2d.sim.probe import Probe
from core2d.truth.metrics import sensor_metrics
from outlines import slotted_block
from slicer.contact.exact import ExactContact

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
    loops, ws = _pockets()
    contact = ExactContact(loops)
    base = sense_slice(contact, ws, 1.0)
    assert sensor_metrics(loops, base, 1.0, 0.0)["coverage_sensor"] >= 0.99
    covs = []
    for seed in SEEDS:
        res = sense_slice(contact, ws, 1.0, sensor=SensorModel.of_eps(1.0, NOISE, 0.0, seed))
        m = sensor_metrics(loops, res, 1.0, NOISE)
        assert not res.stats.budget_hit, f"seed {seed}"
        assert m["precision_sensor"] >= 0.98, f"seed {seed}: {m['precision_sensor']:.4f}"
        assert m["w3_unsound_count_sensor"] == 0, f"seed {seed}"
        assert res.stats.motions <= 2 * base.stats.motions, (seed, res.stats.motions)
        covs.append(m["coverage_sensor"])
    assert np.mean(covs) >= THRESHOLD, np.round(covs, 4)


def test_end_radius_is_the_papers_while_the_sensor_resolves_half_eps():
    assert end_radius(Resolution.of(1.0)) == 0.5  # perfect sensing: eps/2
    assert end_radius(Resolution.of(1.0, noise=0.1)) == 0.5  # jitter 0.42 <= eps/2 - tol
    coarse = Resolution.of(1.0, noise=0.3, taxel=0.25)  # jitter 1.52: the same-contact radius
    assert end_radius(coarse) == coarse.tip_zone > 0.5


def _touching(sensor):
    """A probe inserted straight down into the widest pocket, its tip on the
    pocket's floor at x = 22.05 (the true contact (22.05, 8)), and the reading."""
    loops, ws = _pockets()
    probe = Probe(ExactContact(loops), ws, 1.0, sensor=sensor)
    probe.approach(np.array([22.05, 8.0]), np.array([0.0, -1.0]))
    return probe, probe.insert()


def test_reread_pass_averages_a_fine_sensor_and_keeps_others():
    truth = np.array([22.05, 8.0])
    one, mean = [], []
    for seed in range(20):
        probe, r = _touching(SensorModel.of_eps(1.0, NOISE, 0.0, seed))
        motions = probe.motions
        c, pose = reread_pass(probe, r)
        assert probe.motions == motions  # no motion
        one.append(np.hypot(*(r.tip_contact.point - truth)))
        mean.append(np.hypot(*(c - truth)))
    assert np.mean(mean) < 0.4 * np.mean(one), (np.mean(mean), np.mean(one))
    for sensor in (None, SensorModel.of_eps(1.0, 0.3, 0.25, 0)):
        probe, r = _touching(sensor)
        c, pose = reread_pass(probe, r)
        assert c is r.tip_contact.point and np.array_equal(pose.joint, r.joint)
