"""slicer.planes and slicer.degenerate: frames, plane families, nudging."""
from __future__ import annotations

import logging

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st

from slicer import make_planes, nudge_planes, nudge_report, parse_axis
from slicer.degenerate import DEGENERATE_TOL, mesh_scale, vertex_clearance
from slicer.planes import SlicePlane, extent_along, frame_for_normal

BOUNDS = np.array([[-1.0, 2.0, 0.5], [3.0, 5.0, 4.5]])

# ------------------------------------------------------------------ frames


@pytest.mark.parametrize(
    "axis, u, v",
    [
        ("z", [1, 0, 0], [0, 1, 0]),
        ("x", [0, 1, 0], [0, 0, 1]),
        ("y", [0, 0, 1], [1, 0, 0]),
    ],
)
def test_axis_frames(axis, u, v):
    fu, fv, fn = frame_for_normal(parse_axis(axis))
    assert fu.tolist() == u and fv.tolist() == v
    assert np.array_equal(np.cross(fu, fv), fn)


normals = st.tuples(*[st.floats(-1, 1, allow_nan=False)] * 3).filter(
    lambda t: np.linalg.norm(t) > 1e-3
)


@settings(max_examples=200, deadline=None)
@given(normals)
def test_frame_orthonormal_right_handed(n):
    u, v, nn = frame_for_normal(n)
    m = np.stack([u, v, nn])
    assert np.allclose(m @ m.T, np.eye(3), atol=1e-12)
    assert np.allclose(np.cross(u, v), nn, atol=1e-12)
    assert np.linalg.det(m) > 0
    assert np.allclose(nn, np.asarray(n) / np.linalg.norm(n))


@settings(max_examples=100, deadline=None)
@given(normals, st.floats(-3, 3), st.integers(0, 2**31 - 1))
def test_round_trip_in_plane(n, off, seed):
    u, v, nn = frame_for_normal(n)
    origin = np.array([0.3, -2.0, 1.0])
    origin = origin + (off - origin @ nn) * nn
    p = SlicePlane(0, origin, nn, u, v, off)
    xy = np.random.default_rng(seed).uniform(-50, 50, (20, 2))
    world = p.to_3d(xy)
    assert np.allclose(p.heights(world), 0.0, atol=1e-12)
    assert np.allclose(p.to_2d(world), xy, atol=1e-12)
    assert np.allclose(p.to_3d(p.to_2d(world)), world, atol=1e-12)


def test_plane_is_frozen_and_readonly():
    p = make_planes(BOUNDS, "z", count=2)[0]
    with pytest.raises(AttributeError):
        p.offset = 1.0
    with pytest.raises(ValueError):
        p.origin[0] = 5.0


@pytest.mark.parametrize(
    "axis, expected",
    [("x", [1, 0, 0]), ("-y", [0, -1, 0]), ("0,0,2", [0, 0, 1]), ((3, 4, 0), [0.6, 0.8, 0])],
)
def test_parse_axis(axis, expected):
    assert np.allclose(parse_axis(axis), expected)


@pytest.mark.parametrize("axis", ["0,0,0", (0, 0, 0), "w", "1,2", "a,b,c", (1, np.nan, 0)])
def test_parse_axis_rejects(axis):
    with pytest.raises(ValueError):
        parse_axis(axis)


# ----------------------------------------------------------- plane families


@pytest.mark.parametrize("axis", ["x", "y", "z", "1,1,0", "0.2,-0.5,1"])
@pytest.mark.parametrize("count", [1, 2, 7, 64])
def test_count_family_evenly_spaced_strictly_inside(axis, count):
    lo, hi = extent_along(BOUNDS, axis)
    planes = make_planes(BOUNDS, axis, count=count)
    offs = np.array([p.offset for p in planes])
    assert len(planes) == count
    assert np.all((offs > lo) & (offs < hi))
    assert np.allclose(offs, lo + (np.arange(count) + 0.5) * (hi - lo) / count)
    assert [p.index for p in planes] == list(range(count))
    for p in planes:
        assert p.nudge == 0.0 and p.nudge_reason == ""
        assert abs(p.origin @ p.normal - p.offset) < 1e-12
    if count > 1:
        assert np.allclose(np.diff(offs), (hi - lo) / count)


