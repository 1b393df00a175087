"""Tests of the ``meshes`` package: built-in scenes, file loading, reports."""
from __future__ import annotations

import csv
import inspect
import warnings
from pathlib import Path

import numpy as np
import pytest
import shapely
import trimesh

import meshes
from meshes import MeshError, MeshWarning

NAMES = meshes.names()
# Scenes with no curved geometry: resolution cannot change them.
STRAIGHT = {"deep_slot", "dovetail", "comb", "stepped_pyramid", "textured_pocket", "knurled_pocket"}
FORMATS = ["stl", "obj", "ply", "off", "glb"]


@pytest.fixture(scope="module")
def built():
    """name -> (manifold, trimesh) at default settings, built once."""
    return {n: (meshes.build(n), meshes.load(n)) for n in NAMES}


def section(mesh: trimesh.Trimesh, z: float) -> list[shapely.Polygon]:
    """Polygons (with holes) of the slice of ``mesh`` at height ``z``, in
    world x-y coordinates; computed by trimesh, independently of manifold3d."""
    path3 = mesh.section(plane_origin=[0.0, 0.0, z], plane_normal=[0.0, 0.0, 1.0])
    if path3 is None:
        return []
    to_xy = np.eye(4)
    to_xy[2, 3] = -z
    path2, _ = path3.to_2D(to_2D=to_xy)
    return list(path2.polygons_full)


def mid_z(mesh: trimesh.Trimesh) -> float:
    return float(mesh.bounds[:, 2].mean()) + 0.0123  # off any vertex plane


def free_rays(poly: shapely.Polygon, point, n: int = 1440) -> int:
    """Number of rays (of ``n`` sampled directions) from ``point`` on the
    contour that reach far away without touching ``poly``."""
    t = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    d = np.column_stack([np.cos(t), np.sin(t)])
    p = np.asarray(point, dtype=float)
    coords = np.stack([p + 1e-4 * d, p + 1e3 * d], axis=1)
    return int((~shapely.intersects(shapely.linestrings(coords), poly)).sum())


# --------------------------------------------------------------- registry


def test_names_unique_sorted_and_enough():
    assert NAMES == sorted(set(NAMES))
    assert len(NAMES) >= 11
    for required in ["fig17_pocket", "fig18_overhangs", "deep_slot", "mushroom",
                     "dovetail", "bowl", "cup_handle", "gear", "bored_block",
                     "terrain"]:
        assert required in NAMES


@pytest.mark.parametrize("name", NAMES)
def test_describe_and_signature(name):
    text = meshes.describe(name)
    assert text and "\n" not in text and len(text) < 120
    params = inspect.signature(meshes.scene_info(name).builder).parameters
    assert params["resolution"].default >= 8


# ----------------------------------------------------------------- scenes


@pytest.mark.parametrize("name", NAMES)
def test_scene_is_valid_solid(name, built):
    solid, mesh = built[name]
    assert mesh.is_watertight
    assert mesh.is_winding_consistent
    assert mesh.vertices.dtype == np.float64
    assert len(mesh.faces) == solid.num_tri() <= 5000
    assert mesh.volume > 0
    assert mesh.volume == pytest.approx(solid.volume(), rel=1e-9)
    assert mesh.units == "mm"
    assert np.allclose(mesh.bounds[0], 0.0)
    assert np.all(mesh.extents <= 100.0 + 1e-9)
    assert len(mesh.vertices) == len(np.unique(mesh.faces))  # no orphans


@pytest.mark.parametrize("name", NAMES)
def test_scene_bodies_as_intended(name, built):
    solid, mesh = built[name]
    bodies = meshes.scene_info(name).bodies
    assert mesh.body_count == bodies
    assert len(solid.decompose()) == bodies


@pytest.mark.parametrize("name", NAMES)
def test_face_count_grows_with_resolution_but_bounded(name, built):
    default = inspect.signature(meshes.scene_info(name).builder).parameters[
        "resolution"].default
    base = len(built[name][1].faces)
    fine = meshes.load(name, resolution=2 * default)
    assert fine.is_watertight
    if name in STRAIGHT:
        assert len(fine.faces) == base
    else:
        assert base < len(fine.faces) <= 5 * base


