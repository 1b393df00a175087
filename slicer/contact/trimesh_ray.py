"""Per-slice contact through trimesh's generic ray engine (no Embree).

The backend a user without Embree would reach for (it loads without
``embreex``): the triangles that cross the plane, in the plane's own frame
(float64, :func:`slicer.contact.crossing.plane_crossing`), queried with
``trimesh.ray.ray_triangle.RayMeshIntersector`` (pure numpy, an R-tree of
triangle bounds for candidates). One
``intersects_id(..., multiple_hits=False)`` call per batch gives the first
triangle each ray hits; the contact distance is the hit's projection on the
ray, the normal the unit perpendicular of that triangle's section segment
oriented against the ray (the Embree backend's rule). It exists for the
backend benchmark and the stability study; it answers the contract of
:mod:`core2d.sim.contact`.

Examples
--------
>>> import trimesh
>>> from slicer import slice_mesh
>>> (cut,) = slice_mesh(trimesh.creation.box(extents=[2.0, 2.0, 2.0]), "z", offsets=[0.3])
>>> tc = TrimeshContact(cut.mesh, cut.plane)
>>> d, p, n = tc.cast(np.array([[-3.0, 0.5], [0.0, 0.0]]), np.array([[1.0, 0.0], [0.0, 1.0]]), 10.0)
>>> d.tolist(), p.tolist(), n.tolist()
([2.0, 1.0], [[-1.0, 0.5], [0.0, 1.0]], [[-1.0, 0.0], [0.0, -1.0]])
"""
from __future__ import annotations

import numpy as np

from slicer.contact.crossing import plane_crossing

__all__ = ["TrimeshContact"]


class TrimeshContact:
    """trimesh ray casting in one slice plane (the ``core2d`` contact contract).

    Parameters
    ----------
    mesh, plane : trimesh.Trimesh, SlicePlane
        The mesh (``vertices`` (v, 3), ``faces`` (f, 3)) and the plane, as
        :func:`slicer.contact.crossing.plane_crossing` takes them.

    Attributes
    ----------
    face_index, segments, outward : (k,) int, (k, 2, 2) float, (k, 2) float
        The crossing faces, their section segments and outward normals
        (:class:`slicer.contact.crossing.PlaneCrossing`); the scene holds
        the faces in this order.
    """

    def __init__(self, mesh, plane):
        import trimesh
        from trimesh.ray.ray_triangle import RayMeshIntersector

        cut = plane_crossing(mesh, plane)
        self.face_index = cut.face_index
        self.segments = cut.segments
        self.outward = cut.outward
        self._engine = None
        if len(cut.triangles):
            tris = cut.triangles
            scene = trimesh.Trimesh(tris.reshape(-1, 3), np.arange(3 * len(tris)).reshape(-1, 3),
                                    process=False)
            self._engine = RayMeshIntersector(scene)

    def cast(self, origins, dirs, max_dist):
        """First contour hit of each in-plane ray (one trimesh query).

        Parameters
        ----------
        origins, dirs : (n, 2) float
            Ray origins and unit directions.
        max_dist : (n,) float or float

        Returns
        -------
        distances : (n,) float
            ``inf`` on a miss (the contract of :mod:`core2d.sim.contact`).
        points, normals : (n, 2) float
            ``nan`` on a miss; normals point against the rays.
        """
        o = np.atleast_2d(np.asarray(origins, dtype=np.float64))
        d = np.atleast_2d(np.asarray(dirs, dtype=np.float64))
        n = len(o)
        max_dist = np.broadcast_to(np.asarray(max_dist, dtype=np.float64), (n,))
        dist = np.full(n, np.inf)
        points = np.full((n, 2), np.nan)
        normals = np.full((n, 2), np.nan)
        if n == 0 or self._engine is None:
            return dist, points, normals
        o3 = np.zeros((n, 3))
        d3 = np.zeros((n, 3))
        o3[:, :2], d3[:, :2] = o, d
        tri, ray, loc = self._engine.intersects_id(o3, d3, multiple_hits=False,
                                                   return_locations=True)
        if len(tri) == 0:
            return dist, points, normals
        loc = np.asarray(loc, dtype=np.float64).reshape(-1, 3)
        s = np.einsum("ij,ij->i", loc[:, :2] - o[ray], d[ray])
        ok = (s >= 0) & (s <= max_dist[ray])
        tri, ray, s = tri[ok], ray[ok], s[ok]
        dist[ray] = s
        points[ray] = o[ray] + s[:, None] * d[ray]
        nrm = self.outward[tri].copy()
        flip = np.einsum("ij,ij->i", nrm, d[ray]) > 0
        nrm[flip] *= -1
        normals[ray] = nrm + 0.0
        return dist, points, normals
