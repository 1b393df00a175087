"""Per-slice Embree contact scene: in-plane rays against crossing triangles.

The scene holds the triangles that cross the plane
(:func:`slicer.contact.crossing.plane_crossing`), in the plane's own frame
``(p - origin) @ [u, v, normal].T``, cast to float32: coordinates stay
small (the origin is near the section centre) and a 2D ray ``(x, y), (dx,
dy)`` is the 3D ray ``(x, y, 0), (dx, dy, 0)`` with no per-call transform
(this is ``to_3d`` up to the rigid change of frame).

All scenes of a process share one ``embreex`` device
(:mod:`slicer.contact.embree_device`). One
``EmbreeScene.run(..., query='INTERSECT')`` per batch gives the first
triangle hit by each ray. The distance is then refined in float64 against
that triangle's section segment (precomputed per slice, ``segments``): the
ray is intersected with the segment's line, the segment parameter is clamped
to [0, 1] (a float32 hit on a neighbour at a shared vertex, or a grazing
ray, lands on the endpoint) and the distance is the projection of that point
on the ray. The normal is the segment's unit perpendicular oriented against
the ray. Robust mode is kept: without it ~4% of rays through vertices miss.

Embree is asked for the primitive only (``query='INTERSECT'``, whole ray);
``max_dist`` is applied to the refined float64 distance. Every batch is
refined ray by ray in compiled code (:mod:`slicer.contact.refine`: numpy's
per-call overhead dominates the small batches of a probe motion, and the
loop is ~6x faster than vectorised numpy on large ones).
:attr:`EmbreeContact.ray_kernel` gives compiled callers the same answer one
ray at a time (:mod:`slicer.contact.embree_direct`).
"""
from __future__ import annotations

import logging

import numpy as np
from embreex import mesh_construction, rtcore, rtcore_scene

from slicer.contact.crossing import plane_crossing
from slicer.contact.embree_device import PerProcess
from slicer.contact.embree_direct import DirectScene, ray_function
from slicer.contact.refine import NO_LIMITS, fill_fan, fill_rays, refine_hits
from slicer.degenerate import DEGENERATE_TOL, mesh_scale

__all__ = ["EmbreeContact", "SMALL_BATCH"]

logger = logging.getLogger(__name__)

SMALL_BATCH = 24
"""Batches up to this size keep their buffer views cached (a probe's fans)."""

_DEVICE = PerProcess(rtcore.EmbreeDevice)
"""The embreex device of every scene of this process (embreex would open one
per scene; see :mod:`slicer.contact.embree_device`)."""


