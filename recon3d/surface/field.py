"""Signed distance field of one slice family (shape-based interpolation).

Per slice, the filled region of :mod:`recon3d.surface.closure` gives a 2D signed
distance on a regular grid of the family's frame (positive inside, the
convention of ``manifold3d.Manifold.level_set``), truncated at +-T with T
the largest gap between neighbouring slices (and, between two slices, at
the gap between them: with uneven gaps -- adaptive slicing -- a step in the
section stays a step). Between two slices the field is interpolated along the
normal by one of two routes (:data:`ROUTES`):

* ``'warp'`` (default) -- the two slices aligned first (:mod:`recon3d.surface.warp`):
  a thin wall that moves more than its thickness from one slice to the next stays a
  wall, a ring stays a ring; space a slice only closed with unknown chords or bridges,
  where the neighbour disagrees, ends at that slice (:mod:`recon3d.surface.caps`), also
  when a run of slices closed it (:mod:`recon3d.surface.runs`); a lid whose walls stand
  still in the neighbouring gaps is a step at mid-gap (:mod:`recon3d.surface.steps`); a
  boundary follows a curve through four slices, bent by the neighbouring gaps' moves
  (:func:`recon3d.surface.warp.bend_shift`);
* ``'linear'`` -- plain shape-based interpolation (Herman et al. 1992): a loop that keeps
  its shape makes a straight prism, a loop that vanishes tapers off at roughly 45 degrees,
  loops that split or merge do so half-way.

The volume is indexed ``[il, iy, ix]`` (so ``ravel()`` is VTK point order):
``x = x0 + ix * step`` along ``u``, ``y = y0 + iy * step`` along ``v``, and
layer ``il`` along the normal. Slice
``i`` sits on layer ``1 + i * k`` (``k`` sub-layers per gap); the first and
last layers are padding (outside) so that the zero level set is closed.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from functools import partial

import numpy as np
import shapely
from scipy.spatial import cKDTree

from recon3d.surface.caps import CapSettings, cap_unsensed, own_caps
from recon3d.surface.runs import run_caps
from recon3d.surface.steps import gap_steps
from recon3d.surface.confidence import (ConfidenceSettings, agreement, between_confidence, cone,
                                        in_plane_share, seen_map)
from recon3d.surface.warp import WarpSettings, bend_shift, gap_displacement, warp_blend

__all__ = ["ROUTES", "FamilyField", "FamilyGrid", "family_grid", "slice_sdf", "family_volume", "grid_step"]

ROUTES = ("warp", "linear")
"""Between-slice routes: aligned (:mod:`recon3d.surface.warp`) and plain shape-based."""

#: smallest |value| kept in the field, times the step: keeps level-set
#: vertices apart from grid nodes (no zero-length edges)
_MIN_VALUE = 1e-3

#: a family of at least this many slices splits its work in two halves (``pair``)
_SPLIT = 4


@dataclass(frozen=True)
class FamilyGrid:
    """The sampling grid of one slice family.

    x0, y0 : float -- 2D frame coordinates of node (0, 0).
    step : float -- in-plane node spacing.
    shape : (nx, ny) -- in-plane nodes.
    heights : (m,) float -- slice offsets along the normal (ascending).
    k : int -- layers per gap between neighbouring slices.
    truncation : float -- |field| <= truncation.
    """

    x0: float
    y0: float
    step: float
    shape: tuple
    heights: np.ndarray
    k: int
    truncation: float

    @property
    def layers(self) -> int:
        """Number of layers, padding included."""
        return (len(self.heights) - 1) * self.k + 3

    def slice_layer(self, i: int) -> int:
        """Layer index of slice ``i``."""
        return 1 + i * self.k

    def nodes(self) -> np.ndarray:
        """(nx * ny, 2) float: node coordinates, x fastest (VTK point order)."""
        nx, ny = self.shape
        xs = self.x0 + self.step * np.arange(nx)
        ys = self.y0 + self.step * np.arange(ny)
        gx, gy = np.meshgrid(xs, ys, indexing="xy")
        return np.column_stack([gx.ravel(), gy.ravel()])

    def layer_height(self, layer) -> np.ndarray:
        """Height along the normal of (fractional) layer coordinates.

        Piecewise linear through the slice heights, so vertices on a slice
        layer land exactly on that slice's plane; padding layers continue the
        first and last gaps.
        """
        h = np.asarray(self.heights, dtype=np.float64)
        first = h[1] - h[0] if len(h) > 1 else 1.0
        last = h[-1] - h[-2] if len(h) > 1 else 1.0
        lay = np.concatenate([[0], 1 + self.k * np.arange(len(h)), [self.layers - 1]])
        hh = np.concatenate([[h[0] - first / self.k], h, [h[-1] + last / self.k]])
        return np.interp(np.asarray(layer, dtype=np.float64), lay, hh)


@dataclass(frozen=True)
class FamilyField:
    """One family's field, what fusing families needs of it.

    grid : FamilyGrid
    vol : (layers, ny, nx) float32 -- the field (positive inside).
    conf : (layers, ny, nx) float32 -- its confidence (:mod:`recon3d.surface.confidence`).
    planes : tuple of slicer.SlicePlane -- ascending offsets (``planes[0]`` is the frame).
    regions : tuple of SliceRegion -- the slices' regions, same order.
    """

    grid: FamilyGrid
    vol: np.ndarray
    conf: np.ndarray
    planes: tuple
    regions: tuple


def grid_step(eps: float, diagonal: float, lo: float = 1 / 400, hi: float = 1 / 100) -> float:
    """In-plane grid step: ``eps`` clipped to ``[lo, hi] x diagonal``.

    >>> grid_step(0.5, 100.0), grid_step(1e-3, 100.0), grid_step(9.0, 100.0)
    (0.5, 0.25, 1.0)
    """
    return float(np.clip(eps, lo * diagonal, hi * diagonal))


def family_grid(regions, heights, step: float) -> FamilyGrid:
    """Grid covering every region of a family, two steps of margin.

    Parameters
    ----------
    regions : list of SliceRegion -- one per slice, ascending heights.
    heights : (m,) float -- slice offsets along the normal, m >= 2.
    step : float -- in-plane spacing (see :func:`grid_step`).
    """
    heights = np.asarray(heights, dtype=np.float64)
    if len(heights) < 2:
        raise ValueError("a surface needs at least two slices per family")
    boxes = np.array([r.geometry.bounds for r in regions if not r.geometry.is_empty])
    if len(boxes) == 0:
        boxes = np.zeros((1, 4))
    lo = boxes[:, :2].min(axis=0) - 2 * step
    hi = boxes[:, 2:].max(axis=0) + 2 * step
    shape = tuple(int(n) for n in np.ceil((hi - lo) / step).astype(int) + 1)
    gaps = np.diff(heights)
    k = max(1, int(np.ceil(gaps.max() / step)))
    return FamilyGrid(float(lo[0]), float(lo[1]), float(step), shape, heights, k,
                      float(max(gaps.max(), 2 * step)))


def slice_sdf(region, grid: FamilyGrid) -> np.ndarray:
    """(nx * ny,) float32: signed distance to ``region``, positive inside.

    Distances come from the boundary sampled every step / 16 (error below
    step / 32 next to it), truncated at +-``grid.truncation``; values are
    kept at least 1e-3 step away from 0.
    """
    nodes = grid.nodes()
    t, s = grid.truncation, grid.step
    geom = region.geometry
    if geom.is_empty:
        return np.full(len(nodes), -t, dtype=np.float32)
    edge = shapely.get_coordinates(shapely.segmentize(geom.boundary, s / 16))
    d, _ = cKDTree(edge).query(nodes, distance_upper_bound=t)
    d = np.minimum(d, t)
    shapely.prepare(geom)
    inside = shapely.contains_xy(geom, nodes[:, 0], nodes[:, 1])
    d = np.maximum(d, _MIN_VALUE * s)
    return np.where(inside, d, -d).astype(np.float32)


def _neighbours_say(seen: list, f: list, f0: list, drops=()) -> list:
    """The slices' confidence maps, with the mean of the two neighbours' where
    :func:`recon3d.surface.caps.own_caps` changed a slice's own field (``f`` against ``f0``),
    and the run neighbours' (interpolated by height) where
    :func:`recon3d.surface.runs.run_caps` dropped a run's fill (``drops``): the value there is
    the neighbours' say, so is the trust."""
    out = list(seen)
    for i in range(1, len(f) - 1):
        if f[i] is not f0[i]:
            changed = f[i] != f0[i]
            mean = 0.5 * (seen[i - 1] + seen[i + 1])
            out[i] = np.where(changed, np.maximum(seen[i], mean), seen[i]).astype(np.float32)
    for d in drops:
        say = (1 - d.t) * seen[d.lo] + d.t * seen[d.hi]
        out[d.slice] = np.where(d.mask, np.maximum(out[d.slice], say),
                                out[d.slice]).astype(np.float32)
    return out


