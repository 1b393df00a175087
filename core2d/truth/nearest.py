"""Distance from points to their nearest segment, compiled, equal to GEOS's.

The ground-truth metrics (:mod:`core2d.truth.metrics`) measure every contour
sample against the detected W1 / W2 geometry and every piece of detected
geometry against the true contour. They used shapely's ``STRtree.query_nearest``
(one point geometry per sample, GEOS's ``DistanceOp``), whose distance from a
point to a line string is the minimum over its segments of GEOS's
``Distance::pointToSegment``. :func:`segment_distances` computes that very
minimum with the very float64 operations of ``pointToSegment`` (a minimum
does not depend on the order it is taken in), so the distances are
bit-identical (tested against shapely on real slices and random segments),
without the point geometries; a uniform grid of cells prunes the segments.
"""
from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["segment_distances", "polyline_segments"]


def polyline_segments(polylines) -> tuple[np.ndarray, np.ndarray]:
    """Consecutive vertex pairs of polylines with at least two vertices.

    Returns
    -------
    a, b : (n, 2) float -- segment starts and ends.
    """
    parts = [np.asarray(p, dtype=np.float64).reshape(-1, 2) for p in polylines]
    parts = [p for p in parts if len(p) >= 2]
    if not parts:
        return np.zeros((0, 2)), np.zeros((0, 2))
    return (np.concatenate([p[:-1] for p in parts]), np.concatenate([p[1:] for p in parts]))


def segment_distances(points, seg_a, seg_b) -> np.ndarray:
    """(m,) distance from each point to the nearest segment ``seg_a[i] -> seg_b[i]``.

    Parameters
    ----------
    points : (m, 2) float
    seg_a, seg_b : (n, 2) float -- a zero-length segment is a point.

    Returns
    -------
    (m,) float -- GEOS's point-to-line-string distance to the nearest segment
    (bit for bit); ``inf`` without segments.
    """
    p = np.ascontiguousarray(points, dtype=np.float64).reshape(-1, 2)
    a = np.ascontiguousarray(seg_a, dtype=np.float64).reshape(-1, 2)
    b = np.ascontiguousarray(seg_b, dtype=np.float64).reshape(-1, 2)
    out = np.full(len(p), np.inf)
    if len(p) == 0 or len(a) == 0:
        return out
    if np.isfinite(a).all() and np.isfinite(b).all():
        lo = np.minimum(a, b).min(axis=0)
        hi = np.maximum(a, b).max(axis=0)
        span = float(max((hi - lo).max(), 1e-300))
        h = span / max(1, min(512, int(math.sqrt(len(a)))))
        nx, ny = int((hi[0] - lo[0]) // h) + 1, int((hi[1] - lo[1]) // h) + 1
    else:  # one cell holds every segment: each point meets all of them
        lo, h, nx, ny = np.zeros(2), 1.0, 1, 1
    start, items = _grid(a, b, lo[0], lo[1], h, nx, ny)
    _query(p, a, b, lo[0], lo[1], h, nx, ny, start, items, out)
    return out


@numba.njit(cache=True, nogil=True)
def _point_segment(px, py, ax, ay, bx, by):  # pragma: no cover - compiled
    """GEOS ``Distance::pointToSegment``, operation for operation."""
    if ax == bx and ay == by:
        dx, dy = px - ax, py - ay
        return math.sqrt(dx * dx + dy * dy)
    len2 = (bx - ax) * (bx - ax) + (by - ay) * (by - ay)
    r = ((px - ax) * (bx - ax) + (py - ay) * (by - ay)) / len2
    if r <= 0.0:
        dx, dy = px - ax, py - ay
        return math.sqrt(dx * dx + dy * dy)
    if r >= 1.0:
        dx, dy = px - bx, py - by
        return math.sqrt(dx * dx + dy * dy)
    s = ((ay - py) * (bx - ax) - (ax - px) * (by - ay)) / len2
    return abs(s) * math.sqrt(len2)


@numba.njit(cache=True, nogil=True)
def _cells(x, x0, h, n):  # pragma: no cover - compiled
    """Cell index of coordinate ``x``, clamped to ``[0, n)``."""
    k = int(math.floor((x - x0) / h))
    return min(max(k, 0), n - 1)


@numba.njit(cache=True, nogil=True)
def _box(a, b, j, x0, y0, h, nx, ny):  # pragma: no cover - compiled
    """Cell ranges ``(i0, i1, k0, k1)`` of segment j's bounding box, one cell wider on
    every side (so a rounded cell index never loses a segment)."""
    i0 = max(_cells(min(a[j, 0], b[j, 0]), x0, h, nx) - 1, 0)
    i1 = min(_cells(max(a[j, 0], b[j, 0]), x0, h, nx) + 1, nx - 1)
    k0 = max(_cells(min(a[j, 1], b[j, 1]), y0, h, ny) - 1, 0)
    k1 = min(_cells(max(a[j, 1], b[j, 1]), y0, h, ny) + 1, ny - 1)
    return i0, i1, k0, k1


@numba.njit(cache=True, nogil=True)
def _grid(a, b, x0, y0, h, nx, ny):  # pragma: no cover - compiled
    """The segments of each cell (:func:`_box`): CSR ``start`` (nx * ny + 1), ``items``."""
    count = np.zeros(nx * ny + 1, np.int64)
    for j in range(a.shape[0]):
        i0, i1, k0, k1 = _box(a, b, j, x0, y0, h, nx, ny)
        for i in range(i0, i1 + 1):
            for k in range(k0, k1 + 1):
                count[i * ny + k + 1] += 1
    start = np.cumsum(count)
    fill = start[:-1].copy()
    items = np.empty(start[-1], np.int64)
    for j in range(a.shape[0]):
        i0, i1, k0, k1 = _box(a, b, j, x0, y0, h, nx, ny)
        for i in range(i0, i1 + 1):
            for k in range(k0, k1 + 1):
                items[fill[i * ny + k]] = j
                fill[i * ny + k] += 1
    return start, items


@numba.njit(cache=True, nogil=True)
def _query(p, a, b, x0, y0, h, nx, ny, start, items, out):  # pragma: no cover - compiled
    """Nearest-segment distance per point, ring of cells by ring of cells.

    Every segment was put in the cells of its bounding box widened by one cell, so
    after the rings 0 .. r round a point's cell (clamped into the grid), every
    segment not yet seen has its box at least ``r + 2`` cells away, farther than
    ``(r + 1) * h`` from the point (a rounded cell index is off by at most one): the
    search stops once the best distance is below ``(r + 0.5) * h``."""
    limit = max(nx, ny)
    for i in range(p.shape[0]):
        px, py = p[i, 0], p[i, 1]
        ci, ck = _cells(px, x0, h, nx), _cells(py, y0, h, ny)
        best = np.inf
        r = 0
        while True:
            for di in range(-r, r + 1):
                ii = ci + di
                if ii < 0 or ii >= nx:
                    continue
                edge = di == -r or di == r
                step = 1 if edge else 2 * r
                for dk in range(-r, r + 1, max(step, 1)):
                    kk = ck + dk
                    if kk < 0 or kk >= ny:
                        continue
                    c = ii * ny + kk
                    for q in range(start[c], start[c + 1]):
                        j = items[q]
                        d = _point_segment(px, py, a[j, 0], a[j, 1], b[j, 0], b[j, 1])
                        if d < best:
                            best = d
            if best < (r + 0.5) * h or r > limit:
                break
            r += 1
        out[i] = best
