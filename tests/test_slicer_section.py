"""slicer.section and slicer.slices: reference loops, areas, Slice API."""
from __future__ import annotations

import warnings

import numpy as np
import pytest
import shapely
import trimesh

import meshes
from conftest import REAL_MESHES
from slicer import Slice, sections, slice_mesh
from slicer.section import signed_area

SCENES = meshes.names()
REAL = [m for m in REAL_MESHES if m != "ajc_teapot.obj"]  # open mesh: no closed sections


def load_real(shared_meshes_dir, name):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return meshes.load(shared_meshes_dir / name)


def check_loops(slc):
    assert len(slc.holes) == len(slc.loops)
    for loop, hole in zip(slc.loops, slc.holes):
        assert loop.ndim == 2 and loop.shape[1] == 2 and loop.dtype == np.float64
        assert len(loop) >= 3
        assert not np.any(np.all(loop == np.roll(loop, -1, axis=0), axis=1)), "repeat"
        a = signed_area(loop)
        assert (a < 0) == bool(hole), "outer loops CCW, holes CW"
        assert shapely.Polygon(loop).exterior.is_ccw == (not hole)


def segment_area(slc) -> float:
    """Section area from the crossing triangles' own segments (the Embree
    backend's per-slice precomputation; oriented, so a shoelace sum)."""
    seg = slc.contact("embree").segments
    return 0.5 * float(np.sum(seg[:, 0, 0] * seg[:, 1, 1] - seg[:, 0, 1] * seg[:, 1, 0]))


def trimesh_area(mesh, plane) -> float:
    """Section area by trimesh + shapely (independent of manifold3d)."""
    path3 = mesh.section(plane_origin=plane.origin, plane_normal=plane.normal)
    if path3 is None:
        return 0.0
    to_2d = np.eye(4)
    to_2d[:3, :3] = plane.basis
    to_2d[:3, 3] = -plane.basis @ plane.origin
    path2, _ = path3.to_2D(to_2D=to_2d)
    return float(sum(p.area for p in path2.polygons_full))


@pytest.mark.parametrize("name", SCENES)
@pytest.mark.parametrize("axis", ["x", "y", "z"])
def test_scene_loops_and_area(name, axis):
    mesh = meshes.load(name)
    for slc in slice_mesh(mesh, axis=axis, count=5):
        assert slc.method == "manifold"
        check_loops(slc)
        area = sum(signed_area(lp) for lp in slc.loops)
        assert area == pytest.approx(trimesh_area(mesh, slc.plane), rel=1e-9, abs=1e-12)
        assert area == pytest.approx(segment_area(slc), rel=1e-9, abs=1e-12)


def _is_z_prism(mesh) -> bool:
    z = mesh.vertices[:, 2]
    return bool(np.all((z == z.min()) | (z == z.max())))


PRISMS = [n for n in SCENES if _is_z_prism(meshes.load(n))]


def test_some_scenes_are_prisms():
    assert len(PRISMS) >= 3


@pytest.mark.parametrize("name", PRISMS)
def test_prism_scene_area_equals_volume_over_depth(name):
    """Scenes extruded along z: every z-section has area volume / depth."""
    mesh = meshes.load(name)
    z = mesh.vertices[:, 2]
    depth = z.max() - z.min()
    for slc in slice_mesh(mesh, axis="z", count=3):
        area = sum(signed_area(lp) for lp in slc.loops)
        assert area == pytest.approx(mesh.volume / depth, rel=1e-9)


@pytest.mark.shared
@pytest.mark.parametrize("name", REAL)
@pytest.mark.parametrize("axis", ["x", "y", "z", "1,2,3"])
def test_real_loops_and_area(shared_meshes_dir, name, axis):
    mesh = load_real(shared_meshes_dir, name)
    for slc in slice_mesh(mesh, axis=axis, count=6):
        check_loops(slc)
        assert slc.method == "manifold"
        area = sum(signed_area(lp) for lp in slc.loops)
        assert area == pytest.approx(segment_area(slc), rel=1e-9, abs=1e-14 * slc.scale**2)
        # trimesh merges section vertices at 1e-8 absolute: on the small
        # metre-unit meshes its area is off by up to ~1.2e-6 (octagonal
        # pocket), while manifold and the segments agree to ~1e-13
        ref = trimesh_area(mesh, slc.plane)
        assert area == pytest.approx(ref, rel=1e-5, abs=1e-12 * slc.scale**2)


