"""The one door to pyvista and matplotlib (internal).

Both load slowly and only some runs need them, so they are imported here,
lazily, and nowhere else in recon3d: the pictures (:mod:`recon3d.viz`),
VTK's flying edges (:mod:`recon3d.surface.solid`), VTK's exact distances
(:mod:`recon3d.score.evaluate`) and the charts of ``recon3d bench``
(:mod:`recon3d.benchmark.charts`, the one user of matplotlib) come through these functions, so
``import recon3d`` loads neither.
"""
from __future__ import annotations

import types

import numpy as np
import trimesh

__all__ = ["pyvista", "polydata", "pyplot", "ticker"]


def pyvista() -> types.ModuleType:
    """The pyvista module."""
    import pyvista as pv  # lazy: slow to load, not needed by every run

    return pv


def polydata(mesh: trimesh.Trimesh):
    """trimesh -> pyvista.PolyData (geometry only)."""
    return pyvista().PolyData.from_regular_faces(np.asarray(mesh.vertices, dtype=np.float64),
                                                 np.asarray(mesh.faces, dtype=np.int64))


def pyplot() -> types.ModuleType:
    """matplotlib.pyplot on the Agg backend (files, no window), with matplotlib.ticker loaded."""
    import matplotlib  # lazy: slow to load, only the bench charts draw with it

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: after choosing the backend

    return plt


def ticker() -> types.ModuleType:
    """matplotlib.ticker (axis locators and formatters of the bench charts)."""
    import matplotlib.ticker as t  # lazy: matplotlib is slow to load

    return t
