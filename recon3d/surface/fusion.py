"""Fusion of slice families that never loses: confidence-weighted fields, one level set.

The rule: **a family removes space only where its own sensing shows the space empty (near
its sensed slices), never by its interpolation alone; every family adds what only it saw.**
Each family ``f`` brings its field ``F_f`` (:mod:`recon3d.surface.field`, positive inside) and
its confidence ``c_f`` (:mod:`recon3d.surface.confidence`): 1 where its slices show the space
empty or right behind a traced W1/W2 wall, ``unseen`` (0.03) in what it only filled in (holes,
behind W3 lids, bridges) and in what its closure left out beside an unknown chord (within
``ConfidenceSettings.unswept_reach`` steps: not shown empty either, the unknown contour may
stand on either side of the chord), and between its
slices only as much as its two neighbouring slices agree there. The fused field is

    F(x) = sum_f c_f(x)^p F_f(x) / sum_f c_f(x)^p      (p = ``power``, 2)

with every ``F_f`` clipped to the smallest truncation of the families (a family with wider
gaps must not outvote the others by magnitude). **An empty a family did not see yields to a
sensed solid** (``FusionSettings.explained``, :mod:`recon3d.surface.support`): where ``F_f < 0``
and another family ``g`` has a *sensed* solid (inside its region behind a traced W1/W2 wall,
not closed by a W3 lid, an unknown chord or a bridge), ``f``'s weight counts fully only as far
as ``f``'s own slice planes showed empty where ``g`` says solid (the contradiction, blended
between ``f``'s planes, so it falls with the distance to ``f``'s nearest plane in units of its
slice spacing); elsewhere it is at most ``cap`` (0.03) x ``g``'s weight. Conversely (``filled``)
**a solid a family only filled in yields to an empty the other family's planes saw**: where
``F_g > 0`` deeper than ``depth`` steps behind g's traced walls (or closed by a lid, a chord,
a bridge: :func:`recon3d.surface.support.filled_in`) and ``F_f < 0``, ``g``'s weight counts
fully only as far as ``f``'s planes do *not* contradict it, elsewhere at most ``cap`` x
``f``'s weight (a cavity enclosed in g's planes -- the Ravens cup's along z -- whose walls
f's planes trace). Beyond f's slab
``F_f`` is its end slice extended, with a weight only near that slice's walls
(``FusionSettings.extend``). The surface is ``{F > 0}`` cut to the union of the slabs (faces
on the cut: caps, label 5), bodies smaller than (``speck`` x step)^3 dropped.

What it means: a hole through the part along the other axis is *seen empty* (weight 1) by the
family slicing across it and only *filled, unseen* (weight 0.03^2) by the family along it, so
it stays open; a family's interpolation across a change of shape weighs next to nothing, so it
cannot carve material another family saw; the faces perpendicular to one axis come from the
family whose slab reaches them.

The fields are resampled (trilinear) on one world rectilinear grid whose lines along an
axis-aligned family's normal are that family's layers (its slice planes stay grid planes),
contoured at 0 with VTK and checked and cut with manifold3d.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import partial

import manifold3d
import numpy as np
import trimesh
from scipy.ndimage import map_coordinates
from scipy.spatial import cKDTree

from recon3d.surface.closure import KIND_LABEL, sample_pieces
from recon3d.surface.support import contradiction, solid_shares
from recon3d.viz import libs

__all__ = ["FusionSettings", "world_axes", "resample", "value_in_slab", "fused_field",
           "fuse_weighted", "empty_surface", "mesh_of"]


@dataclass(frozen=True)
class FusionSettings:
    """Parameters of the weighted fusion (measured in ``bench/bench_surface.py``).

    power : float -- weights are c^power.
    outside : float -- least weight of a family beyond its slab.
    speck : float -- bodies under (speck x step)^3 are dropped.
    extend : float -- beyond its slab a family's end slice counts ``extend`` x its confidence,
        near its walls only (fading over ``extend_scale`` grid steps inside), falling off as
        1 / (1 + (s / extend_scale)^2) at ``s`` grid steps beyond: it shapes the walls there,
        the family that sees the end decides where the part ends.
    explained : bool -- a family's empty weighs fully against another family's *sensed*
        solid only as far as its own slice planes contradict that solid
        (:mod:`recon3d.surface.support`); elsewhere its weight is at most ``cap`` x the solid
        family's weight. ``grow``: the contradiction's in-plane growth (grid steps).
        Beyond a family's slab its end slice extended counts as its solid for this rule,
        fading as 1 / (1 + (s / ``reach``)^2) in the contradiction and as
        1 / (1 + (s / ``solid_reach``)^2) as the solid that caps (``s`` grid steps beyond).
    filled : bool -- the converse (with ``explained``): a solid a family only filled in
        (:func:`recon3d.surface.support.filled_in`: deeper than ``depth`` grid steps behind
        its traced walls, or behind a W3 lid, an unknown chord, a bridge) weighs fully
        against another family's empty only as far as that family's planes do *not*
        contradict it; where they do, it is at most ``cap`` x that family's weight.
        Measured (``bench/surface_cases.py``, z+x F@1%, the rule off with
        ``ConfidenceSettings.unswept_reach`` 8 -> on with it unbounded): the Ravens cup
        0.9165 -> 0.9207, ``trimesh_idler_riser`` 0.9718 -> 0.9801, ``mushroom`` 0.9737 -> 0.9794,
        ``featuretype`` 0.9342 -> 0.9388, ``cup_handle`` 0.9964 -> 0.9995; ``comb`` 0.8416
        -> 0.8392 (x alone 0.482), the open teapot 0.8858 -> 0.8850 (with the reach of 8
        steps it fell to 0.8806: z's channels between its unknown chords, counted as shown
        empty, carved x's filled pot).
    """

    power: float = 2.0
    outside: float = 1e-6
    speck: float = 3.0
    extend: float = 0.1
    extend_scale: float = 4.0
    explained: bool = True
    cap: float = 0.03
    grow: float = 2.0
    reach: float = 4.0
    solid_reach: float = 16.0
    filled: bool = True
    depth: float = 4.0


def empty_surface() -> trimesh.Trimesh:
    """A trimesh without faces, with an empty ``label`` face attribute."""
    mesh = trimesh.Trimesh(np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64), process=False)
    mesh.face_attributes["label"] = np.zeros(0, dtype=np.int32)
    return mesh


def _corners(ff) -> np.ndarray:
    """(8, 3) world corners of a family's grid."""
    g, p = ff.grid, ff.planes[0]
    xs = [g.x0, g.x0 + (g.shape[0] - 1) * g.step]
    ys = [g.y0, g.y0 + (g.shape[1] - 1) * g.step]
    hs = g.layer_height([0, g.layers - 1])
    return np.array([p.origin + x * p.u + y * p.v + (h - p.offset) * p.normal
                     for x in xs for y in ys for h in hs])


def world_axes(fields, step: float) -> list[np.ndarray]:
    """Node coordinates along x, y, z covering every family's grid.

    Along an axis some family's normal follows (up to sign), that family's layer heights,
    extended by ``step`` to both ends; else uniform at ``step``.
    """
    c = np.concatenate([_corners(f) for f in fields])
    lo, hi = c.min(axis=0), c.max(axis=0)
    axes = []
    for a in range(3):
        coords = None
        for ff in fields:
            n = np.asarray(ff.planes[0].normal, dtype=np.float64)
            if abs(abs(n[a]) - 1) < 1e-9:
                g = ff.grid
                h = np.sort(g.layer_height(np.arange(g.layers)) * np.sign(n[a]))
                below = h[0] - step * np.arange(int(np.ceil((h[0] - lo[a]) / step)) + 1, 0, -1)
                above = h[-1] + step * np.arange(1, int(np.ceil((hi[a] - h[-1]) / step)) + 2)
                coords = np.concatenate([below, h, above])
                break
        if coords is None:
            coords = lo[a] - step + step * np.arange(int(np.ceil((hi[a] - lo[a]) / step)) + 3)
        axes.append(coords)
    return axes


def _coords(ff, pts: np.ndarray):
    """Grid coordinates of world points in a family's volume, their heights, in-slab mask."""
    g, p = ff.grid, ff.planes[0]
    rel = pts - p.origin
    h = pts @ np.asarray(p.normal, dtype=np.float64)
    lay = np.interp(h, g.layer_height(np.arange(g.layers)), np.arange(g.layers))
    tol = 1e-9 * max(1.0, float(np.abs(g.heights).max()))
    inslab = (h >= g.heights[0] - tol) & (h <= g.heights[-1] + tol)
    lay = np.clip(lay, g.slice_layer(0), g.slice_layer(len(g.heights) - 1))
    return [lay, (rel @ p.v - g.y0) / g.step, (rel @ p.u - g.x0) / g.step], h, inslab


def value_in_slab(ff, pts: np.ndarray, scale: float = 4.0) -> tuple[np.ndarray, np.ndarray]:
    """Field value (n,) float of one family at world points (n, 3), and (n,) float: 1 in its
    slab, beyond it falling off as 1 / (1 + (s / scale steps)^2) (the end slice extended)."""
    coords, h, _ = _coords(ff, pts)
    g = ff.grid
    beyond = np.maximum(np.maximum(g.heights[0] - h, h - g.heights[-1]), 0)
    return (map_coordinates(ff.vol, coords, order=1, mode="nearest"),
            1 / (1 + (beyond / (scale * g.step)) ** 2))


def resample(ff, pts: np.ndarray, outside: float = 1e-6, extend: float = 0.0,
             scale: float = 4.0, volumes=()) -> tuple[np.ndarray, ...]:
    """Field value and confidence of one family at world points.

    Parameters
    ----------
    ff : FamilyField; pts : (n, 3) float.
    outside, extend, scale : float -- confidence beyond the family's slab
        (:class:`FusionSettings`).
    volumes : sequence of (layers, ny, nx) arrays on ``ff``'s grid -- also sampled.

    Returns
    -------
    value, conf, *sampled : (n,) float -- trilinear; beyond the slab the end slice extended.
    """
    g = ff.grid
    coords, h, inslab = _coords(ff, pts)
    v = map_coordinates(ff.vol, coords, order=1, mode="nearest")
    c = map_coordinates(ff.conf, coords, order=1, mode="nearest")
    beyond = np.maximum(g.heights[0] - h, h - g.heights[-1])
    shallow = np.clip(1 - np.maximum(v, 0) / (scale * g.step), 0, 1)
    ext = extend * c * shallow / (1 + (beyond / (scale * g.step)) ** 2)
    extra = tuple(map_coordinates(vol, coords, order=1, mode="nearest") for vol in volumes)
    return (v, np.where(inslab, c, np.maximum(ext, outside))) + extra


def _slab_distance(fields, pts: np.ndarray) -> np.ndarray:
    """(n,) float: signed distance to the union of the families' slabs (positive inside)."""
    out = np.full(len(pts), -np.inf)
    for ff in fields:
        h = pts @ np.asarray(ff.planes[0].normal, dtype=np.float64)
        out = np.maximum(out, np.minimum(h - ff.grid.heights[0], ff.grid.heights[-1] - h))
    return out


def _family_terms(ff, fields, pts: np.ndarray, settings: FusionSettings):
    """One family at world points (n, 3): field value, weight c^power, the contradiction
    supporting its empty, its sensed solid share and its filled-in share (the last three 0
    without ``explained``), (n,) each."""
    others = [o for o in fields if o is not ff] if settings.explained else []
    extra = ((contradiction(ff, others, partial(value_in_slab, scale=settings.reach),
                            settings.grow), *solid_shares(ff, settings.depth))
             if others else ())
    v, c, *ks = resample(ff, pts, settings.outside, settings.extend, settings.extend_scale,
                         extra)
    wgt = c.astype(np.float64) ** settings.power
    if not ks:
        zero = np.zeros(len(pts))
        return v, wgt, zero, zero, zero
    reach = value_in_slab(ff, pts, settings.solid_reach)[1]
    solid = np.where(v > 0, np.clip(ks[1], 0, 1) * reach, 0.0)
    filled = np.where(v > 0, np.clip(ks[2], 0, 1), 0.0) if settings.filled else 0 * v
    return v, wgt, np.clip(ks[0], 0, 1), solid, filled


def fused_field(fields, step: float, settings: FusionSettings = FusionSettings()
                ) -> tuple[list[np.ndarray], np.ndarray]:
    """World grid axes (x, y, z) and the fused field (module doc), shape (nz, ny, nx).

    The field is cut to the union of the slabs here (``min`` with the slabs' signed
    distance), so the caps come out of the same contour: no boolean leaves slivers on a
    slice plane.
    """
    xs, ys, zs = world_axes(fields, step)
    gz, gy, gx = np.meshgrid(zs, ys, xs, indexing="ij")
    pts = np.column_stack([gx.ravel(), gy.ravel(), gz.ravel()])
    tc = min(ff.grid.truncation for ff in fields)
    vals, parts = [], []
    for ff in fields:
        v, wgt, k, solid, filled = _family_terms(ff, fields, pts, settings)
        vals.append(np.clip(v, -tc, tc))
        parts.append((wgt, k, solid, filled))
    num = np.zeros(len(pts))
    den = np.zeros(len(pts))
    for j, (v, (wgt, k, _, filled)) in enumerate(zip(vals, parts)):
        if settings.explained and len(fields) > 1:
            capped, yields = wgt, wgt
            for i, (wo, ko, so, _) in enumerate(parts):
                if i == j:
                    continue
                # an unexplained empty yields to another family's sensed solid (so)
                capped = (1 - so) * capped + so * np.minimum(capped, settings.cap * wo)
                # a filled-in solid yields where the other family's planes saw it empty (ko)
                share = filled * np.where(vals[i] < 0, ko, 0.0)
                yields = (1 - share) * yields + share * np.minimum(yields, settings.cap * wo)
            wgt = np.where(v < 0, k * wgt + (1 - k) * capped, yields)
        num += wgt * v
        den += wgt
    fused = np.minimum(num / den, _slab_distance(fields, pts))
    small = np.abs(fused) < 1e-3 * step  # keeps level-set vertices apart from grid nodes
    fused[small] = np.copysign(1e-3 * step, fused[small])
    return [xs, ys, zs], fused.reshape(len(zs), len(ys), len(xs))


def _labels(points, faces, fields, step: float) -> np.ndarray:
    """(f,) int: W-kind of the nearest piece for faces touching a slice plane (a vertex
    within step / 4 of it), else 4 (between slices) -- the rule of one family's level set
    (:func:`recon3d.surface.solid._face_labels`: a face with a vertex on a slice plane)."""
    cen = points[faces].mean(axis=1)
    lab = np.full(len(faces), 4, dtype=np.int32)
    best = np.full(len(faces), np.inf)
    for ff in fields:
        h = points[faces] @ np.asarray(ff.planes[0].normal, dtype=np.float64)  # (f, 3)
        for plane, reg in zip(ff.planes, ff.regions):
            on = np.flatnonzero(np.abs(h - plane.offset).min(axis=1) < step / 4)
            if len(on) == 0 or not reg.pieces:
                continue
            p2, owner = sample_pieces(reg.pieces, step / 4)
            kinds = np.array([KIND_LABEL[p.kind] for p in reg.pieces])[owner]
            p3 = plane.origin + np.outer(p2[:, 0], plane.u) + np.outer(p2[:, 1], plane.v)
            d, j = cKDTree(p3).query(cen[on], distance_upper_bound=2 * step)
            better = d < best[on]
            lab[on[better]] = kinds[j[better]]
            best[on[better]] = d[better]
    return lab


def mesh_of(man: manifold3d.Manifold, owners: dict) -> trimesh.Trimesh:
    """A manifold as a trimesh, labels carried as face ids.

    owners : dict -- manifold3d original id -> (f,) int labels of that mesh's faces; faces of
    any other origin (the slab boxes) are caps (5).
    """
    if man.is_empty():
        return empty_surface()
    out = man.to_mesh64()
    tri = np.asarray(out.tri_verts, dtype=np.int64)
    fid = np.asarray(out.face_id, dtype=np.int64)
    run = np.asarray(out.run_index, dtype=np.int64) // 3
    rid = np.asarray(out.run_original_id, dtype=np.int64)
    labels = np.full(len(tri), 5, dtype=np.int32)
    for k, oid in enumerate(rid):
        if int(oid) in owners:
            sl = slice(run[k], run[k + 1])
            labels[sl] = owners[int(oid)][fid[sl]]
    verts = np.array(out.vert_properties, dtype=np.float64)[:, :3]  # a copy: no view
    mesh = trimesh.Trimesh(verts, tri, process=False)  # keeps the Mesh64 alive at exit
    mesh.face_attributes["label"] = labels
    return mesh


def fuse_weighted(fields, step: float, settings: FusionSettings = FusionSettings()
                  ) -> trimesh.Trimesh:
    """The surface of the confidence-weighted fusion (module doc).

    Parameters
    ----------
    fields : list of FamilyField -- at least one.
    step : float -- world grid step.

    Returns
    -------
    trimesh.Trimesh -- watertight, ``face_attributes['label']`` (f,) int32 (5 on slab cuts).
    """
    (xs, ys, zs), fused = fused_field(fields, step, settings)
    fused[0], fused[-1] = -step, -step  # the rim is outside: a closed level set
    fused[:, 0], fused[:, -1], fused[:, :, 0], fused[:, :, -1] = (-step,) * 4
    pv = libs.pyvista()  # VTK contours the rectilinear grid
    grid = pv.RectilinearGrid(xs, ys, zs)
    grid.point_data["f"] = fused.ravel().astype(np.float32)
    iso = grid.contour([0.0], scalars="f").triangulate()
    if iso.n_cells == 0:
        return empty_surface()
    faces = np.ascontiguousarray(iso.faces.reshape(-1, 4)[:, 1:], dtype=np.int64)
    pts = np.asarray(iso.points, dtype=np.float64)
    labels = _labels(pts, faces, fields, step)
    man = manifold3d.Manifold(manifold3d.Mesh64(
        vert_properties=np.ascontiguousarray(pts), tri_verts=faces.astype(np.uint64),
        face_id=np.arange(len(faces), dtype=np.uint64)))
    if man.status() != manifold3d.Error.NoError:  # pragma: no cover - VTK contours are closed
        raise RuntimeError(f"fused level set is not a manifold: {man.status().name}")
    parts = man.decompose()
    if len(parts) > 1:  # specks, and voids no probe from outside can sense
        kept = [p for p in parts if p.volume() >= (settings.speck * step) ** 3]
        man = manifold3d.Manifold.compose(kept) if kept else man
    out = man.to_mesh64()
    tri = np.asarray(out.tri_verts, dtype=np.int64)
    if len(tri) == 0:
        return empty_surface()
    verts = np.array(out.vert_properties, dtype=np.float64)[:, :3]  # a copy (as above)
    labels = labels[np.asarray(out.face_id, dtype=np.int64)]
    on_cut = np.abs(_slab_distance(fields, verts)) < 1e-2 * step
    labels[on_cut[tri].all(axis=1)] = 5  # the slab ends: caps
    mesh = trimesh.Trimesh(verts, tri, process=False)
    mesh.face_attributes["label"] = labels
    return mesh
