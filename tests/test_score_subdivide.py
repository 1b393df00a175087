"""The coloured ground truth's subdivision: trimesh's ``subdivide_to_size`` arrays, the same
vertices and faces in the same order (``==``, dtypes too), looking only at the faces made in
the round before."""
import numpy as np
import pytest
import trimesh

import meshes
from recon3d.config import diagonal
from recon3d.score import subdivide as subdivide_module
from recon3d.score.evaluate import classified_ground_truth, contour_cloud
from recon3d.score.subdivide import face_centres, subdivide_to_size
from recon3d.surface.field import grid_step


def _bumpy():
    """An icosphere with jittered vertices and a few faces stretched: uneven edges, faces
    with one, two and three long edges in the same round."""
    m = trimesh.creation.icosphere(subdivisions=2)
    rng = np.random.default_rng(3)
    v = m.vertices * (1 + 0.3 * rng.random((len(m.vertices), 1)))
    v[:5] *= 2.5
    return v, m.faces


def _cases():
    for name in ("bored_block", "fig18_overhangs", "gear", "cup_handle"):
        mesh = meshes.load(name)
        d = diagonal(mesh)
        for share in (1.0, 2.0):  # the run's edge (2 x grid step) and coarser
            yield name, mesh.vertices, mesh.faces, share * 2 * grid_step(d / 200, d)
    v, f = _bumpy()
    for edge in (0.05, 0.2, 0.6, 5.0):  # 5.0: nothing to split
        yield f"bumpy@{edge}", v, f, edge


@pytest.mark.parametrize("name, vertices, faces, edge", list(_cases()),
                         ids=lambda x: x if isinstance(x, str) else "")
def test_the_same_arrays_as_trimesh(name, vertices, faces, edge):
    want_v, want_f = trimesh.remesh.subdivide_to_size(vertices, faces, edge, max_iter=12)
    got_v, got_f = subdivide_to_size(vertices, faces, edge, max_iter=12)
    assert got_v.dtype == want_v.dtype and got_f.dtype == want_f.dtype
    assert np.array_equal(got_v, want_v)
    assert np.array_equal(got_f, want_f)


def test_too_few_rounds_raise_as_trimesh_does():
    v, f = _bumpy()
    with pytest.raises(ValueError, match="max_iter"):
        trimesh.remesh.subdivide_to_size(v, f, 0.01, max_iter=2)
    with pytest.raises(ValueError, match="max_iter"):
        subdivide_to_size(v, f, 0.01, max_iter=2)


def test_a_round_looks_only_at_the_faces_made_in_the_round_before(monkeypatch):
    """The speed decision itself: the faces whose edges are all short are set aside, so the
    rounds look at fewer faces than trimesh's (which looks at every face every round)."""
    seen = []
    real = subdivide_module._round

    def counting(vertices, faces, max_edge):
        seen.append(len(faces))
        return real(vertices, faces, max_edge)

    monkeypatch.setattr(subdivide_module, "_round", counting)
    mesh = meshes.load("bored_block")
    d = diagonal(mesh)
    _, faces = subdivide_to_size(mesh.vertices, mesh.faces, 2 * grid_step(d / 200, d), 12)
    assert seen[0] == len(mesh.faces) and seen[-1] < len(faces)
    assert sum(seen) < 0.75 * len(seen) * len(faces)


def test_the_coloured_ground_truth_uses_it():
    mesh = meshes.load("fig18_overhangs")
    d = diagonal(mesh)
    edge = 2 * grid_step(d / 200, d)
    cloud = contour_cloud([])
    gt = classified_ground_truth(mesh, cloud, edge)
    want_v, want_f = trimesh.remesh.subdivide_to_size(mesh.vertices, mesh.faces, edge, 12)
    assert np.array_equal(gt.vertices, want_v) and np.array_equal(gt.faces, want_f)


@pytest.mark.parametrize("name", ["fig18_overhangs", "gear"])
def test_face_centres_are_trimeshs_numbers(name):
    """The coloured ground truth classifies its faces at :func:`face_centres`: the very
    floats of trimesh's ``triangles_center`` (a face on the boundary between two classes
    keeps its class), on a subdivided scene and on random corners."""
    mesh = meshes.load(name)
    d = diagonal(mesh)
    v, f = subdivide_to_size(mesh.vertices, mesh.faces, 2 * grid_step(d / 200, d), 12)
    want = trimesh.Trimesh(v, f, process=False).triangles_center
    assert np.array_equal(face_centres(v, f), want)
    rng = np.random.default_rng(5)
    v = rng.normal(size=(300, 3)) * 10.0 ** rng.integers(-3, 4, size=(300, 1))
    f = rng.integers(0, 300, size=(2000, 3))
    assert np.array_equal(face_centres(v, f), trimesh.Trimesh(v, f, process=False).triangles_center)
