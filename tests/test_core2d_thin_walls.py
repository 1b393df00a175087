"""The back of a thin wall under a noisy sensor (:mod:`core2d.planner.thin_walls`).

A wall 0.7 eps thick beside a slit 2.67 eps wide (the outer wall of
``trimesh_octagonal_pocket`` z0 / z7, eps 1 here, exact backend): its outer face traced,
the lids laid along its slit side used to be closed as contour recorded from B to A.
``far_face``: a point recorded on a face running against a given one (a needle's two faces,
read by their directions, not by a depth the sensor cannot resolve); ``far_face_means``: where
that face's record lies, averaged over its local lines. ``touched_from_behind``:
a contact whose rod lies on the material side of the record it reads on.
"""
from __future__ import annotations

import numpy as np
import pytest

from core2d import SensorModel, sense_slice
from core2d.planner.known import KnownContour
from core2d.planner.thin_walls import (behind_recorded, far_face, far_face_means,
                                      touched_from_behind)
from core2d.resolution import Resolution
from core2d.truth.metrics import sensor_metrics
from slicer.contact.exact import ExactContact

FINE = Resolution.of(1.0, noise=0.1)  # jitter 0.42, near 0.52, tip zone 0.92


def _wall(y=0.0, scatter=0.0, seed=0):
    """A map of one piece along y = ``y`` from x = 0 to 6, material below (on its right)."""
    x = np.arange(0.0, 6.01, 0.5)
    pts = np.column_stack([x, y + scatter * np.random.default_rng(seed).standard_normal(len(x))])
    known = KnownContour(join=0.5)
    known.add(pts)
    return known


@pytest.mark.parametrize("point, behind", [
    ([3.0, -0.7], True),  # the back of a wall 0.7 thick
    ([3.0, -0.3], False),  # within the jitter: a reading of the recorded face
    ([3.0, 0.5], False),  # the free side
    ([6.3, -0.7], False),  # past the piece's end: the surface may turn round a corner
])
def test_behind_is_deeper_than_the_jitter_on_the_material_side(point, behind):
    assert behind_recorded(_wall(), FINE, point, FINE.tip_zone) is behind


def test_a_noisy_trace_is_read_by_its_local_line_not_its_nearest_point():
    """Scattered by 0.15 (the trace's spikes come within the radius of a point 0.7 behind
    the face), the chord over the window still puts the point behind it."""
    known = _wall(scatter=0.15, seed=3)
    assert known.distance([3.0, -0.7]) < 0.7
    assert behind_recorded(known, FINE, [3.0, -0.7], FINE.tip_zone)


def test_a_piece_in_front_keeps_the_point_on_the_map():
    """A second piece through the point (the back face recorded too): on the map."""
    known = _wall()
    known.add([[6.0, -0.7], [0.0, -0.7]])  # the back face, material above
    assert not behind_recorded(known, FINE, [3.0, -0.7], FINE.tip_zone)


def test_perfect_sensing_and_short_pieces_are_left_alone():
    assert not behind_recorded(_wall(), Resolution.of(1.0), [3.0, -0.7], 0.5)
    short = KnownContour(join=0.5)
    short.add([[0.0, 0.0], [0.5, 0.0]])  # a chord shorter than eps has no line to speak of
    assert not behind_recorded(short, FINE, [0.25, -0.7], FINE.tip_zone)


def _box(x0, y0, x1, y1):
    return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], dtype=float)


def test_the_slit_side_of_a_thin_wall_is_traced_at_sigma_01():
    """Without the rule seeds 1 - 3 cover 0.976, 0.992, 0.985 (the lids along the wall's
    slit side closed as traced); with it every seed >= 0.99."""
    loops = [_box(0.0, 0.0, 30.0, 40.0), _box(-3.37, 0.0, -2.67, 40.0)]
    pts = np.concatenate(loops)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    ws = ((lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2 + 1.0))
    contact = ExactContact(loops)
    base = sense_slice(contact, ws, 1.0)
    for seed in range(4):
        res = sense_slice(contact, ws, 1.0, sensor=SensorModel.of_eps(1.0, 0.1, 0.0, seed))
        m = sensor_metrics(loops, res, 1.0, 0.1)
        assert m["coverage_sensor"] >= 0.99, f"seed {seed}: {m['coverage_sensor']:.4f}"
        assert m["precision_sensor"] >= 0.98, f"seed {seed}"
        assert m["w3_unsound_count_sensor"] == 0, f"seed {seed}"
        assert not res.stats.budget_hit and res.stats.motions <= 2 * base.stats.motions