def _serial(first, second):
    """``(first(), second())`` in this process: :func:`family_volume`'s default ``pair``."""
    return first(), second()


def _slice_fields(regions, grid: FamilyGrid, lo: int, hi: int, warped: bool,
                  confidence: bool, trust: ConfidenceSettings, caps: CapSettings):
    """Slices ``lo .. hi - 1``: their own fields (ny, nx), their seen maps (or None) and the
    caps rule's decision for the gaps ``lo .. hi - 2`` between them (None where not warped)."""
    nx, ny = grid.shape
    f = [slice_sdf(r, grid).reshape(ny, nx) for r in regions[lo:hi]]
    seen = ([seen_map(r, fi, grid, trust) for r, fi in zip(regions[lo:hi], f)]
            if confidence else None)
    gaps = np.diff(grid.heights)
    capped = []
    for i in range(lo, hi - 1):
        t = _clip(float(gaps[i]), grid)
        capped.append(cap_unsensed(np.clip(f[i - lo], -t, t), np.clip(f[i + 1 - lo], -t, t),
                                   regions[i], regions[i + 1], grid, float(gaps[i]), caps)
                      if warped else None)
    return f, seen, capped


def _clip(gap: float, grid: FamilyGrid) -> np.float32:
    """A gap's truncation of the fields it blends: steps stay sharp."""
    return np.float32(max(gap, 2 * grid.step))


