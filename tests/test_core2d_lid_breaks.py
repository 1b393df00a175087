"""Contour the noisy planner closed as traced without recording it: the mouths of slots
under the breaks of the record (:func:`core2d.planner.mouths.record_gaps`) and under the hops
of a chain of recorded pieces (:func:`core2d.planner.mouths.traced_gaps`), written W2.

* a lid closed as traced because it lies along recorded contour writes W2 chords over
  the breaks of the record under it: a slot 0.81 eps wide of the ``comb`` outline, seed 0,
  whose mouth lay under such a lid was covered by nothing (sigma 0.3 eps with taxels
  0.25 eps, 15 reads, keyed sensor seed 2000: the sensor study's repeat 2);
* an area closed as traced through other areas writes W2 chords over the hops of its
  chain of recorded pieces: a slot 0.89 eps wide of the ``comb`` scene whose mouth the
  chain hopped was covered by nothing (sigma 0.1 eps, keyed sensor seed 7).
"""
from __future__ import annotations

import numpy as np
import pytest

from core2d import SensorModel, sense_slice
from core2d.planner.known import KnownContour
from core2d.planner.mouths import record_gaps, traced_gaps
from core2d.resolution import Resolution, repeated_reads
from core2d.truth.metrics import sensor_metrics
from slicer.contact.exact import ExactContact

FINE = Resolution.of(1.0, noise=0.3 / np.sqrt(15), taxel=0.25)  # near 0.55 eps


def _known(*pieces):
    known = KnownContour(join=FINE.w2_dist)
    for p in pieces:
        known.add(np.asarray(p, float))
    return known


@pytest.mark.parametrize("pieces, gaps", [
    # two pieces along the lid with a break of 1.2 eps: one chord joining them
    ([[[0, 0], [3, 0]], [[4.2, 0.1], [8, 0]]], [[[3, 0], [4.2, 0.1]]]),
    # the second piece read against the lid's direction: the same break
    ([[[0, 0], [3, 0]], [[8, 0], [4.2, 0.1]]], [[[3, 0], [4.2, 0.1]]]),
    # overlapping pieces, and a break narrower than the fan spacing: none
    ([[[0, 0], [5, 0]], [[4, 0.1], [8, 0]]], []),
    ([[[0, 0], [3, 0]], [[3.2, 0], [8, 0]]], []),
    # a piece farther from the lid than near (a wall behind it) fills nothing
    ([[[0, 0], [3, 0]], [[3.3, -0.8], [3.9, -0.8]], [[4.2, 0], [8, 0]]], [[[3, 0], [4.2, 0]]]),
    # a break as wide as the W2 distance (1.45 eps) or wider is no chord
    ([[[0, 0], [3, 0]], [[4.6, 0], [8, 0]]], []),
    # a piece crossing the band counts where it lies within it: the chords end where
    # it enters and leaves the band
    ([[[0, 0], [3, 0]], [[4, 2], [4, -2]], [[5, 0], [8, 0]]],
     [[[3, 0], [4, 0.55]], [[4, -0.55], [5, 0]]]),
])
def test_the_breaks_of_the_record_along_a_lid(pieces, gaps):
    got = record_gaps(_known(*pieces), (0.0, 0.0), (8.0, 0.0), FINE)
    assert len(got) == len(gaps)
    for g, want in zip(got, gaps):
        np.testing.assert_allclose(g, want, atol=0.01)


BASE = [[[0, 0], [3, 0]], [[3.2, 0], [8, 0]]]


@pytest.mark.parametrize("extra, b, gaps", [
    # the last piece along the lid ends 1.2 eps before B_i, a reading 0.1 eps from
    # the record (a piece starting past B_i): a chord to B_i
    ([[[9.3, 0], [12, 0]]], (9.2, 0.0), [[[8, 0], [9.2, 0]]]),
    # B_i 1.3 eps from the record: end_chords' chord, none here
    ([], (9.3, 0.0), []),
])
def test_a_break_between_an_end_and_the_record(extra, b, gaps):
    """A_i and B_i are readings: where they lie within eps of the record
    (end_chords writes nothing for them) the stretch of the lid between an end
    and the nearest piece along it is a break like any other."""
    known = _known(*BASE, *extra)
    for forward in (True, False):  # and the lid read from B_i to A_i
        lid = ((0.0, 0.0), b) if forward else (b, (0.0, 0.0))
        got = record_gaps(known, *lid, FINE)
        assert len(got) == len(gaps)
        for g, w in zip(got, gaps):
            np.testing.assert_allclose(g if forward else g[::-1], w, atol=0.01)
    assert (known.distance(np.array(b)) <= FINE.eps) == bool(gaps)


def test_no_break_without_a_record_or_a_lid():
    assert record_gaps(_known(), (0.0, 0.0), (8.0, 0.0), FINE) == []
    assert record_gaps(_known([[0, 0], [3, 0]]), (1.0, 0.0), (1.0, 0.0), FINE) == []


