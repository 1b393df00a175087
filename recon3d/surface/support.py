"""Where a family's *empty* contradicts another family's solid on its own slice planes.

The fusion's rule (:mod:`recon3d.surface.fusion`): a family removes space only where its own
sensing shows the space empty. On a slice plane of family ``B`` the probe swept the plane
(§3.3: the free area F grown by the passes), so ``B``'s empty there is sensed; between ``B``'s
planes it is ``B``'s interpolation. Another family ``A`` slices across ``B``'s planes; its
field there (sensed on ``A``'s planes, interpolated between them) may say *solid* where ``B``
sensed *empty*: a hole through the part along ``A``'s axis (``A`` fills it, it cannot see it),
or ``A``'s interpolation across a change of shape. That is what ``B``'s sensing explains and
``A``'s does not. The **contradiction** of ``B`` on its slice ``i`` is, per node,

    k_i = clip(-F_B / step, 0, 1) * c_B * max_A r_A clip(F_A / step, 0, 1)

(``r_A`` 1 in A's slab, beyond it falling off as A's end slice extended does in the fusion),
grown by ``grow`` grid steps in the plane (a hole's edge moves between planes), and between
``B``'s slices it is blended linearly, ``(1 - w) k_i + w k_{i+1}``: so it falls with the
distance to ``B``'s nearest sensed plane in units of ``B``'s slice spacing, and stays 1
between two planes that both saw the contradiction (a bore crossing several planes).

Where ``B``'s field says empty and another family's says solid, the fusion lets ``B`` weigh
fully only as far as this support reaches; elsewhere ``B``'s interpolated empty is capped
below the solid family's weight (:func:`recon3d.surface.fusion.fused_field`) -- where that
solid is **sensed** (:func:`sensed_solid`): inside a slice's region whose nearest piece is a
traced wall (W1, W2). Space closed by a W3 lid, an unknown chord or a bridge is filled, not
sensed, and yields to any family's empty.
"""
from __future__ import annotations

import numpy as np
from scipy.ndimage import maximum_filter
from scipy.spatial import cKDTree

from recon3d.surface.closure import sample_pieces

__all__ = ["plane_points", "contradiction", "sensed_solid", "filled_in", "solid_shares"]


def plane_points(ff, i: int) -> np.ndarray:
    """(ny * nx, 3) world points of family ``ff``'s grid nodes on its slice ``i``."""
    p, g = ff.planes[0], ff.grid
    xy = g.nodes()
    return (p.origin + np.outer(xy[:, 0], p.u) + np.outer(xy[:, 1], p.v)
            + (g.heights[i] - p.offset) * np.asarray(p.normal, dtype=np.float64))


def _blend(planes, g) -> np.ndarray:
    """(layers, ny, nx) float32: per-slice maps blended linearly between slices."""
    nx, ny = g.shape
    out = np.zeros((g.layers, ny, nx), dtype=np.float32)
    w = (np.arange(g.k, dtype=np.float32) / g.k)[:, None, None]
    for i in range(len(planes) - 1):
        a = g.slice_layer(i)
        out[a:a + g.k] = (1 - w) * planes[i] + w * planes[i + 1]
    out[g.slice_layer(len(planes) - 1)] = planes[-1]
    return out


def _inside_depths(ff, i: int):
    """Slice ``i``'s nodes inside its region: flat indices (m,), distance to the nearest traced
    piece (W1, W2) and to the nearest closed one (W3, unknown chord, bridge), (m,) each."""
    g, region = ff.grid, ff.regions[i]
    nodes = g.nodes()
    sel = np.flatnonzero(ff.vol[g.slice_layer(i)].ravel() > 0)
    traced = [p for p in region.pieces if p.kind in ("W1", "W2")]
    closed = [p for p in region.pieces if p.kind not in ("W1", "W2")]
    far = np.full(len(sel), np.inf)
    dt = (cKDTree(sample_pieces(traced, g.step / 2)[0]).query(nodes[sel])[0]
          if traced and len(sel) else far)
    dc = (cKDTree(sample_pieces(closed, g.step / 2)[0]).query(nodes[sel])[0]
          if closed and len(sel) else far)
    return sel, dt, dc


