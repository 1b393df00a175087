"""Scenes built from implicit functions with ``Manifold.level_set``.

manifold3d's level_set treats POSITIVE values as inside. Same conventions
as the other scene modules: millimetres, "up" = +y, minimum corner at the
origin, inside a 100 mm cube.
"""
from __future__ import annotations

import math

from manifold3d import Manifold

from .geometry import check_resolution, place
from .registry import scene

__all__ = ["terrain", "terrain_height"]

_SIZE_X, _SIZE_Z = 100.0, 60.0


def terrain_height(x: float, z: float) -> float:
    """Top height y (mm) of :func:`terrain` above ``(x, z)``: 25 +- 13 mm."""
    return (25.0 + 6.0 * math.sin(2 * math.pi * x / 45.0)
            + 4.0 * math.sin(2 * math.pi * z / 35.0 + 1.0)
            + 3.0 * math.sin(2 * math.pi * (x + z) / 25.0))


@scene()
def terrain(*, resolution: int = 25) -> Manifold:
    """Slab whose top is a sum of sines y = h(x, z), cut to 100 x 60 mm (level_set).

    The top height ranges over about 12..38 mm (:func:`terrain_height`).
    Every z-slice is a smooth wavy profile with shallow reachable pockets,
    and the profile changes continuously with z, which tests stacking of
    per-slice results into a surface. The sides and bottom are exact planes
    (the level-set slab is trimmed by a box). ``resolution``: grid cells
    along x (edge length ``100 / resolution`` mm).
    """
    res = check_resolution(resolution)
    edge = _SIZE_X / res

    def inside(x: float, y: float, z: float) -> float:  # > 0 inside
        return min(terrain_height(x, z) - y, y + 2.0 * edge)

    pad = 2.0 * edge
    bounds = [-pad, -3.0 * edge, -pad, _SIZE_X + pad, 45.0, _SIZE_Z + pad]
    slab = Manifold.level_set(inside, bounds, edge)
    box = Manifold.cube((_SIZE_X, 45.0, _SIZE_Z))
    return place(slab ^ box)
