"""The scores' fast paths give the numbers of the slow ones.

* :func:`recon3d.score.closest.mesh_distances` (the distances of the 3D scores and of the
  coloured ground truth) equals VTK's exact distances (``vtkImplicitPolyDataDistance``)
  up to rounding, near a surface, far from it and inside it, and the scores computed with
  either give the same F-scores.
* The distance calls of :func:`recon3d.score.evaluate.surface_metrics` run side by
  side (both directions' points split between two calls, one in a forked child) give the
  very metrics of one call after the other.
"""
import subprocess
import sys

import numpy as np
import pytest
import trimesh

from recon3d.api import _side_by_side
from recon3d.score.closest import mesh_distances
from recon3d.score import evaluate
from recon3d.score.evaluate import (ContourCloud, Domain, GroundTruthSamples, one_after_other,
                                    surface_metrics)
from recon3d.viz import libs


def vtk_distances(points, mesh):
    """(n,) float: VTK's exact distances (``vtkImplicitPolyDataDistance``), the reference."""
    cloud = libs.pyvista().PolyData(np.asarray(points, dtype=np.float64))
    res = cloud.compute_implicit_distance(libs.polydata(mesh))
    return np.abs(np.asarray(res["implicit_distance"], dtype=np.float64))


def _meshes():
    box = trimesh.creation.box(extents=(2.0, 1.0, 0.5))
    ring = trimesh.creation.annulus(0.5, 1.0, 0.4)
    sphere = trimesh.creation.icosphere(subdivisions=4)
    return [box, ring, sphere]


@pytest.mark.parametrize("k", range(3))
def test_mesh_distances_equal_vtk(k):
    mesh = _meshes()[k]
    rng = np.random.default_rng(k)
    pts = np.vstack([mesh.sample(3000, seed=k) + rng.normal(scale=0.01, size=(3000, 3)),
                     rng.normal(size=(1000, 3)),             # inside and around
                     rng.normal(size=(200, 3)) * 30.0,       # far away
                     mesh.vertices[:50]])                    # on the surface
    on = min(50, len(mesh.vertices))
    ours = mesh_distances(pts, mesh.vertices, mesh.faces)
    vtk = vtk_distances(pts, mesh)
    assert ours.shape == (len(pts),)
    np.testing.assert_allclose(ours, vtk, rtol=1e-9, atol=1e-12)
    assert np.all(ours[-on:] <= 1e-12)


_COMPILE_CHECK = """
import numpy as np, trimesh
from recon3d.score import {module} as m
kernels = tuple(getattr(m, name) for name in {kernels!r})
assert not any(k.signatures for k in kernels)  # a fresh process: nothing compiled yet
m.compile_kernels()
compiled = [list(k.signatures) for k in kernels]
assert all(compiled), compiled
mesh = trimesh.creation.icosphere(subdivisions=2)
{calls}
assert [list(k.signatures) for k in kernels] == compiled
"""
_DISTANCE_CALLS = """
m.mesh_distances(np.asfortranarray(mesh.sample(100, seed=1)), mesh.vertices, mesh.faces)
m.mesh_distances(mesh.vertices[::2].astype(np.float32),
                 mesh.vertices.astype(np.float32), mesh.faces.astype(np.int32))
"""
_SUBDIVIDE_CALLS = """
m.subdivide_to_size(mesh.vertices, mesh.faces, 0.1, max_iter=12)
m.subdivide_to_size(mesh.vertices.astype(np.float32), mesh.faces.astype(np.int32), 0.1, 12)
m.subdivide_to_size(np.asfortranarray(mesh.vertices), mesh.faces[::-1], 0.1, max_iter=12)
"""


@pytest.mark.parametrize("module, kernels, calls", [
    ("closest", ("_query", "_build"), _DISTANCE_CALLS),
    ("subdivide", ("_long_edges", "_made"), _SUBDIVIDE_CALLS)], ids=["distances", "subdivide"])
