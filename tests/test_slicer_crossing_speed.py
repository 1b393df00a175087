"""The plane-crossing test without numpy's row reductions, and the mesh's scale asked once:
the same faces, triangles and segments as the plain formulas."""
import numpy as np
import pytest
import trimesh

import slicer.contact.embree as ec_mod
from slicer import make_planes, slice_mesh
from slicer.contact.crossing import crossing_faces, plane_crossing, section_segments


def _plain_crossing_faces(heights_per_face):
    above = np.asarray(heights_per_face) > 0
    return np.flatnonzero(above.any(axis=1) & ~above.all(axis=1))


def _plain_plane_crossing(mesh, plane):
    vertices = np.asarray(mesh.vertices, dtype=np.float64)
    faces = np.asarray(mesh.faces)
    local_v = (vertices - plane.origin) @ plane.basis.T
    z = local_v[:, 2]
    idx = _plain_crossing_faces(z[faces])
    local = local_v[faces[idx]]
    seg, outward = section_segments(local)
    keep = np.any(seg[:, 0] != seg[:, 1], axis=1)
    return z, idx[keep], local[keep], seg[keep], outward[keep]


def test_crossing_faces_is_any_and_not_all():
    rng = np.random.default_rng(5)
    h = rng.choice([-1.0, 0.0, -0.0, 1e-300, 2.0], size=(5000, 3))  # zeros count as below
    got = crossing_faces(h)
    assert np.array_equal(got, _plain_crossing_faces(h))
    assert 0 < len(got) < len(h)


@pytest.mark.parametrize("axis", ["z", "x", "0.3,-1,0.2"])
def test_plane_crossing_is_the_plain_one(axis):
    mesh = trimesh.creation.icosphere(subdivisions=4)
    mesh.vertices += np.random.default_rng(1).normal(0, 0.01, mesh.vertices.shape)
    planes = make_planes(mesh, axis, count=9) + make_planes(mesh, axis, offsets=[0.0])
    for plane in planes:
        cut = plane_crossing(mesh, plane)
        want = _plain_plane_crossing(mesh, plane)
        got = (cut.heights, cut.face_index, cut.triangles, cut.segments, cut.outward)
        for a, b in zip(got, want):
            assert a.dtype == b.dtype and np.array_equal(a, b)
        assert len(cut.face_index) > 0


def test_a_slice_hands_its_scale_to_the_embree_scene(monkeypatch):
    """The mesh's bounding-box diagonal is known to the slice (computed once per mesh):
    the scene of every plane does not measure the whole mesh again."""
    mesh = trimesh.creation.icosphere(subdivisions=3)
    cuts = slice_mesh(mesh, "z", count=3)

    def measured(*_):
        raise AssertionError("mesh_scale asked again")

    monkeypatch.setattr(ec_mod, "mesh_scale", measured)
    for cut in cuts:
        assert len(cut.contact("embree").face_index) > 0
    with pytest.raises(AssertionError, match="asked again"):
        ec_mod.EmbreeContact(mesh, cuts[0].plane)
