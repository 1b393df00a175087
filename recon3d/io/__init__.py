"""Files: the JSON documents (:mod:`.documents`), ``surface.ply`` (:mod:`.ply`), the one
staged all-or-nothing writer (:mod:`.staged`) and the outputs of a run (:mod:`.outputs`).

Its two public names load their modules on first use (``__getattr__``), so importing a
light module of the room (``recon3d.io.side``: forks and the cyclic collector) loads no
records, core2d or numba.
"""
from __future__ import annotations

import importlib

__all__ = ["without_timing", "read_ply_labels"]

_WHERE = {"without_timing": "recon3d.io.documents", "read_ply_labels": "recon3d.io.ply"}


def __getattr__(name: str):
    if name in _WHERE:
        return getattr(importlib.import_module(_WHERE[name]), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
