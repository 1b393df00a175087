"""Between-slice surfaces that keep thin walls, and the fusion of families that never loses.

Slice regions are made from the true cross-sections (every loop traced, W1; holes filled by
the closure as the probe cannot see them), so every difference from the ground truth is the
reconstruction's. Topology (bodies, genus) is manifold3d's, containment trimesh's.
"""
import numpy as np
import pytest
import shapely
import trimesh
from manifold3d import Manifold, Mesh64

import slicer
from recon3d.surface.closure import slice_region
from recon3d.surface.confidence import ConfidenceSettings
from recon3d.surface.fusion import FusionSettings
from recon3d.surface.solid import family_solid, fuse


def _regions(mesh, axis, count):
    cuts = slicer.slice_mesh(mesh, axis=axis, count=count)
    regions = [slice_region([np.vstack([lp, lp[:1]]) for lp in c.loops], [], [], [], 1e-9)
               for c in cuts]
    return regions, [c.plane for c in cuts]


def _solid(mesh, axis, count, step, route="warp", keep=True, trust=ConfidenceSettings()):
    regions, planes = _regions(mesh, axis, count)
    return family_solid(regions, planes, step, route, keep, trust)


def _topology(mesh):
    """(bodies, genus) of a closed surface."""
    m = Mesh64(vert_properties=np.array(mesh.vertices, dtype=np.float64).view(np.ndarray),
               tri_verts=np.array(mesh.faces, dtype=np.uint64).view(np.ndarray))
    m.merge()
    parts = Manifold(m).decompose()
    return len(parts), int(sum(p.genus() for p in parts))


def _tilted(mesh, degrees):
    mesh.apply_transform(trimesh.transformations.rotation_matrix(np.radians(degrees), [1, 0, 0]))
    return mesh


@pytest.fixture(scope="module")
def wall():
    """A 1 mm slab tilted 45 degrees: with 16 z-slices its section moves ~2.6 x its width."""
    return _tilted(trimesh.creation.box((60.0, 60.0, 1.0)), 45.0)


@pytest.fixture(scope="module")
def ring():
    """A thin torus (genus 1) tilted 60 degrees: z-slices cut it in two moving blobs."""
    return _tilted(trimesh.creation.torus(25.0, 1.5, major_sections=96, minor_sections=16), 60.0)


@pytest.mark.parametrize("route, one_wall", [("warp", True), ("linear", False)])
def test_thin_tilted_wall_sliced_across_stays_one_wall(wall, route, one_wall):
    surface = fuse([_solid(wall, "z", 16, 0.25, route, keep=False)], wall.bounds)
    assert surface.is_watertight
    bodies, genus = _topology(surface)
    # the truth is one body of genus 0; plain shape-based interpolation breaks it into fins
    assert ((bodies, genus) == (1, 0)) is one_wall, (bodies, genus)


@pytest.mark.parametrize("route, kept", [("warp", True), ("linear", False)])
def test_thin_tilted_ring_stays_a_ring(ring, route, kept):
    surface = fuse([_solid(ring, "z", 16, 0.25, route, keep=False)], ring.bounds)
    assert _topology(surface) == (1, 1)
    # plain blending bulges the moving blobs between slices; the aligned blend follows them
    lab = surface.face_attributes["label"]
    far = np.abs(trimesh.proximity.signed_distance(ring, surface.triangles_center[lab != 5]))
    assert bool((far > 0.5).mean() < 0.03) is kept  # 0.5: a third of the ring's radius


def _block_with_bore():
    """A 40 x 30 x 20 block with a 10 mm bore along z: z-slices cannot see the bore."""
    block = trimesh.creation.box((40.0, 30.0, 20.0))
    bore = trimesh.creation.cylinder(5.0, 40.0, sections=32)
    return block.difference(bore, engine="manifold")