def test_cup_handle_slices_have_islands(built):
    mesh = built["cup_handle"][1]
    z_cup = 30.0 + 0.0123               # cup axis after placement
    centre = section(mesh, z_cup)
    assert len(centre) == 1 and len(centre[0].interiors) == 0  # open-top U
    assert centre[0].area < 0.5 * centre[0].convex_hull.area   # the cavity
    handle_only = section(mesh, z_cup + 33.0)   # beyond the wall (r = 30)
    assert len(handle_only) == 2                # two handle islands


def test_twin_posts_slices_have_two_outer_loops(built):
    loops = section(built["twin_posts"][1], 12.0123)
    assert len(loops) == 2 and not any(p.interiors for p in loops)


def test_bored_block_slices(built):
    mesh = built["bored_block"][1]
    across = section(mesh, 20.0123)
    assert len(across) == 1 and len(across[0].interiors) == 1
    assert across[0].interiors[0].centroid.distance(shapely.Point(40, 30)) < 0.1
    # an x-slice through the bore splits the block in two
    path3 = mesh.section(plane_origin=[40.0123, 0, 0], plane_normal=[1, 0, 0])
    assert len(path3.to_2D()[0].polygons_full) == 2


def vertical_line_pieces(poly: shapely.Polygon) -> np.ndarray:
    """For vertical lines across ``poly``, the number of pieces of each
    line inside it (1 everywhere = the top edge is a function graph)."""
    x0, y0, x1, y1 = poly.bounds
    xs = np.linspace(x0, x1, 403)[1:-1]
    lines = shapely.linestrings([[(x, y0 - 1), (x, y1 + 1)] for x in xs])
    return shapely.get_num_geometries(shapely.intersection(lines, poly))


def test_fig18_has_overhangs_fig17_does_not(built):
    (p17,) = section(built["fig17_pocket"][1], 20.0123)
    (p18,) = section(built["fig18_overhangs"][1], 20.0123)
    assert np.all(vertical_line_pieces(p17) == 1)
    pieces = vertical_line_pieces(p18)
    assert pieces.max() >= 2           # lips: vertical lines cross > 2 times
    assert (pieces >= 2).mean() > 0.2


# point on the z-slice contour, and whether a straight ray from it escapes
REACH = [
    ("fig18_overhangs", (28.0, 40.0), False),   # under the left lip
    ("fig18_overhangs", (83.0, 40.0), False),   # under the right lip
    ("fig18_overhangs", (98.0, 26.0), False),   # back of the side notch
    ("fig18_overhangs", (50.0, 30.0), True),    # top of the big hill
    ("mushroom", (24.0, 25.0), False),          # chamber side wall
    ("mushroom", (40.0, 9.0), True),            # chamber floor under the neck
    ("dovetail", (54.0, 39.0), True),           # undercut flank, yet convex
    ("dovetail", (57.9, 28.0), True),           # acute bottom corner
    ("dovetail", (40.0, 28.0), True),           # groove floor
    ("deep_slot", (30.0, 15.0), True),          # slot floor
    ("fig17_pocket", (45.0, 25.0), True),       # pocket bottom
]


@pytest.mark.parametrize("name, point, reachable", REACH)
def test_never_touching_areas(name, point, reachable, built):
    (poly,) = section(built[name][1], 20.0123)
    point = poly.exterior.interpolate(poly.exterior.project(shapely.Point(point)))
    assert poly.exterior.distance(shapely.Point(point)) < 1e-9
    assert (free_rays(poly, point.coords[0]) > 0) == reachable


def test_fig17_everything_reachable(built):
    (poly,) = section(built["fig17_pocket"][1], 20.0123)
    ring = poly.exterior
    for s in np.linspace(0.0, ring.length, 150, endpoint=False):
        assert free_rays(poly, ring.interpolate(s).coords[0], n=360) > 0


def test_comb_gaps_span_eps(built):
    (poly,) = section(built["comb"][1], 15.0123)
    # horizontal line through the teeth: the gaps are the pieces outside
    line = shapely.LineString([(-1, 30), (poly.bounds[2] + 1, 30)])
    gaps = sorted(g.length for g in shapely.get_parts(line.difference(poly))
                  if 0 < g.bounds[0] and g.bounds[2] < poly.bounds[2])
    assert len(gaps) == 9 and gaps[0] < 0.2 and gaps[-1] == pytest.approx(8.0)


