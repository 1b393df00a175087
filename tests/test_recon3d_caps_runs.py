"""A fill closed by chords on a run of slices ends at the run's empty neighbours
(recon3d.surface.runs).

The constructed case: the U-shaped prism of ``test_recon3d_caps`` (a block with a slot open
at the top, extruded along z) in 7 z-slices. Slices 2, 3 and 4 never entered the slot: their
W1 stops at the slot's mouth and an unknown chord A_iB_i closes it (§3.3), so the closure
fills the slot on three slices in a row; slices 1 and 5 show it empty. The caps rule alone
(two neighbouring slices) ends the fill only at slices 2 and 4 towards 1 and 5: between 2
and 4 the slot stays filled, with a plate on each end plane. The run rule keeps the U.
Checked against the truth with trimesh (volume, distance of the surface to the true prism).
"""
import numpy as np
import pytest
import trimesh

import slicer
from recon3d.surface.caps import CapSettings
from recon3d.surface.closure import slice_region
from recon3d.surface.solid import family_solid, fuse

STEP = 0.5
U = np.array([[-10, -6], [10, -6], [10, 6], [6, 6], [6, -2], [-6, -2], [-6, 6], [-10, 6]],
             dtype=float)


def _regions(closed_on):
    loop = np.vstack([U, U[:1]])
    traced = slice_region([loop], [], [], [], 1e-9)
    outside = U[[3, 2, 1, 0, 7, 6]]  # W1 from B = (6, 6) round the outside to A = (-6, 6)
    closed = slice_region([outside], [], [], [np.array([U[6], U[3]])], 1e-9)
    assert closed.area == pytest.approx(240.0) and traced.area == pytest.approx(144.0)
    return [closed if i in closed_on else traced for i in range(7)]


@pytest.fixture(scope="module")
def prism():
    mesh = trimesh.creation.extrude_polygon(trimesh.path.polygons.Polygon(U), 21.0)
    planes = [c.plane for c in slicer.slice_mesh(mesh, axis="z", count=7)]
    lo, hi = planes[0].offset, planes[-1].offset
    truth = trimesh.creation.extrude_polygon(trimesh.path.polygons.Polygon(U),
                                             hi - lo).apply_translation([0, 0, lo])
    return mesh, planes, truth


def _far(prism, closed_on, caps=CapSettings()):
    """The surface's volume and its samples' largest distance to the true prism."""
    mesh, planes, truth = prism
    surface = fuse([family_solid(_regions(closed_on), planes, STEP, caps=caps)], mesh.bounds)
    assert surface.is_watertight
    pts, _ = trimesh.sample.sample_surface(surface, 5000, seed=3)
    return surface.volume, np.abs(trimesh.proximity.signed_distance(truth, pts)).max()


@pytest.mark.parametrize("closed_on", [(2, 3, 4), (2, 3), (1, 2, 3, 4, 5)])
def test_a_slot_closed_on_a_run_of_slices_stays_a_slot(prism, closed_on):
    volume, far = _far(prism, closed_on)
    assert volume == pytest.approx(prism[2].volume, rel=0.01)
    assert far < 2 * STEP  # nothing inside the slot


@pytest.mark.parametrize("closed_on", [(2, 3, 4), (2, 3)])
def test_without_the_run_rule_the_slot_is_filled_between_the_run(prism, closed_on):
    """The failing side: the caps rule alone keeps the fill between the run's slices."""
    volume, far = _far(prism, closed_on, CapSettings(runs=False))
    assert far > 2 * STEP
    assert volume > prism[2].volume * 1.05


def test_a_run_that_reaches_the_end_slice_is_kept(prism):
    """Slices 4, 5, 6 close the slot and the last slice ends the family: no empty neighbour
    shows the slot's end, so the fill stays (the closure's claim is all there is)."""
    mesh, planes, truth = prism
    volume, _ = _far(prism, (4, 5, 6))
    assert volume > truth.volume * 1.05


def test_a_traced_slice_in_the_run_keeps_its_material(prism):
    """Slices 2 and 4 close the slot with a chord, slice 3 traces a full block (W1 all
    round: the sensing shows material there). The run stops at the traced slice: slice 3's
    block stays (a point in the slot on its plane is inside the surface). Without the test of
    the run's boundary being unsensed, the block would be dropped with the chords' fills."""
    mesh, planes, truth = prism
    regions = _regions((2, 4))
    block = np.array([[-10, -6], [10, -6], [10, 6], [-10, 6], [-10, -6]], dtype=float)
    regions[3] = slice_region([block], [], [], [], 1e-9)
    surface = fuse([family_solid(regions, planes, STEP)], mesh.bounds)
    probe = np.array([[0.0, 2.0, planes[3].offset]])
    assert surface.contains(probe)[0]
