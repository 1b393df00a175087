"""Short lids under a coarse noisy sensor (sigma 0.3 eps, taxels 0.25 eps):
:mod:`core2d.planner.short_lids`.

Two 16-gons 13 eps across (the handle of the built-in ``cup_handle``,
slices z6 / z7): their sides are 2.6 eps long, so the lids A_iB_i over
their arcs are 2.5 - 4 eps long -- longer than the W2 distance eps + jitter
(2.52 eps) and shorter than twice the same-contact radius eps/2 + jitter
(4.04 eps). With that radius such a lid had no point farther than it from
both ends: no pass could find a new contact, the W3 proof had no line to
check, and its middle lay within ``near`` of the ends' recorded pieces, so
the lid was closed without a pass (``unknown``, or "traced" on the map).
"""
from __future__ import annotations

import numpy as np

from core2d.planner.grazing import end_radius
from core2d.planner.short_lids import lid_end_radius, on_map
from core2d.resolution import Resolution
from noisy_runs import coverages

_T = np.linspace(0.0, 2 * np.pi, 16, endpoint=False)
_RING = 6.6 * np.c_[np.cos(_T), np.sin(_T)]
TWO_RINGS = [_RING + [0.0, 18.0], _RING - [0.0, 18.0]]
WORKSPACE = (np.zeros(2), 26.6)


def test_a_short_lid_keeps_a_middle_band():
    coarse, fine = Resolution.of(1.0, noise=0.3, taxel=0.25), Resolution.of(1.0, noise=0.1)
    assert lid_end_radius(coarse, 3.5) == 1.5  # Dist/2 - eps/4: a band eps/2 wide
    assert lid_end_radius(coarse, 2.6) == 1.05
    assert lid_end_radius(coarse, 10.0) == end_radius(coarse)  # a long lid: unchanged
    for dist in (1.5, 3.0, 10.0):  # perfect and fine sensors: unchanged
        assert lid_end_radius(fine, dist) == end_radius(fine) == 0.5
        assert lid_end_radius(Resolution.of(1.0), dist) == 0.5
        assert on_map(fine, dist) == fine.near
    assert on_map(coarse, 3.5) == 1.5 < coarse.near  # the band is off the map
    assert on_map(coarse, 10.0) == coarse.near


def test_short_lids_over_small_rings_at_sigma_03_eps():
    covs = coverages(TWO_RINGS, WORKSPACE, 0.3, range(6), taxel=0.25)
    assert covs.mean() >= 0.99, covs
