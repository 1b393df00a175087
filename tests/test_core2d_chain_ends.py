"""The ends of a chain "traced through other areas", and a mouth whose inside
was closed along one wall (:mod:`core2d.planner.mouths`).

With a noisy sensor the chain of recorded pieces from A_i to B_i may start on a
piece other than A_i's own, across an opening narrower than the same-contact
radius: the gap from A_i to where the chain starts is a hop like the others
(:func:`~core2d.planner.mouths.traced_gaps`). A processed mouth whose inside the
revisit closed along a wall it cannot tell from the other is W2
(:func:`~core2d.planner.mouths.close_unresolved`).
"""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from core2d.planner import mouths, revisit
from core2d.planner import run as run_module
from core2d.planner.areas import Area
from core2d.planner.known import KnownContour
from core2d.planner.mouths import ALONG_RECORD, close_unresolved, traced_gaps
from core2d.planner.run import Budget, Exploration
from core2d.resolution import Resolution
from noisy_runs import outline_run

FINE = Resolution.of(1.0, noise=0.0775, taxel=0.25)  # sigma 0.3 eps read 16 times: jitter 0.45
PERFECT = Resolution.of(1.0)
B = np.array([7.0, 0.0])


def _far_wall(start: float) -> KnownContour:
    """One recorded piece from (start, 0) to B, nothing through A_i."""
    known = KnownContour(join=FINE.w2_dist)
    known.add(np.array([[start, 0.0], B]))
    return known


def test_hops_with_ends_give_the_gaps_to_where_the_chain_starts_and_ends():
    known = _far_wall(0.9)
    assert known.hops((0.0, 0.0), B, 0.95) == []
    first, last = known.hops((0.0, 0.0), (7.2, 0.0), 0.95, ends=True)
    assert np.allclose(first, [[0.0, 0.0], [0.9, 0.0]])
    assert np.allclose(last, [[7.0, 0.0], [7.2, 0.0]])
    assert known.hops((-0.2, 0.0), B, 0.95, ends=True) is None  # no piece within tol


@pytest.mark.parametrize("a, chord", [
    (0.0, True),    # 0.90 eps from the chain's start: the slot mouth of the star case
    (0.35, True),   # 0.55 eps: wider than the jitter
    (0.6, False)])  # 0.30 eps: the scatter of A_i's own reading
def test_the_gap_from_a_to_the_chain_start_is_a_w2_chord_past_the_jitter(a, chord):
    gaps = traced_gaps(_far_wall(0.9), (a, 0.0), B, FINE.tip_zone, FINE)
    assert gaps is not None  # covered: the gap is narrower than eps
    assert len(gaps) == int(chord)
    if chord:
        assert np.allclose(gaps[0], [[a, 0.0], [0.9, 0.0]])


def test_a_chain_starting_eps_away_covers_nothing_with_a_fine_sensor():
    assert traced_gaps(_far_wall(1.05), (0.0, 0.0), B, 1.2, FINE) is None
    # perfect sensing: the paper's flow as it was (an end within eps of the record)
    assert traced_gaps(_far_wall(0.9), (0.0, 0.0), B, 0.95, PERFECT) == []


def test_star_slot_whose_mouth_a_chain_started_across():
    """``star`` outline seed 21, sensor seed 2021, sigma 0.3 eps + taxels 0.25 eps
    (16 reads): a Case 2-1 area over a slot mouth 0.89 eps wide read 1.05 eps; the
    chain to B_i started on the piece across the mouth, 0.93 eps from A_i, and the
    area was closed as traced with no chord: the slot's 30 eps of contour were
    covered by nothing (coverage within eps/2 + 2 sigma 0.910 before, 1.000 now)."""
    res, m = outline_run("star", 21, 2021)
    assert m["coverage_sensor"] >= 0.98, m["coverage_sensor"]
    assert m["precision_sensor"] >= 0.98 and m["w3_unsound_count_sensor"] == 0


