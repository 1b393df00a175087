"""A noisy sensor's closure leaves the faces the probe swept unfilled
(recon3d.surface.closure: step 4, ``swept_faces``)."""
import numpy as np
import pytest
import shapely

from recon3d.surface.closure import (closure_lengths, probe_postures, result_region,
                                     slice_region, swept_faces)

# a block 20 x 20 with a slot 4 wide from its top face down to y = 5; the walls were traced
# only up to y = 14, and the top face's ends stop 0.3 short of the slot's corners
OUTER = np.array([[12.3, 20.0], [20.0, 20.0], [20.0, 0.0], [0.0, 0.0], [0.0, 20.0], [7.7, 20.0]])
WALLS = np.array([[8.0, 14.0], [8.0, 5.0], [12.0, 5.0], [12.0, 14.0]])
TRUTH = shapely.Polygon([[0, 0], [20, 0], [20, 20], [12, 20], [12, 5], [8, 5], [8, 20], [0, 20]])
LOWER_SLOT = shapely.box(8.0, 5.0, 12.0, 14.0)
# the probe down the slot (joint far above), and postures touching the block's faces
DOWN = np.array([[[x, 60.0], [x + 0.02 * k, 5.1]] for x in (8.8, 9.6, 10.4, 11.2)
                 for k in (-1, 0, 1)])
TOUCH = np.array([[[-30.0, 10.0], [0.05, 10.0]], [[10.0, -30.0], [10.0, 0.05]],
                  [[50.0, 12.0], [19.95, 12.0]], [[4.0, 60.0], [4.0, 19.95]]])


def _region(free, jitter):
    return slice_region([OUTER, WALLS], [], [], [], snap=0.05, free=free, margin=0.05,
                        jitter=jitter)


def test_the_bridged_slot_is_filled_without_the_rule_and_open_with_it():
    """The loose ends are bridged closest first: across the walls' tops (4.0) and across the
    mouth (4.6), so the slot is closed twice and filled; the postures down the slot sweep the
    face below the walls' bridge, which is left out. The face above it is the block's own
    (merged through the untraced wall tops) and swept little: it stays, and so does the
    block."""
    free = np.concatenate([DOWN, TOUCH])
    blind = _region(free, 0.0).geometry
    seen = _region(free, 0.3).geometry
    assert blind.difference(TRUTH).area == pytest.approx(4 * 15, rel=1e-6)  # slot filled
    assert seen.intersection(LOWER_SLOT).area < 1e-6
    assert seen.difference(TRUTH).area == pytest.approx(4 * 6, rel=1e-6)  # y 14 .. 20 stays
    assert TRUTH.difference(seen).area < 1e-6  # no material lost


def test_postures_touching_the_faces_sweep_nothing():
    """A posture ends where the probe touched: within the jitter of the pieces, outside the
    faces' cores, so the block is not swept."""
    faces = np.array([_region(None, 0.0).geometry])  # the block with its slot filled
    assert not swept_faces(faces, TOUCH, 0.05, 0.3).any()
    assert _region(TOUCH, 0.3).geometry.symmetric_difference(_region(TOUCH, 0.0).geometry).area \
        < 1e-9


@pytest.mark.parametrize("postures, share", [(1, False), (4, True)])
def test_a_face_is_free_when_the_postures_sweep_most_of_its_core(postures, share):
    """One posture down a 4-wide slot sweeps a strip of width 2 (snap + jitter / 2 each
    side, 0.05 + 0.45 = 0.5, so 1.0) of a core 4 - 2 (snap + jitter) = 2.1 wide: under half;
    four spread across it sweep all of it."""
    box = shapely.box(8.0, 5.0, 12.0, 14.0)
    xs = np.linspace(8.8, 11.2, postures) if postures > 1 else [10.0]
    free = np.array([[[x, 60.0], [x, 5.1]] for x in xs])
    assert swept_faces(np.array([box]), free, 0.05, 0.9)[0] == share


def test_a_perfect_sensor_keeps_the_closure_as_it_was():
    """jitter 0 (the paper's sensing): no face is left out, whatever the postures."""
    assert closure_lengths(0.45, 0.0225)[2] == 0.0
    free = np.concatenate([DOWN, TOUCH])
    assert _region(free, 0.0).geometry.symmetric_difference(
        _region(None, 0.0).geometry).area < 1e-9


