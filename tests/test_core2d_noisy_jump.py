"""Slots narrower than eps under a noisy sensor (sigma = 0.1 eps, exact
backend, eps 1): P_2nd of a Case 2 jump read again where the probe stands
(:func:`core2d.planner.tracing.reread_jump`).

A trace sliding over the mouth of a slot narrower than eps jumps from one
corner to the other (Case 2, §4.3.2); the pair (P_1st, P_2nd) is W2 at once
(§3.1) and its chord stands for the slot behind it. Read once, P_2nd
scatters by about sqrt(3) sigma per axis and can land beside P_1st on the
near corner: the chord then stands for no slot (the slot's walls are
missed). Measured on the outline below, seeds 0-15: mean reachable coverage
within eps/2 + 2 sigma 0.884 with one reading, 0.927 with the mean of 25
(noiseless 0.998).
"""
from __future__ import annotations

import numpy as np

from core2d import SensorModel
import pytest

from core2d.planner.tracing import reread_jump, reread_pass
from core2d.sim.probe import Probe
from noisy_runs import coverages
from outlines import slotted_block
from slicer.contact.exact import ExactContact

SLOTS = (0.55, 0.65, 0.75, 0.85)
NOISE = 0.1


def _slotted():
    """A block with slots ``SLOTS`` wide, 12 deep (eps 1), and its workspace."""
    return slotted_block(SLOTS, tooth=6.0, depth=12.0, base=10.0)


def test_slots_narrower_than_eps_at_sigma_01_eps():
    covs = coverages(*_slotted(), NOISE, range(16))
    assert np.mean(covs) >= 0.91, np.round(covs, 3)


def _touching(sensor):
    """A probe inserted straight down onto the top of the slotted block, its
    tip touching at x = 3 (the true contact (3, 22)), and the reading."""
    loops, ws = _slotted()
    probe = Probe(ExactContact(loops), ws, 1.0, sensor=sensor)
    probe.approach(np.array([3.0, 22.0]), np.array([0.0, -1.0]))
    return probe, probe.insert()


@pytest.mark.parametrize("reread", [reread_jump, reread_pass])
def test_reread_jump_averages_free_readings_of_a_noisy_tip_contact(reread):
    """P_2nd of a jump (reread_jump) and a pass's contact C (reread_pass) alike."""
    truth = np.array([3.0, 22.0])
    one, mean = [], []
    for seed in range(20):
        probe, r = _touching(SensorModel.of_eps(1.0, NOISE, 0.0, seed))
        motions = probe.motions
        p2, pose = reread(probe, r)
        assert probe.motions == motions  # re-reading is no motion
        assert abs(np.hypot(*pose.direction) - 1.0) < 1e-12
        one.append(np.hypot(*(r.tip_contact.point - truth)))
        mean.append(np.hypot(*(p2 - truth)))
    assert np.mean(mean) < 0.4 * np.mean(one), (np.mean(mean), np.mean(one))


@pytest.mark.parametrize("reread", [reread_jump, reread_pass])
def test_reread_jump_keeps_a_perfect_or_a_coarse_reading(reread):
    """A perfect sensor, and one whose readings of one point do not resolve
    eps/2 (sigma 0.3 eps, taxels 0.25 eps): the jump's own reading, no re-read."""
    for sensor in (None, SensorModel.of_eps(1.0, 0.3, 0.25, 0)):
        probe, r = _touching(sensor)
        state = None if sensor is None else probe.sensor.rng.bit_generator.state
        p2, pose = reread(probe, r)
        assert p2 is r.contacts[0].point and np.array_equal(pose.joint, r.joint)
        if sensor is not None:  # no reading drawn
            assert probe.sensor.rng.bit_generator.state == state
