"""Deep slots a few eps wide under a noisy sensor (sigma = 0.1 eps, one case at
0.3 eps with taxels; exact backend, eps 1): the rules of :mod:`core2d.planner.grazing`.

The constructed comb below has slots 6, 4, 2.5 and 1.5 eps wide and 40 eps
deep (the built-in ``comb`` scene: gaps 19 ... 0.3 eps, 84 eps deep, where
every slice hit the 20,000-motion budget at sigma 0.1 eps). Every line from F
crosses a lid laid along a slot wall at a few degrees; without the rules the
revisit spends its passes on such lids (measured, seeds 0-2: 19,297 motions
against 3 x 2,308 noiseless, 2.79 x; with them 12,563, 1.81 x).
"""
from __future__ import annotations

import numpy as np

from core2d import SensorModel, sense_slice
from core2d.planner.grazing import Blockers, beyond_ends, resolves_half_eps, steep_enough
from core2d.resolution import Resolution
from core2d.truth.metrics import sensor_metrics
from outlines import outline, slotted_block
from slicer.contact.exact import ExactContact

SLOTS = (6.0, 4.0, 2.5, 1.5)


def _comb(tooth=8.0, depth=40.0, base=12.0):
    """Counter-clockwise outline of a comb, teeth up, slots ``SLOTS`` (eps 1)."""
    return slotted_block(SLOTS, tooth, depth, base)


def test_comb_at_sigma_01_eps_within_twice_the_noiseless_motions():
    loops, ws = _comb()
    contact = ExactContact(loops)
    base = sense_slice(contact, ws, 1.0)
    assert not base.stats.budget_hit
    total = 0
    for seed in range(3):
        res = sense_slice(contact, ws, 1.0, sensor=SensorModel.of_eps(1.0, 0.1, 0.0, seed))
        m = sensor_metrics(loops, res, 1.0, 0.1)
        assert not res.stats.budget_hit, f"seed {seed}"
        assert m["precision_sensor"] >= 0.98, f"seed {seed}: {m['precision_sensor']:.4f}"
        assert m["w3_unsound_count_sensor"] == 0, f"seed {seed}"
        total += res.stats.motions
    assert total <= 2 * 3 * base.stats.motions, (total, base.stats.motions)


def test_beyond_ends_is_the_lid_line_past_its_ends_only():
    res = Resolution.of(1.0, noise=0.1)  # jitter 0.42
    a, b = np.array([0.0, 0.0]), np.array([0.0, 10.0])
    assert beyond_ends(res, a, b, [0.2, 14.0])  # on the line, past B
    assert beyond_ends(res, a, b, [-0.3, -3.0])  # on the line, before A
    assert not beyond_ends(res, a, b, [0.2, 5.0])  # on the lid itself
    assert not beyond_ends(res, a, b, [1.0, 14.0])  # past B, off the line
    assert not beyond_ends(Resolution.of(1.0), a, b, [0.0, 14.0])  # perfect sensing


def test_steep_enough_drops_grazing_sweep_passes_of_a_fine_sensor_only():
    a, b = np.array([0.0, 0.0]), np.array([10.0, 0.0])
    res = Resolution.of(1.0, noise=0.1)  # tan(alpha) must exceed 0.2
    shallow, steep = np.array([np.cos(0.1), -np.sin(0.1)]), np.array([np.cos(0.5), -np.sin(0.5)])
    assert not steep_enough(res, a, b, shallow) and steep_enough(res, a, b, steep)
    assert steep_enough(Resolution.of(1.0), a, b, shallow)  # perfect sensing
    coarse = Resolution.of(1.0, noise=0.3)  # jitter 1.27 > eps/2 - tol
    assert not resolves_half_eps(coarse) and steep_enough(coarse, a, b, shallow)
    assert resolves_half_eps(res) and not resolves_half_eps(Resolution.of(1.0))


