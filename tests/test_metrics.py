"""Ground-truth metrics (core2d.truth.metrics) on shapes whose answers are known by hand."""
from __future__ import annotations

import json

import numpy as np
import pytest

from core2d.truth.metrics import slice_metrics, total_metrics
from core2d.truth.reachability import reachable_samples
from core2d.result import SenseStats, SliceResult

try:
    from polygen import keyhole, slotted_box
except ImportError:  # tests/ imported as a package
    from tests.polygen import keyhole, slotted_box

# keyhole(3): box [-50, 50]^2, neck |x| < 3 (20 < y < 50), chamber |x| < 30, |y| < 20.
# Reachable (tests/test_reachability.py): box sides, neck walls, floor |x| < 11.
KEY = keyhole(3.0)
KEY_LENGTH = 394 + 60 + 54 + 80 + 60  # box sides, neck walls, ceiling, chamber walls, floor
KEY_REACHABLE = 394 + 60 + 22
KEY_W1 = [np.array([[-11, -20], [11, -20]], dtype=float),
          np.array([[3, 20], [3, 50], [50, 50], [50, -50], [-50, -50], [-50, 50], [-3, 50], [-3, 20]],
                   dtype=float)]
RIGHT_LID = np.array([[11, -20], [3, 20]], dtype=float)  # floor x > 11, right wall, right ceiling
LEFT_LID = np.array([[-3, 20], [-11, -20]], dtype=float)
LID_ARC = 19 + 40 + 27

BOX = np.array([[-50, -50], [50, -50], [50, 50], [-50, 50]], dtype=float)
HOLE = np.array([[-10, -10], [-10, 10], [10, 10], [10, -10]], dtype=float)  # clockwise


def circle(radius, n=200):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return radius * np.c_[np.cos(t), np.sin(t)]


def metrics(loops, eps=1.0, **parts):
    m = slice_metrics(loops, SliceResult(**parts), eps)
    json.dumps(m, allow_nan=False)  # plain JSON, always
    return m


@pytest.mark.parametrize("eps", [0.5, 1.0, 2.0])
def test_w1_exactly_the_reachable_contour(eps):
    m = metrics(KEY, eps, w1=KEY_W1)
    assert m["coverage"] == 1.0 and m["precision"] == 1.0
    assert m["contour_length"] == pytest.approx(KEY_LENGTH, abs=1e-9)
    assert m["reachable_length"] == pytest.approx(KEY_REACHABLE, abs=2 * m["spacing"])
    assert m["hausdorff_detected_to_true"] < 1e-9
    assert m["hausdorff_true_reachable_to_detected"] < 1e-9
    assert m["w1_length"] == pytest.approx(KEY_REACHABLE)
    assert m["tol"] == eps / 2 and m["spacing"] == eps / 4


def test_partial_w1():
    m = metrics(KEY, w1=KEY_W1[:1])
    assert m["coverage"] == pytest.approx(22 / KEY_REACHABLE, abs=1e-3)
    assert m["precision"] == 1.0
    # the farthest reachable point from the floor segment is a top corner of the box
    assert m["hausdorff_true_reachable_to_detected"] == pytest.approx(np.hypot(50 - 11, 70), abs=0.3)


@pytest.mark.parametrize("tol", [0.1, 0.5, 2.0])
@pytest.mark.parametrize("factor,expect", [(5.0, 0.0), (0.5, 1.0)])
def test_w1_offset_from_the_contour(tol, factor, expect):
    true = [circle(40.0)]
    off = circle(40.0 + factor * tol)  # every point factor * tol (x cos(pi/200)) away
    res = SliceResult(w1=[np.vstack([off, off[:1]])])
    m = slice_metrics(true, res, eps=1.0, tol=tol)
    assert m["precision"] == expect and m["coverage"] == expect
    gap = factor * tol
    assert m["hausdorff_detected_to_true"] == pytest.approx(gap, rel=0.01)
    assert m["hausdorff_true_reachable_to_detected"] == pytest.approx(gap, rel=0.01)


