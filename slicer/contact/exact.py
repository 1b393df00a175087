"""Exact 2D contact backend: rays against the reference contour's segments.

Segment intersection in float64, every ray against every segment, compiled
(numba): each ray-segment pair computes ``w = p - o``, ``denom = d x e``,
``s = (w x e) / denom`` and ``r = (w x d) / denom`` in that order, as a numpy
expression would (tested to the bit), and the least admissible s wins. A
ray's answer depends on that ray alone, never on the batch it came in, so
the backend also offers the probe simulator a *ray function*
(:attr:`ExactContact.ray_kernel`, the contract of
:mod:`slicer.contact.embree_direct`): the simulator's compiled engine
(:mod:`core2d.sim.kernels`) resolves contacts on it ray by ray, with the
answers of ``cast`` (tested: the same runs as through the Python engine).

It has the same ``cast`` interface as the two mesh backends, Embree
(:mod:`slicer.contact.embree`) and trimesh (:mod:`slicer.contact.trimesh_ray`),
see :mod:`core2d.sim.contact`, and is the reference for tests and for the
stability study; the planner never sees the contour itself.
"""
from __future__ import annotations

import functools

import numba
import numpy as np
from numba import types

__all__ = ["ExactContact", "loops_to_segments"]

_SLACK = 1e-12
"""Segments are closed with this slack on the segment parameter, so a ray
through a shared vertex hits one of the two segments despite rounding."""


def loops_to_segments(loops) -> tuple[np.ndarray, np.ndarray]:
    """Closed loops -> segment start points and edge vectors.

    Parameters
    ----------
    loops : list of (k, 2) float
        Closed polygon loops (last vertex not repeated).

    Returns
    -------
    starts : (m, 2) float
    edges : (m, 2) float
    """
    starts, edges = [], []
    for loop in loops:
        p = np.asarray(loop, dtype=np.float64)
        if len(p) < 2:
            continue
        q = np.roll(p, -1, axis=0)
        starts.append(p)
        edges.append(q - p)
    if not starts:
        return np.zeros((0, 2)), np.zeros((0, 2))
    return np.concatenate(starts), np.concatenate(edges)


class ExactContact:
    """Ray casting against closed 2D loops.

    Parameters
    ----------
    loops : list of (k, 2) float
        The contour, e.g. a slice's reference loops.
    chains : list of (k, 2) float, optional
        Open polylines (not closed), e.g. a non-watertight slice's open chains.

    Examples
    --------
    >>> square = [np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)]
    >>> d, p, n = ExactContact(square).cast(np.array([[-1, 0.5]]), np.array([[1, 0]]), 5.0)
    >>> float(d[0]), p[0].tolist(), n[0].tolist()
    (1.0, [0.0, 0.5], [-1.0, 0.0])
    """

    def __init__(self, loops, chains=()):
        starts, edges = loops_to_segments(loops)
        for chain in chains:
            c = np.asarray(chain, dtype=np.float64)
            if len(c) >= 2:
                starts = np.concatenate([starts, c[:-1]])
                edges = np.concatenate([edges, c[1:] - c[:-1]])
        lengths = np.hypot(edges[:, 0], edges[:, 1])
        keep = lengths > 0
        self.starts, self.edges = starts[keep], edges[keep]
        nrm = np.stack([-self.edges[:, 1], self.edges[:, 0]], axis=1)
        self._normals = nrm / np.linalg.norm(nrm, axis=1, keepdims=True)  # turned left, unit
        # the ray function's context: the segment count, then (start x, y, edge x, y) rows
        self._context = np.concatenate([[float(len(self.starts))],
                                        np.hstack([self.starts, self.edges]).reshape(-1)])
        self._table = self._context[1:].reshape(-1, 4)

    @property
    def ray_kernel(self):
        """``(address, context)`` of the one-ray function ``ray(ctx, ox, oy, dx, dy,
        max_dist, out)`` writing ``out[:3] = distance, x, y`` (``inf, nan, nan`` for a miss),
        the answer :meth:`cast` gives that ray; None when there is no segment."""
        if not len(self.starts):
            return None
        return _ray_function(), self._context

    def cast(self, origins, dirs, max_dist):
        """First contour hit of each ray; see :mod:`core2d.sim.contact`.

        Parameters
        ----------
        origins, dirs : (n, 2) float
            Ray origins and directions.
        max_dist : (n,) float or float

        Returns
        -------
        distances : (n,) float
            ``inf`` where no segment is hit within ``max_dist``.
        points : (n, 2) float
        normals : (n, 2) float
            Unit, oriented against the rays; both ``nan`` on a miss.
        """
        origins = np.ascontiguousarray(origins, dtype=np.float64).reshape(-1, 2)
        dirs = np.ascontiguousarray(dirs, dtype=np.float64).reshape(-1, 2)
        n = len(origins)
        max_dist = np.ascontiguousarray(max_dist, dtype=np.float64).reshape(-1)
        if len(max_dist) != n and len(max_dist) != 1:
            raise ValueError(f"max_dist holds {len(max_dist)} values for {n} rays")
        return _cast(origins, dirs, max_dist, self._table, self._normals)


