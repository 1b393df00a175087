"""Space a slice only closed by an unknown chord ends at that slice (recon3d.surface.caps).

The constructed case: a U-shaped prism (a block with a slot open at the top, extruded along
z), sliced along z. Every slice traces the U (W1) except the middle one, whose probe never
entered the slot: its W1 stops at the slot's mouth and an unknown chord A_iB_i closes it
(§3.3), so the closure fills the slot there. The neighbouring slices show the slot empty.
The plain aligned blend turns that one filled slot into surface between slices (a plate on
the middle plane with tents to both neighbours); the rule keeps the U. Checked against the
truth with trimesh (volume, distance of the surface to the true prism), not recon3d code.
"""
import numpy as np
import pytest
import trimesh

import slicer
from recon3d.surface.caps import CapSettings, cap_unsensed
from recon3d.surface.closure import slice_region
from recon3d.surface.field import family_grid, slice_sdf
from recon3d.surface.solid import family_solid, fuse

STEP = 0.5
#: the U's outline, counter-clockwise: a 20 x 12 block, the slot 12 wide and 8 deep from y = 6
U = np.array([[-10, -6], [10, -6], [10, 6], [6, 6], [6, -2], [-6, -2], [-6, 6], [-10, 6]],
             dtype=float)


@pytest.fixture(scope="module")
def u_prism():
    """The truth (z in [0, 20]) and its 5 z-slices, the middle one closed by a chord."""
    mesh = trimesh.creation.extrude_polygon(trimesh.path.polygons.Polygon(U), 20.0)
    planes = [c.plane for c in slicer.slice_mesh(mesh, axis="z", count=5)]
    loop = np.vstack([U, U[:1]])
    traced = slice_region([loop], [], [], [], 1e-9)
    # the middle slice: W1 from B = (6, 6) round the outside to A = (-6, 6), chord A B
    outside = U[[3, 2, 1, 0, 7, 6]]
    chord = np.array([U[6], U[3]])
    closed = slice_region([outside], [], [], [chord], 1e-9)
    assert closed.area == pytest.approx(240.0) and traced.area == pytest.approx(144.0)
    regions = [traced, traced, closed, traced, traced]
    return mesh, planes, regions


def _surface(u_prism, caps=CapSettings()):
    mesh, planes, regions = u_prism
    solid = family_solid(regions, planes, STEP, caps=caps)
    return fuse([solid], mesh.bounds)


def _truth_in_slab(mesh, planes):
    lo, hi = planes[0].offset, planes[-1].offset
    return trimesh.creation.extrude_polygon(trimesh.path.polygons.Polygon(U),
                                            hi - lo).apply_translation([0, 0, lo])


def test_a_slot_one_slice_closes_with_a_chord_stays_a_slot(u_prism):
    mesh, planes, _ = u_prism
    surface = _surface(u_prism)
    truth = _truth_in_slab(mesh, planes)
    assert surface.is_watertight
    assert surface.volume == pytest.approx(truth.volume, rel=0.01)
    pts, _ = trimesh.sample.sample_surface(surface, 5000, seed=3)
    far = np.abs(trimesh.proximity.signed_distance(truth, pts))
    assert far.max() < 2 * STEP  # nothing inside the slot


@pytest.mark.parametrize("off", [{"enabled": False}, {"own": False}])
def test_without_the_rule_the_slot_is_bridged(u_prism, off):
    """The failing side of the decision: the plain blend (or the rule without dropping the
    middle slice's own fill) leaves surface inside the slot, farther than 2 steps from the
    truth."""
    mesh, planes, _ = u_prism
    surface = _surface(u_prism, CapSettings(**off))
    pts, _ = trimesh.sample.sample_surface(surface, 5000, seed=3)
    far = np.abs(trimesh.proximity.signed_distance(_truth_in_slab(mesh, planes), pts))
    assert far.max() > 2 * STEP


def test_only_a_fill_closed_by_a_chord_is_capped(u_prism):
    """Where both sides of a disagreement are traced walls (a true change of shape: the slot
    against a block traced all round) the rule decides nothing; the same block closed by the
    chord is capped on the slot, and only there."""
    _, _, regions = u_prism
    block = slice_region([np.array([[-10, -6], [10, -6], [10, 6], [-10, 6], [-10, -6]],
                                   dtype=float)], [], [], [], 1e-9)
    grid = family_grid([regions[0], block], [0.0, 4.0], STEP)
    nx, ny = grid.shape
    f_u, f_block, f_closed = (slice_sdf(r, grid).reshape(ny, nx)
                              for r in (regions[0], block, regions[2]))
    assert cap_unsensed(f_block, f_u, block, regions[0], grid, 4.0) is None
    caps = cap_unsensed(f_closed, f_u, regions[2], regions[0], grid, 4.0)
    slot = (f_closed > 0) & (f_u <= 0)
    assert caps is not None and np.array_equal(caps.fill_a, slot)
    assert not (caps.fill_b.any() or caps.empty_a.any() or caps.empty_b.any())