def test_fusion_gains_the_through_hole_only_the_other_axis_sees():
    mesh = _block_with_bore()
    z = _solid(mesh, "z", 8, 0.3)
    x = _solid(mesh, "x", 12, 0.3)
    assert _topology(fuse([z], mesh.bounds)) == (1, 0)  # z alone: the bore filled
    fused = fuse([z, x], mesh.bounds)
    assert fused.is_watertight
    assert _topology(fused) == (1, 1)  # the bore, seen empty by x, stays open
    # a family's filled-in space counts as seen, and does not yield to the other family's
    # sensed empty (FusionSettings.filled off): x cannot open the bore against z
    blind = ConfidenceSettings(unseen=1.0)
    zb = _solid(mesh, "z", 8, 0.3, trust=blind)
    xb = _solid(mesh, "x", 12, 0.3, trust=blind)
    assert _topology(fuse([zb, xb], mesh.bounds, "weighted",
                          FusionSettings(filled=False))) == (1, 0)


def test_fused_faces_on_slice_planes_keep_their_sensed_label():
    """A fused face with a vertex on a slice plane takes the kind of the nearest sensed
    piece (W1 here), as one family's faces do: the fused surface labels W1 at least the
    share of the surface one family alone labels (the rule of ``fusion._labels``)."""
    mesh = _block_with_bore()
    z, x = _solid(mesh, "z", 8, 0.3), _solid(mesh, "x", 12, 0.3)

    def w1_share(surface):
        lab = np.asarray(surface.face_attributes["label"])
        return surface.area_faces[lab == 1].sum() / surface.area_faces[lab != 5].sum()

    alone = max(w1_share(fuse([z], mesh.bounds)), w1_share(fuse([x], mesh.bounds)))
    assert alone > 0.05
    assert w1_share(fuse([z, x], mesh.bounds)) >= 0.9 * alone


def _ridge():
    """A 40 x 10 block (x, y) with a narrow raised-cosine ridge on top, extruded 20 along z.

    Four x-slices (x = 5, 15, 25, 35) see the ridge only at 2.5 of its 8 mm: its peak
    (x = 20) lies half-way between two of them. z-slices see the whole profile.
    """
    t = np.linspace(0.0, 1.0, 33)
    bump = np.column_stack([12.0 + 16.0 * t, 10.0 + 4.0 * (1 - np.cos(2 * np.pi * t))])
    outline = np.vstack([[[0.0, 0.0], [40.0, 0.0], [40.0, 10.0]], bump[::-1], [[0.0, 10.0]]])
    return trimesh.creation.extrude_polygon(shapely.Polygon(outline), 20.0)


@pytest.fixture(scope="module")
def ridge_families():
    mesh = _ridge()
    return mesh, _solid(mesh, "z", 6, 0.25), _solid(mesh, "x", 4, 0.25)


def test_fusion_keeps_what_one_family_saw_against_the_others_interpolation(ridge_families):
    mesh, z, x = ridge_families
    peak = np.array([[20.0, 17.6, 10.0]])  # 0.4 mm under the peak, between two x-slices
    assert mesh.contains(peak)[0]
    assert fuse([z], mesh.bounds).contains(peak)[0]
    assert not fuse([x], mesh.bounds).contains(peak)[0]  # x's interpolation misses the peak
    assert not fuse([z, x], mesh.bounds, "carve").contains(peak)[0]  # carving loses it
    assert fuse([z, x], mesh.bounds).contains(peak)[0]  # the weighted fusion keeps it


def _sensed_points(solid, margin):
    """World points on a family's slice planes: shown empty (outside its region, farther than
    ``margin`` from the boundary) and shown solid (inside, ``margin`` / 2 to ``margin`` behind
    a traced wall)."""
    empty, full = [], []
    inner = slice(1, -1)  # the first and last planes bound the slab: on the cut
    for plane, region in zip(solid.field.planes[inner], solid.field.regions[inner]):
        lo, hi = np.array(region.geometry.bounds[:2]), np.array(region.geometry.bounds[2:])
        g = np.stack(np.meshgrid(*[np.linspace(a - 4 * margin, b + 4 * margin, 40)
                                   for a, b in zip(lo, hi)]), axis=-1).reshape(-1, 2)
        d = shapely.distance(region.geometry.boundary, shapely.points(g))
        inside = shapely.contains_xy(region.geometry, g[:, 0], g[:, 1])
        world = plane.origin + np.outer(g[:, 0], plane.u) + np.outer(g[:, 1], plane.v)
        empty.append(world[~inside & (d > margin)])
        full.append(world[inside & (d > margin / 2) & (d < margin)])
    return np.concatenate(empty), np.concatenate(full)


