"""``surface.ply``: the reconstructed surface with an integer face property ``label``."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import trimesh

__all__ = ["write_ply", "read_ply_labels"]


def write_ply(path, vertices, faces, labels) -> None:
    """Binary PLY with an ``int label`` face property (float32 vertices).

    vertices : (v, 3) float; faces : (f, 3) int; labels : (f,) int.
    """
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    mesh.face_attributes["label"] = np.asarray(labels, np.int32)
    Path(path).write_bytes(trimesh.exchange.ply.export_ply(mesh, encoding="binary"))


def read_ply_labels(path) -> trimesh.Trimesh:
    """Load ``surface.ply`` as a trimesh with ``face_attributes['label']`` (f,) int32."""
    mesh = trimesh.load(str(path), process=False)
    raw = mesh.metadata.get("_ply_raw", {}).get("face", {}).get("data")
    if raw is None or "label" not in raw.dtype.names:
        raise ValueError(f"{path} has no face property 'label'")
    mesh.face_attributes["label"] = np.asarray(raw["label"], dtype=np.int32)
    return mesh