def test_contour_behind_a_w2_chord_is_approximated():
    """§3.1: L_A^B stands for C_A^B when Dist(A, B) < eps: a slot narrower
    than eps closed by a W2 chord counts as covered. The chord reversed would
    lid the whole outside: it credits nothing and is counted as long."""
    width = 0.8
    loops = slotted_box(width, 20.0)
    outside = np.array([[width / 2, 50], [50, 50], [50, -50], [-50, -50], [-50, 50], [-width / 2, 50]])
    chord = np.array([[-width / 2, 50.0], [width / 2, 50.0]])  # material on the right: into the slot
    bare = metrics(loops, eps=1.0, w1=[outside])
    assert bare["coverage"] < 0.92  # the slot walls are reachable and not detected
    m = metrics(loops, eps=1.0, w1=[outside], w2=[chord])
    assert m["w2_arc_length"] == pytest.approx(40 + width, abs=2 * m["spacing"])
    assert m["coverage"] == 1.0 and m["w2_long_arcs"] == 0
    rev = metrics(loops, eps=1.0, w1=[outside], w2=[chord[::-1]])
    assert rev["w2_long_arcs"] == 1 and rev["w2_arc_length"] == 0.0
    assert rev["coverage"] < 0.92
    # credited through the arc only: the slot's walls and bottom farther than tol
    # (eps / 2) from the chord and from W1, i.e. all but the top tol of each wall; the
    # rest is what W1 alone covers
    assert m["w2_credit_length"] == pytest.approx(40 + width - 2 * 0.5, abs=2 * m["spacing"])
    assert m["covered_length"] - m["w2_credit_length"] == pytest.approx(
        bare["covered_length"], abs=2 * m["spacing"])
    assert bare["w2_credit_length"] == 0.0 and rev["w2_credit_length"] == 0.0
    assert m["w2_material_arcs"] == 0  # the slot's arc closes round free space


@pytest.mark.parametrize("offset", [0.0, 1e6, 1e7])  # the numerics outlines sit at 1e6; at 1e7
# the shoelace without A as its origin gets the arc's sign wrong (tried: it fails there)
def test_a_w2_chord_across_a_needle_credits_not_its_tip(offset):
    """A chord across a wall thinner than tol (a needle 0.1 eps thick at its base, 20 eps
    long) spans no opening: the arc it lids, the needle's tip, closes round material, and
    none of it is covered but what lies within tol of the chord. A noisy sensor can read
    the two faces of such a needle as one; crediting its tip would report a needle never
    traced as covered."""
    needle = np.array([[-0.05, -50.0], [0.0, -70.0], [0.05, -50.0]])
    loops = [np.vstack([BOX[:1], needle, BOX[1:]])]
    y = -55.0  # the chord, A on the right face, B on the left: its arc runs round the tip
    half = 0.05 * (70 + y) / 20
    chord = np.array([[half, y], [-half, y]])
    outline = np.vstack([loops[0][4:], loops[0][:2], [[-half, y]]])  # all but the tip
    w1 = [outline, np.vstack([[half, y], loops[0][3:5]])]
    loops, w1, chord = [lp + offset for lp in loops], [pl + offset for pl in w1], chord + offset
    bare = metrics(loops, eps=1.0, w1=w1)
    m = metrics(loops, eps=1.0, w1=w1, w2=[chord])
    assert m["w2_material_arcs"] == 1 and m["w2_long_arcs"] == 0
    assert m["w2_credit_length"] == 0.0 and m["coverage"] == bare["coverage"]
    # independent: both faces of the tip (15 eps of needle each) but their tol nearest
    # the chord, over the reachable length (every side of the box and the needle)
    face = np.hypot(0.05, 20.0) * 15 / 20
    missed = 2 * (face - 0.5)
    assert m["reachable_length"] == pytest.approx(400 - 0.1 + 2 * np.hypot(0.05, 20.0), abs=0.01)
    assert m["coverage"] == pytest.approx(1 - missed / m["reachable_length"], abs=2e-3)


def test_coincident_ends_make_no_arc():
    """Two ends one point apart in the reverse order do not lid the whole loop."""
    p = np.array([20.0, -50.0])
    m = metrics([BOX], eps=1.0, w2=[np.stack([p, p + [1e-9, 0]])], w3=[np.stack([p, p + [1e-9, 0]])])
    assert m["w2_arc_length"] == 0.0 and m["w3_lidded_length"] == 0.0
    assert m["w3_soundness"] == 1.0


