"""Two separate objects in one slice (outside §3.2's single object), far apart.

The slice: two circles of radius 1.5 (about 4 eps) whose centres lie about
50 apart -- slice 7 of 16 along x of a torus r = 1.5, R = 25 tilted 60
degrees (``bench.bench_surface.tilted_ring``), rebuilt here as two 24-gons,
exact contact, eps as in that run (its bounding-box diagonal / 200).

Only two of the bootstrap's insertions touch anything, one per circle. The
two contacts are two unknown areas, C_A^B and C_B^A -- the contour round
each side. Their lids run through the 50-wide gap; passes through them
leave into F (the areas end ``open``) and never reach the far sides of the
circles, which face away from the gap. What carries the exploration on is
the robot's map: the recorded contour of each circle stops at a loose end
and begins again at a loose start, and the audit registers the stretch
between them.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np
from core2d.planner.bootstrap import bootstrap
from core2d.planner.flow import PULLING
from core2d.planner.known import KnownContour
from core2d.planner.loose_ends import recorded_stops
from core2d.planner.run import explore
from core2d.sim.probe import Probe
from core2d.truth.metrics import slice_metrics
from slicer.contact.exact import ExactContact

EPS = 0.3787  # the tilted ring's bounding-box diagonal / 200
CENTRE = np.array([12.46, 21.60])  # the upper circle; the lower one at -CENTRE
WORKSPACE = (np.zeros(2), 26.44 + EPS)  # the slice's bounding circle + eps


def _two_circles(n=24, r=1.5):
    t = 2 * np.pi * np.arange(n) / n
    ring = r * np.c_[np.cos(t), np.sin(t)]
    return [CENTRE + ring, -CENTRE + ring]


_CACHE = {}


def _sensed(flow=PULLING):
    if flow not in _CACHE:
        loops = _two_circles()
        res = explore(Probe(ExactContact(loops), WORKSPACE, EPS), EPS, flow=flow)
        _CACHE[flow] = res, slice_metrics(loops, res, EPS)
    return _CACHE[flow]


def test_both_circles_are_traced_all_round():
    """The far side of each circle (what the open lids do not reach) is
    traced: reachable coverage 1, no budget hit, nothing left unknown."""
    res, m = _sensed()
    assert not res.stats.budget_hit and res.stats.pushes == 0
    assert [a.outcome for a in res.areas if a.rule == "bootstrap"] == ["split", "split"]
    assert any(a.outcome == "open" for a in res.areas)  # the lids across the gap
    assert any(a.rule == "audit" for a in res.areas)  # ... do not end the exploration
    assert m["coverage"] >= 0.999, m["coverage"]
    assert m["unknown_count"] == 0 and m["w3_count"] == 0 and m["precision"] >= 0.99


def test_two_contacts_make_the_two_sides_of_the_contour():
    """The bootstrap with two contacts registers C_A^B and C_B^A, never the
    same area twice."""
    loops = _two_circles()
    probe = Probe(ExactContact(loops), WORKSPACE, EPS)
    first, second = bootstrap(probe)
    np.testing.assert_array_equal(first.a, second.b)
    np.testing.assert_array_equal(first.b, second.a)
    assert first.pose_a is second.pose_b and first.pose_b is second.pose_a


def test_a_trace_end_with_a_short_chord_on_it_is_still_a_loose_end():
    """A W2 chord shorter than ``join`` laid at the end of a trace, and the
    same stretch recorded twice, continue nothing: the contour beyond is
    unrecorded. A chain of short chords that runs on does continue it."""
    k = KnownContour(join=0.4)
    k.add([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]])
    k.add([[2.0, 0.0], [2.1, -0.05]])  # a short chord at the trace's end
    k.add([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]])  # the same stretch again
    ends, starts = recorded_stops(k)
    assert len(ends) == 1 and np.hypot(*(ends[0][0] - [2.0, 0.0])) <= 0.4
    assert len(starts) == 1 and np.allclose(starts[0][0], [0.0, 0.0])
    for x in np.arange(2.1, 3.0, 0.1):  # short chords running on, 0.1 each
        k.add([[x, 0.0], [x + 0.1, 0.0]])
    ends, _ = recorded_stops(k)  # where the recorded contour stops
    assert len(ends) == 1 and np.allclose(ends[0][0], [3.0, 0.0])


def test_a_piece_shorter_than_join_is_continued_whichever_way_it_points():
    """A trace step recorded as a piece a hair long (here pointing back) has
    no direction to read: the trace running on from its end continues it."""
    k = KnownContour(join=0.4)
    k.add([[0.0, 0.0], [1.0, 0.0]])
    k.add([[1.0, 0.0], [1.0 - 1e-4, 0.0]])
    k.add([[1.0, 0.0], [2.0, 0.0]])
    ends, _ = recorded_stops(k)
    assert len(ends) == 1 and np.allclose(ends[0][0], [2.0, 0.0])


def test_contour_left_untraced_is_reported_unknown():
    """Without the audit the open lids leave the far sides of both circles
    untraced. They are not dropped: each lies under an unknown chord from
    the loose end to the loose start (rule "loose"), so the reachable
    contour is covered or reported unknown, all of it."""
    res, m = _sensed(replace(PULLING, audit=False))
    assert m["coverage"] < 0.9  # the far sides are not traced
    loose = [a for a in res.areas if a.rule == "loose"]
    assert len(loose) == 2 and all(a.outcome == "unknown" for a in loose)
    assert m["unknown_count"] == 2 and not res.stats.budget_hit
    assert m["covered_length"] + m["unknown_reachable_length"] >= 0.999 * m["reachable_length"]