class EmbreeContact:
    """Embree ray casting in one slice plane (the ``core2d`` contact contract).

    Parameters
    ----------
    mesh : trimesh.Trimesh
        Anything with ``vertices`` (v, 3) and ``faces`` (f, 3).
    plane : SlicePlane
        Should be non-degenerate (see :func:`slicer.degenerate.nudge_planes`);
        a warning is logged otherwise.
    scale : float or None
        :func:`slicer.degenerate.mesh_scale` of ``mesh`` when the caller knows it
        (a :class:`slicer.Slice` does: computed once per mesh, not once per plane).

    Attributes
    ----------
    face_index : (k,) int
        Mesh faces in the scene (those crossing the plane); Embree primitive
        ``i`` is face ``face_index[i]``.
    segments : (k, 2, 2) float
        Section segment of each scene triangle in the 2D frame.
    outward : (k, 2) float
        Unit outward in-plane normal of each segment.

    Notes
    -----
    ``cast`` reuses preallocated float32 ray buffers: use one instance per
    thread.

    Examples
    --------
    >>> import trimesh
    >>> from slicer.planes import make_planes
    >>> box = trimesh.creation.box(extents=[2.0, 2.0, 2.0])
    >>> plane = make_planes(box, "z", offsets=[0.3])[0]
    >>> ec = EmbreeContact(box, plane)
    >>> len(ec.face_index), len(box.faces)
    (8, 12)
    >>> d, p, n = ec.cast(np.array([[-3.0, 0.5]]), np.array([[1.0, 0.0]]), 10.0)
    >>> float(d[0]), p[0].tolist(), n[0].tolist()
    (2.0, [-1.0, 0.5], [-1.0, 0.0])
    """

    def __init__(self, mesh, plane, scale: float | None = None):
        self.plane = plane
        cut = plane_crossing(mesh, plane)
        z = cut.heights
        if scale is None:
            scale = mesh_scale(np.asarray(mesh.vertices, dtype=np.float64))
        near = np.abs(z).min() if len(z) else np.inf
        if near < DEGENERATE_TOL * scale:
            logger.warning(
                "plane %d passes within %.1e*scale of a vertex; contacts there "
                "are ill-defined (nudge the plane first)", plane.index, near / scale,
            )
        self.face_index = cut.face_index
        self.segments = cut.segments
        self.outward = cut.outward
        start = self.segments[:, 0]
        edge = self.segments[:, 1] - start
        table = np.hstack([start, edge, self.outward])  # (k, 6)
        self._table = np.ascontiguousarray(table)
        self._triangles = np.ascontiguousarray(cut.triangles, dtype=np.float32)
        self._scene = None
        self._kernel = None
        if len(self._triangles):
            self._scene = rtcore_scene.EmbreeScene(_DEVICE.get(), robust=True)
            mesh_construction.TriangleMesh(self._scene, self._triangles)
        self._cap = 0
        self._grow(64)

    @property
    def scene(self):
        """The ``embreex`` scene (None when no triangle crosses the plane)."""
        return self._scene

    @property
    def ray_kernel(self):
        """``(address, context)`` of the compiled one-ray function of this
        scene (:mod:`slicer.contact.embree_direct`: the same answers as :meth:`cast`,
        callable from compiled code), or None when there is nothing to hit
        or no Embree library to call directly. Built on first use."""
        if self._kernel is None:
            address = ray_function() if self._scene is not None else 0
            self._direct = DirectScene(self._triangles, self._table) if address else None
            self._kernel = (address, self._direct.context) if address else False
        return self._kernel or None

    @property
    def triangles(self) -> np.ndarray:
        """(k, 3, 3) float32 scene triangles in the plane frame."""
        return self._triangles

    def rays3d(self, origins, dirs):
        """2D rays -> float32 scene-frame rays ``((n, 3), (n, 3))`` (for benchmarks)."""
        o = np.zeros((len(origins), 3), np.float32)
        d = np.zeros((len(dirs), 3), np.float32)
        o[:, :2], d[:, :2] = origins, dirs
        return o, d

    def _grow(self, n):
        cap = max(n, 2 * self._cap)
        self._o32 = np.zeros((cap, 3), np.float32)
        self._d32 = np.zeros((cap, 3), np.float32)
        self._o64 = np.zeros((cap, 2))
        self._d64 = np.zeros((cap, 2))
        self._cap = cap
        self._views = {}  # n -> the first n rows of the buffers (Embree reads whole arrays)
        self._fan_views = {}  # n -> the first n rows of the float64 fan buffers

    def _view(self, n):
        """The first n rows of the float32 ray buffers (kept for small n)."""
        views = (self._o32[:n], self._d32[:n])
        if n <= SMALL_BATCH:
            self._views[n] = views
        return views

    def fan(self, origin, angles, max_dist):
        """``cast`` of the rays from one ``origin`` at ``angles``, fused.

        The same rays as ``cast(origin repeated, (cos, sin) of angles,
        max_dist)`` and the same answer (same kernels), built in compiled
        code: a probe swing casts thousands of such small fans.

        Parameters
        ----------
        origin : (2,) float
        angles : (n,) float
        max_dist : float

        Returns
        -------
        distances : (n,) float
        points : (n, 2) float
        """
        n = len(angles)
        if n == 0 or self._scene is None:
            return self._all_miss(n)[:2]
        if n > self._cap:
            self._grow(n)
        views = self._views.get(n)
        if views is None:
            views = self._view(n)
        rays = self._fan_views.get(n)
        if rays is None:
            rays = (self._o64[:n], self._d64[:n])
            if n <= SMALL_BATCH:
                self._fan_views[n] = rays
        fill_fan(float(origin[0]), float(origin[1]), angles, rays[0], rays[1],
                 self._o32, self._d32)
        prim = self._scene.run(views[0], views[1], query="INTERSECT")
        res = np.empty((n, 5))
        refine_hits(self._table, prim, rays[0], rays[1], float(max_dist), NO_LIMITS, res)
        return res[:, 0], res[:, 1:3]

    def cast(self, origins, dirs, max_dist):
        """First contour hit of each in-plane ray (one Embree call).

        Parameters
        ----------
        origins : (n, 2) float
        dirs : (n, 2) float
            Unit directions.
        max_dist : (n,) float or float

        Returns
        -------
        distances : (n,) float
            ``inf`` where nothing is hit within ``max_dist``.
        points : (n, 2) float
            ``nan`` for misses.
        normals : (n, 2) float
            Unit, ``normals . dirs <= 0``, ``nan`` for misses.
        """
        o = np.asarray(origins, dtype=np.float64)
        d = np.asarray(dirs, dtype=np.float64)
        if o.ndim != 2:
            o = o.reshape(-1, 2)
            d = d.reshape(-1, 2)
        n = len(o)
        if n == 0 or self._scene is None:
            return self._all_miss(n)
        if n > self._cap:
            self._grow(n)
        fill_rays(o, d, self._o32, self._d32)
        views = self._views.get(n)
        if views is None:
            views = self._view(n)
        # Embree searches the whole ray; max_dist is applied in float64
        prim = self._scene.run(views[0], views[1], query="INTERSECT")
        kind = type(max_dist)
        if kind is float or kind is np.float64 or kind is int:
            md, limits = float(max_dist), NO_LIMITS
        elif kind is np.ndarray and max_dist.shape == (n,) and max_dist.dtype == np.float64:
            md, limits = 0.0, max_dist  # per-ray limits as given (no broadcast_to: ~5 us)
        else:
            md, limits = 0.0, np.broadcast_to(np.asarray(max_dist, dtype=np.float64), (n,))
        res = np.empty((n, 5))
        refine_hits(self._table, prim, o, d, md, limits, res)
        return res[:, 0], res[:, 1:3], res[:, 3:5]

    @staticmethod
    def _all_miss(n):
        return np.full(n, np.inf), np.full((n, 2), np.nan), np.full((n, 2), np.nan)
