"""Ground-truth samples on hole loops (recon3d.score.evaluate.on_holes): the one STRtree query
over loop segments gives the loop an argmin over every loop's exact distance gives, ties too."""
from types import SimpleNamespace

import numpy as np
import shapely

from recon3d.score.evaluate import on_holes


def _brute(loops, holes, points):
    where = shapely.points(points)
    d = np.array([shapely.distance(where, shapely.LinearRing(lp)) for lp in loops])
    return np.asarray(holes)[np.argmin(d, axis=0)]


def _square(x0, y0, x1, y1, n=1):
    """A square loop with ``n`` points per side (CCW)."""
    t = np.linspace(0, 1, n, endpoint=False)
    sides = [np.c_[x0 + (x1 - x0) * t, np.full(n, y0)], np.c_[np.full(n, x1), y0 + (y1 - y0) * t],
             np.c_[x1 - (x1 - x0) * t, np.full(n, y1)], np.c_[np.full(n, x0), y1 - (y1 - y0) * t]]
    return np.concatenate(sides)


def test_nearest_loop_matches_brute_force_on_random_points():
    rng = np.random.default_rng(3)
    loops = [_square(0, 0, 10, 10, 7), _square(2, 2, 4, 4, 5)[::-1], _square(6, 5, 9, 8, 3)[::-1]]
    holes = [False, True, True]
    pts = rng.uniform(-1, 11, size=(4000, 2))
    cut = SimpleNamespace(loops=loops, holes=holes)
    got = on_holes(cut, pts)
    assert np.array_equal(got, _brute(loops, holes, pts))
    assert 0 < got.sum() < len(pts)


def test_a_tie_goes_to_the_first_loop_as_argmin_does():
    loops = [_square(0, 0, 10, 10), _square(2, 2, 4, 4)[::-1]]
    cut = SimpleNamespace(loops=loops, holes=[False, True])
    tie = np.array([[1.0, 3.0]])  # 1 from the outer loop's left side and from the hole's
    assert not on_holes(cut, tie)[0] and not _brute(loops, [False, True], tie)[0]
    cut = SimpleNamespace(loops=loops[::-1], holes=[True, False])
    assert on_holes(cut, tie)[0]


def test_the_worker_marks_the_samples_on_holes_and_the_cloud_takes_them():
    """Each slice's samples on hole loops come from the worker that sensed it (beside its
    other reference samples): the marks on_holes gives, taken by contour_cloud as sent."""
    import dataclasses

    import meshes
    from recon3d.score.evaluate import contour_cloud
    from recon3d.sensing import sense_mesh
    from recon3d.spellings import make_config

    mesh = meshes.load("bored_block")
    run = sense_mesh(mesh, "bored_block", make_config(slices=2, jobs=1, eps=2.0))
    assert all(s.truth.in_hole is not None for s in run.slices)
    marks = [on_holes(s.slice, s.truth.points) for s in run.slices]
    assert any(m.any() for m in marks)  # the bore is a hole of every z-slice
    for s, m in zip(run.slices, marks):
        assert np.array_equal(s.truth.in_hole, m)
    cloud = contour_cloud(run.families)
    assert np.array_equal(cloud.in_hole, np.concatenate(marks))
    flipped = [dataclasses.replace(s, truth=dataclasses.replace(s.truth, in_hole=~m))
               for s, m in zip(run.slices, marks)]
    fam = dataclasses.replace(run.families[0], slices=flipped)
    assert np.array_equal(contour_cloud([fam]).in_hole, ~np.concatenate(marks))