def test_w2_segments_count():
    pts = np.linspace(BOX[0], BOX[1], 201)  # bottom side in 200 chords of 0.5 < eps
    w2 = [np.stack([p, q]) for p, q in zip(pts[:-1], pts[1:])]
    m = metrics([BOX], eps=1.0, w2=w2)
    assert m["w2_count"] == 200 and m["w1_count"] == 0
    assert m["w2_long_arcs"] == 200  # drawn counter-clockwise: reversed chords
    right_way = metrics([BOX], eps=1.0, w2=[seg[::-1] for seg in w2])
    assert right_way["w2_long_arcs"] == 0 and right_way["coverage"] == pytest.approx(m["coverage"])
    # the bottom side and, within tol of it, the lowest tol of both sides
    assert m["coverage"] == pytest.approx((100 + 2 * m["tol"]) / 400, abs=1e-3)
    assert m["precision"] == 1.0
    assert m["detected_length"] == pytest.approx(100.0)


def test_nothing_detected():
    m = metrics(KEY)
    assert m["coverage"] == 0.0 and m["covered_length"] == 0.0
    assert m["precision"] == 1.0 and m["w3_soundness"] == 1.0 and m["w3_count"] == 0
    assert m["hausdorff_detected_to_true"] is None
    assert m["hausdorff_true_reachable_to_detected"] is None


@pytest.mark.parametrize("lids,length,unsound,hidden", [
    ([RIGHT_LID], LID_ARC, 0, 0.0),
    ([LEFT_LID], LID_ARC, 0, 0.0),
    ([RIGHT_LID, LEFT_LID], 2 * LID_ARC, 0, 0.0),
    ([RIGHT_LID[::-1]], KEY_LENGTH - LID_ARC, 1, KEY_REACHABLE - 2),  # the long way
    ([np.array([[-5, -20], [5, -20]])], 10, 1, 8.0),  # floor under the neck: reachable
    ([np.array([[5, -20], [-5, -20]])], KEY_LENGTH - 10, 1, KEY_REACHABLE - 10 - 2),
    # reachable floor 10.5 < x < 11 under the lid, all of it within eps of A: sound
    ([np.array([[10.5, -20], [3, 20]])], LID_ARC + 0.5, 0, 0.0),
    # reachable floor 9 < x < 11: the part farther than eps from A makes it unsound
    ([np.array([[9.0, -20], [3, 20]])], LID_ARC + 2, 1, 1.0),
])
def test_w3_lids_on_the_keyhole(lids, length, unsound, hidden):
    m = metrics(KEY, eps=1.0, w3=lids)
    sp = m["spacing"]
    assert m["w3_count"] == len(lids) and m["w3_cross_loop"] == 0 and m["w3_off_contour"] == 0
    assert m["w3_lidded_length"] == pytest.approx(length, abs=2 * sp * len(lids))
    assert m["w3_unsound_count"] == unsound
    assert m["w3_soundness"] == 1 - unsound / len(lids)
    # reachable contour under the lids, less eps at each touched end
    assert m["w3_hidden_reachable_length"] == pytest.approx(hidden, abs=2 * sp)


@pytest.mark.parametrize("lid,length", [
    ([[-10, 0], [0, 10]], 60.0),  # hole (CW): down, bottom, right side, top to the middle
    ([[0, 10], [-10, 0]], 20.0),
    ([[50, 0], [0, 50]], 300.0),  # outer box (CCW): down, bottom, left side, top
    ([[0, 50], [50, 0]], 100.0),
])
def test_lid_arcs_follow_material_on_the_right(lid, length):
    m = metrics([BOX, HOLE], eps=1.0, w3=[np.array(lid, dtype=float)])
    assert m["w3_lidded_length"] == pytest.approx(length, abs=2 * m["spacing"])
    on_hole = np.abs(lid).max() <= 10
    assert m["w3_soundness"] == (1.0 if on_hole else 0.0)
    assert (m["w3_hidden_reachable_length"] == 0) == on_hole
    assert m["hole_length"] == pytest.approx(80.0)


