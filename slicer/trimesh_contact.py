"""Per-slice contact through trimesh's generic ray engine (no Embree).

The backend a user without Embree would reach for: the triangles that cross
the plane, in the plane's own frame (float64, as :mod:`slicer.embree_contact`
builds them), queried with ``trimesh.ray.ray_triangle.RayMeshIntersector``
(pure numpy, an R-tree of triangle bounds for candidates). One
``intersects_id(..., multiple_hits=False)`` call per batch gives the first
triangle each ray hits; the contact distance is the hit's projection on the
ray, the normal the unit perpendicular of that triangle's section segment
oriented against the ray (the Embree backend's rule). It exists for the
backend benchmark and the stability study; it answers the contract of
:mod:`core2d.sim.contact`.

Examples
--------
>>> import trimesh
>>> from slicer.planes import make_planes
>>> box = trimesh.creation.box(extents=[2.0, 2.0, 2.0])
>>> plane = make_planes(box, "z", offsets=[0.3])[0]
>>> tc = TrimeshContact(box, plane)
>>> d, p, n = tc.cast(np.array([[-3.0, 0.5]]), np.array([[1.0, 0.0]]), 10.0)
>>> float(d[0]), p[0].tolist(), n[0].tolist()
(2.0, [-1.0, 0.5], [-1.0, 0.0])
"""
from __future__ import annotations

import numpy as np

from slicer.embree_contact import crossing_faces, section_segments

__all__ = ["TrimeshContact"]


class TrimeshContact:
    """trimesh ray casting in one slice plane (the ``core2d`` contact contract).

    Parameters
    ----------
    mesh : trimesh.Trimesh
        Anything with ``vertices`` (v, 3) and ``faces`` (f, 3).
    plane : SlicePlane

    Attributes
    ----------
    face_index : (k,) int -- mesh faces crossing the plane (the scene).
    segments : (k, 2, 2) float -- their section segments in the 2D frame.
    """

    def __init__(self, mesh, plane):
        import trimesh
        from trimesh.ray.ray_triangle import RayMeshIntersector

        vertices = np.asarray(mesh.vertices, dtype=np.float64)
        faces = np.asarray(mesh.faces)
        local_v = (vertices - plane.origin) @ plane.basis.T
        idx = crossing_faces(local_v[:, 2][faces])
        local = local_v[faces[idx]]
        seg, outward = section_segments(local)
        keep = np.any(seg[:, 0] != seg[:, 1], axis=1)
        self.face_index = idx[keep]
        self.segments = seg[keep]
        self.outward = outward[keep]
        self._engine = None
        if keep.any():
            tris = local[keep]
            scene = trimesh.Trimesh(tris.reshape(-1, 3), np.arange(3 * len(tris)).reshape(-1, 3),
                                    process=False)
            self._engine = RayMeshIntersector(scene)

    def cast(self, origins, dirs, max_dist):
        """First contour hit of each in-plane ray (one trimesh query).

        Parameters
        ----------
        origins, dirs : (n, 2) float -- ray origins and unit directions.
        max_dist : (n,) float or float

        Returns
        -------
        distances (n,) float (``inf`` on a miss), points (n, 2), normals (n, 2)
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
