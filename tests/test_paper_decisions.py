"""The paper's own decisions, each shown to decide a whole slice (or shown not to).

Four decisions of the paper can be changed through :class:`core2d.planner.flow.Flow`
(``detection``, ``pair``, ``lifo``, ``same``). On the built-in scenes the
default planner reaches the same coverage with each changed: its deferral,
revisits and audit take their job over. Here each runs on a whole slice of
``figure_scenes.py`` (exact contact, eps = 1, bootstrap from the workspace
ring) under ``--method paper`` (:data:`~core2d.planner.flow.PAPER`), where
no addition covers for it, and the test fails when the decision is removed:

* single probe detection (Fig. 6, §4.2.1): without it an area whose A_i and
  B_i lie on one posture has the degenerate G_i of Definition 1 and is W3
  at once -- a lid over reachable contour. The planner makes the detection
  where the area is registered (Fig. 12(c), Case 2-1) or, failing that,
  when it is processed; either covers for the other, so only removing both
  (``detection``) changes a slice;
* Case 2-1 registers (P_1st, P_2nd) (§4.3.3): without it the contour the tip
  jumped over is held by no area and is never traced;
* the same-contact radius eps/2: at 2 eps a Theorem 1 pass that found new
  contact is taken for a repeat of A_i or B_i, and the area is W3 (§4.2.1);
* the order of processing areas: with no map the areas share nothing but
  the probe, so last-registered-first senses the same slice with the same
  motions (it cannot matter under the paper's flow).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from core2d.planner.flow import PAPER, PULLING
from core2d.planner.run import explore
from core2d.sim.probe import Probe
from core2d.truth.metrics import slice_metrics
from figure_scenes import EPS, HILL, OVERHANG_LEFT, WORKSPACE, block
from slicer.contact.exact import ExactContact

_CACHE = {}


def sensed(top, flow):
    """(SliceResult, metrics) of the whole block slice with top edge ``top``."""
    key = (tuple(top), flow)
    if key not in _CACHE:
        loops = block(top)
        res = explore(Probe(ExactContact(loops), WORKSPACE, EPS), EPS, flow=flow)
        _CACHE[key] = res, slice_metrics(loops, res, EPS)
    return _CACHE[key]


def _sound(m) -> bool:
    return m["coverage"] >= 0.99 and m["w3_unsound_count"] == 0


def test_single_probe_detection_decides_the_hill_slice():
    """Fig. 12(c) areas (D_i, Q) of the hill slice lie on one posture: the
    pivot about the tip gives them a G_i to pass through. Without it they
    are W3 at once and hide a fifth of the reachable contour."""
    _, m = sensed(HILL, PAPER)
    _, off = sensed(HILL, replace(PAPER, detection=False))
    assert _sound(m), m
    assert off["coverage"] < 0.9 and off["w3_unsound_count"] >= 1, off


def test_single_probe_detection_is_taken_over_by_deferral_and_revisits():
    """The default flow defers the same areas and revisits them: sound, at the
    price of more motions."""
    res, m = sensed(HILL, replace(PULLING, detection=False))
    _, base = sensed(HILL, PULLING)
    assert _sound(m) and _sound(base)
    assert any(a.rule == "revisit" for a in res.areas)
    assert m["motions"] > base["motions"]


def test_case_2_1_pair_decides_the_overhang_slice():
    """The tip jumps over the lip of the overhang (Case 2-1); (P_1st, P_2nd)
    holds the wall under it. Dropped, that wall is never traced."""
    res, m = sensed(OVERHANG_LEFT, PAPER)
    _, off = sensed(OVERHANG_LEFT, replace(PAPER, pair=False))
    assert any(a.rule == "case2-1" for a in res.areas)
    assert m["coverage"] >= 0.99, m
    assert off["coverage"] < m["coverage"] - 0.03, (m["coverage"], off["coverage"])


def test_case_2_1_pair_is_not_fully_taken_over_by_the_audit():
    """The default flow's audit registers loose ends again, but not all of the
    contour a dropped (P_1st, P_2nd) held."""
    _, m = sensed(OVERHANG_LEFT, PULLING)
    _, off = sensed(OVERHANG_LEFT, replace(PULLING, pair=False))
    assert m["coverage"] >= 0.99 and off["coverage"] < m["coverage"] - 0.01


def test_same_contact_radius_decides_the_overhang_slice():
    """At 2 eps a pass that found new contact near A_i or B_i is read as the
    same contact: more W3 lids, over reachable contour."""
    _, m = sensed(OVERHANG_LEFT, PAPER)
    _, wide = sensed(OVERHANG_LEFT, replace(PAPER, same=4.0))
    assert wide["w3_unsound_count"] > m["w3_unsound_count"]
    assert wide["coverage"] < m["coverage"] - 0.01


def _lids(res):
    return sorted(tuple(np.round(lid, 9).ravel()) for lid in res.w3)


@pytest.mark.parametrize("top", [OVERHANG_LEFT, HILL], ids=["overhang", "hill"])
def test_area_order_cannot_matter_in_the_paper_flow(top):
    """Without the map the areas share nothing but the probe: processed last
    registered first, the same areas are processed in another order, and
    the slice is sensed the same (W1, W2, W3, motions)."""
    fifo, m = sensed(top, PAPER)
    lifo, m2 = sensed(top, replace(PAPER, lifo=True))
    assert [a.rule for a in fifo.areas] != [a.rule for a in lifo.areas]  # another order
    assert m["motions"] == m2["motions"] and m["coverage"] == m2["coverage"]
    assert _lids(fifo) == _lids(lifo)
    np.testing.assert_allclose(sum(len(p) for p in fifo.w1), sum(len(p) for p in lifo.w1))
