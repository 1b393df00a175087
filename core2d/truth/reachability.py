"""Exact reachable set of a closed 2D contour for a rod coming from outside.

DESIGN.md "The 2D problem on a closed cross-section": a contour point ``p``
is *reachable* when some ray from ``p`` to infinity, in the plane, crosses no
contour edge. A probe of length >= 2 x the slice diameter then has its joint
in the free area F (outside the convex hull), so this is exactly the set a
rigid rod from F can touch with its tip.

The test is done with angular intervals, not sampled directions: seen from
``p`` every edge not containing ``p`` blocks the *closed* arc of directions it
subtends (an edge always subtends less than pi). At a point interior to an
edge only the open half-plane of directions on the edge's outward side can be
free, so the arcs are clipped to that half-plane, which also removes the
+-pi branch cut (the cut lies in the blocked material half-plane). At a
vertex the whole circle is used and arcs crossing the cut are split in two.
``p`` is reachable iff the union of blocked arcs leaves an open gap wider
than ``angle_tol`` (default 1e-9 rad): touching counts as blocking, so a ray
that only grazes a vertex, and any measure-zero set of free directions, is
treated as blocked.

Conventions: ``loops`` is a list of (k, 2) arrays, closed implicitly, outer
loops counter-clockwise and holes clockwise (shapely), so the material is on
the *left* of every edge. Edges are numbered globally: edge ``offset[l] + i``
of loop ``l`` runs from vertex ``i`` to vertex ``i + 1``.

Examples
--------
>>> sq = [np.array([[0., 0.], [1., 0.], [1., 1.], [0., 1.]])]
>>> samples, ok = reachable_samples(sq, 0.25)
>>> bool(ok.all()), samples.points.shape
(True, (16, 2))
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from core2d.visibility import free_gaps

from .free_ray import HALF_ANGLE, normal_cone_free

__all__ = [
    "ContourSamples",
    "as_loops",
    "contour_edges",
    "loop_is_hole",
    "subdivide",
    "sample_contour",
    "free_angle",
    "reachable",
    "reachable_samples",
]

#: pairs (points x edges) per chunk; ~15 float64 temporaries of this size
_CHUNK = 500_000
#: points per chunk
_MAX_ROWS = 4096
#: smallest ``angle_tol`` for which hole samples are decided without arcs (:func:`_sealed`)
SEALED_TOL = 1e-9


@dataclass(frozen=True, eq=False)
class ContourSamples:
    """Midpoints of sub-segments of a contour, each no longer than ``spacing``.

    points : (m, 2) float -- sample points (sub-segment midpoints).
    lengths : (m,) float -- length of contour each sample stands for.
    loop : (m,) int -- loop index.
    edge : (m,) int -- global edge index (see :func:`contour_edges`).
    s : (m,) float -- arc length of the sample along its loop, measured from
        vertex 0 in stored vertex order (CCW for outer loops, CW for holes).
    is_hole : (m,) bool -- sample lies on a hole (clockwise) loop.
    loop_lengths : (L,) float -- perimeter of every loop.
    """

    points: np.ndarray
    lengths: np.ndarray
    loop: np.ndarray
    edge: np.ndarray
    s: np.ndarray
    is_hole: np.ndarray
    loop_lengths: np.ndarray


def as_loops(loops) -> list[np.ndarray]:
    """Loops as float64 (k, 2) arrays; a repeated closing vertex is dropped."""
    out = []
    for lp in loops:
        lp = np.asarray(lp, dtype=np.float64).reshape(-1, 2)
        if len(lp) > 3 and np.array_equal(lp[0], lp[-1]):
            lp = lp[:-1]
        out.append(lp)
    return out


def contour_edges(loops) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """All edges of all loops.

    Returns
    -------
    a, b : (n, 2) float -- edge start and end points.
    loop : (n,) int -- loop index of every edge.
    """
    loops = as_loops(loops)
    if not loops:
        z = np.zeros((0, 2))
        return z, z.copy(), np.zeros(0, dtype=np.int64)
    a = np.concatenate(loops)
    b = np.concatenate([np.roll(lp, -1, axis=0) for lp in loops])
    loop = np.repeat(np.arange(len(loops)), [len(lp) for lp in loops])
    return a, b, loop


def loop_is_hole(loops) -> np.ndarray:
    """(L,) bool: the loop is clockwise (negative shoelace area), i.e. a hole."""
    out = []
    for lp in as_loops(loops):
        x, y = lp[:, 0], lp[:, 1]
        out.append(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)) < 0)
    return np.array(out, dtype=bool)


def subdivide(a, b, spacing) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Split segments ``a[i] -> b[i]`` into equal pieces no longer than ``spacing``.

    Zero-length segments give no piece.

    Returns
    -------
    seg : (m,) int -- segment index of every piece.
    frac : (m,) float -- position of the piece midpoint along its segment, in (0, 1).
    lengths : (m,) float -- piece lengths.
    """
    if spacing <= 0:
        raise ValueError("spacing must be positive")
    a = np.asarray(a, dtype=np.float64).reshape(-1, 2)
    b = np.asarray(b, dtype=np.float64).reshape(-1, 2)
    elen = np.hypot(*(b - a).T)
    k = np.where(elen > 0, np.maximum(np.ceil(elen / spacing), 1), 0).astype(np.int64)
    seg = np.repeat(np.arange(len(a)), k)
    first = np.cumsum(k) - k
    j = np.arange(len(seg)) - first[seg]
    frac = (j + 0.5) / k[seg]
    return seg, frac, elen[seg] / k[seg]