#: sigma 0.3 eps over the planner's 16 reads (0.075), taxels 0.25 eps: tip zone 0.94 eps
COARSE = Resolution.of(1.0, noise=0.075, taxel=0.25)


@pytest.mark.parametrize("face, against", [
    ((-1.0, 0.0), True),  # antiparallel: the wall's other face
    ((-0.8, 0.6), True),  # turned 143 degrees
    ((-0.6, 0.8), False),  # turned 127 degrees: a corner, not a wall
    ((0.0, -1.0), False),  # a concave corner's other face
    ((1.0, 0.0), False),  # the same face
])
def test_far_face_reads_the_turn_between_the_two_faces(face, against):
    """The map's piece runs +x (material below); ``face`` is the one slid along."""
    assert far_face(_wall(scatter=0.15, seed=3), COARSE, [3.0, 0.1], np.array(face),
                    COARSE.tip_zone) is against


def test_far_face_needs_a_readable_piece_each_of_which_runs_against():
    face = np.array([-1.0, 0.0])
    assert not far_face(_wall(), COARSE, [3.0, 2.0], face, COARSE.tip_zone)  # nothing near
    short = KnownContour(join=0.5)
    short.add([[3.0, 0.0], [3.4, 0.0]])  # 0.4 long, under the jitter (0.44): no direction
    assert not far_face(short, COARSE, [3.2, 0.0], face, COARSE.tip_zone)
    both = _wall()
    assert far_face(both, COARSE, [3.0, 0.0], face, COARSE.tip_zone)
    both.add([[x, 0.3] for x in np.arange(5.5, 0.4, -0.5)])  # a second face, running along it
    assert not far_face(both, COARSE, [3.0, 0.1], face, COARSE.tip_zone)
    short_too = _wall()
    short_too.add([[3.1, 0.3], [3.5, 0.3]])  # a chord under the jitter beside it: skipped
    assert far_face(short_too, COARSE, [3.0, 0.1], face, COARSE.tip_zone)


def test_far_face_means_average_the_far_faces_record_per_piece():
    """One mean point per piece running against the face, over its readings within the
    window: the far face 0.1 behind the line y = 0 of a face slid along -x, read with a
    scatter of 0.15, and a reading of it at 0.15 in front of that line -- the mean of the
    7 readings lies behind the line, within 3 standard errors (0.17) of the far face. None
    at all when a piece near the point runs along the face (not a far face)."""
    face = np.array([-1.0, 0.0])
    known = _wall(y=-0.1, scatter=0.15, seed=3)
    means = far_face_means(known, COARSE, [3.0, 0.15], face, COARSE.tip_zone)
    assert means.shape == (1, 2) and means[0, 1] < 0.0 and abs(means[0, 1] + 0.1) < 0.17
    assert abs(means[0, 0] - 3.0) < 0.3  # the window's readings about the point
    known.add([[x, 0.3] for x in np.arange(5.5, 0.4, -0.5)])  # a second face, running along it
    assert far_face_means(known, COARSE, [3.0, 0.15], face, COARSE.tip_zone).shape == (0, 2)
    assert far_face_means(_wall(), COARSE, [3.0, 2.0], face, COARSE.tip_zone).shape == (0, 2)


def test_with_perfect_sensing_the_far_face_is_where_the_reading_is():
    """Jitter 0: the reading is exact and tells its side itself; the record is not averaged
    (``across_wall`` asks P_fin's own side, as before the far face's record was read)."""
    exact = Resolution.of(1.0)
    face = np.array([-1.0, 0.0])
    means = far_face_means(_wall(y=-0.1), exact, [3.0, 0.05], face, 0.5)
    np.testing.assert_array_equal(means, [[3.0, 0.05]])
    assert far_face_means(_wall(y=-0.1), exact, [3.0, 0.05], -face, 0.5).shape == (0, 2)


@pytest.mark.parametrize("point, joint, res, behind", [
    ([3.0, -0.1], [3.0, -40.0], FINE, True),  # the rod up through the material: the far face
    ([3.0, -0.1], [40.0, -30.0], FINE, True),  # slanting: an eps back, 0.73 below the line
    ([3.0, -0.1], [40.0, -10.0], FINE, False),  # flatter: 0.36 below, within the jitter 0.42
    ([3.0, 0.1], [3.0, 40.0], FINE, False),  # from the free side: a reading of the face
    ([6.3, -0.1], [6.3, -40.0], FINE, False),  # past the piece's end: round a corner, maybe
    ([3.0, -0.1], [3.0, -40.0], Resolution.of(1.0), False),  # perfect sensing: as it was
])
def test_a_contact_touched_from_behind_the_record_is_another_surface(point, joint, res, behind):
    assert touched_from_behind(_wall(), res, point, joint) is behind
