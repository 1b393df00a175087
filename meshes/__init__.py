"""Ground-truth meshes: built-in procedural scenes and loading of user files.

Scenes are built with manifold3d and returned as :class:`trimesh.Trimesh`.
Conventions shared by all scenes: units are millimetres, the bounding-box
minimum is the origin and every scene fits in a 100 mm cube; "up" is +y, so
pockets, slots and overhangs open toward +y and the z-slices (planes of
constant z) cut through them. Every scene builder takes a ``resolution``
keyword (circle segments or grid density).

Examples
--------
>>> import meshes
>>> "fig17_pocket" in meshes.names()
True
>>> mesh = meshes.load("fig17_pocket")
>>> mesh.is_watertight, mesh.units
(True, 'mm')
>>> meshes.format_report(meshes.mesh_report(mesh))     # doctest: +ELLIPSIS
'fig17_pocket: 112 faces, ...'
"""
from __future__ import annotations

import os
from pathlib import Path

import trimesh
from manifold3d import Manifold

from . import scenes_fields, scenes_profiles, scenes_solids, scenes_textured  # noqa: F401  (register)
from .errors import MeshError, MeshWarning
from .geometry import to_trimesh
from .loading import SUPPORTED_EXTENSIONS, load_file
from .validate import check_finite, check_overlap, check_solid
from .registry import Scene, describe, get, names, unknown_scene
from .registry import build as _build
from .report import format_report, mesh_report

__all__ = [
    "MeshError",
    "MeshWarning",
    "SUPPORTED_EXTENSIONS",
    "Scene",
    "names",
    "describe",
    "scene_info",
    "build",
    "load",
    "to_trimesh",
    "mesh_report",
    "format_report",
    "check_finite",
    "check_solid",
    "check_overlap",
]


def scene_info(name: str) -> Scene:
    """The registry entry of scene ``name`` (builder, summary, bodies)."""
    return get(name)


def build(name: str, **kwargs) -> Manifold:
    """Build scene ``name`` as a :class:`manifold3d.Manifold` (the exact
    solid, e.g. for ``volume()`` or ``slice(z)``); kwargs go to the scene."""
    return _build(name, **kwargs)


def load(name_or_path: str | os.PathLike, drop_nonfinite: bool = False,
         **kwargs) -> trimesh.Trimesh:
    """A scene by name, or a mesh file by path, as one :class:`trimesh.Trimesh`.

    Parameters
    ----------
    name_or_path : str or path-like
        A name from :func:`names` (tried first) or a path to an
        ``.stl/.obj/.ply/.off/.glb`` file.
    drop_nonfinite : bool
        Files only: drop NaN / inf vertices and their faces (with a warning)
        instead of raising :class:`MeshError`.
    **kwargs
        Scene parameters such as ``resolution``; not allowed for files.

    Returns
    -------
    mesh : trimesh.Trimesh
        Vertices ``(n, 3)`` float64, faces ``(m, 3)`` int64.
        ``mesh.metadata`` holds ``scene`` and ``params``, or ``file_name``.

    Raises
    ------
    MeshError
        One-line reason: unknown name (with close matches), missing, empty,
        corrupt or unsupported file, no faces, non-finite vertices, a flat
        mesh, bad scene parameter.

    Warns
    -----
    MeshWarning
        A file mesh that is not watertight (loaded anyway), was inside
        out (inverted), has overlapping bodies, or lost non-finite vertices.
    """
    if not isinstance(name_or_path, (str, os.PathLike)):
        raise MeshError(f"expected a scene name or a file path, got "
                        f"{type(name_or_path).__name__}")
    if isinstance(name_or_path, str) and name_or_path in names():
        mesh = to_trimesh(_build(name_or_path, **kwargs), units="mm")
        mesh.metadata.update(scene=name_or_path, params=dict(kwargs))
        return mesh
    path = Path(name_or_path)
    looks_like_path = (not isinstance(name_or_path, str) or bool(path.suffix)
                       or len(path.parts) > 1)
    if path.exists() or looks_like_path:
        if kwargs:
            raise MeshError(f"keyword arguments {sorted(kwargs)} apply only to "
                            f"built-in scenes, not to the file {path}")
        return load_file(path, drop_nonfinite=drop_nonfinite)
    raise unknown_scene(name_or_path)
