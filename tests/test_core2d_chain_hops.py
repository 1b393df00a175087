"""The record's gaps under a lid traced through other areas, with a noisy sensor
(:meth:`core2d.planner.known.KnownContour.hops`, :func:`core2d.planner.mouths.traced_gaps`).

A hop of the chain is the record's own gap: from one piece's last point to the point where
the next piece passes it, not to that piece's first point. A hop of eps or more makes a fine
sensor's ``traced_gaps`` refuse the chain (it may be a mouth), so a hop measured to a piece
that begins back along the wall left lids over traced slots unknown, each after its revisit
passes. Maps of straight pieces; the distances here are computed by hand.
"""
from __future__ import annotations

import numpy as np

from core2d.planner.known import KnownContour
from core2d.planner.mouths import traced_gaps
from core2d.resolution import Resolution

FINE = Resolution.of(1.0, noise=0.1)  # W2 distance 1.42 eps; readings resolve eps/2


def _map(*pieces):
    known = KnownContour(join=FINE.w2_dist)
    for piece in pieces:
        known.add(np.asarray(piece, float))
    return known


def test_a_hop_ends_where_the_next_piece_passes_the_last_point():
    # the second piece starts 1 eps back along the wall and passes the first's end 0.1 off
    known = _map([[0.0, 0.0], [4.0, 0.0]], [[3.0, 0.1], [8.0, 0.1]])
    a, b = np.array([0.5, 0.0]), np.array([7.5, 0.1])
    hops = known.hops(a, b, FINE.tip_zone)
    assert len(hops) == 1
    np.testing.assert_allclose(hops[0], [[4.0, 0.0], [4.0, 0.1]], atol=1e-12)
    assert traced_gaps(known, a, b, FINE.tip_zone, FINE) is not None  # a gap of 0.1 eps


def test_a_real_gap_of_eps_still_refuses_the_chain():
    known = _map([[0.0, 0.0], [4.0, 0.0]], [[5.2, 0.0], [10.0, 0.0]])  # hop 1.2 eps
    a, b = np.array([0.0, 0.2]), np.array([10.0, 0.2])
    assert known.covers(a, b, FINE.tip_zone)
    assert traced_gaps(known, a, b, FINE.tip_zone, FINE) is None
