"""Profile scenes whose pocket carries a fine surface texture (teeth of a few tol).

The paper's case for pulling (§1, Fig. 1): a probe pushed along a surface
"is often blocked by a small irregularity", a pulled one is not. These
scenes give a probe those irregularities: teeth far below eps (invisible in
W1/W2/W3 at the default eps = diagonal / 200 ~ 0.6 mm) but a few contact
tolerances (tol = eps / 20 ~ 0.03 mm) high, with faces steep enough to put
the rod axis inside a friction cone (:mod:`core2d.sim.friction`). Same
conventions as :mod:`meshes.scenes_profiles`: one 2D profile extruded along
z, "up" = +y, millimetres, minimum corner at the origin.
"""
from __future__ import annotations

import numpy as np
from manifold3d import Manifold

from .geometry import check_resolution, place, polygon
from .registry import scene

__all__ = ["textured_pocket", "knurled_pocket", "teeth"]


def teeth(path: np.ndarray, pitch: float, height: float, rise: float) -> np.ndarray:
    """Cut teeth into a polyline: (k, 2) points -> (m, 2) points.

    The path is resampled every ``pitch`` (arc length); after each sample a
    notch ``height`` deep is cut on the path's left (the material's side for
    a counter-clockwise outline), its bottom ``(1 - rise) x pitch`` along:
    ``rise`` is the share of the pitch the tooth takes to climb back (0.5: a
    symmetric knurl; 0.2: a sawtooth with a steep face).
    """
    path = np.asarray(path, dtype=np.float64)
    seg = np.diff(path, axis=0)
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(seg[:, 0], seg[:, 1]))])
    n = int(np.floor(arc[-1] / pitch))
    if n < 1 or not 0 < rise < 1 or not height > 0:
        raise ValueError("teeth need a path longer than the pitch, 0 < rise < 1, height > 0")

    def at(s):
        x = np.interp(s, arc, path[:, 0])
        y = np.interp(s, arc, path[:, 1])
        k = np.clip(np.searchsorted(arc, s, side="right") - 1, 0, len(seg) - 1)
        e = seg[k] / np.hypot(seg[k, 0], seg[k, 1])[:, None] if np.ndim(s) else None
        return np.column_stack([x, y]), e

    s = pitch * np.arange(n)
    top, _ = at(s)
    bottom, e = at(s + (1.0 - rise) * pitch)
    left = np.column_stack([-e[:, 1], e[:, 0]])
    out = np.empty((2 * n + 1, 2))
    out[0:2 * n:2] = top
    out[1:2 * n:2] = bottom + height * left
    out[-1] = path[-1]
    return out


def _pocket_profile(texture) -> Manifold:
    """100 x 50 mm block, a trapezoid pocket 50 mm wide at the top, 20 mm deep,
    floor 24 mm wide; ``texture(path)`` cuts the pocket's flanks and floor."""
    pocket = np.array([[75.0, 50.0], [62.0, 30.0], [38.0, 30.0], [25.0, 50.0]])
    outline = np.vstack([[[0.0, 0.0], [100.0, 0.0], [100.0, 50.0]], texture(pocket),
                         [[0.0, 50.0]]])
    return place(polygon(outline).extrude(40.0))


@scene()
def textured_pocket(*, resolution: int = 8, pitch: float = 0.5,
                    height: float = 0.12) -> Manifold:
    """Trapezoid pocket whose flanks and floor carry a fine sawtooth (teeth of a few tol).

    Profile 100 x 50 mm, pocket 20 mm deep. Teeth every ``pitch`` mm,
    ``height`` mm deep (4 tol at the default eps), each with a steep face
    (a fifth of the pitch) looking back along the outline: a probe pushed
    up a tooth's steep face meets a wall, a pulled one slides off it.
    ``resolution`` is accepted for the registry (the profile is polygonal).
    """
    check_resolution(resolution)
    return _pocket_profile(lambda path: teeth(path, pitch, height, 0.2))


@scene()
def knurled_pocket(*, resolution: int = 8, pitch: float = 0.4,
                   height: float = 0.08) -> Manifold:
    """Trapezoid pocket whose flanks and floor carry a fine symmetric knurl.

    The pocket of :func:`textured_pocket` with symmetric V teeth every
    ``pitch`` mm, ``height`` mm deep: small irregularities with no
    preferred direction. ``resolution`` is accepted for the registry.
    """
    check_resolution(resolution)
    return _pocket_profile(lambda path: teeth(path, pitch, height, 0.5))