def test_cross_loop_and_off_contour_lids():
    cross = np.array([[50, 0], [10, 0]], dtype=float)
    m = metrics([BOX, HOLE], eps=1.0, w3=[cross, np.array([[-10, 0], [0, 10]], dtype=float)])
    assert m["w3_cross_loop"] == 1 and m["w3_unsound_count"] == 1
    assert m["w3_soundness"] == 0.5  # a bridge between two loops is unsound, the hole lid sound
    assert m["w3_hidden_reachable_length"] == 0.0
    tol = m["tol"]
    off = metrics([BOX, HOLE], eps=1.0, w3=[np.array([[-10 + 2 * tol, 0], [0, 10 - 0.5 * tol]])])
    assert off["w3_off_contour"] == 1 and off["w3_lidded_length"] == pytest.approx(60, abs=0.5)


def test_unknown_areas_and_stats():
    stats = SenseStats(motions=12, rays=345, joint_path=6.5, pushes=0, areas=3, escapes=1,
                       budget_hit=True, seconds=0.25)
    res = SliceResult(w1=KEY_W1, unknown=[np.array([[-5, -20], [5, -20]], dtype=float)], stats=stats)
    m = slice_metrics(KEY, res, eps=1.0)
    assert m["unknown_count"] == 1
    assert m["unknown_length"] == pytest.approx(10, abs=0.5)
    assert m["unknown_reachable_length"] == pytest.approx(10, abs=0.5)
    for k, v in stats.as_dict().items():
        assert m[k] == v
    cached = slice_metrics(KEY, res, eps=1.0, samples=reachable_samples(KEY, 0.25))
    assert cached == m


def test_total_metrics_weighting():
    s1 = SenseStats(motions=3, rays=10, joint_path=1.5, seconds=0.5)
    s2 = SenseStats(motions=4, rays=20, joint_path=2.0, budget_hit=True, seconds=1.0)
    full = slice_metrics(KEY, SliceResult(w1=KEY_W1, w3=[RIGHT_LID], stats=s1), eps=1.0)
    floor = slice_metrics(KEY, SliceResult(w1=KEY_W1[:1] + [KEY_W1[1] + [0, 5.0]],
                                           w3=[RIGHT_LID[::-1]], stats=s2), eps=1.0)
    empty = slice_metrics([BOX], SliceResult(), eps=1.0)
    t = total_metrics([full, floor, empty])
    json.dumps(t, allow_nan=False)
    assert t["slices"] == 3
    reach = full["reachable_length"] + floor["reachable_length"] + 400.0
    assert t["reachable_length"] == pytest.approx(reach)
    assert t["coverage"] == pytest.approx((full["covered_length"] + floor["covered_length"]) / reach)
    assert t["coverage"] != pytest.approx(np.mean([full["coverage"], floor["coverage"], 0.0]))
    # precision weighted by detected length: the shifted polyline is mostly off
    det = full["detected_length"] + floor["detected_length"]
    assert t["precision"] == pytest.approx((full["precise_length"] + floor["precise_length"]) / det)
    assert t["precision"] < 0.9
    assert t["precision"] != pytest.approx(np.mean([full["precision"], floor["precision"], 1.0]))
    assert t["w3_soundness"] == 0.5  # one sound lid, one the long way round
    assert t["w3_count"] == 2 and isinstance(t["w3_count"], int)
    assert t["motions"] == 7 and t["rays"] == 30 and t["joint_path"] == pytest.approx(3.5)
    assert t["budget_hit"] is True and t["budget_hits"] == 1 and t["seconds"] == pytest.approx(1.5)
    assert t["hausdorff_detected_to_true"] == pytest.approx(5.0)  # the shifted polyline
    assert total_metrics([empty])["hausdorff_detected_to_true"] is None
    assert total_metrics([])["slices"] == 0


def test_empty_contour():
    """A slice that cuts nothing (recon3d passes ``[]``): no crash, plain JSON."""
    assert metrics([])["coverage"] == 1.0
    m = metrics([], w1=[np.array([[0.0, 0.0], [1.0, 1.0]])], w3=[np.array([[0.0, 0.0], [1.0, 0.0]])],
                w2=[np.array([[0.0, 0.0], [0.5, 0.0]])])
    assert m["w2_arc_length"] == 0.0 and m["coverage"] == 1.0
    assert m["precision"] == 0.0 and m["hausdorff_detected_to_true"] is None
    assert m["w3_soundness"] == 0.0 and m["w3_off_contour"] == 1
