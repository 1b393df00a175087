"""The ends of a lid closed as traced through other areas (:func:`core2d.planner.mouths.traced_gaps`):
A_i and B_i may lie up to the same-contact radius from the recorded chain, so the contour
between them and the chain is written W2 when it is longer than eps. Checked on a map of
straight pieces (the nearest points computed here by projection), with perfect sensing
(nothing written) and on a slice where the rule was read, against the same run without it."""
from __future__ import annotations

import numpy as np
import pytest

import core2d.planner.mouths as mouths
import core2d.planner.revisit as revisit
from core2d import SensorModel, sense_slice
from core2d.planner.known import KnownContour
from core2d.resolution import Resolution

COARSE = Resolution.of(1.0, noise=0.3, taxel=0.25)  # tip zone 2.02 eps, W2 distance 2.52
FINE = Resolution.of(1.0, noise=0.1)  # readings resolve eps/2: hops of eps or more cover nothing
PERFECT = Resolution.of(1.0)


def _map(res, *pieces):
    known = KnownContour(join=res.w2_dist)
    for piece in pieces:
        known.add(np.asarray(piece, float))
    return known


@pytest.mark.parametrize("a, b, chords", [
    ((0.5, 0.3), (9.5, -0.2), []),                               # both ends near the wall
    ((-1.6, 0.3), (9.5, -0.2), [((-1.6, 0.3), (0.0, 0.0))]),     # A 1.63 eps before the start
    ((0.5, 0.3), (8.0, 1.5), [((8.0, 0.0), (8.0, 1.5))]),        # B 1.5 eps off the wall
    ((3.0, -1.9), (11.8, 0.1), [((3.0, -1.9), (3.0, 0.0)), ((10.0, 0.0), (11.8, 0.1))]),
])
def test_an_end_farther_than_eps_is_joined_to_the_nearest_recorded_point(a, b, chords):
    known = _map(COARSE, [[0.0, 0.0], [4.0, 0.0], [10.0, 0.0]])
    gaps = mouths.traced_gaps(known, np.asarray(a, float), np.asarray(b, float),
                              COARSE.tip_zone, COARSE)
    assert len(gaps) == len(chords)
    for got, want in zip(gaps, chords):
        np.testing.assert_allclose(got, np.asarray(want, float), atol=1e-12)
        length = float(np.hypot(*(got[1] - got[0])))
        assert COARSE.eps < length <= COARSE.tip_zone  # within the W2 distance


def test_nothing_is_traced_when_no_chain_leads_from_a_to_b():
    known = _map(COARSE, [[0.0, 0.0], [4.0, 0.0]], [[7.0, 0.0], [10.0, 0.0]])  # a 3 eps hop
    assert mouths.traced_gaps(known, np.array([0.0, 0.5]), np.array([10.0, 0.5]),
                              COARSE.tip_zone, COARSE) is None
    assert not mouths.covered(known, np.array([0.0, 0.5]), np.array([10.0, 0.5]),
                              COARSE.tip_zone, COARSE)


def test_a_fine_sensor_keeps_the_mouth_rule_a_hop_of_eps_covers_nothing():
    known = _map(FINE, [[0.0, 0.0], [4.0, 0.0]], [[5.2, 0.0], [10.0, 0.0]])  # hop 1.2 eps
    args = (np.array([0.0, 0.2]), np.array([10.0, 0.2]), FINE.tip_zone)
    assert known.covers(*args)  # the map joins it (W2 distance 1.42 eps) ...
    assert mouths.traced_gaps(known, *args, FINE) is None  # ... but it may be a mouth


def test_perfect_sensing_writes_nothing():
    """The ends lie within the tip zone, eps/2, of the chain: never farther than eps."""
    rng = np.random.default_rng(5)
    known = _map(PERFECT, [[0.0, 0.0], [4.0, 0.0], [10.0, 0.0]])
    for _ in range(200):
        a = np.array([rng.uniform(0, 3), rng.uniform(-0.5, 0.5)])
        b = np.array([rng.uniform(7, 10), rng.uniform(-0.5, 0.5)])
        gaps = mouths.traced_gaps(known, a, b, PERFECT.tip_zone, PERFECT)
        assert gaps == []


END_CHORDS = mouths.end_chords  # the rule itself, whatever a test patched