def test_sensed_empty_stays_empty_and_sensed_solid_stays_solid(ridge_families):
    mesh, z, x = ridge_families
    fused = fuse([z, x], mesh.bounds)
    margin = 2 * 0.25  # two grid steps: a traced wall's full confidence reaches that deep
    for solid in (z, x):
        empty, full = _sensed_points(solid, margin)
        assert len(empty) > 100 and len(full) > 100
        assert not fused.contains(empty).any()
        assert fused.contains(full).all()


def _gear():
    """A 12-tooth star prism (radii 20 / 14), 10 high along z: every face is a z-wall or a lid."""
    t = np.linspace(0.0, 2 * np.pi, 24, endpoint=False)
    r = np.where(np.arange(24) % 2 == 0, 20.0, 14.0)
    return trimesh.creation.extrude_polygon(shapely.Polygon(np.column_stack([r * np.cos(t),
                                                                             r * np.sin(t)])), 10.0)


def test_beyond_its_slab_a_family_shapes_walls_but_does_not_decide_where_the_part_ends():
    """Between z's last slice (z = 9.17) and the top face (z = 10) only x senses: its planes
    cut the top face across. z's end slice, extended, shapes the teeth there (without it the
    surface is worse) but must not push them through the top face x saw (at
    ``FusionSettings.extend`` = 0.3 it did: 57 of 20 000 samples above the top)."""
    mesh, step = _gear(), 0.4
    z, x = _solid(mesh, "z", 6, step), _solid(mesh, "x", 16, step)
    assert z.slab[1] < 10.0 - step  # the top face lies beyond z's slab
    diag = np.linalg.norm(mesh.extents)

    def sampled(settings):
        pts, _ = trimesh.sample.sample_surface(fuse([z, x], mesh.bounds, "weighted", settings),
                                               20000, seed=0)
        far = np.abs(trimesh.proximity.signed_distance(mesh, pts)) > 0.01 * diag
        return pts, far.mean()

    pts, far = sampled(FusionSettings())
    assert pts[:, 2].max() < 10.0 + step  # nothing through the top face
    _, far_unextended = sampled(FusionSettings(extend=0.0))
    assert far < far_unextended  # the extension still helps


@pytest.mark.parametrize("degrees", [90.0, 60.0, 30.0])
def test_in_plane_share_is_the_sine_of_the_normal_to_the_slicing_axis(degrees):
    """The facing weight's measure: on a plane whose normal makes ``degrees`` with the slicing
    axis, a stack of 2D signed distances has in-plane gradient share sin(degrees)."""
    from recon3d.surface.confidence import in_plane_share
    from recon3d.surface.field import FamilyGrid
    grid = FamilyGrid(0.0, 0.0, 0.5, (20, 10), np.array([0.0, 2.0, 4.0]), 4, 4.0)
    phi = np.radians(degrees)
    h = grid.layer_height(np.arange(grid.layers))[:, None, None]
    x = (grid.x0 + grid.step * np.arange(grid.shape[0]))[None, None, :]
    vol = np.broadcast_to(x + h / np.tan(phi) - 5.0, (grid.layers, 10, 20))  # in-plane SDF
    share = in_plane_share(vol, grid)
    assert np.allclose(share, np.sin(phi), atol=1e-4)


