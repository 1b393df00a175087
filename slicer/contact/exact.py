"""Exact 2D contact backend: rays against the reference contour's segments.

Pure numpy segment intersection in float64 (segments outside the bounding
box of a batch's finite rays are culled first). It has the same ``cast``
interface as the two mesh backends, Embree (:mod:`slicer.contact.embree`)
and trimesh (:mod:`slicer.contact.trimesh_ray`), see
:mod:`core2d.sim.contact`, and is the reference for tests and for the
stability study; the planner never sees the contour itself.
"""
from __future__ import annotations

import numpy as np

__all__ = ["ExactContact", "loops_to_segments"]

_CHUNK = 2_000_000  # rays x segments evaluated per numpy pass
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
        ends = self.starts + self.edges
        self._lo = np.minimum(self.starts, ends)
        self._hi = np.maximum(self.starts, ends)

    def _culled(self, o, d, max_dist):
        """Segments whose bounding box meets the rays' bounding box."""
        if not np.all(np.isfinite(max_dist)):
            return self.starts, self.edges
        ends = o + max_dist[:, None] * d
        lo = np.minimum(o, ends).min(axis=0)
        hi = np.maximum(o, ends).max(axis=0)
        keep = np.all((self._hi >= lo) & (self._lo <= hi), axis=1)
        return self.starts[keep], self.edges[keep]

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
        origins = np.atleast_2d(np.asarray(origins, dtype=np.float64))
        dirs = np.atleast_2d(np.asarray(dirs, dtype=np.float64))
        n = len(origins)
        max_dist = np.broadcast_to(np.asarray(max_dist, dtype=np.float64), (n,))
        dist = np.full(n, np.inf)
        seg = np.full(n, -1, dtype=np.int64)
        starts, edges = self._culled(origins, dirs, max_dist) if n else (self.starts, self.edges)
        m = len(starts)
        if m and n:
            step = max(1, _CHUNK // m)
            for lo in range(0, n, step):
                hi = min(n, lo + step)
                dist[lo:hi], seg[lo:hi] = self._first_hits(
                    starts, edges, origins[lo:hi], dirs[lo:hi], max_dist[lo:hi]
                )
        hit = np.isfinite(dist)
        points = np.full((n, 2), np.nan)
        normals = np.full((n, 2), np.nan)
        points[hit] = origins[hit] + dist[hit, None] * dirs[hit]
        e = edges[seg[hit]]
        nrm = np.stack([-e[:, 1], e[:, 0]], axis=1)
        nrm /= np.linalg.norm(nrm, axis=1, keepdims=True)
        flip = np.einsum("ij,ij->i", nrm, dirs[hit]) > 0
        nrm[flip] *= -1
        nrm += 0.0  # no negative zeros
        normals[hit] = nrm
        return dist, points, normals

    @staticmethod
    def _first_hits(starts, edges, o, d, max_dist):
        """Nearest hit distance (n,) and segment index (n,) of rays (n, 2)
        against segments (m, 2); ``inf`` and 0 where nothing is hit."""
        p, e = starts[None, :, :], edges[None, :, :]
        w = p - o[:, None, :]
        denom = d[:, None, 0] * e[..., 1] - d[:, None, 1] * e[..., 0]
        with np.errstate(divide="ignore", invalid="ignore"):
            s = (w[..., 0] * e[..., 1] - w[..., 1] * e[..., 0]) / denom
            r = (w[..., 0] * d[:, None, 1] - w[..., 1] * d[:, None, 0]) / denom
        ok = (denom != 0) & (s >= 0) & (r >= -_SLACK) & (r <= 1 + _SLACK) & (s <= max_dist[:, None])
        s = np.where(ok, s, np.inf)
        seg = np.argmin(s, axis=1)
        return s[np.arange(len(o)), seg], seg
