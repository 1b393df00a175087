"""A lid closed as traced because it lies along recorded contour
(:mod:`core2d.planner.along`): only contour recorded from A_i towards B_i counts.

With a noisy sensor, :func:`~core2d.planner.along.on_recorded` closes an area whose
lid lies within ``near`` of the record: two readings of one wall. In a slot narrower
than that radius a wall of C_B^A is within it too, recorded the other way:
a lid from one wall to the far corner of the slot's mouth then lay "on recorded
contour" and the slot behind it, C_A^B, was covered by nothing.
"""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from core2d.planner.along import on_recorded
from core2d.planner.known import KnownContour
from core2d.resolution import Resolution
from noisy_runs import outline_run

FINE = Resolution.of(1.0, noise=0.0775, taxel=0.25)  # sigma 0.3 eps read 16 times
WALL = np.array([[x, 0.0] for x in np.arange(0.0, 6.01, 0.25)])  # traced left to right


def _run(res, *pieces):
    known = KnownContour(join=res.w2_dist)
    for pl in pieces:
        known.add(pl)
    return SimpleNamespace(res=res, known=known)


def _lid(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return SimpleNamespace(a=a, b=b, dist=float(np.hypot(*(b - a))))


@pytest.mark.parametrize("a, b, lies_on", [
    ((1.0, 0.2), (5.0, 0.2), True),     # along the wall, a hair off it
    ((1.0, -0.1), (5.0, 0.1), True),    # a hair inside it
    ((5.0, 0.2), (1.0, 0.2), False),    # against the record: C_B^A
    ((1.0, 0.2), (5.0, 1.5), False)])   # its far end off the record
def test_a_lid_lies_on_contour_recorded_towards_b(a, b, lies_on):
    assert on_recorded(_run(FINE, WALL), _lid(a, b)) is lies_on


def test_in_a_slit_only_the_wall_recorded_towards_b_counts():
    """A slit 0.5 eps wide: the upper wall recorded right to left, the lower left to
    right. A lid inside it from left to right lies on the lower wall's record; with the
    lower wall unrecorded only the facing wall is near it, and it does not."""
    upper = WALL[::-1] + [0.0, 0.5]
    lid = _lid((1.0, 0.25), (5.0, 0.25))
    assert on_recorded(_run(FINE, upper, WALL), lid)
    assert not on_recorded(_run(FINE, upper), lid)
    assert on_recorded(_run(FINE, upper), _lid((5.0, 0.25), (1.0, 0.25)))


def test_perfect_sensing_keeps_the_papers_flow():
    assert not on_recorded(_run(Resolution.of(1.0), WALL), _lid((1.0, 0.0), (5.0, 0.0)))


@pytest.mark.parametrize("sensor_seed, least", [(20, 0.97), (1020, 0.98)])
def test_comb_slots_entered_past_a_lid_along_a_wall_recorded_the_other_way(sensor_seed, least):
    """``comb`` outline seed 20, sigma 0.3 eps + taxels 0.25 eps (16 reads). Seed 20:
    a lid from the left wall of a slot 0.72 eps wide (2.3 eps deep) to its right
    corner lay within ``near`` of the left wall, traced downwards, and was closed
    "on recorded contour": the slot's other 40 eps were covered by nothing
    (coverage within eps/2 + 2 sigma 0.926; now the slot is entered and traced,
    0.976; most of the rest is the bottom of a slot 0.51 eps wide, whose lid from its
    left corner to its right wall was closed by ``reversed_lid``: the chain up that
    wall passes within the same-contact radius of the left corner). Seed 1020: the
    same lid in the slot 0.72 eps wide, and two in the slot 0.51 eps wide
    (0.968 -> 1.000)."""
    res, m = outline_run("comb", 20, sensor_seed)
    assert m["coverage_sensor"] >= least, m["coverage_sensor"]
    assert m["precision_sensor"] >= 0.98 and m["w3_unsound_count_sensor"] == 0


def test_a_coarse_sensor_keeps_the_distance_alone():
    """Past eps/2 of jitter (sigma 1 eps, one read) the direction does not count."""
    coarse = Resolution.of(1.0, noise=1.0)
    assert not coarse.resolves_half_eps
    assert on_recorded(_run(coarse, WALL), _lid((5.0, 0.2), (1.0, 0.2)))
