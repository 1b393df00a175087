"""The VTK multiblock of a run (``scene.vtm``): what the pictures are drawn from.

Blocks, all in world coordinates:

* ``ground_truth`` -- the mesh subdivided to the grid step, cell array
  ``coverage`` (0 outside the slab, 1 touched, 2 reachable but missed,
  3 unreachable, 4 inside a hole, 5 in an opening narrower than eps;
  :data:`recon3d.records.COVERAGE_CLASSES`);
* ``surface`` -- the reconstruction, cell array ``label``
  (:data:`recon3d.records.LABELS`);
* ``curves`` -- the sensed slice curves as lines, cell arrays ``class``
  (1 W1, 2 W2, 3 W3, 4 unknown: :data:`recon3d.records.CURVE_CLASSES`),
  ``family`` and ``slice``.

``ground_truth`` also carries the point array ``distance`` (to the scored
surface, % of the diagonal) when the run was scored; the multiblock's field
data holds ``headline`` (text lines of the scores), ``axes`` (family labels)
and ``normals`` ((k, 3) family normals), so ``recon3d show`` draws what
coverage.png shows.

Plain data: drawing is in :mod:`recon3d.viz.plot`.
"""
from __future__ import annotations

import numpy as np
import trimesh

from recon3d.records import SliceRun
from recon3d.viz import libs

__all__ = ["curves_polydata", "scene_blocks", "read_scene"]


def _lines(polylines):
    """VTK ``lines`` connectivity and points for a list of (k, 3) polylines."""
    pts = np.concatenate(polylines) if polylines else np.zeros((0, 3))
    sizes = np.array([len(p) for p in polylines], dtype=np.int64)
    starts = np.cumsum(sizes) - sizes
    conn = [np.concatenate([[n], s + np.arange(n)]) for n, s in zip(sizes, starts)]
    return pts, (np.concatenate(conn) if conn else np.zeros(0, dtype=np.int64))


def curves_polydata(slice_runs: list[SliceRun]):
    """pyvista.PolyData of the sensed curves of ``slice_runs`` (see module doc)."""
    pv = libs.pyvista()
    polys, cls, fam, idx = [], [], [], []
    for s in slice_runs:
        r = s.result
        for code, group in ((1, r.w1), (2, r.w2), (3, r.w3), (4, r.unknown)):
            for pl in group:
                pl = np.asarray(pl, dtype=np.float64).reshape(-1, 2)
                if len(pl) >= 2:
                    polys.append(s.slice.to_3d(pl))
                    cls.append(code)
                    fam.append(s.family)
                    idx.append(s.slice.index)
    pts, lines = _lines(polys)
    out = pv.PolyData(pts, lines=lines) if len(polys) else pv.PolyData()
    if len(polys):
        out.cell_data["class"] = np.array(cls, dtype=np.int32)
        out.cell_data["family"] = np.array(fam, dtype=np.int32)
        out.cell_data["slice"] = np.array(idx, dtype=np.int32)
    return out


def _polydata(mesh: trimesh.Trimesh, name: str):
    if len(mesh.faces) == 0:
        return libs.pyvista().PolyData()
    out = libs.polydata(mesh)
    out.cell_data[name] = np.asarray(mesh.face_attributes[name]).astype(np.int32)
    if "distance" in mesh.vertex_attributes:
        out.point_data["distance"] = np.asarray(mesh.vertex_attributes["distance"], float)
    return out


def scene_blocks(ground_truth: trimesh.Trimesh, surface: trimesh.Trimesh,
                 slice_runs: list[SliceRun], headline=(), normals=(), axes=()):
    """pyvista.MultiBlock with ``ground_truth``, ``surface`` and ``curves`` (module doc).

    Parameters
    ----------
    ground_truth : trimesh.Trimesh with ``face_attributes['coverage']`` and
        optionally ``vertex_attributes['distance']``
        (:func:`recon3d.score.evaluate.coverage_mesh`).
    surface : trimesh.Trimesh with ``face_attributes['label']``.
    slice_runs : list of recon3d.records.SliceRun
    headline : list of str -- text lines drawn into the picture.
    normals : (k, 3) float; axes : list of str -- the families' normals and labels.
    """
    blocks = libs.pyvista().MultiBlock()
    blocks["ground_truth"] = _polydata(ground_truth, "coverage")
    blocks["surface"] = _polydata(surface, "label")
    blocks["curves"] = curves_polydata(slice_runs)
    blocks.field_data["headline"] = np.array(list(headline) or [""])
    blocks.field_data["axes"] = np.array(list(axes) or [""])
    blocks.field_data["normals"] = np.asarray(normals, dtype=np.float64).reshape(-1, 3)
    return blocks


def read_scene(path):
    """Read a ``scene.vtm`` back; ValueError (one line) when it is not one of ours."""
    pv = libs.pyvista()
    blocks = pv.read(str(path))
    names = set(blocks.keys()) if isinstance(blocks, pv.MultiBlock) else set()
    if not {"ground_truth", "surface", "curves"} <= names:
        raise ValueError(f"{path} is not a recon3d scene (blocks: {sorted(names)})")
    return blocks