def _gap_layers(f: list, capped: list, seen, grid: FamilyGrid, lo: int, hi: int, warped: bool,
                warp: WarpSettings, trust: ConfidenceSettings, caps: CapSettings):
    """The layers of gaps ``lo .. hi - 1`` (each gap ``i`` from slice ``i``'s layer on, that
    layer included): ((hi - lo) k, ny, nx) float32 field and confidence (None without
    ``seen``). A gap's blend bends with its neighbours' moves, so those of gaps ``lo - 1``
    and ``hi`` are made too."""
    nx, ny = grid.shape
    w = np.arange(grid.k, dtype=np.float32) / grid.k
    w3 = w[:, None, None]
    gaps = np.diff(grid.heights)
    clip = [_clip(float(g), grid) for g in gaps]
    vol = np.empty(((hi - lo) * grid.k, ny, nx), dtype=np.float32)
    conf = np.empty(vol.shape, dtype=np.float32) if seen is not None else None
    held, moves = [None] * (len(f) - 1), [None] * (len(f) - 1)
    for i in range(max(lo - 1, 0), min(hi + 1, len(f) - 1)) if warped else ():
        t, cap = clip[i], capped[i]  # every gap's move the blends need, then the blends
        fa, fb = np.clip(f[i], -t, t), np.clip(f[i + 1], -t, t)
        held[i] = gap_steps(fa, fb, np.clip(f[i - 1], -t, t) if i > 0 else None,
                            np.clip(f[i + 2], -t, t) if i + 2 < len(f) else None,
                            grid.step, caps.step_tol) if caps.steps else None
        skip = cap.skip() if cap is not None else (None, None)
        if held[i] is not None:
            still = held[i].skip()
            skip = tuple(still if s is None else s | still for s in skip)
        end = warp if 0 < i < len(f) - 2 else replace(warp, reach=warp.end_reach)
        moves[i] = gap_displacement(fa, fb, grid, float(gaps[i]), end, *skip)
    for i in range(lo, hi):
        a = (i - lo) * grid.k
        gap, t, cap = float(gaps[i]), clip[i], capped[i]
        fa, fb = np.clip(f[i], -t, t), np.clip(f[i + 1], -t, t)
        if warped:
            steps, shift = held[i], None
            if warp.bend:  # the neighbouring gaps' moves, as if their gaps were this one's
                before = moves[i - 1] * (gap / gaps[i - 1]) if i > 0 else None
                after = moves[i + 1] * (gap / gaps[i + 1]) if i + 2 < len(f) else None
                shift = bend_shift(moves[i], before, after, w, warp.bend_cap * gap, grid)
            val, va, vb, move = warp_blend(fa, fb, grid, w, moves[i], shift)
            if steps is not None:  # a lid no neighbouring gap continues: a step at mid-gap
                val = steps.apply(val, fa, fb, w3)
            if cap is not None:
                val = cap.apply(val, w3)
        else:
            val = (1 - w3) * fa + w3 * fb
            va, vb, move = np.broadcast_to(fa, val.shape), np.broadcast_to(fb, val.shape), None
        vol[a:a + grid.k] = val
        vol[a] = f[i]
        if conf is not None:
            ag = agreement(va, vb, grid.step)
            if move is not None:  # an alignment that moves far is trusted less
                plaus = np.exp(-0.5 * (move / gap) ** 2)
                ag = ag * np.maximum(agreement(fa, fb, grid.step), plaus)
            if trust.cone:
                ag = cone(ag, va, vb, w3, gap)
            conf[a:a + grid.k] = between_confidence(seen[i], seen[i + 1], w3, ag, grid, gap,
                                                    trust)
    return vol, conf