def test_terrain_profile_changes_with_z(built):
    mesh = built["terrain"][1]
    a, b = section(mesh, 10.0123), section(mesh, 40.0123)
    assert len(a) == len(b) == 1
    assert abs(a[0].area - b[0].area) > 10.0
    hs = [meshes.scenes_fields.terrain_height(x, 10.0123) for x in (20.0, 70.0)]
    for x, h in zip((20.0, 70.0), hs):
        top = a[0].intersection(shapely.LineString([(x, -1), (x, 99)])).bounds[3]
        assert top == pytest.approx(h, abs=1.0)


@pytest.mark.parametrize("kwargs, text", [
    ({"resolution": 3}, "resolution must be >= 8"),
    ({"resolution": "high"}, "must be an integer"),
    ({"colour": "red"}, "unexpected keyword"),
])
def test_bad_scene_parameters(kwargs, text):
    with pytest.raises(MeshError, match=text) as info:
        meshes.load("bowl", **kwargs)
    assert "\n" not in str(info.value)


# ---------------------------------------------------------------- loading


@pytest.mark.parametrize("fmt", FORMATS)
def test_round_trip_export(fmt, tmp_path, built):
    mesh = built["cup_handle"][1]
    path = tmp_path / f"cup.{fmt}"
    mesh.export(path)
    with warnings.catch_warnings():
        warnings.simplefilter("error", MeshWarning)
        back = meshes.load(path)
    assert back.is_watertight
    assert len(back.faces) == len(mesh.faces)
    assert back.volume == pytest.approx(mesh.volume, rel=1e-6)
    assert meshes.load(str(path)).metadata["file_name"] == path.name


def test_glb_with_several_geometries_is_concatenated(tmp_path, built):
    a = built["bowl"][1]
    b = built["gear"][1].copy()
    scene = trimesh.Scene()
    scene.add_geometry(a, geom_name="bowl")
    scene.add_geometry(b, geom_name="gear", transform=trimesh.transformations
                       .translation_matrix([200.0, 0, 0]))
    path = tmp_path / "two.glb"
    scene.export(path)
    mesh = meshes.load(path)
    assert len(mesh.faces) == len(a.faces) + len(b.faces)
    assert mesh.body_count == 2
    assert mesh.bounds[1, 0] == pytest.approx(200.0 + b.bounds[1, 0])
    assert mesh.volume == pytest.approx(a.volume + b.volume, rel=1e-6)


def _box_without_a_face() -> trimesh.Trimesh:
    box = trimesh.creation.box((10, 20, 30))
    return trimesh.Trimesh(box.vertices, box.faces[1:], process=False)


def test_open_mesh_warns_but_loads(tmp_path):
    path = tmp_path / "open.ply"
    _box_without_a_face().export(path)
    with pytest.warns(MeshWarning, match="not watertight"):
        mesh = meshes.load(path)
    assert len(mesh.faces) == 11
    report = meshes.mesh_report(mesh)
    assert report["watertight"] is False and report["volume"] is None


def test_inside_out_mesh_is_inverted(tmp_path):
    box = trimesh.creation.box((10, 20, 30))
    path = tmp_path / "inverted.obj"
    trimesh.Trimesh(box.vertices, box.faces[:, ::-1], process=False).export(path)
    with pytest.warns(MeshWarning, match="inside out"):
        mesh = meshes.load(path)
    assert mesh.volume == pytest.approx(6000.0)


def test_cleaning_keeps_slivers_drops_degenerate_and_duplicates(tmp_path):
    box = trimesh.creation.box((10, 10, 10))
    v = np.vstack([box.vertices, box.vertices[:1]])      # a duplicate vertex
    extra = [[0, 0, 1], [8, 0, 3]]                      # repeated index (after weld)
    faces = np.vstack([box.faces, box.faces[:1], extra])
    path = tmp_path / "dirty.obj"
    trimesh.Trimesh(v, faces, process=False).export(path)
    mesh = meshes.load(path)
    assert len(mesh.faces) == 12 and len(mesh.vertices) == 8
    assert mesh.is_watertight
    # a zero-area face with three distinct vertices is topology: kept
    assert len(meshes.loading.clean(trimesh.Trimesh(
        [[0, 0, 0], [1, 0, 0], [2, 0, 0]], [[0, 1, 2]], process=False)).faces) == 1


def _write(path: Path, data: bytes) -> Path:
    path.write_bytes(data)
    return path


