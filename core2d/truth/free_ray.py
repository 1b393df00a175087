"""A sufficient test of reachability: a thin free cone along the outward normal.

:func:`core2d.truth.reachability.reachable` answers exactly (DESIGN.md "The 2D
problem on a closed cross-section"): a contour point is reachable when the
union of the closed arcs of directions its edges block leaves an open gap
wider than ``angle_tol`` (:func:`core2d.visibility.free_gaps`). That needs
every arc of every (point, edge) pair, an ``arctan2`` each, and a sort.

Most contour points are reachable along their outward normal. This module
proves it without angles: a point is *certainly reachable* when no edge
meets the cone of half-angle ``HALF_ANGLE`` around its outward normal,
enlarged by a margin ``margin`` on every side (apex included). Then the
true free gap around the normal is at least ``2 x HALF_ANGLE`` wide, and the
exact test's arcs, off by rounding only (relative error ~1e-16 of the
coordinates, far below ``margin``), leave a computed gap of about the same
width, > ``angle_tol`` whenever ``angle_tol`` < ``HALF_ANGLE``. Points it
cannot prove (the cone meets an edge) go to the exact test; so
``reachable`` answers as before, bit for bit (tested on real slices and
random contours).

The test is conservative everywhere the exact one is lenient: edges within
``atol`` of the point (which the exact test ignores) and the point's own
edge's neighbours count as blocking when they meet the cone.
"""
from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["HALF_ANGLE", "CHUNK", "candidate_directions", "chunk_boxes", "normal_cone_free"]

#: half-angle (rad) of a cone that must be free
HALF_ANGLE = 1e-5
#: turns (rad) of the outward normal tried besides it, both ways
TURNS = (0.6, 1.2, 0.5 * math.pi - 0.05, 0.5 * math.pi - 0.01)
#: largest turn from the normal a candidate may have (the cone stays in the free half-plane)
MAX_TURN = 1.4
#: consecutive segments per bounding box: a box wholly outside a cone's boundary is skipped
CHUNK = 16
#: a box is skipped only when it is outside by more than this (x the coordinates' size):
#: far above the rounding of a boundary's equation at a corner, far below ``margin``
SLACK = 1e-12


def normal_cone_free(points, tangents, seg_a, seg_b, own, margin: float,
                     center=None) -> np.ndarray:
    """(c,) bool: for each point, some candidate cone meets no segment.

    Parameters
    ----------
    points : (c, 2) float -- contour points.
    tangents : (c, 2) float -- unit tangents of their edges; the outward
        normal (the free side, as in :func:`core2d.visibility.free_gaps`) is
        on the right: ``(ty, -tx)``.
    seg_a, seg_b : (n, 2) float -- the contour's edges.
    own : (c,) int -- each point's own edge (ignored for it).
    margin : float > 0 -- the cone's boundary lines moved outwards by this.
    center : (2,) float, optional -- also try the direction away from it.

    Returns
    -------
    (c,) bool -- True: certainly reachable; False: not proved (ask the exact test).
    """
    p = np.ascontiguousarray(points, dtype=np.float64).reshape(-1, 2)
    dirs = candidate_directions(p, tangents, center)
    a = np.ascontiguousarray(seg_a, dtype=np.float64).reshape(-1, 2)
    b = np.ascontiguousarray(seg_b, dtype=np.float64).reshape(-1, 2)
    own = np.ascontiguousarray(own, dtype=np.int64).reshape(-1)
    out = np.zeros(len(p), dtype=np.bool_)
    if len(p):
        lo, hi = chunk_boxes(a, b)
        size = max(float(np.abs(a).max()), float(np.abs(b).max())) if len(a) else 0.0
        _cone_free(p, dirs, a, b, own, float(margin), math.cos(HALF_ANGLE),
                   math.sin(HALF_ANGLE), lo, hi, CHUNK, SLACK * size, out)
    return out


