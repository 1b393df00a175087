"""Checks of a ground-truth mesh that decide whether a run means anything.

Each check either raises :class:`~meshes.errors.MeshError` (the mesh cannot
be used: a one-line reason) or warns with :class:`~meshes.errors.MeshWarning`
(the run goes on, and the warning says what the defect does to the scores).

* Non-finite vertices (NaN or inf): an error, unless the caller asks to drop
  them together with every face that uses them (a warning says how many).
* A flat mesh (every vertex in one plane, e.g. a single triangle): an error;
  a probe senses solids, and no plane cuts a closed section out of it.
* Overlapping bodies: a warning. The faces of one body that lie inside
  another are part of the ground truth but no probe can touch them, so they
  count as missed: completeness and the F-score drop although the picture
  looks right.
"""
from __future__ import annotations

import warnings

import numpy as np
import trimesh
from manifold3d import Error, Manifold, Mesh, OpType

from .errors import MeshError, MeshWarning

__all__ = ["FLAT_SHARE", "OVERLAP_SHARE", "check_finite", "check_solid", "overlap_volume",
           "check_overlap"]

FLAT_SHARE = 1e-9
"""A mesh whose thinnest extent (across its best-fit plane) is below this share of its
bounding-box diagonal is flat."""

OVERLAP_SHARE = 1e-6
"""Bodies overlap when their shared volume exceeds this share of their total volume."""


def check_finite(mesh: trimesh.Trimesh, label: str, drop: bool = False) -> trimesh.Trimesh:
    """``mesh`` if every vertex is finite; else an error, or a copy without them.

    Parameters
    ----------
    mesh : trimesh.Trimesh
    label : str -- the mesh's name in messages.
    drop : bool -- drop non-finite vertices and the faces that use them
        (with a :class:`MeshWarning`) instead of raising.

    Examples
    --------
    >>> import numpy as np, trimesh
    >>> box = trimesh.creation.box()
    >>> v = box.vertices.copy(); v[0] = np.nan
    >>> check_finite(trimesh.Trimesh(v, box.faces, process=False), "box")
    Traceback (most recent call last):
    ...
    meshes.errors.MeshError: box: 1 of 8 vertices are not finite (NaN or inf), used by 4 of 12 faces; fix the file, or drop them and their faces (--drop-nonfinite; drop_nonfinite=True in Python)
    """
    bad = ~np.isfinite(np.asarray(mesh.vertices, dtype=np.float64)).all(axis=1)
    if not bad.any():
        return mesh
    faces = np.asarray(mesh.faces)
    used = bad[faces].any(axis=1) if len(faces) else np.zeros(0, dtype=bool)
    what = (f"{int(bad.sum())} of {len(bad)} vertices are not finite (NaN or inf), used by "
            f"{int(used.sum())} of {len(faces)} faces")
    if not drop:
        raise MeshError(f"{label}: {what}; fix the file, or drop them and their faces "
                        f"(--drop-nonfinite; drop_nonfinite=True in Python)")
    out = mesh.copy()
    out.update_faces(~used)
    out.remove_unreferenced_vertices()
    warnings.warn(MeshWarning(f"{label}: dropped {what} (the surface has holes there)"),
                  stacklevel=2)
    return out


def check_solid(mesh: trimesh.Trimesh, label: str) -> None:
    """Raise :class:`MeshError` when ``mesh`` has no faces, no extent or is flat.

    Examples
    --------
    >>> import trimesh
    >>> tri = trimesh.Trimesh([[0, 0, 0], [1, 0, 0], [0, 1, 1]], [[0, 1, 2]])
    >>> check_solid(tri, "tri")
    Traceback (most recent call last):
    ...
    meshes.errors.MeshError: tri: the mesh is flat (all its vertices lie in one plane): a probe senses solids, and no slice of it is a closed section
    """
    if len(mesh.faces) == 0:
        raise MeshError(f"{label}: the mesh has no faces")
    v = np.asarray(mesh.vertices, dtype=np.float64)[np.unique(mesh.faces)]
    diag = float(np.linalg.norm(np.ptp(v, axis=0)))
    if not np.isfinite(diag) or diag == 0.0:
        raise MeshError(f"{label}: the mesh has no extent (all vertices at one point)")
    centred = v - v.mean(axis=0)
    thickness = float(np.linalg.svd(centred, compute_uv=False)[-1]) / np.sqrt(len(v))
    if thickness <= FLAT_SHARE * diag:
        raise MeshError(f"{label}: the mesh is flat (all its vertices lie in one plane): a probe "
                        f"senses solids, and no slice of it is a closed section")


def overlap_volume(mesh: trimesh.Trimesh) -> tuple[int, float, float]:
    """(bodies, shared volume, total volume) of a watertight mesh's bodies.

    The shared volume is the sum of the bodies' volumes minus the volume of
    their union (manifold3d); 0 for one body or bodies that only touch.

    Examples
    --------
    >>> import trimesh
    >>> a = trimesh.creation.box((2, 2, 2))
    >>> b = a.copy().apply_translation((1, 0, 0))
    >>> n, shared, total = overlap_volume(trimesh.util.concatenate([a, b]))
    >>> n, round(shared, 9), round(total, 9)
    (2, 4.0, 16.0)
    """
    bodies = mesh.split(only_watertight=False)
    solids = [Manifold(Mesh(np.ascontiguousarray(b.vertices, np.float32),
                            np.ascontiguousarray(b.faces, np.uint32))) for b in bodies]
    total = float(sum(s.volume() for s in solids))
    if len(solids) < 2 or any(s.status() != Error.NoError for s in solids):
        return len(solids), 0.0, total  # one body, or a body manifold3d cannot take
    union = Manifold.batch_boolean(solids, OpType.Add)
    return len(solids), max(0.0, total - float(union.volume())), total


def check_overlap(mesh: trimesh.Trimesh, label: str) -> None:
    """Warn (:class:`MeshWarning`) when the bodies of a watertight mesh overlap."""
    if not mesh.is_watertight or mesh.body_count < 2:
        return
    n, shared, total = overlap_volume(mesh)
    if total > 0 and shared > OVERLAP_SHARE * total:
        warnings.warn(MeshWarning(
            f"{label}: {n} bodies overlap (shared volume {shared:.4g}, "
            f"{100 * shared / total:.2g}% of theirs); faces inside the union are scored as "
            f"ground truth no probe can touch, which lowers completeness and F-score: "
            f"unite the bodies first"), stacklevel=2)
