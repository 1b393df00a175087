"""Watertight labelled surface from the slice regions of one or more families.

Route: per family, the field of :mod:`recon3d.surface.field` (between slices: the aligned
blend of :mod:`recon3d.surface.warp` by default) is contoured at 0 with VTK flying edges
(positive inside) and moved to world coordinates; the level set extends one layer beyond
the first and last slice. ``manifold3d`` checks it; with one family it is cut to the
**slab** between the first and last slice (flat caps).

Several families are fused by one of two rules (:data:`FUSIONS`):

* ``'weighted'`` (default, :mod:`recon3d.surface.fusion`) -- a family removes space only
  where its own sensing shows it empty, never by its interpolation alone, and adds what only
  it saw: the families' fields averaged with weights from their confidence;
* ``'carve'`` -- the space carving of visual hulls, kept for comparison: family ``f`` proves
  empty the part of its slab outside its level set, ``E_f = slab_f - level_f``, and the
  surface bounds ``S = (slab_1 u slab_2 u ...) - (E_1 u E_2 u ...)`` (``E_f`` cut from a box
  half a layer longer at each end, so that no face is coplanar with a slab's). A family's
  interpolation between its slices then carves true material another family saw.

Face labels (:data:`recon3d.records.LABELS`): a face with a vertex on a slice plane takes the
kind of the nearest sensed piece of that slice (W1 -> 1, W2 -> 2, W3 -> 3;
unknown chords and bridges -> 4); other faces of the level set are
interpolated between slices (4); faces on a plane that bounds a slab are
caps (5). ``manifold3d`` carries the labels through the booleans as face
ids.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import manifold3d
import numpy as np
import trimesh
from scipy.spatial import cKDTree

import slicer
from recon3d.surface.caps import CapSettings
from recon3d.surface.closure import KIND_LABEL, SliceRegion, sample_pieces
from recon3d.surface.confidence import ConfidenceSettings
from recon3d.surface.warp import WarpSettings
from recon3d.surface.field import ROUTES, FamilyField, family_grid, family_volume
from recon3d.surface.fusion import FusionSettings, empty_surface, fuse_weighted, mesh_of
from recon3d.viz import libs

__all__ = ["FamilySolid", "family_solid", "fuse", "empty_surface", "FUSIONS"]

FUSIONS = ("weighted", "carve")
"""Rules for several families: confidence-weighted (:mod:`recon3d.surface.fusion`, default)
or the space carving of visual hulls (module doc)."""

#: margin of the box the slabs are cut from, times the largest extent
_BOX_MARGIN = 0.05

@dataclass(frozen=True)
class FamilySolid:
    """One family's level set (one layer beyond its slab at each end).

    manifold : manifold3d.Manifold
    original_id : int -- manifold3d run id of the level set.
    labels : (f,) int -- label of each level-set face (manifold face id).
    normal : (3,) float -- the family's unit normal.
    slab : (2,) float -- first and last slice offsets along ``normal``.
    overshoot : float -- how far beyond the slab ``E_f`` is cut (half a layer).
    field : FamilyField or None -- field and confidence, kept for the weighted fusion.
    """

    manifold: manifold3d.Manifold
    original_id: int
    labels: np.ndarray
    normal: np.ndarray
    slab: tuple
    overshoot: float
    field: FamilyField | None = None


def _piece_trees(regions, step):
    """Per slice: a KD-tree over the pieces sampled every step / 4, and their labels."""
    out = []
    for reg in regions:
        pts, owner = sample_pieces(reg.pieces, step / 4)
        lab = np.array([KIND_LABEL[p.kind] for p in reg.pieces], dtype=np.int32)
        out.append((cKDTree(pts) if len(pts) else None, lab[owner] if len(pts) else lab))
    return out


def _face_labels(points, faces, grid, regions) -> np.ndarray:
    """(f,) int: label of every level-set face (see module doc).

    points : (n, 3) float -- (x, y, layer) grid coordinates.
    faces : (f, 3) int
    """
    z = points[:, 2]
    zr = np.round(z)
    sl = (zr - 1) / grid.k
    on = (np.abs(z - zr) < 1e-9) & (sl == np.round(sl)) & (sl >= 0) & (sl <= len(regions) - 1)
    vslice = np.where(on, sl, -1).astype(np.int64)
    fs = vslice[faces]  # (f, 3)
    face_slice = fs.max(axis=1)
    labels = np.full(len(faces), 4, dtype=np.int32)
    trees = _piece_trees(regions, grid.step)
    for i in np.unique(face_slice[face_slice >= 0]):
        sel = np.flatnonzero(face_slice == i)
        mask = (fs[sel] == i)[:, :, None]
        xy = (points[faces[sel], :2] * mask).sum(axis=1) / mask.sum(axis=1)
        tree, lab = trees[i]
        if tree is None:
            continue
        d, j = tree.query(xy, distance_upper_bound=2 * grid.step)
        hit = np.isfinite(d)
        labels[sel[hit]] = lab[j[hit]]
    return labels


def family_solid(regions: list[SliceRegion], planes: list[slicer.SlicePlane],
                 step: float, route: str = "warp", keep_field: bool = False,
                 trust: ConfidenceSettings = ConfidenceSettings(),
                 caps: CapSettings = CapSettings(),
                 warp: WarpSettings = WarpSettings(), pair: Callable | None = None
                 ) -> FamilySolid | None:
    """Level set of one family's field (see module doc).

    Parameters
    ----------
    regions : list of SliceRegion -- one per plane.
    planes : list of slicer.SlicePlane -- same family (same frame), >= 2.
    step : float -- grid step (see :func:`recon3d.surface.field.grid_step`).
    route : {'warp', 'linear'} -- between-slice route (:data:`recon3d.surface.field.ROUTES`).
    keep_field : bool -- also compute the confidence and keep the field (for the weighted
        fusion of several families).
    trust : ConfidenceSettings -- parameters of that confidence.
    caps : CapSettings -- unsensed space ends at its slice (:mod:`recon3d.surface.caps`).
    warp : WarpSettings -- the aligned blend (:mod:`recon3d.surface.warp`).
    pair : callable(first, second), optional -- how the field's two halves run
        (:func:`recon3d.surface.field.family_volume`); None: here, one after the other.

    Returns
    -------
    FamilySolid, or None when nothing was sensed.
    """
    pv = libs.pyvista()  # VTK's flying edges contours the field
    if route not in ROUTES:
        raise ValueError(f"unknown between-slice route {route!r}; expected one of {ROUTES}")
    order = np.argsort([p.offset for p in planes], kind="stable")
    planes = [planes[i] for i in order]
    regions = [regions[i] for i in order]
    heights = np.array([p.offset for p in planes])
    grid = family_grid(regions, heights, step)
    vol, conf = family_volume(regions, grid, route, confidence=keep_field, warp=warp,
                              trust=trust, caps=caps, pair=pair)
    img = pv.ImageData(dimensions=(grid.shape[0], grid.shape[1], grid.layers),
                       spacing=(step, step, 1.0), origin=(grid.x0, grid.y0, 0.0))
    img.point_data["f"] = vol.ravel()
    iso = img.contour([0.0], scalars="f", method="flying_edges")
    if iso.n_cells == 0:
        return None
    faces = iso.faces.reshape(-1, 4)
    if not (faces[:, 0] == 3).all():  # pragma: no cover - flying edges makes triangles
        raise RuntimeError("level set produced non-triangular faces")
    faces = np.ascontiguousarray(faces[:, 1:], dtype=np.int64)
    pts = np.asarray(iso.points, dtype=np.float64)
    labels = _face_labels(pts, faces, grid, regions)
    p0 = planes[0]
    h = grid.layer_height(pts[:, 2])
    world = p0.origin + np.outer(pts[:, 0], p0.u) + np.outer(pts[:, 1], p0.v) \
        + np.outer(h - p0.offset, p0.normal)
    mesh = manifold3d.Mesh64(vert_properties=np.ascontiguousarray(world),
                             tri_verts=faces.astype(np.uint64),
                             face_id=np.arange(len(faces), dtype=np.uint64))
    man = manifold3d.Manifold(mesh)
    if man.status() != manifold3d.Error.NoError:  # pragma: no cover - flying edges is closed
        raise RuntimeError(f"level set is not a manifold: {man.status().name}")
    oid = int(np.asarray(man.to_mesh64().run_original_id)[0])
    n = np.asarray(p0.normal, dtype=np.float64)
    delta = 0.5 * float(np.diff(heights).min()) / grid.k
    field = FamilyField(grid, vol, conf, tuple(planes), tuple(regions)) if keep_field else None
    return FamilySolid(man, oid, labels, n, (float(heights[0]), float(heights[-1])), delta,
                       field)


def _box(solids, bounds, margin: float = _BOX_MARGIN) -> manifold3d.Manifold:
    """A box around the level sets and ``bounds`` ((2, 3) float), with a margin."""
    boxes = [np.reshape(s.manifold.bounding_box(), (2, 3)) for s in solids]
    if bounds is not None:
        boxes.append(np.asarray(bounds, dtype=np.float64).reshape(2, 3))
    lo = np.min([b[0] for b in boxes], axis=0)
    hi = np.max([b[1] for b in boxes], axis=0)
    pad = margin * float((hi - lo).max())
    return manifold3d.Manifold.cube((hi - lo) + 2 * pad).translate(lo - pad)


def fuse(solids: list[FamilySolid | None], bounds=None, rule: str = "weighted",
         settings: FusionSettings = FusionSettings()) -> trimesh.Trimesh:
    """The surface of one or more families.

    One family: its level set cut to its slab. Several: ``rule`` -- ``'weighted'``
    (:func:`recon3d.surface.fusion.fuse_weighted`; needs solids made with ``keep_field``)
    or ``'carve'``, ``S = union of slabs - union of E_f`` (module doc).

    Parameters
    ----------
    solids : list of FamilySolid (None entries are skipped).
    bounds : (2, 3) float, optional -- the ground truth's bounds (the slabs
        are cut from a box around these and the level sets).
    rule : {'weighted', 'carve'}
    settings : FusionSettings -- parameters of the weighted fusion.

    Returns
    -------
    trimesh.Trimesh -- watertight, float64 vertices,
    ``face_attributes['label']`` (f,) int32; empty when nothing remains.
    """
    if rule not in FUSIONS:
        raise ValueError(f"unknown fusion rule {rule!r}; expected one of {FUSIONS}")
    solids = [s for s in solids if s is not None]
    if not solids:
        return empty_surface()
    if rule == "weighted" and len(solids) > 1:
        if any(s.field is None for s in solids):
            raise ValueError("the weighted fusion needs family solids made with keep_field=True")
        return fuse_weighted([s.field for s in solids], min(s.field.grid.step for s in solids),
                             settings)
    box = _box(solids, bounds)
    big = _box(solids, bounds, 2 * _BOX_MARGIN)
    slabs, empty = [], []
    for s in solids:
        n, (lo, hi), d = s.normal, s.slab, s.overshoot
        slabs.append(box.trim_by_plane(n, lo).trim_by_plane(-n, -hi))
        empty.append(big.trim_by_plane(n, lo - d).trim_by_plane(-n, -(hi + d)) - s.manifold)
    op = manifold3d.OpType
    man = manifold3d.Manifold.batch_boolean(slabs, op.Add) - \
        manifold3d.Manifold.batch_boolean(empty, op.Add)
    return mesh_of(man, {s.original_id: s.labels for s in solids})
