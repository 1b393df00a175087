"""Shared pytest fixtures."""
from __future__ import annotations

from pathlib import Path

import pytest

SHARED_MESHES = Path(__file__).resolve().parents[1].parent / "shared" / "meshes"


@pytest.fixture(scope="session")
def shared_meshes_dir() -> Path:
    """Directory of real meshes (``../shared/meshes`` beside the repo, with
    ``MANIFEST.tsv``); the requesting test is skipped when it is absent."""
    if not (SHARED_MESHES / "MANIFEST.tsv").is_file():
        pytest.skip(f"real meshes not available: {SHARED_MESHES}/MANIFEST.tsv "
                    f"does not exist (expected beside the repository)")
    return SHARED_MESHES
