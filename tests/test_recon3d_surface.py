"""The stacked surface (recon3d.surface.field / recon3d.surface.solid) from exact slice regions.

Regions are made from the true cross-sections (as if every loop were traced,
W1), so every difference from the ground truth is the reconstruction's.
Checks use manifold3d and trimesh on the written PLY, not recon3d code.
"""
import numpy as np
import pytest
import trimesh
from manifold3d import Manifold

import slicer
from recon3d.io.ply import read_ply_labels, write_ply
from recon3d.surface.closure import slice_region
from recon3d.surface.field import grid_step
from recon3d.surface.solid import family_solid, fuse


def _mesh(man: Manifold) -> trimesh.Trimesh:
    m = man.to_mesh64()
    return trimesh.Trimesh(np.asarray(m.vert_properties)[:, :3], np.asarray(m.tri_verts),
                           process=False)


def _solid(mesh, axis, count, step, keep=False):
    cuts = slicer.slice_mesh(mesh, axis=axis, count=count)
    regions = [slice_region([np.vstack([lp, lp[:1]]) for lp in c.loops], [], [], [], 1e-9)
               for c in cuts]
    return family_solid(regions, [c.plane for c in cuts], step, keep_field=keep), cuts


def _written(tmp_path, surface, name="s.ply"):
    write_ply(tmp_path / name, surface.vertices, surface.faces,
              surface.face_attributes["label"])
    return read_ply_labels(tmp_path / name)


def _as_manifold(mesh):
    from slicer.section import to_manifold

    return to_manifold(mesh)


@pytest.fixture(scope="module")
def pants():
    """A round trunk that splits into two legs and ends in one leg (branching)."""
    trunk = Manifold.cylinder(12.0, 10.0, circular_segments=48).translate([0, 0, 0])
    legs = (Manifold.cylinder(10.0, 5.0, circular_segments=32).translate([-5.5, 0, 10])
            + Manifold.cylinder(16.0, 4.0, circular_segments=32).translate([6.0, 0, 10]))
    return _mesh(trunk + legs)


def test_branching_surface_is_watertight_and_passes_through_every_slice(tmp_path, pants):
    solid, cuts = _solid(pants, "z", 7, 0.25)
    surface = _written(tmp_path, fuse([solid], pants.bounds))
    assert surface.is_watertight and surface.is_winding_consistent and surface.volume > 0
    rec = _as_manifold(surface)
    assert rec is not None  # manifold3d accepts it: an oriented closed 2-manifold
    for c in cuts[1:-1]:
        true = sum(trimesh.path.polygons.Polygon(lp).area for lp in c.loops)
        got = rec.slice(c.plane.offset).area()
        assert got == pytest.approx(true, rel=0.02), c.plane.index
    counts = [len(c.loops) for c in cuts]
    assert 1 in counts and 2 in counts  # the loops split


def test_labels_slice_faces_between_faces_and_caps(tmp_path, pants):
    solid, cuts = _solid(pants, "z", 5, 0.3)
    surface = _written(tmp_path, fuse([solid], pants.bounds))
    lab = surface.face_attributes["label"]
    assert set(np.unique(lab).tolist()) == {1, 4, 5}
    h = np.asarray(surface.vertices, dtype=float)[:, 2]
    planes = np.array([c.plane.offset for c in cuts])
    on = np.abs(h[:, None] - planes[None, :]).min(axis=1) < 1e-4  # float32 PLY
    fh = h[surface.faces]
    caps = lab == 5
    assert np.all(np.isclose(fh[caps], planes[0], atol=1e-4) | np.isclose(fh[caps], planes[-1],
                                                                          atol=1e-4))
    assert np.allclose(np.abs(surface.face_normals[caps][:, 2]), 1.0)
    assert on[surface.faces[lab == 1]].any(axis=1).all()  # W1 faces touch a slice plane
    inner = ~caps & on[surface.faces].any(axis=1)
    assert (lab[inner] == 1).all()  # every face touching a slice is labelled from it


@pytest.fixture(scope="module")
def bored():
    box = Manifold.cube([40.0, 30.0, 20.0])
    return _mesh(box - Manifold.cylinder(40.0, 6.0, circular_segments=48)
                 .translate([20.0, 15.0, -10.0]))


@pytest.mark.parametrize("rule", ["weighted", "carve"])
def test_families_fuse_carving_what_another_family_sees(tmp_path, bored, rule):
    step = 0.4
    z, _ = _solid(bored, "z", 4, step, keep=True)
    x, xcuts = _solid(bored, "x", 5, step, keep=True)
    only_z = _written(tmp_path, fuse([z], bored.bounds), "z.ply")
    both = _written(tmp_path, fuse([z, x], bored.bounds, rule), "zx.ply")
    assert only_z.is_watertight and both.is_watertight
    mid = [c for c in xcuts if len(c.loops) == 2][0].plane.offset  # an x-slice through the bore
    in_bore = [[mid, 15.0, 10.0]]
    assert only_z.contains(in_bore)[0]  # z-slices cannot see the bore: filled
    assert not both.contains(in_bore)[0]  # the x family shows it empty: carved
    near_top = [[mid + 2.0, 3.0, 19.5]]  # above the last z-slice, inside the x slab
    assert not only_z.contains(near_top)[0] and both.contains(near_top)[0]
    assert both.volume < only_z.volume + 40 * 30 * 20 * 0.2


def test_nothing_sensed_gives_no_solid():
    mesh = trimesh.creation.box(extents=[2.0, 2.0, 2.0])
    cuts = slicer.slice_mesh(mesh, "z", count=3)
    regions = [slice_region([], [], [], [], 1e-9) for _ in cuts]
    assert family_solid(regions, [c.plane for c in cuts], grid_step(0.05, 3.5)) is None
    assert len(fuse([None]).faces) == 0


def test_unknown_route_or_rule_is_one_line_error():
    with pytest.raises(ValueError, match="route"):
        family_solid([], [], 0.5, route="spline")
    with pytest.raises(ValueError, match="fusion rule"):
        fuse([None], rule="vote")
