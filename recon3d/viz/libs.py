"""The one door to pyvista and matplotlib (internal).

Both load slowly and only some runs need them, so they are imported here,
lazily, and nowhere else in recon3d: the pictures (:mod:`recon3d.viz`),
VTK's flying edges (:mod:`recon3d.surface.solid`), VTK's exact distances
(:mod:`recon3d.score.evaluate`) and the charts of ``recon3d bench``
(:mod:`recon3d.benchmark.charts`) and the 2D slice figures (:mod:`recon3d.viz.figure2d`) come
through these functions, so
``import recon3d`` loads neither.
"""
from __future__ import annotations

import types
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # an annotation only: the package loads no trimesh (recon3d --help)
    import trimesh

__all__ = ["pyvista", "pyvista_plotting", "vtm_writer", "polydata", "pyplot", "ticker",
           "collections", "lines", "pil_image"]


def pyvista() -> types.ModuleType:
    """The pyvista module."""
    import pyvista as pv  # lazy: slow to load, not needed by every run

    return pv


def pyvista_plotting() -> types.ModuleType:
    """pyvista.plotting (its renderers: slow to load, only pictures need it)."""
    import pyvista.plotting as plotting  # lazy: only a picture needs it

    return plotting


def vtm_writer():
    """A new ``vtkXMLMultiBlockDataWriter`` (``scene.vtm``), with the zlib compressor's Python
    wrapper loaded so that its level can be set."""
    # lazy: files only; vtkIOCore holds the zlib compressor's Python wrapper
    import vtkmodules.vtkIOCore  # noqa: F401
    from vtkmodules.vtkIOXML import vtkXMLMultiBlockDataWriter  # lazy: files only

    return vtkXMLMultiBlockDataWriter()


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


def collections() -> types.ModuleType:
    """matplotlib.collections (the line collections of the 2D slice figures)."""
    pyplot()  # the Agg backend first
    import matplotlib.collections as c  # lazy: matplotlib is slow to load

    return c


def lines() -> types.ModuleType:
    """matplotlib.lines (legend handles of the 2D slice figures)."""
    pyplot()
    import matplotlib.lines as m  # lazy: matplotlib is slow to load

    return m



def pil_image() -> types.ModuleType:
    """PIL.Image (matplotlib's own dependency): the GIF frames of ``recon3d figure --animate``."""
    from PIL import Image  # lazy: only an animation needs it

    return Image