def family_volume(regions, grid: FamilyGrid, route: str = "warp", confidence: bool = False,
                  warp: WarpSettings = WarpSettings(),
                  trust: ConfidenceSettings = ConfidenceSettings(),
                  caps: CapSettings = CapSettings(), pair: Callable | None = None
                  ) -> tuple[np.ndarray, np.ndarray | None]:
    """The field of a family and, optionally, its confidence (see module doc).

    Parameters
    ----------
    regions : list of SliceRegion -- one per slice, ascending heights.
    grid : FamilyGrid
    route : {'warp', 'linear'} -- aligned blend (:mod:`recon3d.surface.warp`) or the plain
        shape-based interpolation.
    confidence : bool -- also return the confidence (:mod:`recon3d.surface.confidence`).
    caps : CapSettings -- with the aligned blend, space a slice only closed (unknown chords,
        bridges) ends at that slice (:mod:`recon3d.surface.caps`).
    pair : callable(first, second) -> (first(), second()), optional -- how two halves of
        the work run: the slices' own fields and caps, then the gaps' layers, each split
        in two at the middle slice (a slice's or a gap's work depends on no other's, so
        the field is the same however they run; e.g. one half in a forked child). None:
        one after the other, here.

    Returns
    -------
    vol : (layers, ny, nx) float32 -- the field; on a slice layer the slice's own field.
    conf : (layers, ny, nx) float32 or None -- in (0, 1].
    """
    if route not in ROUTES:
        raise ValueError(f"unknown between-slice route {route!r}; expected one of {ROUTES}")
    pair = _serial if pair is None else pair
    nx, ny = grid.shape
    n, warped = len(regions), route == "warp" and grid.k > 1
    half = n // 2 if n >= _SPLIT else None
    fields = partial(_slice_fields, regions, grid, warped=warped, confidence=confidence,
                     trust=trust, caps=caps)
    if half is None:
        f, seen, capped = fields(0, n)
    else:  # slice ``half`` on both sides: the gap below it needs it
        low, high = pair(lambda: fields(0, half + 1), lambda: fields(half, n))
        f, capped = low[0][:half] + high[0], low[2] + high[2]
        seen = low[1][:half] + high[1] if confidence else None
    vol = np.full((grid.layers, ny, nx), -grid.truncation, dtype=np.float32)
    conf = np.full(vol.shape, 1e-3, dtype=np.float32) if confidence else None
    clip = [_clip(float(g), grid) for g in np.diff(grid.heights)]
    drops = []
    if warped:  # a fill closed on a run of slices ends at the run's empty neighbours
        f0 = f
        f, drops = run_caps(f, capped, regions, grid, clip, caps)
        if caps.own:
            f = own_caps(f, capped, grid.step)
        if confidence and caps.own_trust:  # where a slice drops (fills) what both neighbours
            seen = _neighbours_say(seen, f, f0, drops)  # showed empty (solid), they say
    layers = partial(_gap_layers, f, capped, seen, grid, warped=warped, warp=warp, trust=trust,
                     caps=caps)
    parts = ([layers(0, n - 1)] if half is None else
             pair(lambda: layers(0, half), lambda: layers(half, n - 1)))
    a = grid.slice_layer(0)
    for v, c in parts:
        vol[a:a + len(v)] = v
        if confidence:
            conf[a:a + len(v)] = c
        a += len(v)
    last = grid.slice_layer(len(f) - 1)
    vol[last] = f[-1]
    if confidence:
        conf[last] = seen[-1]
    for edge in (np.s_[:, 0], np.s_[:, -1], np.s_[:, :, 0], np.s_[:, :, -1]):
        vol[edge] = np.minimum(vol[edge], -grid.step)  # closed: a bend can reach the margin
    small = np.abs(vol) < _MIN_VALUE * grid.step  # interpolation can cross 0 exactly
    vol[small] = np.copysign(_MIN_VALUE * grid.step, vol[small])
    if confidence and trust.facing > 0:  # a family knows the walls its planes cut across
        share = np.maximum(in_plane_share(vol, grid), trust.facing_floor)
        conf *= share ** np.float32(trust.facing)
    return vol, conf
