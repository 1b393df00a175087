"""Between-slice interpolation with correspondence (shape-based interpolation, aligned).

Plain shape-based interpolation (Herman et al. 1992, :func:`recon3d.surface.field.family_volume`)
blends the 2D signed distances of two neighbouring slices at the *same* in-plane point:
``(1 - w) f_i(x) + w f_{i+1}(x)``. A wall thinner than the distance it moves from one slice to
the next then breaks into fins (neither slice is inside at any point between them). The warp
aligns the two slices first:

1. **boundary samples** -- the zero crossings of each slice's field on the grid edges, with
   outward unit normals (minus the field's gradient);
2. **matches** -- every sample of slice ``i`` is matched to the nearest sample of slice
   ``i+1`` in (position, ``gap`` x normal) space, kept when the normals agree
   (cos > ``min_cos``) and the move is at most ``reach`` x gap; and back from ``i+1`` to ``i``;
3. **displacement field** ``d(x)`` -- the Gaussian-weighted mean of the matched moves placed
   at the pairs' midpoints (sigma = ``sigma`` x gap, at least two grid steps), fading to 0 far
   from every pair (there the warp is the plain blend);
4. **warped blend** at fraction ``w`` of the gap:
   ``(1 - w) f_i(x - w d(x)) + w f_{i+1}(x + (1 - w) d(x))``.

A thin tilted wall then moves as a wall, a ring stays a ring. On a slice layer the field is
the slice's own 2D signed distance, so labels and slice curves are unchanged.

5. **bend** (:func:`bend_shift`) -- with the moves of the neighbouring gaps, a boundary point
   follows a Catmull-Rom curve through four slices instead of the straight line between two:
   both samples are shifted by ``t (1 - t) / 2 ((1 - t)(d_{i-1} - d_i) - t (d_{i+1} - d_i))``
   (``t`` = ``w``; at an end gap the missing move is the parabola's through three slices,
   ``d_{-1} = 2 d_0 - d_1``). The neighbouring moves are read where the boundary point was
   and will be: ``d_{i-1}`` half a move before slice ``i``, ``d_{i+1}`` half a move after
   slice ``i + 1`` (a blob that moves farther than its size per gap takes its own moves,
   not the empty space it left). A curved wall that grazes the planes (a cup's side between two
   planes that cut it near its widest) bulges as it does instead of running as a chord; where
   the moves agree (a straight tilted wall, a prism) the shift is 0.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.ndimage import gaussian_filter, map_coordinates
from scipy.spatial import cKDTree

__all__ = ["WarpSettings", "boundary_samples", "match_boundaries", "displacement_field",
           "sample_field", "gap_displacement", "bend_shift", "warp_blend", "warp_gap"]


@dataclass(frozen=True)
class WarpSettings:
    """Parameters of the aligned interpolation (measured in ``bench/bench_surface.py``).

    reach : float -- largest in-plane move matched between two slices, times the gap.
    sigma : float -- spread of the displacement field, times the gap (>= 2 grid steps).
    min_cos : float -- least cosine between the normals of matched boundary samples.
    fade : float -- weight below which the displacement fades to 0 (no pair near).
    end_reach : float -- ``reach`` in the first and last gap.
    bend : bool -- follow the neighbouring gaps' moves (step 5 of the module doc).
    bend_cap : float -- largest bend, times the gap.
    """

    reach: float = 4.0
    sigma: float = 0.5
    min_cos: float = 0.5
    fade: float = 0.05
    end_reach: float = 12.0
    bend: bool = True
    bend_cap: float = 0.5


def boundary_samples(f: np.ndarray, x0: float, y0: float, step: float
                     ) -> tuple[np.ndarray, np.ndarray]:
    """Zero crossings of a slice field with outward unit normals.

    Parameters
    ----------
    f : (ny, nx) float -- signed distance, positive inside.
    x0, y0, step : float -- frame coordinates of node (0, 0) and the node spacing.

    Returns
    -------
    points : (m, 2) float -- one per grid edge the field changes sign on (linear position).
    normals : (m, 2) float -- outward unit normals (minus the bilinear gradient).
    """
    pts = []
    for axis in (0, 1):
        a = f[:-1, :] if axis == 0 else f[:, :-1]
        c = f[1:, :] if axis == 0 else f[:, 1:]
        iy, ix = np.nonzero((a > 0) != (c > 0))
        t = a[iy, ix] / (a[iy, ix] - c[iy, ix])
        fy, fx = (iy + t, ix.astype(float)) if axis == 0 else (iy.astype(float), ix + t)
        pts.append(np.column_stack([fx, fy]))
    g = np.concatenate(pts)
    if len(g) == 0:
        return np.zeros((0, 2)), np.zeros((0, 2))
    gy, gx = np.gradient(f.astype(np.float64))
    n = -np.column_stack([map_coordinates(gx, [g[:, 1], g[:, 0]], order=1, mode="nearest"),
                          map_coordinates(gy, [g[:, 1], g[:, 0]], order=1, mode="nearest")])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-12)
    return np.column_stack([x0 + g[:, 0] * step, y0 + g[:, 1] * step]), n


def match_boundaries(pa, na, pb, nb, reach: float, weight: float, min_cos: float = 0.5
                     ) -> tuple[np.ndarray, np.ndarray]:
    """Normal-compatible nearest matches from boundary A to boundary B.

    Parameters
    ----------
    pa, na : (m, 2) float -- points and unit normals of A; pb, nb : (k, 2) float -- of B.
    reach : float -- largest accepted move.
    weight : float -- the normals' weight in the 4D distance ``|dp|^2 + weight^2 |dn|^2``.
    min_cos : float -- least cosine between matched normals.

    Returns
    -------
    ia, ib : (j,) int -- matched indices into A and B.
    """
    if len(pa) == 0 or len(pb) == 0:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    _, ib = cKDTree(np.column_stack([pb, weight * nb])).query(np.column_stack([pa, weight * na]))
    ok = ((na * nb[ib]).sum(axis=1) > min_cos) & (np.linalg.norm(pb[ib] - pa, axis=1) <= reach)
    return np.flatnonzero(ok), ib[ok]


def displacement_field(src, dst, grid, sigma: float, fade: float = 0.05) -> np.ndarray:
    """(ny, nx, 2) move from slice ``i`` to slice ``i+1``, spread over the grid.

    Gaussian-weighted mean of the moves ``dst - src`` placed at the pairs' midpoints
    (splatted on the nearest node, smoothed by :func:`scipy.ndimage.gaussian_filter`),
    ``sum w d / (sum w + fade)``: it fades to 0 farther than ~3 sigma from every pair.

    Parameters
    ----------
    src, dst : (j, 2) float -- matched points of the two slices (frame coordinates).
    grid : FamilyGrid
    sigma : float -- Gaussian spread (frame units).
    """
    nx, ny = grid.shape
    if len(src) == 0:
        return np.zeros((ny, nx, 2))
    mid = 0.5 * (src + dst)
    ix = np.clip(np.rint((mid[:, 0] - grid.x0) / grid.step).astype(np.int64), 0, nx - 1)
    iy = np.clip(np.rint((mid[:, 1] - grid.y0) / grid.step).astype(np.int64), 0, ny - 1)
    flat = iy * nx + ix
    s = sigma / grid.step
    scale = 2 * np.pi * s * s  # unnormalised Gaussian: a lone pair weighs 1 at its node
    den = gaussian_filter(np.bincount(flat, minlength=nx * ny).reshape(ny, nx).astype(float),
                          s, truncate=3.0) * scale
    out = np.empty((ny, nx, 2))
    d = dst - src
    for c in (0, 1):
        num = np.bincount(flat, weights=d[:, c], minlength=nx * ny).reshape(ny, nx)
        out[..., c] = gaussian_filter(num, s, truncate=3.0) * scale / (den + fade)
    return out


def sample_field(f: np.ndarray, grid, xy: np.ndarray) -> np.ndarray:
    """Bilinear samples of a (ny, nx) slice field at frame points ``xy`` (..., 2)."""
    gx = (xy[..., 0] - grid.x0) / grid.step
    gy = (xy[..., 1] - grid.y0) / grid.step
    return map_coordinates(f, [gy.ravel(), gx.ravel()], order=1,
                           mode="nearest").reshape(gx.shape)


def _kept(p, n, grid, skip):
    """Boundary samples ``p``, ``n`` (m, 2) whose nearest node is not in ``skip``."""
    if skip is None or len(p) == 0:
        return p, n
    ix = np.clip(np.rint((p[:, 0] - grid.x0) / grid.step).astype(np.int64), 0, skip.shape[1] - 1)
    iy = np.clip(np.rint((p[:, 1] - grid.y0) / grid.step).astype(np.int64), 0, skip.shape[0] - 1)
    keep = ~skip[iy, ix]
    return p[keep], n[keep]


def gap_displacement(fa: np.ndarray, fb: np.ndarray, grid, gap: float,
                     settings: WarpSettings = WarpSettings(), skip_a: np.ndarray | None = None,
                     skip_b: np.ndarray | None = None) -> np.ndarray:
    """(ny, nx, 2) move from slice ``i`` to ``i + 1`` (module doc, steps 1-3).

    fa, fb : (ny, nx) float32 -- the two slices' fields, truncated.
    skip_a, skip_b : (ny, nx) bool, optional -- nodes whose boundary samples are not matched
        (:meth:`recon3d.surface.caps.GapCaps.skip`).
    """
    pa, na = _kept(*boundary_samples(fa, grid.x0, grid.y0, grid.step), grid, skip_a)
    pb, nb = _kept(*boundary_samples(fb, grid.x0, grid.y0, grid.step), grid, skip_b)
    reach = settings.reach * gap
    ia, ib = match_boundaries(pa, na, pb, nb, reach, gap, settings.min_cos)
    jb, ja = match_boundaries(pb, nb, pa, na, reach, gap, settings.min_cos)
    src = np.concatenate([pa[ia], pa[ja]])
    dst = np.concatenate([pb[ib], pb[jb]])
    return displacement_field(src, dst, grid, max(2 * grid.step, settings.sigma * gap),
                              settings.fade)


def _moved(field: np.ndarray, grid, xy: np.ndarray) -> np.ndarray:
    """Bilinear samples of a (ny, nx, 2) move field at frame points ``xy`` (..., 2)."""
    return np.stack([sample_field(field[..., c], grid, xy) for c in (0, 1)], axis=-1)


def bend_shift(d: np.ndarray, before: np.ndarray | None, after: np.ndarray | None,
               w: np.ndarray, cap: float, grid=None) -> np.ndarray | None:
    """(k, ny, nx, 2) shift of the boundary at fractions ``w`` of a gap (module doc, step 5).

    Parameters
    ----------
    d : (ny, nx, 2) float -- this gap's move.
    before, after : (ny, nx, 2) float or None -- the neighbouring gaps' moves, scaled to this
        gap's length (None: an end; both None: no bend).
    w : (k,) float -- fractions of the gap.
    cap : float -- largest shift length (frame units).
    grid : FamilyGrid, optional -- read ``before`` and ``after`` along the move (module doc);
        None: at the same node.

    Examples
    --------
    >>> d = np.ones((1, 1, 2))
    >>> bend_shift(d, d, d, np.array([0.0, 0.5]), 1.0).ravel().tolist()  # moves agree: none
    [0.0, 0.0, 0.0, 0.0]
    >>> # at rest, then 1 per gap: the parabola through 0, 0, 1 (3 after) is 3/8 at mid-gap
    >>> float(bend_shift(d, 0 * d, None, np.array([0.5]), 1.0)[0, 0, 0, 0])
    -0.125
    """
    if before is None and after is None:
        return None
    t = np.asarray(w, dtype=np.float64)[:, None, None, None]
    if grid is not None:  # where the boundary point was half a move before, and will be after
        nx, ny = grid.shape
        nodes = grid.nodes().reshape(ny, nx, 2)[None]
        before = None if before is None else _moved(before, grid, nodes - (t + 0.5) * d[None])
        after = None if after is None else _moved(after, grid, nodes + (1.5 - t) * d[None])
    else:
        before = None if before is None else before[None]
        after = None if after is None else after[None]
    before = 2 * d[None] - after if before is None else before
    after = 2 * d[None] - before if after is None else after
    shift = 0.5 * t * (1 - t) * ((1 - t) * (before - d[None]) - t * (after - d[None]))
    size = np.linalg.norm(shift, axis=-1, keepdims=True)
    return shift * np.minimum(1.0, cap / np.maximum(size, 1e-300))


def warp_blend(fa: np.ndarray, fb: np.ndarray, grid, w: np.ndarray, d: np.ndarray,
               shift: np.ndarray | None = None
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The warped blend at fractions ``w`` (module doc, step 4), bent by ``shift``
    ((k, ny, nx, 2) from :func:`bend_shift`, or None).

    Returns
    -------
    vol : (k, ny, nx) float32 -- the warped blend.
    va, vb : (k, ny, nx) float32 -- the two slices' fields sampled along the move.
    move : (ny, nx) float -- length of the displacement.
    """
    nx, ny = grid.shape
    nodes = grid.nodes().reshape(ny, nx, 2)[None]
    ww = np.asarray(w, dtype=np.float64)[:, None, None, None]
    if shift is not None:
        nodes = nodes - shift
    va = sample_field(fa, grid, nodes - ww * d[None]).astype(np.float32)
    vb = sample_field(fb, grid, nodes + (1 - ww) * d[None]).astype(np.float32)
    wf = ww[..., 0].astype(np.float32)
    return (1 - wf) * va + wf * vb, va, vb, np.linalg.norm(d, axis=2)


def warp_gap(fa: np.ndarray, fb: np.ndarray, grid, gap: float, w: np.ndarray,
             settings: WarpSettings = WarpSettings(), skip_a: np.ndarray | None = None,
             skip_b: np.ndarray | None = None
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The aligned blend of two neighbouring slice fields (module doc, steps 1-4; no bend:
    that needs the neighbouring gaps, :func:`recon3d.surface.field.family_volume`).

    Parameters
    ----------
    fa, fb : (ny, nx) float32 -- slice ``i`` and ``i+1`` fields, truncated.
    grid : FamilyGrid
    gap : float -- distance between the two planes.
    w : (k,) float -- fractions of the gap of the layers to fill (0 = slice ``i``).
    skip_a, skip_b : (ny, nx) bool, optional -- nodes whose boundary samples are not matched
        (:meth:`recon3d.surface.caps.GapCaps.skip`).

    Returns
    -------
    vol, va, vb, move -- as :func:`warp_blend`.
    """
    d = gap_displacement(fa, fb, grid, gap, settings, skip_a, skip_b)
    return warp_blend(fa, fb, grid, w, d)
