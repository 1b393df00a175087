"""Two families round a cavity that one of them cannot see (the Ravens cup's mechanism).

The constructed case: a 20 mm cube with a 12 mm pocket open at the top (+z). Family z slices
across the pocket's axis: each plane through the pocket cuts a ring whose inner loop no probe
in the plane can reach, so z traces the outer loop only and the closure fills the pocket --
solid z only filled in. Family x slices along it: its planes cut a U and see the pocket
empty, except the middle plane, whose probe never entered: its W1 stops at the pocket's
mouth and an unknown chord A_iB_i closes it (§3.3). The caps rule (:mod:`recon3d.surface.caps`)
drops that chord's fill on the middle plane, as both neighbouring x planes show the pocket
empty. Checked against the truth solid with trimesh (``contains``), not recon3d code. Also
the rule that a solid a family only filled in yields to the other family's sensed empty (a
bored block, genus by manifold3d) and its map :func:`recon3d.surface.support.filled_in`
(against shapely distances).
"""
import numpy as np
import pytest
import shapely
import trimesh
from manifold3d import Manifold, Mesh64

import slicer
from recon3d.surface.caps import CapSettings
from recon3d.surface.closure import slice_region
from recon3d.surface.confidence import ConfidenceSettings
from recon3d.surface.fusion import FusionSettings
from recon3d.surface.solid import family_solid, fuse

STEP = 0.5


def _uv(plane, pts3):
    rel = np.asarray(pts3, dtype=float) - plane.origin
    return np.column_stack([rel @ plane.u, rel @ plane.v])


def _cup(caps=CapSettings()):
    """The truth, family z (outer loops only) and family x (middle plane closed by a chord)."""
    pocket = trimesh.creation.box((12.0, 12.0, 12.0)).apply_translation([0, 0, 4.01])
    mesh = trimesh.creation.box((20.0, 20.0, 20.0)).difference(pocket)
    zc = slicer.slice_mesh(mesh, axis="z", count=5)
    zreg = []
    for c in zc:  # the outer loop only: the pocket's wall is enclosed in the plane
        outer = max(c.loops, key=lambda lp: trimesh.path.polygons.Polygon(lp).area)
        zreg.append(slice_region([np.vstack([outer, outer[:1]])], [], [], [], 1e-9))
    xc = slicer.slice_mesh(mesh, axis="x", count=5)
    xreg = [slice_region([np.vstack([lp, lp[:1]]) for lp in c.loops], [], [], [], 1e-9)
            for c in xc]
    mid = xc[2].plane  # x = 0: W1 round the outside from one mouth corner to the other
    w1 = _uv(mid, [[0, 6, 10], [0, 10, 10], [0, 10, -10], [0, -10, -10], [0, -10, 10],
                   [0, -6, 10]])
    chord = np.array([w1[-1], w1[0]])
    xreg[2] = slice_region([w1], [], [], [chord], 1e-9)
    assert xreg[2].area == pytest.approx(400.0)  # the pocket filled on the middle plane
    z = family_solid(zreg, [c.plane for c in zc], STEP, keep_field=True)
    x = family_solid(xreg, [c.plane for c in xc], STEP, keep_field=True, caps=caps)
    return mesh, z, x


@pytest.fixture(scope="module")
def cup():
    return _cup()


def _pocket_on_middle_plane():
    """(n, 3) points in the pocket on the x = 0 plane, 1 mm and more from its walls, inside
    both slabs (z <= 7 < 8, the last z plane)."""
    y, z = np.meshgrid(np.linspace(-5, 5, 11), np.linspace(-1, 7, 9))
    return np.column_stack([np.zeros(y.size), y.ravel(), z.ravel()])


