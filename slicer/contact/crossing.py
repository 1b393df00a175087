"""The triangles that cross a slice plane and their section segments.

Shared by the mesh-based contact models (:mod:`slicer.contact.embree`,
:mod:`slicer.contact.trimesh_ray`): an in-plane ray hits the triangles that
cross the plane exactly where the cross-section contour is, so their scenes
hold only those triangles, in the plane's own frame
``(p - origin) @ [u, v, normal].T``. Pure numpy: no ray engine is imported.

Examples
--------
>>> import trimesh
>>> from slicer.planes import make_planes
>>> box = trimesh.creation.box(extents=[2.0, 2.0, 2.0])
>>> cut = plane_crossing(box, make_planes(box, "z", offsets=[0.3])[0])
>>> cut.heights.shape, cut.face_index.shape, cut.triangles.shape, cut.segments.shape
((8,), (8,), (8, 3, 3), (8, 2, 2))
>>> bool(np.all(np.abs(cut.outward).sum(axis=1) == 1.0))
True
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["PlaneCrossing", "plane_crossing", "crossing_faces", "section_segments"]


@dataclass(frozen=True)
class PlaneCrossing:
    """The mesh triangles crossing one plane, in the plane's frame.

    Attributes
    ----------
    heights : (v,) float
        Signed height of every mesh vertex above the plane.
    face_index : (k,) int
        Mesh faces crossing the plane with a non-degenerate segment.
    triangles : (k, 3, 3) float
        Those faces, coordinates ``(x, y, z)`` in the plane frame.
    segments : (k, 2, 2) float
        Their section segments in the 2D frame (see :func:`section_segments`).
    outward : (k, 2) float
        Unit outward in-plane normal of each segment.
    """

    heights: np.ndarray
    face_index: np.ndarray
    triangles: np.ndarray
    segments: np.ndarray
    outward: np.ndarray


def plane_crossing(mesh, plane) -> PlaneCrossing:
    """The triangles of ``mesh`` that cross ``plane``, with their segments.

    Faces that only touch the plane (a zero-length segment) are left out.

    Parameters
    ----------
    mesh : trimesh.Trimesh
        Anything with ``vertices`` (v, 3) and ``faces`` (f, 3).
    plane : SlicePlane

    Returns
    -------
    PlaneCrossing
    """
    vertices = np.asarray(mesh.vertices, dtype=np.float64)
    faces = np.asarray(mesh.faces)
    local_v = (vertices - plane.origin) @ plane.basis.T
    z = local_v[:, 2]
    above = z > 0  # per vertex, then per face corner: no (f, 3) float gather
    idx = _mixed(above[faces[:, 0]], above[faces[:, 1]], above[faces[:, 2]])
    local = local_v[faces[idx]]
    seg, outward = section_segments(local)
    keep = np.any(seg[:, 0] != seg[:, 1], axis=1)  # touching-only faces
    return PlaneCrossing(z, idx[keep], local[keep], seg[keep], outward[keep])


def crossing_faces(heights_per_face) -> np.ndarray:
    """Indices of faces whose vertices lie on both sides of the plane.

    Parameters
    ----------
    heights_per_face : (m, 3) float
        Signed vertex heights of each face. A height of exactly 0 counts as
        below the plane (half-open convention), so every selected face has
        exactly two crossing edges.

    Returns
    -------
    (k,) int
    """
    above = np.asarray(heights_per_face) > 0
    return _mixed(above[:, 0], above[:, 1], above[:, 2])


def _mixed(a, b, c) -> np.ndarray:
    """Indices where the (m,) bools ``a``, ``b``, ``c`` are not all equal: "any and not
    all" of each row, without numpy's slow reductions along rows of 3."""
    return np.flatnonzero((a != b) | (a != c))


def section_segments(local) -> tuple[np.ndarray, np.ndarray]:
    """Section segments of crossing triangles given in a plane frame.

    Parameters
    ----------
    local : (k, 3, 3) float
        Crossing triangles, coordinates ``(x, y, z)`` in the plane frame
        (``z`` = signed height).

    Returns
    -------
    segments : (k, 2, 2) float
        Start and end of each segment, oriented so that the face's outward
        in-plane normal is on the right (outer loops run CCW).
    outward : (k, 2) float
        Unit right-hand perpendicular ``(ey, -ex) / |e|`` (zero for a
        zero-length segment).
    """
    z = local[..., 2]
    a, b = local, np.roll(local, -1, axis=1)  # edges 0-1, 1-2, 2-0
    za, zb = z, np.roll(z, -1, axis=1)
    cross = (za > 0) != (zb > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(cross, za / (za - zb), 0.0)
    pts = a[..., :2] + t[..., None] * (b[..., :2] - a[..., :2])
    seg = pts[cross].reshape(-1, 2, 2)
    fn = np.cross(local[:, 1] - local[:, 0], local[:, 2] - local[:, 0])[:, :2]
    e = seg[:, 1] - seg[:, 0]
    right = np.stack([e[:, 1], -e[:, 0]], axis=1)
    flip = np.einsum("ij,ij->i", right, fn) < 0
    seg[flip] = seg[flip][:, ::-1]
    right[flip] *= -1
    length = np.hypot(right[:, 0], right[:, 1])
    with np.errstate(divide="ignore", invalid="ignore"):
        unit = np.where(length[:, None] > 0, right / length[:, None], 0.0)
    return seg, unit
