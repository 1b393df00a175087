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

__all__ = ["HALF_ANGLE", "candidate_directions", "normal_cone_free"]

#: half-angle (rad) of a cone that must be free
HALF_ANGLE = 1e-5
#: turns (rad) of the outward normal tried besides it, both ways
TURNS = (0.6, 1.2, 0.5 * math.pi - 0.05, 0.5 * math.pi - 0.01)
#: largest turn from the normal a candidate may have (the cone stays in the free half-plane)
MAX_TURN = 1.4


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
        _cone_free(p, dirs, a, b, own, float(margin), math.cos(HALF_ANGLE),
                   math.sin(HALF_ANGLE), out)
    return out


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
def _cone_free(p, dirs, a, b, own, margin, cos_h, sin_h, out):  # pragma: no cover - compiled
    """Fill ``out[r]``: for some candidate ``d = dirs[r, k]``, the segment ``[a_j, b_j]``
    (``j != own[r]``) meets, for no j, ``{v : cross(dl, v) <= margin and
    cross(dr, v) >= -margin}`` (v = x - p[r]): the cone between ``dl`` and ``dr``,
    ``d`` turned by +-HALF_ANGLE, widened by ``margin``."""
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
            for j in range(a.shape[0]):
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
                    free = False  # a common part (or not a number)
                    break
            if free:
                break
        out[r] = free
