"""A noisy sensor's closure leaves out the free ends of a piece that lies, both ends, on
other pieces (recon3d.surface.closure: step 1b, ``_lying_on_others``)."""
import numpy as np
import pytest
import shapely

from recon3d.surface.closure import slice_region

# a block 20 x 20; the left wall traced up to y = 14, the top face from the right corner to
# x = 6: the corner (0, 14) - (0, 20) - (6, 20) was not traced (18 units² the closure cuts)
WALLS = np.array([[0.0, 14.0], [0.0, 0.0], [20.0, 0.0], [20.0, 20.0]])
TOP = np.array([[20.0, 20.0], [6.0, 20.0]])
TRUTH = shapely.box(0.0, 0.0, 20.0, 20.0)
CORNER = 0.5 * 6.0 * 6.0


def _region(extra, jitter, snap=0.05):
    return slice_region([WALLS, TOP] + extra, [], [], [], snap=snap, jitter=jitter).geometry


@pytest.mark.parametrize("offset", [0.1, -0.1, 0.3])
def test_a_top_face_traced_twice_does_not_cut_the_block(offset):
    """The top face traced again, ``offset`` off it (within snap + jitter = 0.35): its left
    end lies 1.0 from the top trace's free end, so closest first pairs those two and bridges
    its right end to the left wall's free end across the block; left out, the two true free
    ends are bridged across the untraced corner only."""
    again = np.array([[7.0, 20.0 + offset], [13.0, 20.0 - offset / 2], [19.0, 20.0 + offset]])
    blind = _region([again], 0.0)
    seen = _region([again], 0.3)
    assert TRUTH.difference(blind).area > 2 * CORNER  # the diagonal bridge cut the block
    assert TRUTH.difference(seen).area == pytest.approx(CORNER, abs=0.5)
    assert seen.difference(TRUTH).area < 0.5


def test_a_piece_with_one_end_away_from_the_others_is_paired():
    """A trace that starts on the top face but ends 2.0 below it (farther than snap +
    jitter from any piece) is a piece of the curve: both its ends are paired as before."""
    hook = np.array([[7.0, 20.1], [12.0, 20.1], [12.0, 18.0]])
    assert _region([hook], 0.3).symmetric_difference(_region([hook], 0.0)).area < 1e-9


def test_a_perfect_sensor_pairs_every_free_end():
    """jitter 0 (the paper's sensing): the rule is off, whatever lies where."""
    again = np.array([[7.0, 20.1], [19.0, 20.1]])
    a = slice_region([WALLS, TOP, again], [], [], [], snap=0.05)
    b = slice_region([WALLS, TOP, again], [], [], [], snap=0.05, jitter=0.0)
    assert a.geometry.symmetric_difference(b.geometry).area < 1e-12
    assert sum(p.kind == "bridge" for p in a.pieces) == 2
