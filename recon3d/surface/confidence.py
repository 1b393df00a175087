"""How much one slice family knows about each node of its field (for fusing families).

The rule of the fusion (:mod:`recon3d.surface.fusion`): a family removes space only where its
own sensing shows the space empty, never by its interpolation alone, and adds what only it
saw. Its confidence ``c`` in (0, 1] says where its field is sensing and where it is filling in:

* **on a slice** (:func:`seen_map`): outside the region, 1 up to ``near`` grid steps from its
  boundary (space the probe showed empty: a rod swept there, §3.3's free area F grown by the
  passes), then ``1 / (1 + (d / near - 1)^2)`` (far from every contact, "outside" is a weak
  claim: an object the planner never found lies outside every region too), but ``unseen``
  within ``unswept_reach`` steps of an unknown chord that is the nearest piece
  (:func:`unswept`: the unknown contour may stand on either side of it, so nothing beside it
  was shown empty); inside, 1 up to
  ``depth / 2`` steps behind a traced wall (W1, W2), ramping to ``unseen`` at ``depth`` steps;
  ``unseen`` wherever the nearest piece is a W3 lid (the verified never-touching area A_jB_j
  of Area(G_i) = 0), an unknown chord or a bridge, and inside filled holes: the region is
  closed there, not seen.
* **between two slices** (:func:`between_confidence`): the two slices' maps blended, times
  ``max(plane proximity, agreement x 1 / (1 + (s / proximity)^2), floor)`` with ``s`` the
  distance to the nearer slice plane: *agreement* = exp(-((v_a - v_b) / 2 step)^2) of the two
  slices' values at the point (after the warp's alignment, discounted by how far the alignment
  moved unless the unaligned values agree too). So a family's interpolation across a change of
  shape barely counts, and between two families' interpolations the one whose slices lie
  nearer decides. :func:`cone` (an empty claim between slices counted only inside both
  slices' 45-degree cones) was measured and is off by default (``cone=False``): it also
  weakens a family's own well-sensed empty space next to a prism's walls.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from recon3d.surface.closure import sample_pieces
from recon3d.surface.warp import boundary_samples

__all__ = ["ConfidenceSettings", "seen_map", "unswept", "agreement", "cone",
           "between_confidence", "in_plane_share"]


@dataclass(frozen=True)
class ConfidenceSettings:
    """Parameters of a family's confidence (module doc; grid steps unless said otherwise).

    near : float -- outside a region, full confidence up to this distance from its boundary.
    depth : float -- inside, behind a traced wall, confidence falls to ``unseen`` by here.
    unseen : float -- confidence of filled, unseen space (holes, behind lids, bridges).
    floor : float -- least trust in an interpolation between slices (times the blended map).
    proximity : float -- between slices, the agreement counts 1 / (1 + (s / proximity)^2) at
        distance ``s`` from the nearer slice plane (the closer a family's data, the more).
    cone : bool -- an empty claim between slices counts only inside the 45-degree cones.
    facing : float -- exponent of the weight by the surface's facing (:func:`in_plane_share`);
        0 switches it off.
    facing_floor : float -- least facing weight (a lid between slices, seen by no family).
    unswept : bool -- outside a region, space whose nearest piece is an unknown chord counts
        ``unseen`` (:func:`unswept`), not shown empty, up to ``unswept_reach`` steps from it
        (unbounded by default). Measured (``bench/surface_cases.py``, z+x F@1%): before the
        fusion's filled-in rule (``FusionSettings.filled``) and the own-capped slice's trust
        (``CapSettings.own_trust``), 4 / 8 / 12 / unbounded steps gave the open teapot
        0.8722 / 0.8858 / 0.8896 / 0.8895 and the Ravens cup 0.8821 / 0.8815 / 0.8805 /
        0.8775, so 8 was kept; with both, 8 / unbounded give the teapot 0.8806 / 0.8850 (x
        alone 0.8858) and the Ravens cup 0.9247 / 0.9207 (z alone 0.9182).
    """

    near: float = 24.0
    depth: float = 4.0
    unseen: float = 0.03
    floor: float = 0.05
    proximity: float = 2.0
    cone: bool = False
    facing: float = 0.0
    facing_floor: float = 0.05
    unswept: bool = True
    unswept_reach: float = float("inf")


def seen_map(region, f: np.ndarray, grid, settings: ConfidenceSettings = ConfidenceSettings()
             ) -> np.ndarray:
    """(ny, nx) float32 confidence of one slice's field ``f`` (module doc, "on a slice").

    Parameters
    ----------
    region : SliceRegion -- the slice's closed region with its pieces.
    f : (ny, nx) float -- its signed distance on ``grid`` (positive inside).
    grid : FamilyGrid
    """
    s = grid.step
    ny, nx = f.shape
    inside = f > 0
    if not inside.any():
        return np.full(f.shape, 0.1, dtype=np.float32)  # the slice shows nothing: weak
    nodes = grid.nodes()
    pb, _ = boundary_samples(f, grid.x0, grid.y0, s)
    dist = cKDTree(pb).query(nodes)[0].reshape(ny, nx)
    conf = 1 / (1 + np.maximum(dist / (settings.near * s) - 1, 0) ** 2)
    depth = settings.depth * s
    sel = np.flatnonzero(inside.ravel())
    traced = [p for p in region.pieces if p.kind in ("W1", "W2")]
    closed = [p for p in region.pieces if p.kind not in ("W1", "W2")]
    dt = np.full(len(sel), np.inf)
    if traced:  # depth behind a traced wall (the field itself is truncated)
        pt, _ = sample_pieces(traced, s / 2)
        dt, _ = cKDTree(pt).query(nodes[sel], distance_upper_bound=depth)
    ramp = np.clip(2 - 2 * dt / depth, 0, 1)
    inner = settings.unseen + (1 - settings.unseen) * ramp
    if closed:  # behind a lid, an unknown chord or a bridge: closed, not seen
        pc, _ = sample_pieces(closed, s / 2)
        dc, _ = cKDTree(pc).query(nodes[sel], distance_upper_bound=depth)
        inner[dc < dt] = settings.unseen
    conf = conf.reshape(-1)
    conf[sel] = inner
    if settings.unswept:
        out = np.flatnonzero(~inside.ravel())
        conf[out[unswept(region, nodes[out], s, settings.unswept_reach)]] = settings.unseen
    return conf.reshape(ny, nx).astype(np.float32)


def unswept(region, pts: np.ndarray, step: float, reach: float = np.inf) -> np.ndarray:
    """(n,) bool: points within ``reach`` steps of an unknown chord, their nearest piece.

    An unknown chord is the lid A_iB_i of an area still unknown at the end (§3.3). The
    unknown contour C_{A_i}^{B_i} runs from A_i to B_i anywhere in G_i (Def. 1): material
    rooted on it may stand on the chord's free side V_i too (§3.2), so the space beside the
    chord, on either side, was not shown empty. Outside a region it is left out only because
    no traced piece closes it (inside the open teapot's pot, between chords crossing it).

    Parameters
    ----------
    region : SliceRegion
    pts : (n, 2) float
    step : float -- the pieces are sampled every step / 2.
    reach : float -- only points within ``reach`` x ``step`` of the chord.
    """
    if len(pts) == 0 or not any(p.kind == "unknown" for p in region.pieces):
        return np.zeros(len(pts), dtype=bool)
    samples, owner = sample_pieces(region.pieces, step / 2)
    kinds = np.array([p.kind for p in region.pieces])
    d, j = cKDTree(samples).query(pts)
    return (kinds[owner[j]] == "unknown") & (d <= reach * step)


def agreement(a: np.ndarray, b: np.ndarray, step: float) -> np.ndarray:
    """exp(-((a - b) / 2 step)^2), float32, same shape as ``a``: 1 where two slices agree."""
    return np.exp(-((a - b) / (2 * step)) ** 2).astype(np.float32)


def cone(agree: np.ndarray, va: np.ndarray, vb: np.ndarray, w: np.ndarray, gap: float
         ) -> np.ndarray:
    """Trust in an *empty* claim between two slices: only inside both slices' 45-degree cones.

    Parameters
    ----------
    agree, va, vb : (k, ny, nx) float -- agreement and the two slices' values along the move.
    w : (k, 1, 1) float -- fraction of the gap (0 on slice a).
    gap : float

    Returns
    -------
    (k, ny, nx) float32 -- ``agree``, capped where both values are negative by
    ``min(-va / (w gap), -vb / ((1 - w) gap))`` clipped to [0, 1] (1 on a slice).
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        c = np.minimum(np.where(w > 0, -va / (w * gap), 1.0),
                       np.where(w < 1, -vb / ((1 - w) * gap), 1.0))
    c = np.clip(np.nan_to_num(c, nan=1.0), 0, 1)
    return np.where((va < 0) & (vb < 0), np.minimum(agree, c), agree).astype(np.float32)


def between_confidence(ca, cb, w, agree, grid, gap: float,
                       settings: ConfidenceSettings = ConfidenceSettings()) -> np.ndarray:
    """(k, ny, nx) float32 confidence of the layers between two slices (module doc).

    Parameters
    ----------
    ca, cb : (ny, nx) float -- the two slices' :func:`seen_map`.
    w : (k, 1, 1) float -- fraction of the gap of each layer.
    agree : (k, ny, nx) float -- agreement of the two slices along the move (after :func:`cone`).
    grid : FamilyGrid; gap : float
    """
    dist = np.minimum(w, 1 - w) * gap
    near = np.clip(1 - dist / (2 * grid.step), 0, 1)
    prox = 1 / (1 + (dist / (settings.proximity * grid.step)) ** 2)
    trust = np.maximum(np.maximum(near, agree * prox), settings.floor)
    return np.maximum(((1 - w) * ca + w * cb) * trust, 1e-3).astype(np.float32)


def in_plane_share(vol: np.ndarray, grid) -> np.ndarray:
    """(layers, ny, nx) float32: how much the family's own surface faces its slice planes.

    The share of the field's 3D gradient that lies in the slice plane, ``|grad_uv f| / |grad f|``
    = sin of the angle between the surface normal and the slicing axis (a stacked 2D signed
    distance has ``|grad_uv f| = 1`` and ``df/dh = cot`` of that angle). 1 on a wall the
    slices cut across (sensed as W1/W2 in every slice), 0 on a floor or lid parallel to the
    planes (between slices only interpolated, §3: the probe moves in the slice plane). 1 where
    the field is flat (truncated).

    Parameters
    ----------
    vol : (layers, ny, nx) float -- the family's field (positive inside).
    grid : FamilyGrid
    """
    h = grid.layer_height(np.arange(grid.layers))
    gh, gy, gx = np.gradient(vol.astype(np.float32), h, grid.step, grid.step)
    gin = np.hypot(gx, gy)
    norm = np.hypot(gin, gh)
    with np.errstate(divide="ignore", invalid="ignore"):
        share = np.where(norm > 1e-6, gin / norm, 1.0)
    return share.astype(np.float32)