def test_compile_kernels_compiles_what_a_run_calls(module, kernels, calls):
    """The first run compiles the distances and the coloured ground truth's subdivision
    beside the sensing (``recon3d.score.compile_kernels``): in a fresh process each module's
    ``compile_kernels`` gives the entry points (their callees are compiled into them, or load
    inside them from numba's cache) the signatures that every call a run makes uses,
    whatever the dtypes and memory order of its arrays, so those compile nothing more."""
    code = _COMPILE_CHECK.format(module=module, kernels=kernels, calls=calls)
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=600)
    assert proc.returncode == 0, proc.stderr[-2000:]


def test_the_score_kernels_compile_together():
    """``recon3d.score.compile_kernels`` (what the first run's side child calls) compiles
    both modules' kernels."""
    code = ("from recon3d import score\nfrom recon3d.score import closest, subdivide\n"
            "score.compile_kernels()\n"
            "assert closest._query.signatures and subdivide._made.signatures\n")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=600)
    assert proc.returncode == 0, proc.stderr[-2000:]


def test_mesh_distances_hierarchy_prunes_nothing_it_needs():
    """A point nearest a triangle far down the hierarchy's order (the last face) still finds it."""
    mesh = trimesh.creation.icosphere(subdivisions=5)
    c = mesh.triangles_center
    far = c / np.linalg.norm(c, axis=1, keepdims=True) * 1.5
    ours = mesh_distances(far, mesh.vertices, mesh.faces)
    np.testing.assert_allclose(ours, vtk_distances(far, mesh), rtol=1e-9)


def _node_triangles(child, first, count, order, node):
    """Indices of the triangles under ``node`` of a hierarchy of ``closest._build``."""
    if count[node] > 0:
        return order[first[node]:first[node] + count[node]]
    c = child[node]
    return np.concatenate([_node_triangles(child, first, count, order, c),
                           _node_triangles(child, first, count, order, c + 1)])


@pytest.mark.parametrize("mesh", [trimesh.creation.box().subdivide().subdivide(),  # ties
                                  trimesh.creation.icosphere(subdivisions=3)])
def test_hierarchy_boxes_bound_their_triangles_and_split_at_the_median(mesh):
    """Each box is the least box of the triangles under it (made bottom up), every triangle
    is in one leaf, and each split puts the smaller half of the centroids (along the axis
    they spread most) on the first child: the partition that replaced a sort per node."""
    from recon3d.score import closest

    tri = np.ascontiguousarray(mesh.vertices[mesh.faces], dtype=np.float64)
    lo, hi, child, first, count, order = closest._build(tri)
    assert np.array_equal(np.sort(order), np.arange(len(tri)))
    leaves = np.flatnonzero(count > 0)
    assert count[leaves].sum() == len(tri) and count.max() <= closest.LEAF
    cen = tri.mean(axis=1)
    for node in range(len(lo)):
        under = tri[_node_triangles(child, first, count, order, node)]
        assert np.array_equal(lo[node], under.min(axis=(0, 1)))
        assert np.array_equal(hi[node], under.max(axis=(0, 1)))
        if count[node] == 0:
            c = child[node]
            left = cen[_node_triangles(child, first, count, order, c)]
            right = cen[_node_triangles(child, first, count, order, c + 1)]
            axis = int(np.argmax(np.ptp(np.vstack([left, right]), axis=0)))
            assert len(right) - len(left) in (0, 1)
            assert left[:, axis].max() <= right[:, axis].min()


def test_mesh_distances_equal_the_least_triangle_distance():
    """Against every triangle one by one (the least of the triangle distances, bit for bit)
    and against VTK (an independent computation): the hierarchy skips no triangle a point
    needs, on a mesh whose centroids tie along every axis."""
    from recon3d.score import closest

    mesh = trimesh.creation.box().subdivide().subdivide()
    rng = np.random.default_rng(3)
    pts = np.vstack([rng.normal(size=(300, 3)),
                     mesh.vertices + rng.normal(0, 1e-3, (len(mesh.vertices), 3))])
    ours = mesh_distances(pts, mesh.vertices, mesh.faces)
    tri = mesh.vertices[mesh.faces]
    each = np.sqrt([min(closest._tri_dist2(p, *t) for t in tri) for p in pts])
    assert np.array_equal(ours, each)
    np.testing.assert_allclose(ours, vtk_distances(pts, mesh), rtol=1e-9, atol=1e-12)