@pytest.fixture(scope="module")
def slit_block():
    """A 20 x 12 x 20 block; 5 z-slices trace it, the middle one leaves a thin V-slit
    between two unknown chords reaching from the top edge to its middle (a probe that
    entered a gap of an open part: the open teapot's pot between chords crossing it)."""
    mesh = trimesh.creation.box((20.0, 12.0, 20.0)).apply_translation([0, 0, 10])
    planes = [c.plane for c in slicer.slice_mesh(mesh, axis="z", count=5)]
    box = np.array([[-10, -6], [10, -6], [10, 6], [-10, 6], [-10, -6]], dtype=float)
    traced = slice_region([box], [], [], [], 1e-9)
    outline = np.array([[0.4, 6], [10, 6], [10, -6], [-10, -6], [-10, 6], [-0.4, 6]])
    chords = [np.array([[-0.4, 6], [0, -3]]), np.array([[0, -3], [0.4, 6]])]
    slit = slice_region([outline], [], [], chords, 1e-9)
    assert slit.area == pytest.approx(240.0 - 0.8 * 9 / 2)
    return mesh, planes, [traced, traced, slit, traced, traced]


@pytest.mark.parametrize("off", [None, {"enabled": False}, {"enclosed": -1.0},
                                 {"slits": False}])
def test_a_slit_between_chords_inside_the_fill_makes_no_sheet(slit_block, off):
    """With ``slits``, the slit is unsensed empty that the neighbours' fill encloses: it ends at
    its slice. Without the rule (or without its empty half, the default) the slit is blended
    into a sheet of surface reaching into both gaps, farther than 2 steps from the block."""
    mesh, planes, regions = slit_block
    surface = fuse([family_solid(regions, planes, STEP,
                                 caps=CapSettings(**{"slits": True, **(off or {})}))],
                   mesh.bounds)
    lo, hi = planes[0].offset, planes[-1].offset
    truth = trimesh.creation.box((20.0, 12.0, hi - lo)).apply_translation([0, 0, (lo + hi) / 2])
    pts, _ = trimesh.sample.sample_surface(surface, 5000, seed=3)
    far = np.abs(trimesh.proximity.signed_distance(truth, pts)).max()
    assert (far < 2 * STEP) if off is None else (far > 2 * STEP)


def _slanted(z0, z1):
    """A block x in [-10, r(z)], y in [-6, 6], z in [z0, z1], r(z) = 8 - 0.6 z."""
    pts = [(x, y, z) for z in (z0, z1) for x in (-10.0, 8.0 - 0.6 * z) for y in (-6.0, 6.0)]
    return trimesh.convex.convex_hull(np.array(pts))


@pytest.mark.parametrize("traced, off", [((), None), ((), {"slits": True, "enclosed": 1e9}),
                                         ((1, 3), None), ((1, 3), {"deep": 0.0})])
def test_a_slanted_face_closed_by_bridges_stays_slanted(traced, off):
    """Slices close the moving face with a bridge (no contact there), those in ``traced``
    trace it (W1). Between two bridges the strip is neither a fill nor a slit the other slice
    encloses; between a bridge and a traced face it is a fill thinner than the gap (a face
    that moved, under 45 degrees). Either way the blend keeps the slope. Capping the strip
    (the rule without its 'enclosed' or 'deep' test) makes stairs: the volume grows by a
    triangle per gap."""
    mesh = _slanted(0.0, 20.0)
    planes = [c.plane for c in slicer.slice_mesh(mesh, axis="z", count=5)]
    regions = []
    for i, p in enumerate(planes):
        r = 8.0 - 0.6 * p.offset
        loop = np.array([[r, 6], [-10, 6], [-10, -6], [r, -6]] + ([[r, 6]] if i in traced else []))
        regions.append(slice_region([loop], [], [], [], 1e-9))
    assert sum(q.kind == "bridge" for r in regions for q in r.pieces) == 5 - len(traced)
    surface = fuse([family_solid(regions, planes, STEP, caps=CapSettings(**(off or {})))],
                   mesh.bounds)
    truth = _slanted(planes[0].offset, planes[-1].offset)
    same = surface.volume == pytest.approx(truth.volume, rel=0.02)
    assert same if off is None else not same