@pytest.mark.parametrize("spacing", [0.3, 1.0, 1.7, 3.99])
def test_spacing_family(spacing):
    lo, hi = 0.5, 4.5
    offs = np.array([p.offset for p in make_planes(BOUNDS, "z", spacing=spacing)])
    assert offs[0] == pytest.approx(lo + spacing / 2)
    assert np.all((offs > lo) & (offs < hi))
    assert offs[-1] + spacing >= hi
    if len(offs) > 1:
        assert np.allclose(np.diff(offs), spacing)


def test_explicit_offsets():
    planes = make_planes(BOUNDS, "y", offsets=[2.5, 4.9])
    assert [p.offset for p in planes] == [2.5, 4.9]


@pytest.mark.parametrize(
    "kwargs",
    [
        {},
        {"count": 3, "spacing": 0.1},
        {"count": 0},
        {"count": 2.5},
        {"spacing": -1.0},
        {"spacing": 0.0},
        {"spacing": 100.0},
        {"offsets": []},
        {"offsets": [0.5]},  # on the extent boundary
        {"offsets": [1.0, 9.0]},
        {"axis": "0,0,0", "count": 2},
    ],
)
def test_bad_family_arguments(kwargs):
    with pytest.raises(ValueError) as err:
        make_planes(BOUNDS, **{"axis": "z", **kwargs})
    assert "\n" not in str(err.value)


def test_make_planes_from_mesh_uses_vertices():
    mesh = trimesh.creation.icosphere(subdivisions=2)
    lo, hi = extent_along(mesh, "z")
    assert lo == mesh.vertices[:, 2].min() and hi == mesh.vertices[:, 2].max()
    planes = make_planes(mesh, "z", count=3)
    assert np.allclose(planes[1].origin, [0, 0, 0], atol=1e-12)


# ---------------------------------------------------------------- nudging


def _stepped():
    """Two stacked boxes: vertices and horizontal faces at z = 0, 1, 2."""
    a = trimesh.creation.box(bounds=[[0, 0, 0], [2, 2, 1]])
    b = trimesh.creation.box(bounds=[[0.5, 0.5, 1], [1.5, 1.5, 2]])
    return trimesh.util.concatenate([a, b])


def test_vertex_clearance():
    h = np.array([0.0, 1.0, 3.0])
    assert vertex_clearance([0.4, 2.9, -1.0, 5.0], h).tolist() == pytest.approx([0.4, 0.1, 1.0, 2.0])


def test_nudge_fires_through_vertices_and_faces(caplog):
    mesh = _stepped()
    scale = mesh_scale(mesh)
    planes = make_planes(mesh, "z", offsets=[0.5, 1.0, 1.0 + 1e-9, 1.5])
    with caplog.at_level(logging.WARNING, logger="slicer.degenerate"):
        moved = nudge_planes(planes, mesh)
    assert [p.nudge != 0.0 for p in moved] == [False, True, True, False]
    for p in moved[1:3]:
        assert "faces in plane" in p.nudge_reason
        assert int(p.nudge_reason.split("(")[1].split()[0]) > 0  # faces counted
        assert abs(p.nudge) <= 2e-5 * scale
        assert abs(p.origin @ p.normal - p.offset) < 1e-12
        h = mesh.vertices @ p.normal
        assert np.abs(h - p.offset).min() >= DEGENERATE_TOL * scale
    assert len(nudge_report(moved)) == 2
    assert "moved 2 of 4 degenerate planes" in caplog.text


def test_nudge_is_vectorised_and_keeps_order():
    mesh = trimesh.creation.icosphere(subdivisions=3)
    h = np.unique(mesh.vertices[:, 2])
    offs = h[1:-1][::7]
    moved = nudge_planes(make_planes(mesh, "z", offsets=offs), mesh, log=False)
    assert [p.index for p in moved] == list(range(len(offs)))
    assert all(p.nudge != 0.0 for p in moved)
    clear = vertex_clearance([p.offset for p in moved], h)
    assert np.all(clear >= DEGENERATE_TOL * mesh_scale(mesh))


def test_nudge_leaves_clear_planes_alone():
    mesh = trimesh.creation.icosphere(subdivisions=2)
    planes = make_planes(mesh, "x", count=4)  # count=5 would cut x = 0: vertices
    moved = nudge_planes(planes, mesh, log=False)
    assert all(a is b for a, b in zip(planes, moved))