def test_blockers_stop_passes_through_the_spot_a_pass_stopped_at_in_front():
    a, b = np.array([0.0, 0.0]), np.array([10.0, 0.0])  # V_i (free side) is y > 0
    blk = Blockers.of(Resolution.of(1.0, noise=0.1), reach=100.0)  # radius near = 0.52
    blk.add(a, b, joint=[5.0, 50.0], point=[5.0, -2.0])  # behind the lid: not kept
    assert blk.points == []
    blk.add(a, b, joint=[5.0, 50.0], point=[5.0, 20.0])  # in front of it: kept
    down = np.array([0.0, -1.0])
    assert blk.stops([5.3, 0.0], down)  # passes 0.3 from the blocker
    assert not blk.stops([7.0, 0.0], down)
    blk.add(a, b, joint=[9.0, 50.0], point=[8.6, 0.1])  # stopped a hair in front of the lid
    assert len(blk.points) == 2
    assert not blk.stops([9.1, 0.0], down)  # 0.51 from the sample: contour at the lid
    assert blk.stops([9.5, 0.0], np.array([0.8, -0.6]))  # 0.46 from it, 0.91 from the sample
    assert blk.off_lid(a, b, [5.0, 20.0]) and not blk.off_lid(a, b, [8.6, 0.1])
    off = Blockers.of(Resolution.of(1.0), reach=100.0)  # perfect sensing: inactive
    off.add(a, b, joint=[5.0, 50.0], point=[5.0, 20.0])
    assert not off.stops([5.0, 0.0], down)


def test_grazing_passes_that_end_at_a_touched_end_prove_no_w3():
    """The ``comb`` outline (seed 1), sensor seed 1001, sigma 0.1 eps: a lid
    1.66 eps long laid across a slot 1.5 eps wide near its top. Every pass
    through it ran within 6 degrees of the lid and met the wall 0.1 - 0.6
    eps below A_i, within eps/2 + 2 sigma of it: without
    :func:`steep_enough` in the revisit's "each ended at a touched end" the
    lid was W3 over the reachable slot (one unsound lid)."""
    loops = outline("comb", np.random.default_rng(1), 1.0)
    pts = np.concatenate(loops)
    ws = ((pts.min(0) + pts.max(0)) / 2, float(np.linalg.norm(np.ptp(pts, axis=0)) / 2 + 1.0))
    res = sense_slice(ExactContact(loops), ws, 1.0, sensor=SensorModel.of_eps(1.0, 0.1, 0.0, 1001))
    m = sensor_metrics(loops, res, 1.0, 0.1)
    assert m["w3_unsound_count_sensor"] == 0
    assert m["precision_sensor"] >= 0.98


def test_a_pass_beside_a_blocker_at_the_lid_enters_the_slot():
    """The ``comb`` outline (seed 0) at sigma 0.3 eps, taxels 0.25 eps, 15 reads, keyed
    sensor seed 1000 (the keyed sensor study's repeat 1): a lid along the top face
    spans the mouth of a slot 1.85 eps wide and 15 deep. The first pass stopped on the
    slot's corner, 0.51 eps from the lid sample of the one pass straight down the mouth;
    counted as a blocker there, it stopped that pass and the slot was never entered
    (0.969). A blocker within its radius of the sample is contour at the lid."""
    loops = outline("comb", np.random.default_rng(0), 1.0)
    pts = np.concatenate(loops)
    ws = ((pts.min(0) + pts.max(0)) / 2, float(np.linalg.norm(np.ptp(pts, axis=0)) / 2 + 1.0))
    res = sense_slice(ExactContact(loops), ws, 1.0,
                      sensor=SensorModel.of_eps(1.0, 0.3, 0.25, 1000, keyed=True, reads=15))
    m = sensor_metrics(loops, res, 1.0, 0.3)
    assert m["coverage_sensor"] >= 0.98, m["coverage_sensor"]
    assert m["precision_sensor"] >= 0.98 and m["w3_unsound_count_sensor"] == 0


def test_the_spread_enters_a_slot_whose_lid_is_free_over_its_mouth_only():
    """The ``comb`` outline (seed 0) at sigma 0.1 eps read once, one stream with its own
    seed 0 (the README's study): a lid along the top face, 6.3 eps long, is free only
    over the mouth of a slot 1.85 eps wide at its B end. The spread's positions 0.5, 0.1
    and 0.3 all fell on the first free sample, at the mouth's corner, and the passes
    straight down the mouth were never made: the slot was never entered (0.9659).
    Taking each free sample once per steer (``spread(distinct=True)``), they are:
    0.9993."""
    loops = outline("comb", np.random.default_rng(0), 1.0)
    pts = np.concatenate(loops)
    ws = ((pts.min(0) + pts.max(0)) / 2, float(np.linalg.norm(np.ptp(pts, axis=0)) / 2 + 1.0))
    res = sense_slice(ExactContact(loops), ws, 1.0, sensor=SensorModel.of_eps(1.0, 0.1, 0.0, 0))
    m = sensor_metrics(loops, res, 1.0, 0.1)
    assert m["coverage_sensor"] >= 0.99, m["coverage_sensor"]
    assert m["precision_sensor"] >= 0.98 and m["w3_unsound_count_sensor"] == 0
