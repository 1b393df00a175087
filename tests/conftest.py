"""Shared pytest fixtures."""
from __future__ import annotations

from pathlib import Path

import recon3d  # noqa: F401  (first: pins the numerics before numpy loads, recon3d.numerics)

import pytest

SHARED_MESHES = Path(__file__).resolve().parents[1].parent / "shared" / "meshes"
# Real meshes of ../shared/meshes/MANIFEST.tsv used by the slicer tests.
REAL_MESHES = [
    "trimesh_featuretype.stl",
    "trimesh_idler_riser.stl",
    "mujoco_spot.ply",
    "vtk_42400-IDGH.stl",
    "ravens_cup.ply",
    "ajc_teapot.obj",  # not watertight: trimesh section fallback
    "trimesh_fandisk.obj",
    "trimesh_octagonal_pocket.stl",
]


@pytest.fixture(scope="session")
def shared_meshes_dir() -> Path:
    """Directory of real meshes (``../shared/meshes`` beside the repo, with
    ``MANIFEST.tsv``); the requesting test is skipped when it is absent."""
    if not (SHARED_MESHES / "MANIFEST.tsv").is_file():
        pytest.skip(f"real meshes not available: {SHARED_MESHES}/MANIFEST.tsv "
                    f"does not exist (expected beside the repository)")
    return SHARED_MESHES