def sample_contour(loops, spacing: float) -> ContourSamples:
    """Sample every loop at sub-segment midpoints, pieces no longer than ``spacing``."""
    loops = as_loops(loops)
    a, b, loop = contour_edges(loops)
    elen = np.hypot(*(b - a).T)
    seg, frac, lengths = subdivide(a, b, spacing)
    loop_lengths = np.bincount(loop, weights=elen, minlength=len(loops))
    before = np.cumsum(elen) - elen  # global arc length at edge start
    loop_start = np.concatenate([[0.0], np.cumsum(loop_lengths)[:-1]]) if len(loops) else np.zeros(0)
    edge_s = before - loop_start[loop]
    return ContourSamples(
        points=a[seg] + frac[:, None] * (b - a)[seg],
        lengths=lengths,
        loop=loop[seg],
        edge=seg,
        s=edge_s[seg] + frac * elen[seg],
        is_hole=loop_is_hole(loops)[loop[seg]],
        loop_lengths=loop_lengths,
    )


def _free_chunk(p, own, a, b, atol):
    """Widest free angle for points ``p`` (c, 2) on edges ``own`` (c,)."""
    ea, eb = a[own], b[own]
    ulen = np.hypot(*(eb - ea).T)
    # does p sit strictly inside its own edge (not at a vertex)?
    inner = (np.hypot(*(p - ea).T) > atol) & (np.hypot(*(p - eb).T) > atol) & (ulen > 0)
    safe = np.where(ulen > 0, ulen, 1.0)
    tangents = (eb - ea) / safe[:, None]
    width, _ = free_gaps(p, tangents, a, b, inner=inner, own=own, atol=atol)
    return width


def _locate(a, b, points):
    """(m,) index of the edge nearest to each point."""
    tree = shapely.STRtree(shapely.linestrings(np.stack([a, b], axis=1)))
    idx = tree.query_nearest(shapely.points(points), all_matches=False)
    out = np.empty(len(points), dtype=np.int64)
    out[idx[0]] = idx[1]
    return out