def test_an_empty_a_family_did_not_see_on_its_planes_yields_to_a_sensed_solid(ridge_families):
    """3 mm (12 grid steps) under the ridge's peak, half-way between x's planes x = 15 and 25:
    z's slices enclose the point behind the traced ridge (a sensed solid, though too deep for
    z's confidence), x's planes see no ridge there (x's empty is interpolated). x may carve
    z's solid only where its own planes contradict it (``FusionSettings.explained``)."""
    mesh, z, x = ridge_families
    deep = np.array([[20.0, 15.0, 10.0]])
    assert mesh.contains(deep)[0] and not fuse([x], mesh.bounds).contains(deep)[0]
    assert fuse([z, x], mesh.bounds).contains(deep)[0]
    # without the rule x's interpolated empty (weight 0.05^2) beats z's deep solid (0.03^2)
    unexplained = FusionSettings(explained=False)
    assert not fuse([z, x], mesh.bounds, "weighted", unexplained).contains(deep)[0]


def test_the_contradiction_supports_an_empty_between_planes_that_both_saw_it():
    """The bore (along z) on x's planes: x sensed it empty where z's filled region says solid.
    Between two x planes that both cut the bore the support stays 1; half-way between x
    planes in the block's solid, where x saw no empty, it is 0."""
    from recon3d.surface.fusion import value_in_slab
    from recon3d.surface.support import contradiction
    mesh = _block_with_bore()
    z, x = _solid(mesh, "z", 8, 0.3).field, _solid(mesh, "x", 12, 0.3).field
    kx = contradiction(x, [z], value_in_slab)
    g = x.grid
    mid = g.slice_layer(5) + g.k // 2  # half-way between x = -1.8 and x = 1.8: in the bore
    frame = [(p - x.planes[0].origin) @ np.array([x.planes[0].u, x.planes[0].v]).T
             for p in (np.zeros(3), np.array([0.0, 10.0, 0.0]))]  # bore axis, solid block
    (bu, bv), (su, sv) = [((u - g.x0) / g.step, (v - g.y0) / g.step) for u, v in frame]
    assert kx[mid, int(round(bv)), int(round(bu))] > 0.99
    assert kx[mid, int(round(sv)), int(round(su))] == 0.0


def test_space_closed_by_a_lid_is_not_a_sensed_solid():
    """A U-shaped cup section: W1 traced outside and along the floor, a W3 lid across the
    mouth. Inside next to W1 the region is a sensed solid; behind the lid it is filled only."""
    from recon3d.surface.field import FamilyField, family_grid, family_volume
    from recon3d.surface.support import sensed_solid
    w1 = [np.array([[10.0, 10.0], [10.0, 0.0], [0.0, 0.0], [0.0, 10.0], [2.0, 10.0],
                    [2.0, 2.0], [8.0, 2.0], [8.0, 10.0], [10.0, 10.0]])]
    lid = [np.array([[2.0, 10.0], [8.0, 10.0]])]
    regions = [slice_region(w1, [], lid, [], 1e-6)] * 2
    grid = family_grid(regions, [0.0, 1.0], 0.25)
    vol, conf = family_volume(regions, grid, confidence=True)
    planes = tuple(slicer.slice_mesh(trimesh.creation.box((20.0, 20.0, 20.0)), "z", 2))
    field = FamilyField(grid, vol, conf, tuple(p.plane for p in planes), tuple(regions))
    solid = sensed_solid(field)
    at = lambda x_, y_: solid[grid.slice_layer(0), int(round((y_ - grid.y0) / grid.step)),
                              int(round((x_ - grid.x0) / grid.step))]
    assert at(1.0, 5.0) == 1.0  # in the cup's wall: W1 on both sides
    assert at(5.0, 8.0) == 0.0  # inside the cup, under the lid: closed, not sensed