def _per_plane(ff, *values) -> list[np.ndarray]:
    """Per function ``value(dt, dc)``: a (layers, ny, nx) float32 map of its value on each
    slice's inside nodes (0 outside), blended linearly between slices (one pass)."""
    g = ff.grid
    nx, ny = g.shape
    planes = [[] for _ in values]
    for i in range(len(ff.regions)):
        sel, dt, dc = _inside_depths(ff, i)
        for out, value in zip(planes, values):
            m = np.zeros(nx * ny, dtype=np.float32)
            m[sel] = value(dt, dc)
            out.append(m.reshape(ny, nx))
    return [_blend(p, g) for p in planes]


def _sensed(dt, dc):
    return np.isfinite(dt) & (dt <= dc)


def _filled(depth: float):
    return lambda dt, dc: np.where(dt <= dc, 1 - np.clip(2 - 2 * dt / depth, 0, 1), 1.0)


def sensed_solid(ff) -> np.ndarray:
    """(layers, ny, nx) float32 in [0, 1]: 1 inside a slice's region where its nearest piece
    is a traced wall (W1, W2), 0 elsewhere (outside, or closed by a W3 lid, an unknown chord,
    a bridge), blended linearly between slices."""
    return _per_plane(ff, _sensed)[0]


def filled_in(ff, depth: float = 4.0) -> np.ndarray:
    """(layers, ny, nx) float32 in [0, 1]: how much of a slice's solid it only filled in.

    Inside a slice's region: 0 up to ``depth / 2`` grid steps behind a traced wall (W1, W2;
    the contact showed material there), rising linearly to 1 at ``depth`` steps (how deep the
    material goes the probe never felt: a thin wall round a cavity enclosed in the plane,
    which the closure fills, reads the same), and 1 where a W3 lid, an unknown chord or a
    bridge is the nearest piece; 0 outside. Blended linearly between slices. The same depth
    ramp as the family's confidence (:func:`recon3d.surface.confidence.seen_map`).
    """
    return _per_plane(ff, _filled(ff.grid.step * depth))[0]


def solid_shares(ff, depth: float = 4.0) -> tuple[np.ndarray, np.ndarray]:
    """:func:`sensed_solid` and :func:`filled_in` of one family, in one pass."""
    a, b = _per_plane(ff, _sensed, _filled(ff.grid.step * depth))
    return a, b


def contradiction(ff, others, sample, grow: float = 2.0) -> np.ndarray:
    """(layers, ny, nx) float32 in [0, 1]: the module doc's support of ``ff``'s empty.

    Parameters
    ----------
    ff : FamilyField -- family ``B``.
    others : list of FamilyField -- the families ``A``.
    sample : callable -- ``sample(A, pts) -> (value, reach)`` of a family at (n, 3) points,
        value (n,) float, reach (n,) float: 1 in A's slab, falling off beyond it.
    grow : float -- in-plane growth of the contradiction, grid steps.
    """
    g = ff.grid
    nx, ny = g.shape
    if not others:
        return np.zeros((g.layers, ny, nx), dtype=np.float32)
    size = 2 * int(np.ceil(grow)) + 1
    planes = []
    for i in range(len(g.heights)):
        lay = g.slice_layer(i)
        pts = plane_points(ff, i)
        solid = np.zeros(len(pts))
        for other in others:
            v, ins = sample(other, pts)
            solid = np.maximum(solid, ins * np.clip(v / g.step, 0, 1))
        empty = np.clip(-ff.vol[lay].ravel() / g.step, 0, 1) * ff.conf[lay].ravel()
        k = (empty * solid).reshape(ny, nx)
        planes.append(maximum_filter(k, size=size, mode="constant").astype(np.float32))
    return _blend(planes, g)
