"""Small manifold3d helpers shared by the scene modules.

Profiles are ``(n, 2)`` float arrays of polygon vertices in the x-y plane;
solids are :class:`manifold3d.Manifold`. Circle segment counts are always
passed explicitly, so manifold3d's global quality defaults
(``set_circular_segments``) are never read or changed.
"""
from __future__ import annotations

import math

import numpy as np
import trimesh
from manifold3d import CrossSection, Manifold

from .errors import MeshError

__all__ = [
    "check_resolution",
    "share",
    "polygon",
    "circle",
    "rect",
    "place",
    "to_trimesh",
]


def check_resolution(resolution: int, minimum: int = 8) -> int:
    """Return ``resolution`` as an int, or raise :class:`MeshError` if it is
    not an integer ``>= minimum``."""
    if isinstance(resolution, bool) or not isinstance(resolution, (int, np.integer)):
        raise MeshError(f"resolution must be an integer, got {resolution!r}")
    if resolution < minimum:
        raise MeshError(f"resolution must be >= {minimum}, got {resolution}")
    return int(resolution)


def share(resolution: int, fraction: float, minimum: int = 2) -> int:
    """Segments for an arc that is ``fraction`` of a full turn, at
    ``resolution`` segments per full turn (at least ``minimum``)."""
    return max(minimum, math.ceil(resolution * fraction - 1e-9))


def polygon(points) -> CrossSection:
    """A :class:`CrossSection` from one simple polygon, either orientation.

    Parameters
    ----------
    points : (n, 2) float
        Vertices, not repeating the first one at the end.
    """
    pts = np.asarray(points, dtype=np.float64)
    x, y = pts[:, 0], pts[:, 1]
    signed = 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
    if signed < 0:  # FillRule.Positive would drop a clockwise contour
        pts = pts[::-1]
    section = CrossSection([np.ascontiguousarray(pts)])
    if section.num_contour() != 1:
        raise MeshError("internal: profile polygon is not simple")
    return section


def circle(center, radius: float, segments: int) -> CrossSection:
    """A regular ``segments``-gon inscribed in the circle."""
    return CrossSection.circle(radius, segments).translate(tuple(center))


def rect(x0: float, y0: float, x1: float, y1: float) -> CrossSection:
    """Axis-aligned rectangle ``[x0, x1] x [y0, y1]``."""
    return CrossSection.square((x1 - x0, y1 - y0)).translate((x0, y0))


def place(solid: Manifold) -> Manifold:
    """Translate ``solid`` so its bounding-box minimum corner is the origin."""
    lo = solid.bounding_box()[:3]
    return solid.translate((-lo[0], -lo[1], -lo[2]))


def to_trimesh(solid: Manifold, units: str | None = "mm") -> trimesh.Trimesh:
    """Convert a Manifold to a float64 :class:`trimesh.Trimesh`.

    Vertices are ``(n, 3)`` float64 from ``to_mesh64``; faces ``(m, 3)`` int64
    keep manifold3d's outward (counter-clockwise) winding. Faces are kept
    as they are (``len(faces) == solid.num_tri()``); vertices no face uses
    are dropped (``Manifold.revolve`` can leave one on the axis).
    """
    mesh64 = solid.to_mesh64()
    vertices = np.asarray(mesh64.vert_properties, dtype=np.float64)[:, :3]
    faces = np.asarray(mesh64.tri_verts, dtype=np.int64)
    used = np.zeros(len(vertices), dtype=bool)
    used[faces.ravel()] = True
    if not used.all():
        remap = np.cumsum(used) - 1
        vertices, faces = vertices[used], remap[faces]
    mesh = trimesh.Trimesh(vertices=vertices, faces=faces, process=False)
    if units is not None:
        mesh.units = units
    return mesh
