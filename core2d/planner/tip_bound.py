"""Theorem 3's swing bound for the bisection (§4.2.2), compiled.

During the bisection the probe swings about its joint P_i^(j); Theorem 3
keeps the tip inside T_i^(j) cap V_i cap G_i, or lets it beyond only
across L_{A_i}^{B_i}. :func:`tip_bound` finds the largest swing that does,
checking the tip's arc at the fan spacing: a swing of ``limit`` is cut into
``n = max(4, limit / fan_angle)`` steps (:meth:`Resolution.fan_angle
<core2d.resolution.Resolution.fan_angle>`) and the first step whose tip is

* in V_i (Definition 3, the free side of A_iB_i) but outside G_i, or
* outside V_i without the probe crossing the lid A_iB_i,

ends it. G_i arrives as the rings of a polygon (:func:`polygon_rings`;
buffered by the contact resolution by the caller). Everything is the
planner's own record: contacts and postures, never the contour.

Examples
--------
>>> from shapely.geometry import box
>>> xy, ends = polygon_rings(box(-1.0, -1.0, 1.0, 1.0))
>>> xy.shape, ends.tolist()
((5, 2), [5])
>>> bool(_inside(xy, ends, 0.5, 0.5)), bool(_inside(xy, ends, 1.5, 0.5))
(True, False)
"""
from __future__ import annotations

import math

import numba
import numpy as np
import shapely

from core2d.planner.robot import Robot

__all__ = ["tip_bound", "polygon_rings"]


def polygon_rings(geom) -> tuple[np.ndarray, np.ndarray]:
    """Every ring (shells and holes) of a shapely (Multi)Polygon.

    Returns
    -------
    xy : (m, 2) float -- the rings' vertices one after the other, each ring closed.
    ends : (r,) int -- where each ring ends in ``xy``.
    """
    rings = [r for poly in getattr(geom, "geoms", [geom]) if not poly.is_empty
             for r in (poly.exterior, *poly.interiors)]
    if not rings:
        return np.zeros((0, 2)), np.zeros(0, dtype=np.int64)
    xy = [shapely.get_coordinates(r) for r in rings]
    return np.concatenate(xy), np.cumsum([len(r) for r in xy]).astype(np.int64)


def tip_bound(probe: Robot, rings, a, b, theta, rot_dir, limit) -> float:
    """Theorem 3: the largest swing (<= ``limit``) from ``theta`` towards
    ``rot_dir`` (+1 ccw, -1 cw) keeping the tip in T_i^(j) cap V_i cap G_i
    or beyond it only across L_{A_i}^{B_i}.

    rings : :func:`polygon_rings` of G_i. a, b : (2,) float -- A_i, B_i.
    """
    if limit <= 0:
        return 0.0
    n = max(4, int(limit / probe.resolution.fan_angle(probe.length)))
    k = _first_bad(float(probe.joint[0]), float(probe.joint[1]), probe.length, float(theta),
                   float(rot_dir * limit), n, float(a[0]), float(a[1]), float(b[0]),
                   float(b[1]), rings[0], rings[1])
    return limit if k < 0 else float(limit * k / n)


@numba.njit(cache=True, nogil=True)
def _inside(xy, ends, x, y):  # pragma: no cover - compiled
    """Even-odd test of (x, y) against the rings (interior of the polygon)."""
    inside = False
    start = 0
    for e in ends:
        for i in range(start, e - 1):
            x0, y0, x1, y1 = xy[i, 0], xy[i, 1], xy[i + 1, 0], xy[i + 1, 1]
            if (y0 > y) != (y1 > y) and x < x0 + (y - y0) * (x1 - x0) / (y1 - y0):
                inside = not inside
        start = e
    return inside


@numba.njit(cache=True, nogil=True)
def _first_bad(jx, jy, L, theta, swing, n, ax, ay, bx, by, xy, ends):
    # pragma: no cover - compiled
    """0-based index of the first step k (tip at ``theta + swing (k+1) / n``)
    breaking Theorem 3, or -1."""
    abx, aby = bx - ax, by - ay
    d1 = abx * (jy - ay) - aby * (jx - ax)  # cross(ab, P - A)
    for k in range(1, n + 1):
        ang = theta + swing * k / n
        qx, qy = jx + L * math.cos(ang), jy + L * math.sin(ang)
        free_side = (ax - qx) * (by - qy) - (ay - qy) * (bx - qx) > 0  # q in V_i
        if free_side:
            if _inside(xy, ends, qx, qy):
                continue
            return k - 1
        d2 = abx * (qy - ay) - aby * (qx - ax)  # cross(ab, q - A)
        ptx, pty = qx - jx, qy - jy
        d3 = ptx * (ay - jy) - pty * (ax - jx)  # cross(q - P, A - P)
        d4 = ptx * (by - jy) - pty * (bx - jx)  # cross(q - P, B - P)
        if not (d1 * d2 < 0 and d3 * d4 < 0):  # the probe does not cross the lid
            return k - 1
    return -1