def _mouth_with_kids(kids):
    """A processed Case 2-1 mouth reading 1.2 eps, split into children closed as
    ``kids`` gives them ((outcome, note) each)."""
    probe = SimpleNamespace(resolution=FINE, length=20.0, motions=7)
    run = Exploration(probe, 1.0, Budget(probe))
    area = Area(np.array([0.0, 0.0]), np.array([1.2, 0.0]), None, None, rule="case2-1",
                mouth=True)
    run.add(area)
    run.mouths.append(area)
    run.close(area, "split")
    for k, (outcome, note) in enumerate(kids):
        kid = Area(np.array([0.1 * k, -1.0]), np.array([0.1 * k + 0.5, -1.0]), None, None,
                   parent=area.index, rule="revisit")
        run.add(kid)
        run.close(kid, outcome, note)
    return run, area


@pytest.mark.parametrize("kids, closed", [
    ((("W2", "Dist(A,B) < eps"), ("traced", ALONG_RECORD[1])), True),
    ((("traced", ALONG_RECORD[0]),), True),
    ((("W2", "Dist(A,B) < eps"), ("traced", "C_A^B traced through other areas")), False)])
def test_a_mouth_closed_along_one_wall_inside_is_w2(kids, closed):
    run, area = _mouth_with_kids(kids)
    assert close_unresolved(run) == int(closed)
    rec = run.result.areas[area.index]
    assert (rec.outcome == "W2") is closed
    assert ("closed along a wall" in rec.note) is closed


def test_comb_slot_entered_through_its_mouth_and_closed_along_one_wall():
    """``comb`` outline seed 20, sensor seed 1020, sigma 0.3 eps + taxels 0.25 eps
    (16 reads): a slot 0.84 eps wide and 30 eps deep read 1.08 eps across its
    mouth and was entered; one wall was traced part way and a lid from it to the
    far corner closed along it (its other wall within ``near``). Without the
    mouth's W2 the rest of the slot was covered by nothing: coverage within
    eps/2 + 2 sigma 0.897, 0.968 with it (the slots narrower than eps elsewhere
    on the comb keep it under 0.98)."""
    res, m = outline_run("comb", 20, 1020)
    closed = [r for r in res.areas if r.outcome == "W2" and "closed along a wall" in r.note]
    assert len(closed) >= 1
    assert m["coverage_sensor"] >= 0.95, m["coverage_sensor"]
    assert m["precision_sensor"] >= 0.98 and m["w3_unsound_count_sensor"] == 0


def _without_ends(known, a, b, tol, res):
    """traced_gaps as it was before the chain's ends were measured (the hops alone)."""
    hops = known.hops(a, b, tol)
    if hops is None:
        return None
    widths = [float(np.hypot(*(h[1] - h[0]))) for h in hops]
    if mouths.resolves_half_eps(res) and max(widths, default=0.0) >= res.eps:
        return None
    ends = mouths.end_chords(known, a, b, res)
    return ends + [h for h, w in zip(hops, widths)
                   if res.fan_spacing < w < mouths._chord_limit(res)]


@pytest.mark.parametrize("kind, seed, sensor_seed", [("star", 1, 1), ("undercut", 4, 2004)])
def test_the_chain_ends_add_chords_and_leave_the_motions_as_they_were(
        monkeypatch, kind, seed, sensor_seed):
    """The ends' gaps are measured to the chain's nearest point and count within
    ``tol`` of A_i and B_i: a chain whose walk begins on a piece reached from another
    (a cycle of continuations) does not start at A_i. Measured to its first point
    the gap read 1.3 - 1.9 eps on ``star-1`` at sigma 0.1 (sensor seed 1): the area
    was processed instead of closed, 1,084 -> 1,214 motions; counted past ``tol``
    (the chain's nearest point 14 eps from A_i on ``undercut-4``, sensor seed 2004),
    2,175 -> 2,201. As kept, the rule only writes chords: the same motions and W1,
    as much W2 or more."""
    now, _ = outline_run(kind, seed, sensor_seed, noise=0.1, taxel=0.0)
    for module in (run_module, revisit):
        monkeypatch.setattr(module, "traced_gaps", _without_ends)
    before, _ = outline_run(kind, seed, sensor_seed, noise=0.1, taxel=0.0)
    assert now.stats.motions == before.stats.motions
    assert len(now.w1) == len(before.w1)
    assert all(np.array_equal(p, q) for p, q in zip(now.w1, before.w1))
    assert len(now.w2) >= len(before.w2)
    if kind == "star":
        assert len(now.w2) > len(before.w2)
