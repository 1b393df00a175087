"""Plain summaries of a mesh: size, closedness, bodies, scale and units."""
from __future__ import annotations

import numpy as np
import trimesh

__all__ = ["mesh_report", "format_report"]


def mesh_report(mesh: trimesh.Trimesh) -> dict:
    """Facts about ``mesh`` as a JSON-friendly dict.

    Returns
    -------
    report : dict
        ``name`` (scene or file name, or None), ``faces``, ``vertices``,
        ``watertight``, ``winding_consistent``, ``bodies`` (connected
        components), ``extents`` (3 floats), ``bbox_diagonal``, ``units``
        (None when unknown; scenes are ``"mm"``) and ``volume`` (None unless
        watertight).

    Examples
    --------
    >>> import trimesh
    >>> round(mesh_report(trimesh.creation.box((1, 2, 3)))["volume"], 9)
    6.0
    """
    empty = len(mesh.faces) == 0
    extents = [0.0, 0.0, 0.0] if empty else [float(e) for e in mesh.extents]
    watertight = bool(not empty and mesh.is_watertight)
    meta = mesh.metadata or {}
    return {
        "name": meta.get("scene") or meta.get("file_name"),
        "faces": int(len(mesh.faces)),
        "vertices": int(len(mesh.vertices)),
        "watertight": watertight,
        "winding_consistent": bool(not empty and mesh.is_winding_consistent),
        "bodies": 0 if empty else int(mesh.body_count),
        "extents": extents,
        "bbox_diagonal": float(np.linalg.norm(extents)),
        "units": getattr(mesh, "units", None),
        "volume": float(mesh.volume) if watertight else None,
    }


def format_report(report: dict) -> str:
    """One line for a :func:`mesh_report` dict.

    Examples
    --------
    >>> format_report({"name": "box", "faces": 12, "vertices": 8,
    ...     "watertight": True, "winding_consistent": True, "bodies": 1,
    ...     "extents": [1, 2, 3], "bbox_diagonal": 3.742, "units": None,
    ...     "volume": 6.0})
    'box: 12 faces, 8 vertices, watertight, 1 body, extents 1 x 2 x 3 (units unknown), diagonal 3.742, volume 6'
    """
    units = report.get("units")
    closed = "watertight" if report["watertight"] else "NOT watertight"
    if not report.get("winding_consistent", True):
        closed += ", inconsistent winding"
    bodies = report["bodies"]
    ext = " x ".join(f"{e:.4g}" for e in report["extents"])
    vol = report.get("volume")
    parts = [
        f"{report['faces']} faces",
        f"{report['vertices']} vertices",
        closed,
        f"{bodies} bod{'y' if bodies == 1 else 'ies'}",
        f"extents {ext} ({units if units else 'units unknown'})",
        f"diagonal {report['bbox_diagonal']:.4g}",
        f"volume {vol:.4g}" if vol is not None else "volume n/a",
    ]
    name = report.get("name")
    return (f"{name}: " if name else "") + ", ".join(parts)