def test_mesh_distances_refuses_an_empty_mesh():
    with pytest.raises(ValueError, match="no faces"):
        mesh_distances(np.zeros((1, 3)), np.zeros((0, 3)), np.zeros((0, 3), int))


def _case():
    gt_mesh = trimesh.creation.icosphere(subdivisions=4, radius=10.0)
    rec = trimesh.creation.icosphere(subdivisions=3, radius=10.3)
    rec.face_attributes["label"] = np.ones(len(rec.faces), dtype=np.int32)
    dom = Domain(np.array([[0.0, 0.0, 1.0]]), np.array([-6.0]), np.array([6.0]))
    gt = GroundTruthSamples(gt_mesh, dom, count=6000)
    t = np.linspace(0, 2 * np.pi, 200, endpoint=False)
    pts = np.column_stack([10 * np.cos(t), 10 * np.sin(t), np.zeros_like(t)])
    cloud = ContourCloud(pts, t < 4.0, t < 2.0, np.zeros(len(t), int), dom)
    return rec, gt, cloud


def test_scores_with_compiled_distances_equal_vtk_scores(monkeypatch):
    """``metrics.json``'s distances are the compiled ones; with VTK's the scores agree to
    rounding and every F-score is the same number."""
    rec, gt, cloud = _case()
    ours = surface_metrics(rec, gt, cloud, count=6000)
    monkeypatch.setattr(evaluate, "distances",
                        lambda pts, mesh, tree=None: vtk_distances(pts, mesh))
    vtk = surface_metrics(rec, gt, cloud, count=6000)
    for got, want in ((ours[0], vtk[0]), (ours[0]["reachable"], vtk[0]["reachable"])):
        assert got["fscore"] == want["fscore"]
        for key in ("accuracy", "completeness", "chamfer_l1", "hausdorff", "hd95"):
            assert got[key] == pytest.approx(want[key], rel=1e-12)


def test_the_hierarchies_are_built_once_for_both_halves(monkeypatch):
    """``surface_metrics`` builds the ground truth's and the reconstruction's hierarchies
    once, before its two halves run (a forked half inherits them), not once per half."""
    from recon3d.score import closest

    built = []
    real = closest._build
    monkeypatch.setattr(closest, "_build", lambda tri: built.append(len(tri)) or real(tri))
    rec, gt, cloud = _case()
    surface_metrics(rec, gt, cloud, count=6000)
    assert sorted(built) == sorted([len(gt.mesh.faces), len(rec.faces)])


def test_side_by_side_metrics_equal_serial():
    rec, gt, cloud = _case()
    serial = surface_metrics(rec, gt, cloud, count=6000)
    calls = []

    def pair(first, second):
        calls.append(1)
        return _side_by_side(first, second)

    forked = surface_metrics(rec, gt, cloud, count=6000, pair=pair)
    assert calls == [1]
    assert forked == serial  # the very numbers, not approximately


def test_pair_gets_half_of_each_direction():
    """Each call of the pair measures half of the ground truth's points and half of the
    reconstruction's samples (which direction costs more depends on the meshes): dropping
    either split (one call doing all of a direction) would change what the calls return."""
    rec, gt, cloud = _case()
    seen = {}

    def pair(first, second):
        a, b = one_after_other(first, second)
        seen["first"], seen["second"] = a, b
        return a, b

    surface_metrics(rec, gt, cloud, count=6000, pair=pair)
    (rec0, gt0), (rec1, gt1) = seen["first"], seen["second"]
    assert len(gt0) + len(gt1) == len(gt.points) and abs(len(gt0) - len(gt1)) <= 1
    assert len(rec0) + len(rec1) == 6000 and abs(len(rec0) - len(rec1)) <= 1