def free_angle(loops, points, edge_ids=None, chunk: int = _CHUNK) -> np.ndarray:
    """Widest open interval of free ray directions at each contour point.

    Parameters
    ----------
    loops : list of (k, 2) float -- the contour (see module conventions).
    points : (m, 2) float -- points on the contour.
    edge_ids : (m,) int, optional -- global edge each point lies on (nearest
        edge when omitted).
    chunk : int -- points x edges pairs handled at once (memory bound).

    Returns
    -------
    (m,) float -- angle in radians, in [0, pi] for points inside an edge and
    in [0, 2 pi] at vertices; 0 where every direction is blocked.
    """
    a, b, _ = contour_edges(loops)
    points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    if len(points) == 0 or len(a) == 0:
        return np.zeros(len(points))
    edge_ids = _locate(a, b, points) if edge_ids is None else np.asarray(edge_ids, dtype=np.int64)
    atol = 1e-9 * max(float(np.ptp(a, axis=0).max()), 1e-300)
    step = max(1, min(_MAX_ROWS, chunk // len(a)))
    out = np.empty(len(points))
    for i in range(0, len(points), step):
        sl = slice(i, i + step)
        out[sl] = _free_chunk(points[sl], edge_ids[sl], a, b, atol)
    return out


def reachable(loops, points, edge_ids=None, angle_tol: float = 1e-9, chunk: int = _CHUNK) -> np.ndarray:
    """(m,) bool: some ray from the point to infinity crosses no contour edge.

    Points on the convex hull boundary are accepted without the full test
    (the outward normal of a supporting line is free), points inside the edges of
    hole loops rejected (``_sealed``: every ray from them leaves the hole through its
    loop; while ``angle_tol`` is at least ``SEALED_TOL``), and points with
    a free cone of directions (:mod:`core2d.truth.free_ray`: a gap of at least
    2e-5 rad, used while ``angle_tol`` is below 1e-5). Elsewhere this is
    ``free_angle(...) > angle_tol``: grazing rays and measure-zero gaps are
    blocked. The answers are those of the exact test alone.

    Examples
    --------
    >>> sq = [np.array([[0., 0.], [2., 0.], [2., 2.], [0., 2.]])]
    >>> reachable(sq, [[1.0, 0.0]], [0]).tolist()
    [True]
    """
    a, b, loop = contour_edges(loops)
    points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    if len(points) == 0 or len(a) == 0:
        return np.zeros(len(points), dtype=bool)
    edge_ids = _locate(a, b, points) if edge_ids is None else np.asarray(edge_ids, dtype=np.int64)
    atol = 1e-9 * max(float(np.ptp(a, axis=0).max()), 1e-300)
    hull = shapely.convex_hull(shapely.multipoints(a)).boundary
    ok = shapely.distance(shapely.points(points), hull) <= atol
    todo = np.flatnonzero(~ok)
    if len(todo) and angle_tol >= SEALED_TOL:  # hole samples: blocked all round, no arcs
        on_hole = loop_is_hole(loops)[loop[edge_ids[todo]]]
        sealed = _sealed(points[todo], edge_ids[todo], a, b, on_hole, 1e3 * atol)
        sealed[0] &= not sealed.all()  # one left for the arcs, as below
        todo = todo[~sealed]
    if len(todo) and angle_tol < HALF_ANGLE:  # a free cone proves most of the rest
        proved = _cone_proves(points[todo], edge_ids[todo], a, b, atol)
        ok[todo] = proved
        # the exact arcs decide the others and check the first proved sample: every
        # call with samples off the hull runs them (the same compiled kernels whatever
        # the cone proves, so numba's cache, and the first-compile notice, do not
        # depend on the contour)
        exact = ~proved
        exact[np.argmax(proved)] = True
        todo = todo[exact]
    if len(todo):
        ok[todo] = free_angle(loops, points[todo], edge_ids[todo], chunk) > angle_tol
    return ok


def _sealed(p, own, a, b, on_hole, margin) -> np.ndarray:
    """(c,) bool: points on a hole loop's edge (``on_hole``) farther than ``margin`` from
    every other edge (so from their own edge's ends too, which the neighbouring edges
    share): unreachable for certain.

    A hole loop runs clockwise, its free side (on the edges' right) is the bounded region it
    encloses: every ray from a point inside one of its edges into that side leaves the
    region through the loop (Jordan), at a point farther than ``margin`` from where it
    started, on an edge whose closed arc of directions holds the ray's -- the exact arcs
    leave no gap but rounding's, far below :data:`SEALED_TOL` while the point keeps
    ``margin`` (1e-6 of the coordinates' size) from every other edge. Points nearer go to
    the exact test."""
    out = np.array(on_hole, dtype=bool)
    idx = np.flatnonzero(out)
    if len(idx):
        tree = shapely.STRtree(shapely.linestrings(np.stack([a, b], axis=1)))
        pi, si = tree.query(shapely.points(p[idx]), predicate="dwithin", distance=margin)
        out[idx[np.unique(pi[si != own[idx][pi]])]] = False
    return out


def _cone_proves(p, own, a, b, atol) -> np.ndarray:
    """(c,) bool: points inside their edge whose outward normal cone is free
    (:func:`core2d.truth.free_ray.normal_cone_free`, margin 1e-9 of the
    coordinates' size): reachable for certain."""
    ea, eb = a[own], b[own]
    ulen = np.hypot(*(eb - ea).T)
    inner = (np.hypot(*(p - ea).T) > atol) & (np.hypot(*(p - eb).T) > atol) & (ulen > 0)
    out = np.zeros(len(p), dtype=bool)
    if inner.any():
        tangents = (eb - ea)[inner] / ulen[inner, None]
        margin = 1e-9 * max(float(np.ptp(a, axis=0).max()), float(np.abs(a).max()), 1e-300)
        center = 0.5 * (a.min(axis=0) + a.max(axis=0))
        out[inner] = normal_cone_free(p[inner], tangents, a, b, own[inner], margin, center)
    return out


def reachable_samples(loops, spacing: float, **kwargs) -> tuple[ContourSamples, np.ndarray]:
    """Sample the contour (:func:`sample_contour`) and test every sample.

    Returns
    -------
    samples : ContourSamples
    ok : (m,) bool -- reachable samples.
    """
    samples = sample_contour(loops, spacing)
    return samples, reachable(loops, samples.points, samples.edge, **kwargs)