@numba.njit(cache=True, nogil=True, inline="always")
def _first_hit(table, ox, oy, dx, dy, max_dist):  # pragma: no cover - compiled
    """``(s, k)``: the least admissible ray parameter and its segment, the first on a tie
    (numpy's ``argmin``); ``(inf, -1)`` when none. Segment k = ``table[k]`` (start x, y,
    edge x, y), closed with ``_SLACK`` on its parameter r."""
    best, seg = np.inf, -1
    for k in range(table.shape[0]):
        ex, ey = table[k, 2], table[k, 3]
        denom = dx * ey - dy * ex
        if denom == 0:
            continue
        wx, wy = table[k, 0] - ox, table[k, 1] - oy
        s = (wx * ey - wy * ex) / denom
        r = (wx * dy - wy * dx) / denom
        if s >= 0 and r >= -_SLACK and r <= 1 + _SLACK and s <= max_dist and s < best:
            best, seg = s, k
    return best, seg


@numba.njit(cache=True, nogil=True)
def _cast(o, d, max_dists, table, unit_normals):  # pragma: no cover - compiled
    """``dist`` (n,), ``points`` and ``normals`` (n, 2) of the rays' first hits (``inf``,
    ``nan`` on a miss); ``max_dists`` (n,), or (1,) for every ray. The normal is the hit
    segment's unit normal turned against the ray (no negative zero)."""
    n = o.shape[0]
    dist = np.full(n, np.inf)
    points = np.full((n, 2), np.nan)
    normals = np.full((n, 2), np.nan)
    for i in range(n):
        md = max_dists[i] if max_dists.shape[0] == n else max_dists[0]
        ox, oy, dx, dy = o[i, 0], o[i, 1], d[i, 0], d[i, 1]
        s, k = _first_hit(table, ox, oy, dx, dy, md)
        if k < 0:
            continue
        dist[i] = s
        points[i, 0] = ox + s * dx
        points[i, 1] = oy + s * dy
        nx, ny = unit_normals[k, 0], unit_normals[k, 1]
        if nx * dx + ny * dy > 0:
            nx, ny = -nx, -ny
        normals[i, 0] = nx + 0.0
        normals[i, 1] = ny + 0.0
    return dist, points, normals


def _ray(ctx, ox, oy, dx, dy, max_dist, out):  # pragma: no cover - compiled
    """The ray function (see :attr:`ExactContact.ray_kernel`)."""
    m = int(numba.carray(ctx, 1, np.float64)[0])
    table = numba.carray(ctx, 1 + 4 * m, np.float64)[1:].reshape((m, 4))
    s, k = _first_hit(table, ox, oy, dx, dy, max_dist)
    if k < 0:
        out[0], out[1], out[2] = np.inf, np.nan, np.nan
    else:
        out[0], out[1], out[2] = s, ox + s * dx, oy + s * dy


_SIGNATURE = types.void(types.voidptr, types.float64, types.float64, types.float64,
                        types.float64, types.float64, types.CPointer(types.float64))


@functools.lru_cache(maxsize=1)
def _ray_function() -> int:
    """Address of the compiled ray function (compiled, or loaded from numba's cache, once
    per process)."""
    return numba.cfunc(_SIGNATURE, nopython=True, cache=True, nogil=True)(_ray).address
