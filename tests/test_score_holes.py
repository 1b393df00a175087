"""Ground-truth samples on hole loops (recon3d.score.evaluate._on_holes): the one STRtree query
over loop segments gives the loop an argmin over every loop's exact distance gives, ties too."""
from types import SimpleNamespace

import numpy as np
import shapely

from recon3d.score.evaluate import _on_holes


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
    srun = SimpleNamespace(slice=SimpleNamespace(loops=loops, holes=holes))
    got = _on_holes(srun, pts)
    assert np.array_equal(got, _brute(loops, holes, pts))
    assert 0 < got.sum() < len(pts)


def test_a_tie_goes_to_the_first_loop_as_argmin_does():
    loops = [_square(0, 0, 10, 10), _square(2, 2, 4, 4)[::-1]]
    srun = SimpleNamespace(slice=SimpleNamespace(loops=loops, holes=[False, True]))
    tie = np.array([[1.0, 3.0]])  # 1 from the outer loop's left side and from the hole's
    assert not _on_holes(srun, tie)[0] and not _brute(loops, [False, True], tie)[0]
    srun = SimpleNamespace(slice=SimpleNamespace(loops=loops[::-1], holes=[True, False]))
    assert _on_holes(srun, tie)[0]
