"""Read user mesh files into one clean :class:`trimesh.Trimesh`.

Cleaning is deliberately conservative, so that a good file keeps its face
count: vertices are welded (positions only, ignoring UVs and normals),
faces that repeat a vertex index or duplicate another face are dropped, and
unreferenced vertices are removed. Zero-area faces with three distinct
vertices are kept: CAD exports use such slivers to close T-junctions, and
removing them would open a watertight mesh. Non-finite vertices (NaN, inf)
are an error unless the caller asks to drop them with their faces, and a
flat mesh is an error (:mod:`meshes.validate`).
"""
from __future__ import annotations

import os
import warnings
from pathlib import Path

import numpy as np
import trimesh

from .errors import MeshError, MeshWarning, one_line
from .validate import check_finite, check_overlap, check_solid

__all__ = ["SUPPORTED_EXTENSIONS", "load_file", "clean", "open_edge_count"]

#: File extensions :func:`load_file` accepts (lower case, with dot).
SUPPORTED_EXTENSIONS: tuple[str, ...] = (".stl", ".obj", ".ply", ".off", ".glb")


def load_file(path: str | os.PathLike, drop_nonfinite: bool = False) -> trimesh.Trimesh:
    """Load a mesh file; several geometries (GLB scenes) are concatenated.

    Parameters
    ----------
    path : str or path-like
        An existing ``.stl``, ``.obj``, ``.ply``, ``.off`` or ``.glb`` file.
    drop_nonfinite : bool
        Drop NaN / inf vertices and the faces that use them (with a warning)
        instead of raising.

    Returns
    -------
    mesh : trimesh.Trimesh
        Cleaned (see module docstring), vertices ``(n, 3)`` float64, faces
        ``(m, 3)`` int64, scene transforms applied.

    Raises
    ------
    MeshError
        Missing, empty, unreadable or unsupported file, no faces, non-finite
        vertices (unless dropped), or a flat mesh.

    Warns
    -----
    MeshWarning
        The mesh is not watertight, it was inside out and got inverted, its
        bodies overlap, or non-finite vertices were dropped.
    """
    p = Path(path)
    if not p.exists():
        raise MeshError(f"mesh file not found: {p}")
    if not p.is_file():
        raise MeshError(f"not a regular file: {p}")
    ext = p.suffix.lower()
    if ext not in SUPPORTED_EXTENSIONS:
        raise MeshError(f"unsupported mesh file extension {ext or '(none)'!r} for "
                        f"{p}; supported: {' '.join(SUPPORTED_EXTENSIONS)}")
    if p.stat().st_size == 0:
        raise MeshError(f"mesh file is empty (0 bytes): {p}")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # parser chatter, not our warnings
            loaded = trimesh.load_scene(str(p), file_type=ext[1:], process=False)
        parts = loaded.dump()
    except Exception as exc:  # parsers raise anything on corrupt input
        raise MeshError(f"cannot read {p} as {ext[1:].upper()}: "
                        f"{type(exc).__name__}: {one_line(exc)}") from None
    meshes = [g for g in parts if isinstance(g, trimesh.Trimesh) and len(g.faces)]
    if not meshes:
        nverts = sum(len(getattr(g, "vertices", ())) for g in parts)
        raise MeshError(f"no faces in {p} ({nverts} vertices, {len(parts)} "
                        f"geometries): not a surface mesh, or corrupt")
    mesh = meshes[0] if len(meshes) == 1 else trimesh.util.concatenate(meshes)
    mesh = clean(check_finite(mesh, p.name, drop=drop_nonfinite))
    if len(mesh.faces) == 0:
        raise MeshError(f"no faces left in {p} after dropping degenerate faces")
    check_solid(mesh, p.name)
    mesh.metadata["file_name"] = p.name
    _check_closed(mesh, p.name)
    check_overlap(mesh, p.name)
    return mesh


def clean(mesh: trimesh.Trimesh) -> trimesh.Trimesh:
    """Return a welded copy of ``mesh`` without index-degenerate or
    duplicate faces (see module docstring); winding is not touched."""
    out = trimesh.Trimesh(vertices=np.asarray(mesh.vertices, dtype=np.float64),
                          faces=np.asarray(mesh.faces, dtype=np.int64),
                          process=False, metadata=dict(mesh.metadata))
    if getattr(mesh, "units", None):
        out.units = mesh.units
    out.merge_vertices(merge_tex=True, merge_norm=True)
    f = out.faces
    out.update_faces((f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2]))
    out.update_faces(out.unique_faces())
    out.remove_unreferenced_vertices()
    return out


def open_edge_count(mesh: trimesh.Trimesh) -> int:
    """Number of edges used by exactly one face (boundary edges)."""
    if len(mesh.faces) == 0:
        return 0
    return len(trimesh.grouping.group_rows(mesh.edges_sorted, require_count=1))


def _check_closed(mesh: trimesh.Trimesh, label: str) -> None:
    if not mesh.is_watertight:
        warnings.warn(MeshWarning(
            f"{label}: mesh is not watertight ({open_edge_count(mesh)} boundary "
            f"edges); slices may give open or broken contours"), stacklevel=3)
    elif mesh.is_winding_consistent and mesh.volume < 0:
        mesh.invert()
        warnings.warn(MeshWarning(f"{label}: mesh was inside out (negative "
                                  f"volume); faces were inverted"), stacklevel=3)