@pytest.mark.shared
@pytest.mark.parametrize("axis", ["x", "y", "z"])
def test_open_mesh_falls_back_to_trimesh(shared_meshes_dir, axis):
    mesh = load_real(shared_meshes_dir, "ajc_teapot.obj")
    assert not mesh.is_watertight
    slices = slice_mesh(mesh, axis=axis, count=8)
    assert all(s.method == "trimesh" for s in slices)
    assert sum(len(s.open_chains) for s in slices) > 0
    for slc in slices:
        check_loops(slc)
        for chain in slc.open_chains:
            assert chain.shape[1] == 2 and len(chain) >= 2


def test_holes_cup_like():
    outer = trimesh.creation.cylinder(radius=2.0, height=2.0, sections=64)
    inner = trimesh.creation.cylinder(radius=1.0, height=3.0, sections=64)
    tube = outer.difference(inner)
    (slc,) = slice_mesh(tube, "z", count=1)
    assert sorted(slc.holes.tolist()) == [False, True]
    check_loops(slc)


def test_manifold_precision_is_scale_free():
    """manifold3d's CrossSection rounds to 1e-8 absolute; we slice at a
    normalised size, so tiny meshes keep exact sections."""
    box = trimesh.creation.box(extents=[3e-6, 2e-6, 1e-6])
    box.apply_translation([1.23456789e-7, 0, 0])
    (slc,) = slice_mesh(box, "z", count=1)
    assert signed_area(slc.loops[0]) == pytest.approx(6e-12, rel=1e-12)
    pts = slc.to_3d(slc.loops[0])
    on_x = np.isclose(pts[:, :1], box.bounds[:, 0], rtol=0, atol=1e-20).any(axis=1)
    on_y = np.isclose(pts[:, 1:2], box.bounds[:, 1], rtol=0, atol=1e-20).any(axis=1)
    assert np.all(on_x | on_y)


def test_sections_method_argument():
    box = trimesh.creation.box()
    planes = [s.plane for s in slice_mesh(box, "z", count=2)]
    assert [s.method for s in sections(box, planes, method="trimesh")] == ["trimesh"] * 2
    with pytest.raises(ValueError):
        sections(box, planes, method="nope")


# --------------------------------------------------------------- Slice API


def test_slice_api_and_bounding_circle():
    mesh = meshes.load("fig17_pocket")
    slices = slice_mesh(mesh, axis="z", spacing=10.0)
    assert all(isinstance(s, Slice) for s in slices)
    for s in slices:
        c, r = s.bounding_circle()
        assert c.shape == (2,) and r > 0
        assert np.all(np.linalg.norm(s.points() - c, axis=1) <= r * (1 + 1e-12))
        assert s.contact("embree") is s.contact("embree")  # cached per slice
        assert s.contact("exact") is not s.contact("embree")
        assert s.scale == pytest.approx(np.linalg.norm(mesh.extents))
    with pytest.raises(ValueError):
        slices[0].contact("raytrace")


def test_empty_slice_has_no_circle():
    a = trimesh.creation.box(bounds=[[0, 0, 0], [1, 1, 1]])
    b = trimesh.creation.box(bounds=[[0, 0, 2], [1, 1, 3]])
    two = trimesh.util.concatenate([a, b])
    (s,) = slice_mesh(two, "z", offsets=[1.5])
    assert s.is_empty
    with pytest.raises(ValueError):
        s.bounding_circle()
    d, p, n = s.contact("embree").cast(np.zeros((3, 2)), np.array([[1.0, 0.0]] * 3), 5.0)
    assert np.all(np.isinf(d)) and np.all(np.isnan(p)) and np.all(np.isnan(n))