GARBAGE = np.random.default_rng(7).integers(0, 256, 600, dtype=np.uint8).tobytes()
ONLY_VERTICES = {
    "obj": b"v 0 0 0\nv 1 0 0\nv 0 1 0\n",
    "ply": b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
           b"property float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n",
    "off": b"OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n",
}


@pytest.mark.parametrize("case, make, text", [
    ("missing", lambda d: d / "nope.stl", "not found"),
    ("missing-dir", lambda d: d / "sub" / "nope", "not found"),
    ("unknown", lambda d: "fig17_poket", "did you mean fig17_pocket"),
    ("unknown-far", lambda d: "zzzz", "known scenes: bored_block"),
    ("directory", lambda d: d, "not a regular file"),
    ("extension", lambda d: _write(d / "m.xyz", b"0 0 0\n"), "unsupported mesh file extension"),
    ("no-extension", lambda d: _write(d / "mesh", b"solid\n"), "unsupported"),
    *[(f"empty-{f}", lambda d, f=f: _write(d / f"e.{f}", b""), "empty")
      for f in FORMATS],
    *[(f"garbage-{f}", lambda d, f=f: _write(d / f"g.{f}", GARBAGE),
       "cannot read|no faces") for f in FORMATS],
    *[(f"vertices-only-{f}", lambda d, f=f, b=b: _write(d / f"v.{f}", b), "no faces")
      for f, b in ONLY_VERTICES.items()],
    ("degenerate-only", lambda d: _write(d / "deg.obj", b"v 0 0 0\nv 1 0 0\nf 1 1 2\n"),
     "no faces"),
])
def test_mesh_errors_are_one_line(case, make, text, tmp_path):
    with pytest.raises(MeshError, match=text) as info:
        meshes.load(make(tmp_path))
    message = str(info.value)
    assert "\n" not in message and len(message) < 400
    assert isinstance(info.value, ValueError)


def test_other_load_errors(tmp_path, built):
    path = tmp_path / "box.stl"
    built["deep_slot"][1].export(path)
    with pytest.raises(MeshError, match="only to built-in scenes"):
        meshes.load(path, resolution=16)
    with pytest.raises(MeshError, match="scene name or a file path"):
        meshes.load(42)


# ---------------------------------------------------------------- reports


def test_report_and_format(built):
    mesh = built["twin_posts"][1]
    report = meshes.mesh_report(mesh)
    assert report["name"] == "twin_posts" and report["bodies"] == 2
    assert report["faces"] == len(mesh.faces) and report["units"] == "mm"
    assert report["bbox_diagonal"] == pytest.approx(np.linalg.norm(mesh.extents))
    assert report["volume"] == pytest.approx(mesh.volume)
    line = meshes.format_report(report)
    assert "\n" not in line and "2 bodies" in line and "(mm)" in line
    assert line.startswith("twin_posts: ")


def test_public_api_is_explicit():
    assert set(meshes.__all__) >= {"names", "describe", "load", "MeshError",
                                   "MeshWarning", "mesh_report", "format_report"}
    assert all(hasattr(meshes, n) for n in meshes.__all__)
    assert issubclass(MeshWarning, UserWarning) and issubclass(MeshError, ValueError)


# ------------------------------------------------------------ real meshes


def _manifest_rows() -> list[dict]:
    path = Path(__file__).resolve().parents[1].parent / "shared" / "meshes" / "MANIFEST.tsv"
    if not path.is_file():
        return [{"file": "<no shared meshes>"}]
    with path.open(newline="") as fh:
        return list(csv.DictReader(fh, delimiter="\t"))


@pytest.mark.shared
@pytest.mark.parametrize("row", _manifest_rows(), ids=lambda r: r["file"])
def test_shared_meshes_load_as_in_manifest(row, shared_meshes_dir):
    watertight = row["watertight"] == "True"
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        mesh = meshes.load(shared_meshes_dir / row["file"])
    ours = [w for w in caught if issubclass(w.category, MeshWarning)]
    assert len(mesh.faces) == int(row["faces"])
    assert mesh.is_watertight == watertight
    assert bool(ours) == (not watertight)
    extents = [float(e) for e in row["extents"].split("x")]
    assert np.allclose(np.sort(mesh.extents), np.sort(extents), rtol=2e-3)
    if watertight:
        assert mesh.volume == pytest.approx(float(row["volume"]), rel=1e-4)
    assert meshes.format_report(meshes.mesh_report(mesh)).startswith(row["file"])