def _outline_run(monkeypatch, kind, seed, sensor_seed, off=None, keyed=False):
    """``kind`` outline ``seed`` at sigma 0.3 eps, taxels 0.25 eps: the result, the end
    chords written (:func:`~core2d.planner.mouths.end_chords`), the loops. ``off``:
    "traced" -- areas traced through other areas write no end chords (those of
    :func:`~core2d.planner.mouths.traced_gaps`); "lies_on" -- lids lying along recorded
    contour write none (those of the revisit). The hops' and breaks' chords are written
    either way. ``keyed``: the sensor's noise keyed by reading (a run that planner changes
    elsewhere leave alone reads the same)."""
    from outlines import outline
    from slicer.contact.exact import ExactContact

    chords = []

    def counting(original, name):
        def wrapped(*args):
            gaps = original(*args)
            if gaps and off == name:
                return []  # as before the end chords: nothing written
            chords.extend(gaps)
            return gaps
        return wrapped

    monkeypatch.setattr(mouths, "end_chords", counting(END_CHORDS, "traced"))
    monkeypatch.setattr(revisit, "end_chords", counting(END_CHORDS, "lies_on"))
    loops = outline(kind, np.random.default_rng(seed), 1.0)
    pts = np.concatenate(loops)
    ws = ((pts.min(0) + pts.max(0)) / 2, float(np.linalg.norm(np.ptp(pts, axis=0)) / 2 + 1.0))
    res = sense_slice(ExactContact(loops), ws, 1.0,
                      sensor=SensorModel.of_eps(1.0, 0.3, 0.25, sensor_seed, keyed=keyed))
    return res, chords, loops


@pytest.mark.parametrize("kind, seed, sensor_seed, rule, keyed", [
    ("comb", 0, 0, "traced", False),    # 0.904 -> 0.990 (the hops' chords either way)
    ("star", 1, 4, "lies_on", True),    # 0.935 -> 1.000
])
def test_the_chords_show_the_openings_the_closures_hopped(monkeypatch, kind, seed, sensor_seed,
                                                          rule, keyed):
    """Read on these runs (sigma 0.3 eps, taxels 0.25 eps). ``comb`` seed 0: an area
    closed as traced whose chain started across the mouth of a slot narrower than the W2
    distance (eps + jitter, 2.52 eps), within the same-contact radius of A_i. ``star``
    seed 1 (keyed noise, sensor seed 4): lids closed as lying along recorded contour with
    an end farther than eps from it; their chords span openings narrower than the W2
    distance. Without the chords those openings were in neither W1, W2 nor an unknown
    lid; the chords approximate them (§3.1 at the sensor's resolution). Reachable coverage within eps/2 + 2 sigma as commented. The
    motions are the same: the chords go into the result, not into the map."""
    import shapely

    from core2d.truth.metrics import sensor_metrics

    without, _, loops = _outline_run(monkeypatch, kind, seed, sensor_seed, off=rule, keyed=keyed)
    with_, chords, _ = _outline_run(monkeypatch, kind, seed, sensor_seed, keyed=keyed)
    assert chords
    assert with_.stats.motions == without.stats.motions
    m0 = sensor_metrics(loops, without, 1.0, 0.3)
    m1 = sensor_metrics(loops, with_, 1.0, 0.3)
    assert m1["coverage_sensor"] >= m0["coverage_sensor"] + 0.04, \
        (m0["coverage_sensor"], m1["coverage_sensor"])
    assert m1["precision_sensor"] >= 0.98
    # each chord joins two points of the true contour and crosses no material
    # (an independent check: shapely distances to the outline's loops)
    tol = COARSE.eps / 2 + 2 * COARSE.noise
    solid = shapely.union_all([shapely.Polygon(lp) for lp in loops])
    boundary = solid.boundary
    for chord in chords:
        assert COARSE.eps < float(np.hypot(*(chord[1] - chord[0]))) <= COARSE.tip_zone
        along = shapely.points(chord[0] + np.linspace(0, 1, 41)[:, None] * (chord[1] - chord[0]))
        assert shapely.distance(shapely.points(chord), boundary).max() <= tol
        deep = shapely.contains(solid, along) & (shapely.distance(along, boundary) > tol)
        assert not deep.any()
