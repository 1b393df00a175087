"""Point and segment geometry of the robot's map (:mod:`core2d.planner.known`).

Distances from a point to the map's segments, where a point projects on them, which
pieces' boxes lie near a point, and the cross product of 2D vectors. The per-point work
are compiled (numba, cached) and do the float64 operations of the numpy expressions they
replace, so the map answers the same to the bit.
"""
from __future__ import annotations

import numba
import numpy as np

__all__ = ["cull_margin", "cross2", "segment_params", "point_segment_distances",
           "near_segments", "segments_within", "nearest_distance", "turns", "continuing",
           "continued_ends"]


def cull_margin(r, lo, hi) -> float:
    """Slack for box culling at distance ``r``: far above the rounding of the
    distances computed near coordinates up to ``lo``, ``hi``."""
    return 1e-9 * (r + max(abs(float(lo[0])), abs(float(lo[1])), abs(float(hi[0])),
                           abs(float(hi[1]))))


def cross2(x, y):
    """(...) z-component of the cross product of 2D vectors ``x`` and ``y`` (..., 2)."""
    return x[..., 0] * y[..., 1] - x[..., 1] * y[..., 0]


def segment_params(p, a, b) -> np.ndarray:
    """(n,) position of the projection of p on each segment a -> b, in [0, 1].

    >>> segment_params([1.0, 1.0], np.array([[0.0, 0.0]]), np.array([[4.0, 0.0]])).tolist()
    [0.25]
    """
    out = np.empty(len(a))
    _project(np.asarray(p, np.float64), _c(a), _c(b), out, np.empty(0))
    return out


def point_segment_distances(p, a, b) -> np.ndarray:
    """(n,) distances from point p to segments a -> b.

    >>> a, b = np.array([[0.0, 0.0], [0.0, 2.0]]), np.array([[4.0, 0.0], [0.0, 2.0]])
    >>> point_segment_distances([1.0, 1.0], a, b).tolist()  # the second has zero length
    [1.0, 1.4142135623730951]
    """
    out = np.empty(len(a))
    _project(np.asarray(p, np.float64), _c(a), _c(b), np.empty(len(a)), out)
    return out


def _c(x) -> np.ndarray:
    """``x`` as a C-contiguous float64 array (one compiled signature of :func:`_project`)."""
    return np.ascontiguousarray(x, dtype=np.float64)


@numba.njit(cache=True, nogil=True)
def near_segments(px, py, r, lo, hi, piece, out):  # pragma: no cover - compiled
    """Segments (ascending, into ``out``; their count returned) of the pieces
    whose box ``lo``, ``hi`` (k, 2) lies within ``r`` of (px, py)."""
    ok = _boxes_near(px, py, r, lo, hi)
    m = 0
    for j in range(piece.shape[0]):
        if ok[piece[j]]:
            out[m] = j
            m += 1
    return m


@numba.njit(cache=True, nogil=True, error_model="numpy")
def segments_within(px, py, cull, r, lo, hi, piece, a, b, first_only, out):  # pragma: no cover
    """Segments (ascending, into ``out``; their count returned) within ``r`` of (px, py):
    :func:`near_segments` at ``cull`` (the pieces' boxes ``lo``, ``hi``), then the
    distances of :func:`point_segment_distances` ``<= r``, in one pass with the same float64
    operations (:func:`_segment_distance`). ``first_only``: only each piece's first such
    segment (the segments of a piece are consecutive, the pieces ascending)."""
    ok = _boxes_near(px, py, cull, lo, hi)
    m, last = 0, -1
    for j in range(piece.shape[0]):
        if not ok[piece[j]] or (first_only and piece[j] == last):
            continue
        if _segment_distance(px, py, a[j, 0], a[j, 1], b[j, 0], b[j, 1])[1] <= r:
            out[m] = j
            m += 1
            last = piece[j]
    return m


@numba.njit(cache=True, nogil=True, error_model="numpy")
def nearest_distance(px, py, starts, lo, hi, piece, a, b):  # pragma: no cover - compiled
    """Distance from (px, py) to the nearest of the segments ``a`` -> ``b`` (at least one):
    the nearest piece start (``starts`` (k, 2), each a segment's first point) bounds it, so
    only the segments of the pieces whose box ``lo``, ``hi`` lies within that bound (plus
    :func:`cull_margin`) are measured. The float64 operations of the numpy expressions
    :meth:`core2d.planner.known.KnownContour.distance` used, the same to the bit."""
    bound = np.inf
    for i in range(starts.shape[0]):
        bound = min(bound, np.hypot(starts[i, 0] - px, starts[i, 1] - py))
    cull = bound + 1e-9 * (bound + max(abs(px), abs(py)))
    ok = _boxes_near(px, py, cull, lo, hi)
    best = np.inf
    for j in range(piece.shape[0]):
        if ok[piece[j]]:
            best = min(best, _segment_distance(px, py, a[j, 0], a[j, 1], b[j, 0], b[j, 1])[1])
    return best


