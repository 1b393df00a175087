"""Compiled per-ray kernels of the Embree contact backend (numba).

Used by :mod:`slicer.contact.embree` (batches) and
:mod:`slicer.contact.embree_direct` (one ray from compiled code); imports no
ray engine.

Embree answers a batch of in-plane rays with the primitive each ray hits
first; everything around that call is done per ray here, in float64:

* :func:`fill_rays` writes 2D rays into the float32 3D ray buffers Embree
  reads (``z = 0``: the scene is stored in the plane's own frame);
* :func:`refine_hits` intersects each ray with its hit triangle's section
  segment: the ray meets the segment's line, the segment parameter is
  clamped to [0, 1] (a float32 hit on a neighbour at a shared vertex, or a
  grazing ray, lands on the endpoint), and the distance is the projection
  of that point on the ray; ``max_dist`` is applied to that distance.

Compiled because the batches of a probe motion are small (1 - 20 rays):
per ray, the interpreter cost ~1 us where the Embree query costs ~0.1 us,
and a numpy call on a small array ~1 us per operation. One call of each
kernel costs ~0.5 us whatever the batch size.

Examples
--------
>>> table = np.array([[1.0, -1.0, 0.0, 2.0, 1.0, 0.0]])  # x = 1, from y = -1 to 1
>>> out = np.empty((2, 5))
>>> refine_hits(table, np.array([0, -1], np.int32), np.zeros((2, 2)),
...             np.array([[1.0, 0.0], [1.0, 0.0]]), 5.0, NO_LIMITS, out)
>>> out[0].tolist(), bool(np.isinf(out[1, 0]))
([1.0, 1.0, 0.0, -1.0, 0.0], True)
"""
from __future__ import annotations

import numba
import numpy as np

__all__ = ["fill_rays", "fill_fan", "refine_hits", "segment_hit", "NO_LIMITS"]

NO_LIMITS = np.zeros(0)
"""Pass as ``limits`` when one ``max_dist`` holds for every ray."""


@numba.njit(cache=True, nogil=True)
def fill_rays(origins, dirs, o32, d32):  # pragma: no cover - compiled
    """Copy (n, 2) float64 rays into the first n rows of (m, 3) float32 buffers."""
    for i in range(origins.shape[0]):
        o32[i, 0] = origins[i, 0]
        o32[i, 1] = origins[i, 1]
        d32[i, 0] = dirs[i, 0]
        d32[i, 1] = dirs[i, 1]


@numba.njit(cache=True, nogil=True)
def fill_fan(jx, jy, angles, o64, d64, o32, d32):  # pragma: no cover - compiled
    """Rays from ``(jx, jy)`` at ``angles`` (n,): unit directions ``(cos, sin)``
    (libm, as numpy's) into the first n rows of (m, 2) float64 and (m, 3)
    float32 buffers."""
    for i in range(angles.shape[0]):
        c = np.cos(angles[i])
        s = np.sin(angles[i])
        o64[i, 0] = jx
        o64[i, 1] = jy
        d64[i, 0] = c
        d64[i, 1] = s
        o32[i, 0] = jx
        o32[i, 1] = jy
        d32[i, 0] = c
        d32[i, 1] = s


@numba.njit(cache=True, nogil=True)
def refine_hits(table, prim, origins, dirs, max_dist, limits, out):  # pragma: no cover
    """Float64 contact of each ray with its hit segment.

    Parameters
    ----------
    table : (k, 6) float -- per segment ``(ax, ay, ex, ey, nx, ny)``: start,
        edge vector, unit outward normal.
    prim : (n,) int32 -- Embree's first hit per ray, -1 for none.
    origins, dirs : (n, 2) float -- the rays (unit directions).
    max_dist : float -- longest distance, unless ``limits`` is given.
    limits : (n,) float or (0,) float -- per-ray longest distance.
    out : (n, 5) float -- written: distance (inf for a miss), point (nan),
        normal oriented against the ray (nan).
    """
    per_ray = limits.shape[0] > 0
    for i in range(prim.shape[0]):
        k = prim[i]
        md = limits[i] if per_ray else max_dist
        if k < 0:
            out[i, 0] = np.inf
            out[i, 1] = out[i, 2] = out[i, 3] = out[i, 4] = np.nan
            continue
        s, px, py, nx, ny = segment_hit(table, k, origins[i, 0], origins[i, 1],
                                        dirs[i, 0], dirs[i, 1], md)
        out[i, 0], out[i, 1], out[i, 2], out[i, 3], out[i, 4] = s, px, py, nx, ny


@numba.njit(cache=True, nogil=True, inline="always")
def segment_hit(table, k, ox, oy, dx, dy, max_dist):  # pragma: no cover - compiled
    """Float64 contact of one ray with segment ``k`` of ``table`` (Embree's hit).

    Returns ``(distance, x, y, nx, ny)``: ``(inf, nan, nan, nan, nan)`` beyond
    ``max_dist``; the normal is oriented against the ray.
    """
    ax, ay, ex, ey = table[k, 0], table[k, 1], table[k, 2], table[k, 3]
    wx = ax - ox
    wy = ay - oy
    den = dx * ey - dy * ex
    if den != 0.0:
        r = (wx * dy - wy * dx) / den
        r = 0.0 if r < 0.0 else (1.0 if r > 1.0 else r)
    else:  # ray along the segment's line: nearer endpoint
        r = 0.0 if wx * dx + wy * dy <= (wx + ex) * dx + (wy + ey) * dy else 1.0
    s = (wx + r * ex) * dx + (wy + r * ey) * dy
    if s < 0.0:
        s = 0.0
    if s > max_dist:
        return np.inf, np.nan, np.nan, np.nan, np.nan
    if den > 0.0:
        return s, ox + s * dx, oy + s * dy, -table[k, 4] + 0.0, -table[k, 5] + 0.0
    return s, ox + s * dx, oy + s * dy, table[k, 4] + 0.0, table[k, 5] + 0.0
