"""Meshes a run cannot trust: non-finite vertices, flat meshes, overlapping bodies."""
from __future__ import annotations

import warnings

import numpy as np
import pytest
import trimesh

import meshes
from meshes import MeshError, MeshWarning
from meshes.validate import overlap_volume


def _with_nan(box: trimesh.Trimesh, value=np.nan) -> trimesh.Trimesh:
    v = box.vertices.copy()
    v[0] = value
    return trimesh.Trimesh(v, box.faces, process=False)


def _load(path, **kw):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        mesh = meshes.load(path, **kw)
    return mesh, [str(w.message) for w in caught if issubclass(w.category, MeshWarning)]


@pytest.mark.parametrize("ext", ["obj", "ply", "off", "stl"])
@pytest.mark.parametrize("value", [np.nan, np.inf])
def test_non_finite_vertex_is_an_error_naming_the_count(tmp_path, ext, value):
    path = tmp_path / f"bad.{ext}"
    with np.errstate(invalid="ignore"):  # the STL writer's face normals
        _with_nan(trimesh.creation.box(), value).export(path)
    with pytest.raises(MeshError, match=r"bad\.\w+: \d+ of \d+ vertices are not finite"):
        meshes.load(path)


@pytest.mark.parametrize("ext", ["obj", "ply"])
def test_drop_nonfinite_drops_the_faces_that_use_them_and_says_so(tmp_path, ext):
    path = tmp_path / f"bad.{ext}"
    _with_nan(trimesh.creation.box()).export(path)
    mesh, notes = _load(path, drop_nonfinite=True)
    assert np.isfinite(mesh.vertices).all()
    # vertex 0 of a box is used by 4 of its 12 triangles (an independent count)
    used = int(np.isin(trimesh.creation.box().faces, [0]).any(axis=1).sum())
    assert len(mesh.faces) == 12 - used
    assert any("dropped 1 of 8 vertices" in n for n in notes)
    assert any("not watertight" in n for n in notes)


def test_a_single_triangle_is_flat(tmp_path):
    path = tmp_path / "tri.stl"
    trimesh.Trimesh([[0, 0, 0], [1, 0, 0], [0, 1, 0.5]], [[0, 1, 2]]).export(path)
    with pytest.raises(MeshError, match="tri.stl: the mesh is flat"):
        meshes.load(path)


def test_a_thin_box_is_not_flat(tmp_path):
    path = tmp_path / "thin.stl"
    trimesh.creation.box((10.0, 10.0, 1e-3)).export(path)
    mesh, _ = _load(path)
    assert len(mesh.faces) == 12


def _two_boxes(shift):
    a = trimesh.creation.box((2.0, 2.0, 2.0))
    b = trimesh.creation.box((2.0, 2.0, 2.0))
    b.apply_translation((shift, 0.0, 0.0))
    return trimesh.util.concatenate([a, b])


@pytest.mark.parametrize("shift, shared", [(1.0, 4.0), (0.5, 6.0), (3.0, 0.0)])
def test_overlap_volume_against_the_boxes_intersection(shift, shared):
    n, got, total = overlap_volume(_two_boxes(shift))
    # two 2x2x2 cubes shifted along x share a (2 - shift) x 2 x 2 box
    assert n == 2 and total == pytest.approx(16.0)
    assert got == pytest.approx(max(0.0, 2.0 - shift) * 4.0, abs=1e-6) == pytest.approx(shared)


def test_overlapping_bodies_warn_with_what_it_does_to_the_scores(tmp_path):
    path = tmp_path / "two.stl"
    _two_boxes(1.0).export(path)
    _, notes = _load(path)
    hits = [n for n in notes if "overlap" in n]
    assert len(hits) == 1 and "lowers completeness and F-score" in hits[0]
    assert "25%" in hits[0]  # 4 of 16


def test_separate_bodies_do_not_warn(tmp_path):
    path = tmp_path / "apart.stl"
    _two_boxes(3.0).export(path)
    _, notes = _load(path)
    assert not [n for n in notes if "overlap" in n]
    scene, _ = _load("twin_posts")  # two posts 6 mm apart
    assert scene.body_count == 2 and overlap_volume(scene)[1] < 1e-6