def test_the_pocket_stays_open_on_the_plane_that_closed_it_with_a_chord(cup):
    """On x's middle plane its own field is dropped to the neighbours' empty; their sensing
    says so, so that empty carries their trust against z's solid, which z only filled in.
    With the slice's own 'unseen' trust there (the closure's chord fill), z's filled solid
    wins on the plane and leaves a plate across the pocket."""
    mesh, z, x = cup
    pts = _pocket_on_middle_plane()
    assert not mesh.contains(pts).any()  # the truth: empty
    assert not fuse([x], mesh.bounds).contains(pts).any()  # x alone: the fill is dropped
    assert fuse([z], mesh.bounds).contains(pts).all()  # z alone fills the pocket
    fused = fuse([z, x], mesh.bounds)
    assert not fused.contains(pts).any()
    _, z, x = _cup(CapSettings(own_trust=False))  # the dropped fill keeps its 'unseen' trust
    assert fuse([z, x], mesh.bounds).contains(pts).mean() > 0.5  # a plate across the pocket


def _genus(mesh):
    m = Mesh64(vert_properties=np.array(mesh.vertices, dtype=np.float64),
               tri_verts=np.array(mesh.faces, dtype=np.uint64))
    m.merge()
    return sum(p.genus() for p in Manifold(m).decompose())


def test_a_solid_only_filled_in_yields_where_the_other_familys_planes_saw_it_empty():
    """A block with a bore along z: z fills the bore (a hole in its planes), x's planes see
    it. With every family's filled-in space trusted as if seen (``unseen=1``), the weights
    alone keep z's fill; the default fusion (``FusionSettings()``, ``filled`` on) lets it
    yield where x's planes contradict it, and the bore opens as in the truth (genus by
    manifold3d)."""
    bore = trimesh.creation.cylinder(5.0, 40.0, sections=32)
    mesh = trimesh.creation.box((40.0, 30.0, 20.0)).difference(bore, engine="manifold")
    blind = ConfidenceSettings(unseen=1.0)
    solids = []
    for axis, count in (("z", 8), ("x", 12)):
        cuts = slicer.slice_mesh(mesh, axis=axis, count=count)
        regs = [slice_region([np.vstack([lp, lp[:1]]) for lp in c.loops], [], [], [], 1e-9)
                for c in cuts]
        solids.append(family_solid(regs, [c.plane for c in cuts], 0.3, keep_field=True,
                                   trust=blind))
    assert _genus(mesh) == 1
    assert _genus(fuse(solids, mesh.bounds, "weighted", FusionSettings())) == 1
    assert _genus(fuse(solids, mesh.bounds, "weighted", FusionSettings(filled=False))) == 0


def test_filled_in_is_zero_behind_a_traced_wall_and_one_deep_or_behind_a_chord():
    """:func:`recon3d.surface.support.filled_in` on the U-slot slice closed by a chord,
    against shapely distances: 0 within depth / 2 of the traced wall, 1 from depth on and
    wherever the chord is the nearer piece, 0 outside."""
    from recon3d.surface.field import FamilyField
    from recon3d.surface.support import filled_in
    box = trimesh.creation.box((20.0, 20.0, 20.0))
    cuts = slicer.slice_mesh(box, axis="z", count=2)
    u = np.array([[-10, -10], [10, -10], [10, 10], [6, 10], [6, -2], [-6, -2], [-6, 10],
                  [-10, 10]], dtype=float)
    outside = u[[3, 2, 1, 0, 7, 6]]
    region = slice_region([outside], [], [], [np.array([u[6], u[3]])], 1e-9)
    solid = family_solid([region, region], [c.plane for c in cuts], STEP, keep_field=True)
    share = filled_in(solid.field, depth=4.0)[solid.field.grid.slice_layer(0)].ravel()
    nodes = solid.field.grid.nodes()
    wall = shapely.LineString(outside)
    chord = shapely.LineString([u[6], u[3]])
    pts = shapely.points(nodes)
    dw, dc = shapely.distance(pts, wall), shapely.distance(pts, chord)
    inside = shapely.contains_xy(region.geometry, nodes[:, 0], nodes[:, 1])
    tol = 0.51 * STEP  # the pieces are sampled every step / 2
    assert (share[~inside] == 0).all()
    assert (share[inside & (dw < 2 * STEP - tol) & (dw < dc - tol)] == 0).all()
    assert (share[inside & (dw > 4 * STEP + tol)] == 1).all()
    assert (share[inside & (dc < dw - tol)] == 1).all()
