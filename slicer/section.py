"""Reference cross-sections: closed loops of a mesh in each plane's 2D frame.

Watertight meshes (those manifold3d accepts) are sliced with manifold3d: one ``Manifold`` is built from
the mesh (float64), rotated once per normal so that the plane frame
``(u, v, normal)`` becomes ``(x, y, z)``, and cut with ``Manifold.slice``.
Other meshes (or meshes manifold3d rejects) fall back to trimesh's
``section_multiplane``; open chains found there are kept apart in
``Section.open_chains``.

Loops follow the shapely orientation convention: outer loops
counter-clockwise, holes clockwise, last vertex not repeated, no repeated
consecutive vertices.

Examples
--------
>>> import trimesh
>>> from slicer.planes import make_planes
>>> box = trimesh.creation.box(extents=[2.0, 1.0, 1.0])
>>> (sec,) = sections(box, make_planes(box, "z", count=1))
>>> sec.method, len(sec.loops), sec.holes.tolist(), round(sec.area, 12)
('manifold', 1, [False], 2.0)
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from slicer.degenerate import mesh_scale

__all__ = ["Section", "sections", "signed_area", "clean_loop", "to_manifold"]


@dataclass(frozen=True, eq=False)
class Section:
    """Cross-section of a mesh by one plane, in the plane's 2D frame.

    Attributes
    ----------
    loops : tuple of (k, 2) float
        Closed loops, outer CCW, holes CW, last vertex not repeated.
    holes : (len(loops),) bool
        True where the loop is a hole.
    open_chains : tuple of (k, 2) float
        Polylines that did not close (only from the trimesh fallback on
        non-watertight meshes).
    method : str
        ``"manifold"`` or ``"trimesh"``.
    """

    loops: tuple = ()
    holes: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=bool))
    open_chains: tuple = ()
    method: str = ""

    @property
    def area(self) -> float:
        """Signed area sum (holes subtract)."""
        return float(sum(signed_area(lp) for lp in self.loops))

    @property
    def is_empty(self) -> bool:
        return not self.loops and not self.open_chains


def signed_area(loop) -> float:
    """Shoelace area of a closed (k, 2) loop, positive when CCW."""
    p = np.asarray(loop, dtype=np.float64)
    if len(p) < 3:
        return 0.0
    x, y = p[:, 0] - p[0, 0], p[:, 1] - p[0, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def clean_loop(loop, closed: bool = True) -> np.ndarray:
    """Drop repeated consecutive vertices (and the closing repeat).

    Parameters
    ----------
    loop : (k, 2) float
    closed : bool
        Treat the last vertex as adjacent to the first.

    Returns
    -------
    (j, 2) float
    """
    p = np.asarray(loop, dtype=np.float64)
    if len(p) < 2:
        return p
    nxt = np.roll(p, -1, axis=0) if closed else np.vstack([p[1:], [np.nan, np.nan]])
    keep = np.any(p != nxt, axis=1)
    if not keep.any():
        return p[:1]
    return p[keep]


def to_manifold(mesh):
    """trimesh -> ``manifold3d.Manifold`` (float64), or None if rejected."""
    import manifold3d

    # fresh writeable copies: nanobind rejects read-only arrays
    verts = np.array(mesh.vertices, dtype=np.float64, order="C")
    faces = np.array(mesh.faces, dtype=np.uint64, order="C")
    if len(faces) == 0:
        return None
    man = manifold3d.Manifold(manifold3d.Mesh64(vert_properties=verts, tri_verts=faces))
    if man.status() != manifold3d.Error.NoError or man.is_empty():
        return None
    if man.volume() < 0:  # pragma: no cover - manifold keeps orientation
        return None
    return man


_CLIPPER_SIZE = 2.0**20
"""Sections are cut at this size: manifold3d's CrossSection (Clipper2) rounds
coordinates to 1e-8 absolute, i.e. ~1e-8 * scale for metre-sized meshes;
at 2**20 the rounding is ~1e-14 * scale."""


def _frame_transform(plane, center, k) -> np.ndarray:
    """(3, 4) world -> frame transform, ``center`` to 0, scaled by ``k``."""
    r = plane.basis * k
    return np.hstack([r, -(r @ center)[:, None]])


def _manifold_sections(man, planes, scale) -> list[Section]:
    c = planes[0].origin
    # power of two: scaling there and back is exact in floating point
    k = 2.0 ** np.round(np.log2(_CLIPPER_SIZE / scale)) if scale > 0 else 1.0
    moved = man.transform(_frame_transform(planes[0], c, k))
    c_h = float(c @ planes[0].normal)
    out = []
    for p in planes:
        shift = p.to_2d(c[None, :])[0]  # c in this plane's frame
        loops, holes = [], []
        for poly in moved.slice(k * (p.offset - c_h)).to_polygons():
            lp = clean_loop(np.asarray(poly, dtype=np.float64) / k + shift)
            a = signed_area(lp)
            if len(lp) < 3 or a == 0.0:
                continue
            loops.append(lp)
            holes.append(a < 0)
        out.append(Section(tuple(loops), np.array(holes, dtype=bool), (), "manifold"))
    return out


def _orient_by_nesting(loops):
    """Outer (even nesting depth) CCW, holes (odd depth) CW."""
    import shapely

    if not loops:
        return [], np.zeros(0, dtype=bool)
    polys = [shapely.Polygon(lp) for lp in loops]
    holes = []
    out = []
    for i, lp in enumerate(loops):
        probe = lp[0]
        depth = sum(
            bool(shapely.contains_xy(polys[j], probe[0], probe[1]))
            for j in range(len(loops))
            if j != i
        )
        hole = depth % 2 == 1
        ccw = signed_area(lp) > 0
        out.append(lp if ccw != hole else lp[::-1].copy())
        holes.append(hole)
    return out, np.array(holes, dtype=bool)


def _trimesh_sections(mesh, planes) -> list[Section]:
    c = planes[0].origin
    n = planes[0].normal
    heights = np.array([p.offset for p in planes]) - float(c @ n)
    paths = mesh.section_multiplane(plane_origin=c, plane_normal=n, heights=heights)
    out = []
    for p, path in zip(planes, paths):
        if path is None or len(path.entities) == 0:
            out.append(Section((), np.zeros(0, dtype=bool), (), "trimesh"))
            continue
        t = np.asarray(path.metadata["to_3D"], dtype=np.float64)
        v2 = np.asarray(path.vertices, dtype=np.float64)
        v3 = v2 @ t[:3, :2].T + t[:3, 3]
        v = p.to_2d(v3)
        loops, chains = [], []
        for ent in path.entities:
            pts = v[np.asarray(ent.points)]
            if ent.closed and len(pts) >= 4:
                lp = clean_loop(pts[:-1])
                if len(lp) >= 3 and signed_area(lp) != 0.0:
                    loops.append(lp)
                    continue
            chain = clean_loop(pts, closed=False)
            if len(chain) >= 2:  # trimesh leaves zero-length bits at vertices
                chains.append(chain)
        loops, holes = _orient_by_nesting(loops)
        out.append(Section(tuple(loops), holes, tuple(chains), "trimesh"))
    return out


def sections(mesh, planes, method: str = "auto", scale=None) -> list[Section]:
    """Cross-sections of a mesh by a list of planes.

    Parameters
    ----------
    mesh : trimesh.Trimesh
    planes : list of SlicePlane
    method : {'auto', 'manifold', 'trimesh'}
        ``auto`` uses manifold3d when it accepts the mesh (closed, oriented
        2-manifold, i.e. watertight), trimesh otherwise.
    scale : float, optional
        Bounding box diagonal, if already known.

    Returns
    -------
    list of Section
        One per plane, in order.
    """
    if method not in ("auto", "manifold", "trimesh"):
        raise ValueError(f"method must be 'auto', 'manifold' or 'trimesh', got {method!r}")
    planes = list(planes)
    if not planes:
        return []
    man = None
    if method != "trimesh":
        # manifold3d accepts exactly the closed oriented 2-manifolds, so it
        # doubles as the watertightness test (trimesh's costs ~40 ms/100k faces)
        man = to_manifold(mesh)
        if man is None and method == "manifold":
            raise ValueError("manifold3d rejected the mesh (not an oriented 2-manifold)")
    groups: dict[tuple, list[int]] = {}  # planes sharing a frame (u, v, normal)
    for i, p in enumerate(planes):
        groups.setdefault(tuple(p.basis.ravel().tolist()), []).append(i)
    out: list = [None] * len(planes)
    for idx in groups.values():
        fam = [planes[i] for i in idx]
        if man is not None:
            res = _manifold_sections(man, fam, mesh_scale(mesh) if scale is None else scale)
        else:
            res = _trimesh_sections(mesh, fam)
        for i, s in zip(idx, res):
            out[i] = s
    return out
