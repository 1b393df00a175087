"""Slices of a mesh: plane + reference contour + contact models.

Examples
--------
>>> import trimesh
>>> mesh = trimesh.creation.box(extents=[4.0, 2.0, 1.0])
>>> (s,) = slice_mesh(mesh, axis="z", count=1)
>>> len(s.loops), s.holes.tolist(), s.plane.nudge
(1, [False], 0.0)
>>> center, radius = s.bounding_circle()
>>> center.tolist(), round(radius, 6)
([0.0, 0.0], 2.236068)
>>> d, p, n = s.contact("embree").cast(np.array([[-5.0, 0.0]]), np.array([[1.0, 0.0]]), 9.0)
>>> float(d[0]), n[0].tolist()
(3.0, [-1.0, 0.0])
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from slicer.contact import contact_class
from slicer.degenerate import mesh_scale, nudge_planes
from slicer.planes import SlicePlane, make_planes
from slicer.section import sections

__all__ = ["Slice", "slice_mesh"]


@dataclass(frozen=True, eq=False)
class Slice:
    """One planar slice of a mesh.

    Attributes
    ----------
    plane : SlicePlane
        The (possibly nudged) plane and its 2D frame.
    loops : tuple of (k, 2) float
        Reference contour in the 2D frame: outer loops CCW, holes CW.
    holes : (len(loops),) bool
        Hole flag per loop.
    open_chains : tuple of (k, 2) float
        Unclosed polylines (non-watertight meshes only).
    scale : float
        Diagonal of the mesh bounding box (the unit of tolerances).
    method : str
        How the reference contour was computed (``manifold`` / ``trimesh``).
    mesh : trimesh.Trimesh
        The source mesh (for the mesh backends, ``embree`` and ``trimesh``).
    """

    plane: SlicePlane
    loops: tuple
    holes: np.ndarray
    open_chains: tuple
    scale: float
    method: str
    mesh: object = field(repr=False)
    _backends: dict = field(default_factory=dict, init=False, repr=False)

    @property
    def index(self) -> int:
        return self.plane.index

    @property
    def is_empty(self) -> bool:
        return not self.loops and not self.open_chains

    def contact(self, backend: str = "embree"):
        """The contact model of this slice (built once, then cached here).

        Parameters
        ----------
        backend : {'embree', 'exact', 'trimesh'}
            ``embree``: :class:`~slicer.contact.embree.EmbreeContact` on the
            triangles crossing the plane (needs ``embreex``); ``exact``:
            :class:`~slicer.contact.exact.ExactContact` on the reference
            contour; ``trimesh``:
            :class:`~slicer.contact.trimesh_ray.TrimeshContact` (trimesh's
            generic ray engine on the crossing triangles).

        Returns
        -------
        object with ``cast(origins, dirs, max_dist)``

        Raises
        ------
        ValueError
            For an unknown backend; ImportError for ``'embree'`` without
            ``embreex`` (see :func:`slicer.contact.contact_class`).
        """
        model = self._backends.get(backend)
        if model is None:
            cls = contact_class(backend)
            if backend == "exact":
                model = cls(self.loops, chains=self.open_chains)
            elif backend == "embree":  # the mesh's scale, known here
                model = cls(self.mesh, self.plane, scale=self.scale)
            else:
                model = cls(self.mesh, self.plane)
            self._backends[backend] = model
        return model

    def points(self) -> np.ndarray:
        """(k, 2) float: all contour vertices (loops and open chains)."""
        parts = [np.asarray(p) for p in (*self.loops, *self.open_chains)]
        return np.concatenate(parts) if parts else np.zeros((0, 2))

    def bounding_circle(self) -> tuple[np.ndarray, float]:
        """A circle containing the whole section: what the robot knows.

        The centre is the centre of the section's 2D bounding box and the
        radius the largest distance from it to a contour vertex (not the
        minimal circle, but within a factor sqrt(2) of it).

        Returns
        -------
        center : (2,) float
        radius : float
        """
        pts = self.points()
        if len(pts) == 0:
            raise ValueError(f"slice {self.index} is empty: no bounding circle")
        center = 0.5 * (pts.min(axis=0) + pts.max(axis=0))
        radius = float(np.sqrt(((pts - center) ** 2).sum(axis=1).max()))
        return center, radius

    def to_3d(self, points) -> np.ndarray:
        """2D frame points (n, 2) -> world (n, 3)."""
        return self.plane.to_3d(points)


def slice_mesh(
    mesh,
    axis="z",
    count=None,
    spacing=None,
    offsets=None,
    method: str = "auto",
    nudge: bool = True,
) -> list[Slice]:
    """Cut a mesh with a family of parallel planes.

    Parameters
    ----------
    mesh : trimesh.Trimesh
    axis : {'x', 'y', 'z'}, str 'nx,ny,nz' or (3,) float
        Plane normal (see :func:`slicer.planes.make_planes`).
    count, spacing, offsets
        Exactly one: the plane family (see :func:`slicer.planes.make_planes`).
    method : {'auto', 'manifold', 'trimesh'}
        Reference contour method (see :func:`slicer.section.sections`).
    nudge : bool
        Move degenerate planes (through vertices / along faces) by a tiny
        reported offset (see :mod:`slicer.degenerate`). Keep it on unless
        studying degeneracy itself.

    Returns
    -------
    list of Slice
    """
    planes = make_planes(mesh, axis=axis, count=count, spacing=spacing, offsets=offsets)
    if nudge:
        planes = nudge_planes(planes, mesh)
    scale = mesh_scale(mesh)
    secs = sections(mesh, planes, method=method, scale=scale)
    return [
        Slice(
            plane=p,
            loops=s.loops,
            holes=s.holes,
            open_chains=s.open_chains,
            scale=scale,
            method=s.method,
            mesh=mesh,
        )
        for p, s in zip(planes, secs)
    ]