def test_deep_slot_at_sigma_03_keeps_its_slot_open():
    """``deep_slot`` at sigma 0.3 eps, taxels 0.25 eps, 4 slices, seed 0: each slice's region
    against its true section (shapely areas of the section's loops, not the planner's),
    closed without the noisy sensor's steps, with step 4 (the swept faces) and with step 5
    (the carve, :mod:`recon3d.surface.sweep`) too: the area filled outside the section falls
    with step 4 (397 -> 310 measured; 230 from the simulator's true postures, which the robot
    does not know) and by half of what is left with step 5 (147); the section's area missed
    grows by at most 2 % of the slot's."""
    import recon3d

    res = recon3d.run("deep_slot", slices=4, jobs=1, noise=0.3, taxel=0.25, seed=0)
    run = res.sensing
    lengths = closure_lengths(run.eps, run.tol, 0.3, 0.25)
    snap, noise, jitter, _ = lengths
    extra, missed = np.zeros(3), np.zeros(3)
    for s in run.slices:
        truth = shapely.union_all([shapely.Polygon(lp) for lp in s.slice.loops])
        r = s.result
        step4 = slice_region(r.w1, r.w2, r.w3, r.unknown, snap, probe_postures(r.motions),
                             snap + 3 * noise, jitter)
        for k, g in enumerate((result_region(r, snap, noise), step4,
                               result_region(r, *lengths))):
            extra[k] += g.geometry.difference(truth).area
            missed[k] += truth.difference(g.geometry).area
    slot = 4 * 4.0 * 37.5  # four slices of a slot about 4 x 37.5
    assert extra[1] < 0.85 * extra[0]
    assert extra[2] < 0.5 * extra[1]
    assert missed[1] <= missed[0] + 0.02 * slot
    assert missed[2] <= missed[0] + 0.02 * slot


def test_a_thin_wall_touched_on_both_sides_stays():
    """A wall 1.0 thick touched every 0.25 along both faces, the tips 0.05 inside the
    pieces (a reading's scatter): the postures widened by snap + jitter / 2 reach 0.4 into
    it from each side, but its core -- shrunk by snap + jitter, where a touch can reach --
    is empty, so it is not swept."""
    wall = shapely.box(0.0, 0.0, 1.0, 10.0)
    ys = np.arange(0.25, 10.0, 0.25)
    free = np.array([[[-30.0, y], [0.05, y]] for y in ys] + [[[31.0, y], [0.95, y]] for y in ys])
    assert not swept_faces(np.array([wall]), free, 0.05, 0.6)[0]


def _reference_swept(faces, free, snap, jitter):
    """The share from the union of every posture (what swept_faces computes from the nearby
    ones only)."""
    cores = shapely.buffer(faces, -(snap + jitter))
    swept = shapely.union_all(shapely.buffer(shapely.linestrings(free), snap + jitter / 2))
    out = np.zeros(len(faces), dtype=bool)
    for k, core in enumerate(cores):
        if not core.is_empty:
            out[k] = core.intersection(swept).area / core.area > 0.5
    return out


@pytest.mark.parametrize("seed", range(12))
def test_the_nearby_postures_decide_as_all_of_them(seed):
    """Postures farther than the widening from every core are left out of the union: the
    decisions are those of the union of all postures, on faces whose cores postures just
    outside them (within the widening) cover by about half."""
    rng = np.random.default_rng(seed)
    snap, jitter = 0.05, 0.9
    faces = np.array([shapely.box(x, 0.0, x + w, 6.0)
                      for x, w in zip((0.0, 10.0, 20.0), rng.uniform(2.6, 3.4, 3))])
    xs = np.concatenate([rng.uniform(-1.0, 25.0, 6), [f.bounds[0] + 0.95 + d
                         for f in faces for d in rng.uniform(-0.5, 0.2, 6)]])
    free = np.array([[[x, 40.0], [x + rng.uniform(-0.1, 0.1), rng.uniform(-2.0, 3.0)]]
                     for x in xs])
    got = swept_faces(faces, free, snap, jitter)
    assert (got == _reference_swept(faces, free, snap, jitter)).all()
