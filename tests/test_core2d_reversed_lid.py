"""A lid laid along a traced wall, read backwards, is traced, not unknown.

``../shared/cases/star_w3_lids_across_interior.json`` (a star whose slender
slit 6-7-8 runs 36 units into the solid, about 2 eps wide at its mouth) was
reported with ten W3 lids across the solid's interior; the planner no longer
makes W3 there, but a Case 2-2 split at a contact on the slit's far wall left
a child whose lid runs along the traced lower wall, read from B to A. Six
passes found nothing new behind it (there is nothing: the lid lies on the
wall) and it was reported as an unknown chord whose C_A^B is the rest of the
loop (673 of 703 units). ``along.reversed_lid`` closes such an area as
traced. The same happens on the built-in ``numerics`` outline of seed 1, so
the rule is tested without ``../shared`` too.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from outlines import outline

from core2d import sense_slice
from core2d.truth.metrics import slice_metrics
from slicer.contact.exact import ExactContact

CASE = Path(__file__).resolve().parents[1].parent / "shared" / "cases" / \
    "star_w3_lids_across_interior.json"


def _sense(loops, eps):
    pts = np.concatenate(loops)
    lo, hi = pts.min(0), pts.max(0)
    ws = ((lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2 + eps))
    res = sense_slice(ExactContact(loops), ws, eps, max_motions=20000)
    return res, slice_metrics(loops, res, eps)


def _assert_clean(res, m):
    assert not res.stats.budget_hit
    assert m["coverage"] >= 0.999 and m["precision"] >= 0.999
    assert m["w3_count"] == 0 and m["w3_cross_loop"] == 0
    closed = [a for a in res.areas if a.note.startswith("the lid lies on contour recorded from B")]
    assert closed, "no lid was read as a traced wall backwards"
    assert m["unknown_count"] == 0, f"unknown chords over {m['unknown_length']:.1f} of contour"


def test_shared_star_case_no_lid_across_the_interior():
    if not CASE.exists():
        pytest.skip(f"{CASE} not found: the shared cases live next to the repository (../shared)")
    case = json.loads(CASE.read_text())
    res, m = _sense([np.asarray(lp, dtype=float) for lp in case["loops"]], float(case["eps"]))
    _assert_clean(res, m)


def test_numerics_outline_lid_on_a_traced_wall_is_traced():
    res, m = _sense(outline("numerics", np.random.default_rng(1), 1.0), 1.0)
    _assert_clean(res, m)
