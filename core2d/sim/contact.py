"""The contact interface between the geometry (slicer) and the 2D world (core2d).

core2d sees the world only through an object with a ``cast`` method:

    cast(origins, dirs, max_dist) -> (distances, points, normals)

origins : (n, 2) float
    Ray origins in the slice's 2D frame (u, v).
dirs : (n, 2) float
    Unit ray directions.
max_dist : (n,) float or float
    Longest distance searched along each ray.

distances : (n,) float
    Distance to the first contour hit, ``inf`` where nothing is hit within
    ``max_dist``.
points : (n, 2) float
    Hit points, ``nan`` where there is no hit.
normals : (n, 2) float
    Unit contour normals at the hits, oriented against the ray
    (``normals @ dir <= 0``), ``nan`` where there is no hit.

One call is one batch (one Embree query for the Embree backend). Rays whose
origin lies exactly on the contour have no defined answer: callers step off
the surface first. Implementations live in :mod:`slicer` (Embree -- through
embreex or called directly --, trimesh and exact); core2d never imports them.

Two optional members make the simulator faster without changing an answer:

``fan(origin, angles, max_dist) -> (distances, points)``
    ``cast`` of the rays from one origin at ``angles`` (unit directions
    ``(cos, sin)``), fused.
``ray_kernel -> (address, context) or None``
    A C function ``ray(ctx, ox, oy, dx, dy, max_dist, out)`` answering one
    ray as ``cast`` does (``out[:3] = distance, x, y``) and the array whose
    data pointer is ``ctx``: with it the probe's ray engine is the compiled
    one (:mod:`core2d.sim.engine`), whose kernels call it ray by ray.
"""
from __future__ import annotations

from typing import Protocol, runtime_checkable

import numpy as np

__all__ = ["ContactModel"]


@runtime_checkable
class ContactModel(Protocol):
    """Anything with the batched in-plane ``cast`` described in the module doc."""

    def cast(
        self, origins: np.ndarray, dirs: np.ndarray, max_dist: np.ndarray | float
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        ...
