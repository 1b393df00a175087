"""Degenerate planes: detect cuts through vertices or along faces, move them.

A plane within ``tol * scale`` of some vertex height (``p . normal``), or
containing faces, gives sections with zero-length edges, touching points and
coplanar faces: Embree and the exact reference disagree there for reasons of
bookkeeping rather than geometry. Such a plane is moved along its normal to
the first of ``+step, -step, +2 step, -2 step, ...`` (``step`` a multiple of
``scale``) that is clear of every vertex height by at least ``tol * scale``
and still strictly inside the mesh extent. The move is recorded on the
plane (``nudge``, ``nudge_reason``) and logged as one warning per call.
``scale`` is the diagonal of the mesh's axis-aligned bounding box.

Detection and the search are vectorised over all planes: vertex heights are
sorted once per normal and every query is a ``np.searchsorted``.

Examples
--------
>>> import trimesh
>>> from slicer.planes import make_planes
>>> box = trimesh.creation.box()            # vertices at z = -0.5 and 0.5
>>> planes = make_planes(box, "z", offsets=[0.0, 0.25])
>>> moved = nudge_planes(planes, box, log=False)
>>> [p.nudge for p in moved]
[0.0, 0.0]
>>> box2 = trimesh.creation.box(bounds=[[0, 0, 0], [1, 1, 2]])
>>> box2 = box2.subdivide()                 # adds vertices (and faces) at z = 1
>>> p = nudge_planes(make_planes(box2, "z", count=1), box2, log=False)[0]
>>> round(p.nudge / mesh_scale(box2), 6), p.nudge_reason.split(";")[0]
(1e-05, '8 vertices within 1e-06*scale (0 faces in plane)')
"""
from __future__ import annotations

import logging

import numpy as np

from slicer.planes import SlicePlane

__all__ = [
    "DEGENERATE_TOL",
    "NUDGE_STEP",
    "mesh_scale",
    "vertex_clearance",
    "nudge_planes",
    "nudge_report",
]

logger = logging.getLogger(__name__)

DEGENERATE_TOL = 1e-6
"""Planes closer than this times ``scale`` to a vertex height are degenerate."""

NUDGE_STEP = 1e-5
"""Nudge search step, times ``scale``."""

_MAX_STEPS = 200


def mesh_scale(mesh_or_vertices) -> float:
    """Diagonal of the axis-aligned bounding box of a mesh's vertices."""
    v = np.asarray(getattr(mesh_or_vertices, "vertices", mesh_or_vertices), float)
    return float(np.linalg.norm(v.max(axis=0) - v.min(axis=0)))


def vertex_clearance(offsets, sorted_heights) -> np.ndarray:
    """Distance from each offset to the nearest vertex height.

    Parameters
    ----------
    offsets : (m, ...) float
    sorted_heights : (k,) float, ascending

    Returns
    -------
    (m, ...) float
    """
    h = sorted_heights
    x = np.asarray(offsets, dtype=np.float64)
    i = np.searchsorted(h, x)
    left = h[np.clip(i - 1, 0, len(h) - 1)]
    right = h[np.clip(i, 0, len(h) - 1)]
    return np.minimum(np.abs(x - left), np.abs(right - x))


def _count_within(sorted_vals, x, tol) -> np.ndarray:
    return np.searchsorted(sorted_vals, x + tol, "right") - np.searchsorted(
        sorted_vals, x - tol, "left"
    )


def _faces_in_plane(order, sorted_h, faces, off, t) -> int:
    """Faces whose three vertices are within ``t`` of height ``off``."""
    if faces is None or len(faces) == 0:
        return 0
    i0 = np.searchsorted(sorted_h, off - t, side="left")
    i1 = np.searchsorted(sorted_h, off + t, side="right")
    near = np.zeros(len(order), dtype=bool)
    near[order[i0:i1]] = True
    cand = faces[near[faces[:, 0]]]
    return int(np.count_nonzero(near[cand[:, 1]] & near[cand[:, 2]]))


def _nudge_family(planes, vertices, faces, scale, tol, step, max_steps):
    n = planes[0].normal
    heights = vertices @ n
    order = np.argsort(heights)
    sh = heights[order]
    lo, hi = sh[0], sh[-1]
    t, s = tol * scale, step * scale
    offs = np.array([p.offset for p in planes])
    bad = np.flatnonzero(vertex_clearance(offs, sh) < t)
    out = list(planes)
    if len(bad) == 0:
        return out
    ks = np.repeat(np.arange(1, max_steps + 1), 2) * np.tile([1.0, -1.0], max_steps)
    cand = offs[bad, None] + ks[None, :] * s
    clear = vertex_clearance(cand, sh)
    clear = np.where((cand > lo + t) & (cand < hi - t), clear, -np.inf)
    ok = clear >= t
    first = np.where(ok.any(axis=1), ok.argmax(axis=1), clear.argmax(axis=1))
    nverts = _count_within(sh, offs[bad], t)
    for j, b in enumerate(bad):
        off = offs[b]
        nfaces = _faces_in_plane(order, sh, faces, off, t)
        delta = float(cand[j, first[j]] - off)
        c = float(clear[j, first[j]])
        note = "" if ok[j, first[j]] else " (best effort: no clear offset found)"
        reason = (
            f"{int(nverts[j])} vertices within {tol:g}*scale ({nfaces} faces in plane); "
            f"moved {delta:+.3g} ({delta / scale:+.1e}*scale), "
            f"clearance {c / scale:.1e}*scale{note}"
        )
        out[b] = planes[b].moved(delta, reason)
    return out


def nudge_planes(
    planes,
    mesh,
    tol: float = DEGENERATE_TOL,
    step: float = NUDGE_STEP,
    max_steps: int = _MAX_STEPS,
    log: bool = True,
) -> list[SlicePlane]:
    """Move degenerate planes off vertex heights; report every move.

    Parameters
    ----------
    planes : list of SlicePlane
    mesh : trimesh.Trimesh
        Anything with ``vertices`` (n, 3) and optionally ``faces`` (m, 3).
    tol, step : float
        Degeneracy tolerance and search step, both times ``scale``.
    max_steps : int
        Search ``+-1 .. +-max_steps`` steps; if none is clear the clearest
        candidate is used and the reason says "best effort".
    log : bool
        Emit one ``logging`` warning listing the moved planes.

    Returns
    -------
    list of SlicePlane
        Same length and order; moved planes have ``nudge != 0`` and a
        ``nudge_reason``.
    """
    planes = list(planes)
    if not planes:
        return planes
    vertices = np.asarray(mesh.vertices, dtype=np.float64)
    faces = getattr(mesh, "faces", None)
    faces = None if faces is None else np.asarray(faces)
    scale = mesh_scale(vertices)
    out = list(planes)
    groups: dict[tuple, list[int]] = {}
    for i, p in enumerate(planes):
        groups.setdefault(tuple(p.normal.tolist()), []).append(i)
    for idx in groups.values():
        fam = _nudge_family(
            [planes[i] for i in idx], vertices, faces, scale, tol, step, max_steps
        )
        for i, p in zip(idx, fam):
            out[i] = p
    if log:
        lines = nudge_report(out)
        if lines:
            logger.warning(
                "moved %d of %d degenerate planes: %s", len(lines), len(out), "; ".join(lines)
            )
    return out


def nudge_report(planes) -> list[str]:
    """One line ``"plane <index>: <reason>"`` per moved plane."""
    return [f"plane {p.index}: {p.nudge_reason}" for p in planes if p.nudge != 0.0]