def turns(d, e) -> np.ndarray:
    """(n,) bool: direction e (n, 2) turns less than 120 degrees from direction d (2,)
    (a zero-length one turns): cos(d, e) > -0.5, with the float64 operations of
    :func:`_turns_less`.

    >>> turns([1.0, 0.0], [[1.0, 0.0], [-1.0, 0.1], [-1.0, 2.0], [0.0, 0.0]]).tolist()
    [True, False, True, True]
    """
    e = _c(np.asarray(e, dtype=np.float64).reshape(-1, 2))
    out = np.empty(len(e), dtype=np.bool_)
    _turns_all(float(d[0]), float(d[1]), e, out)
    return out


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _turns_all(dx, dy, e, out):  # pragma: no cover - compiled
    for i in range(e.shape[0]):
        out[i] = _turns_less(dx, dy, e[i, 0], e[i, 1])


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _turns_less(dx, dy, ex, ey):  # pragma: no cover - compiled
    """Does direction (ex, ey) turn less than 120 degrees from (dx, dy)? cos > -0.5 with
    cos = e.d / (|e| |d|), the norms by ``hypot``; a zero-length direction turns."""
    n = np.hypot(ex, ey) * np.hypot(dx, dy)
    if n == 0.0:
        return True
    return not ((ex * dx + ey * dy) / n <= -0.5)


@numba.njit(cache=True, nogil=True, error_model="numpy")
def continuing(px, py, cull, r, dx, dy, lo, hi, piece, a, b, out):  # pragma: no cover
    """The pieces that continue a piece ending at (px, py) in direction (dx, dy): for each
    piece (ascending), its first segment (into ``out``; their count returned) within ``r``
    of the end (boxes culled at ``cull`` as in :func:`segments_within`) whose direction
    b - a turns less than 120 degrees from (dx, dy) (:func:`_turns_less`)."""
    ok = _boxes_near(px, py, cull, lo, hi)
    m, last = 0, -1
    for j in range(piece.shape[0]):
        if not ok[piece[j]] or piece[j] == last:
            continue
        ax, ay, bx, by = a[j, 0], a[j, 1], b[j, 0], b[j, 1]
        if (_segment_distance(px, py, ax, ay, bx, by)[1] <= r
                and _turns_less(dx, dy, bx - ax, by - ay)):
            out[m] = j
            m += 1
            last = piece[j]
    return m


@numba.njit(cache=True, nogil=True, error_model="numpy")
def continued_ends(ends, dirs, lo, hi, reach, pl, r, out_end, out_seg):  # pragma: no cover
    """The pieces a new polyline ``pl`` (k, 2) continues: each end ``ends[j]`` (ascending)
    inside the polyline's box ``lo``, ``hi`` (2,) grown by ``reach``, with the first
    segment of ``pl`` within ``r`` of it whose step turns less than 120 degrees from that
    piece's end direction ``dirs[j]``: j into ``out_end``, the segment into ``out_seg``;
    their count returned."""
    m = 0
    for j in range(ends.shape[0]):
        px, py = ends[j, 0], ends[j, 1]
        if not (px >= lo[0] - reach and py >= lo[1] - reach and px <= hi[0] + reach
                and py <= hi[1] + reach):
            continue
        for k in range(pl.shape[0] - 1):
            ax, ay, bx, by = pl[k, 0], pl[k, 1], pl[k + 1, 0], pl[k + 1, 1]
            if (_segment_distance(px, py, ax, ay, bx, by)[1] <= r
                    and _turns_less(dirs[j, 0], dirs[j, 1], bx - ax, by - ay)):
                out_end[m] = j
                out_seg[m] = k
                m += 1
                break
    return m


@numba.njit(cache=True, nogil=True)
def _boxes_near(px, py, r, lo, hi):  # pragma: no cover - compiled
    """(k,) bool: which boxes ``lo``, ``hi`` (k, 2) lie within ``r`` of (px, py) along both
    axes (the culling every kernel here starts with)."""
    ok = np.empty(lo.shape[0], dtype=np.bool_)
    for i in range(lo.shape[0]):
        ok[i] = (lo[i, 0] - r <= px and lo[i, 1] - r <= py and hi[i, 0] + r >= px
                 and hi[i, 1] + r >= py)
    return ok


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _segment_distance(px, py, ax, ay, bx, by):  # pragma: no cover - compiled
    """The projection parameter of (px, py) on segment a -> b, clamped to [0, 1] (0 for a
    zero-length segment), and the distance to the projection: the float64 operations of
    the numpy expressions :func:`_project` replaces, shared by every kernel here."""
    ex, ey = bx - ax, by - ay
    s = ((px - ax) * ex + (py - ay) * ey) / (ex * ex + ey * ey)
    s = 0.0 if s < 0.0 else (1.0 if s > 1.0 else s)
    if s != s:  # zero-length segment: its start
        s = 0.0
    return s, np.hypot(ax + s * (bx - ax) - px, ay + s * (by - ay) - py)


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _project(p, a, b, t, dist):  # pragma: no cover - compiled
    """Projection parameter ``t`` (n,) of p on each segment a -> b, clamped to
    [0, 1] (0 for a zero-length segment), and the distance ``dist`` (n,) to
    the projection when ``dist`` has n entries (:func:`_segment_distance`)."""
    px, py = p[0], p[1]
    with_dist = dist.shape[0] > 0
    for i in range(a.shape[0]):
        s, d = _segment_distance(px, py, a[i, 0], a[i, 1], b[i, 0], b[i, 1])
        t[i] = s
        if with_dist:
            dist[i] = d