def _block_with_unswept_wedge(trust):
    """A 20 mm cube. Family x: its exact sections (solid everywhere inside). Family z: each
    plane traced all round but for a 5 mm stretch of one side, from whose ends two unknown
    chords meet at the centre -- the lids of an area the planner never explored. The closure
    leaves that wedge *outside* (no piece closes its mouth), as it left parts of the open
    teapot's pot outside beside the unknown chords crossing it."""
    mesh = trimesh.creation.box((20.0, 20.0, 20.0))
    x = _solid(mesh, "x", 8, 0.25)
    cuts = slicer.slice_mesh(mesh, axis="z", count=6)
    regions = []
    for c in cuts:
        (x0, y0), (x1, y1) = c.loops[0].min(axis=0), c.loops[0].max(axis=0)
        xm, mid = (x0 + x1) / 2, np.array([(x0 + x1) / 2, (y0 + y1) / 2])
        w1 = [np.array([[xm, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0], [xm - 5.0, y0]])]
        chords = [np.array([[xm - 5.0, y0], mid]), np.array([mid, [xm, y0]])]
        regions.append(slice_region(w1, [], [], chords, 1e-6))
    z = family_solid(regions, [c.plane for c in cuts], 0.25, "warp", True, trust)
    plane = cuts[2].plane  # a point in the wedge, half-way between z planes 2 and 3
    (x0, y0), (x1, y1) = cuts[2].loops[0].min(axis=0), cuts[2].loops[0].max(axis=0)
    u, v = (x0 + x1) / 2 - 2.5, y0 + (y1 - y0) / 6
    height = (cuts[3].plane.offset - plane.offset) / 2
    point = plane.origin + u * plane.u + v * plane.v + height * np.asarray(plane.normal)
    return mesh, z, x, point[None]


def test_an_empty_beside_an_unknown_chord_is_not_shown_empty_and_cannot_carve_a_solid():
    """The rule: a family removes space only where its own sensing shows it empty. z's
    planes leave the wedge outside their regions only because no piece closes it; the
    unknown contour between a chord's ends may stand on either side of the chord (Def. 1,
    §3.2), so beside it nothing was shown empty (``ConfidenceSettings.unswept``): x's
    solid stays."""
    mesh, z, x, point = _block_with_unswept_wedge(ConfidenceSettings())
    assert mesh.contains(point)[0] and fuse([x], mesh.bounds).contains(point)[0]
    assert not fuse([z], mesh.bounds).contains(point)[0]  # z's closure leaves the wedge out
    assert fuse([z, x], mesh.bounds).contains(point)[0]
    # an empty beside an unknown chord counted as shown empty carves x's solid
    _, zs, _, _ = _block_with_unswept_wedge(ConfidenceSettings(unswept=False))
    assert not fuse([zs, x], mesh.bounds).contains(point)[0]


@pytest.mark.parametrize("reverse", [False, True])
def test_space_beside_an_unknown_chord_is_unswept_on_either_side(reverse):
    """A square traced but for a stretch of its bottom side, two unknown chords from that
    stretch's ends to the centre. The wedge between them lies outside the region on the
    chords' unknown side (right of A -> B) or, reversed, on their free side V_i: either way
    it was not shown empty. Outside next to the traced wall it was."""
    from recon3d.surface.confidence import unswept
    w1 = [np.array([[10.0, 0.0], [20.0, 0.0], [20.0, 20.0], [0.0, 20.0], [0.0, 0.0],
                    [5.0, 0.0]])]
    chords = [np.array([[5.0, 0.0], [10.0, 10.0]]), np.array([[10.0, 10.0], [10.0, 0.0]])]
    if reverse:
        chords = [c[::-1] for c in chords[::-1]]
    region = slice_region(w1, [], [], chords, 1e-6)
    wedge, beside_wall = np.array([[8.5, 3.0]]), np.array([[15.0, -1.0]])
    assert not shapely.contains_xy(region.geometry, *wedge.T).any()
    assert unswept(region, wedge, 0.25).all()
    assert not unswept(region, beside_wall, 0.25).any()
    assert not unswept(region, wedge, 0.25, reach=4.0).any()  # 1.5 from the chord: beyond
    assert unswept(region, wedge, 0.25, reach=8.0).all()