def chunk_boxes(a, b) -> tuple[np.ndarray, np.ndarray]:
    """(m, 2), (m, 2) float: the bounding box of each run of :data:`CHUNK` consecutive
    segments ``[a_j, b_j]`` (m = ceil(n / CHUNK); the last run may be shorter). A
    contour's consecutive edges lie close together, so a thin cone misses most boxes."""
    n = len(a)
    if n == 0:
        return np.zeros((0, 2)), np.zeros((0, 2))
    m = -(-n // CHUNK)
    pad = m * CHUNK - n
    ends = np.concatenate([a, b], axis=1)  # (n, 4): ax, ay, bx, by
    if pad:
        ends = np.concatenate([ends, np.repeat(ends[-1:], pad, axis=0)])
    ends = ends.reshape(m, CHUNK, 2, 2)
    return (np.ascontiguousarray(ends.min(axis=(1, 2))),
            np.ascontiguousarray(ends.max(axis=(1, 2))))


def candidate_directions(points, tangents, center=None) -> np.ndarray:
    """(c, K, 2) unit directions to try, all at most ``MAX_TURN`` from the
    outward normal (so each cone lies inside the free half-plane): the
    normal, the normal turned by +-``TURNS``, and (with ``center``) the
    direction away from ``center`` where it is within ``MAX_TURN`` (else
    the normal again)."""
    t = np.asarray(tangents, dtype=np.float64).reshape(-1, 2)
    n = np.stack([t[:, 1], -t[:, 0]], axis=1)
    out = [n]
    for turn in TURNS:
        for sgn in (1.0, -1.0):
            c, s = math.cos(turn), sgn * math.sin(turn)
            out.append(np.stack([n[:, 0] * c - n[:, 1] * s, n[:, 0] * s + n[:, 1] * c], axis=1))
    if center is not None:
        r = np.asarray(points, dtype=np.float64).reshape(-1, 2) - np.asarray(center, float)
        rl = np.hypot(r[:, 0], r[:, 1])
        with np.errstate(invalid="ignore", divide="ignore"):
            r = r / rl[:, None]
        ok = (rl > 0) & (np.einsum("ij,ij->i", r, n) > math.cos(MAX_TURN))
        out.insert(1, np.where(ok[:, None], r, n))
    return np.ascontiguousarray(np.stack(out, axis=1))


@numba.njit(cache=True, nogil=True)
def _box_outside(lx, ly, rx, ry, x0, y0, x1, y1, margin, slack):  # pragma: no cover
    """Is the box [x0, x1] x [y0, y1] (relative to the apex) outside the left boundary
    (f > slack at every corner) or the right one (g < -slack at every corner)? Then so
    is every segment in it, as the segment test computes it (f, g are linear: their
    extremes over a box are at its corners; ``slack`` covers the rounding). NaN: no."""
    if not (x0 == x0 and y0 == y0 and x1 == x1 and y1 == y1):
        return False
    fmin = min(min(lx * y0 - ly * x0, lx * y1 - ly * x0),
               min(lx * y0 - ly * x1, lx * y1 - ly * x1)) - margin
    if fmin > slack:
        return True
    gmax = max(max(rx * y0 - ry * x0, rx * y1 - ry * x0),
               max(rx * y0 - ry * x1, rx * y1 - ry * x1)) + margin
    return gmax < -slack


@numba.njit(cache=True, nogil=True)
def _cone_free(p, dirs, a, b, own, margin, cos_h, sin_h, lo, hi, chunk, slack,
               out):  # pragma: no cover - compiled
    """Fill ``out[r]``: for some candidate ``d = dirs[r, k]``, the segment ``[a_j, b_j]``
    (``j != own[r]``) meets, for no j, ``{v : cross(dl, v) <= margin and
    cross(dr, v) >= -margin}`` (v = x - p[r]): the cone between ``dl`` and ``dr``,
    ``d`` turned by +-HALF_ANGLE, widened by ``margin``. The segments of a box
    (``lo``, ``hi``: runs of ``chunk`` segments, :func:`chunk_boxes`) wholly outside a
    boundary are not looked at: each of them would be skipped as wholly outside."""
    n = a.shape[0]
    for r in range(p.shape[0]):
        px, py = p[r, 0], p[r, 1]
        skip = own[r]
        free = False
        for k in range(dirs.shape[1]):
            nx, ny = dirs[r, k, 0], dirs[r, k, 1]
            # left boundary: d turned counter-clockwise; right: clockwise
            lx, ly = nx * cos_h - ny * sin_h, nx * sin_h + ny * cos_h
            rx, ry = nx * cos_h + ny * sin_h, -nx * sin_h + ny * cos_h
            free = True
            for c in range(lo.shape[0]):
                if _box_outside(lx, ly, rx, ry, lo[c, 0] - px, lo[c, 1] - py, hi[c, 0] - px,
                                hi[c, 1] - py, margin, slack):
                    continue
                if not _segments_free(lx, ly, rx, ry, px, py, a, b, c * chunk,
                                      min(n, (c + 1) * chunk), skip, margin):
                    free = False
                    break
            if free:
                break
        out[r] = free


@numba.njit(cache=True, nogil=True)
def _segments_free(lx, ly, rx, ry, px, py, a, b, j0, j1, skip,
                   margin):  # pragma: no cover - compiled
    """Do the segments ``j0 <= j < j1`` (but ``skip``) all miss the widened cone?"""
    for j in range(j0, j1):
        if j == skip:
            continue
        vax, vay = a[j, 0] - px, a[j, 1] - py
        vbx, vby = b[j, 0] - px, b[j, 1] - py
        # f: inside the left boundary when f <= 0; g: inside the right when g >= 0
        fa = lx * vay - ly * vax - margin
        fb = lx * vby - ly * vbx - margin
        ga = rx * vay - ry * vax + margin
        gb = rx * vby - ry * vbx + margin
        if (fa > 0.0 and fb > 0.0) or (ga < 0.0 and gb < 0.0):
            continue  # wholly outside one boundary
        # clip the parameter range [0, 1] to f <= 0 and g >= 0 (Liang-Barsky)
        lo, hi = 0.0, 1.0
        if fa > 0.0:  # enters through f = 0 (fb <= 0 here)
            lo = max(lo, fa / (fa - fb))
        elif fb > 0.0:  # leaves through f = 0
            hi = min(hi, fa / (fa - fb))
        if ga < 0.0:
            lo = max(lo, ga / (ga - gb))
        elif gb < 0.0:
            hi = min(hi, ga / (ga - gb))
        if lo <= hi or not (fa == fa and fb == fb and ga == ga and gb == gb):
            return False  # a common part (or not a number)
    return True
