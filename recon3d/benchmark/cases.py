"""Cases of ``recon3d bench``: built-in scenes and, when present, real meshes.

Real meshes live in ``../shared/meshes`` beside the repository; without
them the bench runs on built-in scenes only and says so.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import trimesh

import meshes
import slicer
from recon3d.config import diagonal

__all__ = ["SHARED", "REAL", "case_list", "diagonal", "middle_slice", "workspace"]

SHARED = Path(__file__).resolve().parents[3] / "shared" / "meshes"
REAL = ("mujoco_spot.ply", "trimesh_featuretype.stl")


def case_list(scenes, real: bool = True) -> list[tuple[str, str]]:
    """``(name, source)`` pairs: the scenes, then the real meshes found in SHARED."""
    out = [(s, s) for s in scenes]
    if real:
        out += [(m, str(SHARED / m)) for m in REAL if (SHARED / m).is_file()]
    return out


def workspace(slc: slicer.Slice, eps: float) -> tuple[np.ndarray, float]:
    """The robot's workspace circle of a slice (as the pipeline builds it)."""
    center, radius = slc.bounding_circle()
    return np.asarray(center, float), float(radius) + eps


def middle_slice(source, axis: str = "z", count: int = 3,
                 index: int | None = None) -> tuple[trimesh.Trimesh, float, slicer.Slice]:
    """The mesh, its diagonal and slice ``index`` (default the middle) of ``count``."""
    mesh = meshes.load(source)
    cuts = slicer.slice_mesh(mesh, axis, count=count)
    return mesh, diagonal(mesh), cuts[count // 2 if index is None else index]