def test_the_hops_of_a_chain_are_w2_with_a_noisy_sensor_only():
    """Three pieces along a wall, joined across 0.6 and 0.2 eps: the chain from A to B
    hops both; the hop wider than the fan spacing (eps/4) is a W2 chord with a noisy
    sensor, none with perfect sensing (the paper's output stays as it was)."""
    pieces = [[[0, 0], [3, 0]], [[3.6, 0], [6, 0]], [[6.2, 0], [9, 0]]]
    known = _known(*pieces)
    hops = known.hops((0.0, 0.0), (9.0, 0.0), 0.5)
    np.testing.assert_allclose(hops, [[[3, 0], [3.6, 0]], [[6, 0], [6.2, 0]]])
    assert known.hops((9.0, 0.0), (0.0, 0.0), 0.5) is None  # against the pieces
    np.testing.assert_allclose(traced_gaps(known, (0, 0), (9, 0), 0.5, FINE), [hops[0]])
    # a sensor that does not resolve eps/2 (sigma 0.3 eps read once) chords hops below eps
    # only: its W2 distance, 2.52 eps, is as wide as the slots it misses
    coarse = Resolution.of(1.0, noise=0.3, taxel=0.25)
    known = KnownContour(join=coarse.w2_dist)
    for p in ([[0, 0], [3, 0]], [[3.6, 0], [6, 0]], [[7.2, 0], [9, 0]]):
        known.add(np.asarray(p, float))
    np.testing.assert_allclose(traced_gaps(known, (0, 0), (9, 0), 0.5, coarse),
                               [[[3, 0], [3.6, 0]]])  # not the hop of 1.2 eps
    perfect = Resolution.of(1.0)
    known = KnownContour(join=perfect.eps)
    for p in pieces:
        known.add(np.asarray(p, float))
    assert traced_gaps(known, (0, 0), (9, 0), 0.5, perfect) == []


@pytest.mark.parametrize("z, seed", [(7, 7), (2, 2)], ids=["hop", "lid-across-the-mouth"])
def test_the_comb_scenes_slot_under_a_hop_or_a_lid_is_covered(z, seed):
    """The ``comb`` scene at sigma 0.1 eps read once, keyed sensor seed = z (the sensor
    study's repeat 0), the slot 0.89 eps wide and 84 eps deep at x 17.35:

    * z7: an area closed as traced through other areas by a chain of recorded pieces
      that hops the slot's mouth. Without the hop's W2 chord the slot (168 eps of
      contour) was covered by nothing: 0.835 instead of 0.914.
    * z2: a lid from the slot's left wall 2.5 eps deep to the far corner of its mouth.
      It was closed as lying along the record, and before the break at its end was
      written W2 the slot was covered by nothing: 0.825 instead of 0.906. The record
      beside the lid is the left wall above A_i, recorded downwards (contour before
      A_i), so :func:`~core2d.planner.along.on_recorded` no longer closes it: its passes
      enter the slot, whose contour they trace or approximate (the break at an end is
      tested above and on the ``comb`` outline below).

    The bound on the slice's coverage is the one it met while the slot 0.32 eps wide that
    the trace steps over was recorded as traced (noiseless z7 0.916); read as a Case 2 jump
    since (:func:`core2d.sim.compliance.overhangs`), noiselessly z7 covers 0.998."""
    import meshes
    import slicer
    from noisy_runs import scene_slice, slot_covered

    res, m = scene_slice("comb", z, 0.1, 0.0, seed, keyed=True)
    mesh = meshes.load("comb")
    eps = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)) / 200)
    loops = [np.asarray(lp) for lp in slicer.slice_mesh(mesh, axis="z", count=8)[z].loops]
    if z == 7:
        assert _spans_mouth(res.w2, loops[0], 17.35, eps), "no W2 chord over the slot's mouth"
    else:
        share = slot_covered(res, loops, 17.35, eps, eps / 2 + 2 * 0.1 * eps)
        assert share >= 0.95, share
    assert m["coverage_sensor"] >= 0.9, m["coverage_sensor"]
    assert m["precision_sensor"] >= 0.98 and m["w3_unsound_count_sensor"] == 0


def _spans_mouth(w2, loop, x, eps) -> bool:
    """Does a W2 chord of ``w2`` join the two sides of the mouth of the slot at ``x`` in the
    top face of ``loop`` (the mouth read from the outline): its ends within eps of the top,
    beside the mouth's middle half?"""
    top = loop[:, 1].max()
    xs = np.sort(loop[np.isclose(loop[:, 1], top) & (np.abs(loop[:, 0] - x) < eps), 0])
    assert len(xs) == 2, xs
    quarter = (xs[1] - xs[0]) / 4
    w2 = np.array(w2)
    lo, hi = w2[:, :, 0].min(axis=1), w2[:, :, 0].max(axis=1)
    on_top = (np.abs(w2[:, :, 1] - top) < eps).all(axis=1)
    return bool((on_top & (lo <= xs[0] + quarter) & (hi >= xs[1] - quarter)).any())


def _comb_0():
    from outlines import outline

    loops = outline("comb", np.random.default_rng(0), 1.0)
    pts = np.concatenate(loops)
    lo, hi = pts.min(0), pts.max(0)
    return loops, ((lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2 + 1.0))


def _sense(loops, ws, seed):
    sensor = SensorModel.of_eps(1.0, 0.3, 0.25, seed, keyed=True,
                                reads=repeated_reads(1.0, 0.3, 0.25))
    res = sense_slice(ExactContact(loops), ws, 1.0, sensor=sensor)
    return res, sensor_metrics(loops, res, 1.0, 0.3)


def test_a_slot_under_a_lid_along_the_record_is_approximated_w2():
    """Keyed seed 2000: a lid along the top face, 7.6 eps long, passes over the mouth of
    the slot 0.81 eps wide (x 27.79 - 28.60) and lies within near of the record at every
    sample; it was closed as traced, and the slot (56 eps of contour) was covered by
    nothing: 0.925. With the record's break written W2, the chord spans the mouth, and
    §3.1 approximates the slot behind it (Dist < eps + the jitter)."""
    loops, ws = _comb_0()
    res, m = _sense(loops, ws, 2000)
    assert _spans_mouth(res.w2, loops[0], 28.2, 1.0), "no W2 chord over the slot's mouth"
    assert m["coverage_sensor"] >= 0.99, m["coverage_sensor"]
    assert m["precision_sensor"] >= 0.98 and m["w3_unsound_count_sensor"] == 0
