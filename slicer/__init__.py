"""slicer: planes, 2D frames, reference contours and in-plane contact.

Cut a triangle mesh with parallel planes; on each plane, get the reference
cross-section (closed loops in the plane's 2D frame) and a contact model
(:mod:`slicer.contact`) whose ``cast(origins, dirs, max_dist)`` answers
in-plane ray queries with Embree (``'embree'``, needs ``embreex``), with
trimesh's generic ray engine (``'trimesh'``) or exactly against the contour
(``'exact'``); see :mod:`core2d.sim.contact` for the contract. Importing
slicer does not import ``embreex``, nor numba: :class:`ExactContact` (compiled) loads on
first use.

Examples
--------
>>> import numpy as np, trimesh
>>> import slicer
>>> mesh = trimesh.creation.annulus(r_min=1.0, r_max=2.0, height=1.0)
>>> slices = slicer.slice_mesh(mesh, axis="z", count=3)
>>> s = slices[1]
>>> len(s.loops), s.holes.tolist()
(2, [False, True])
>>> model = s.contact("embree")
>>> d, p, n = model.cast(np.array([[0.0, 0.0]]), np.array([[0.0, 1.0]]), 10.0)
>>> round(float(d[0]), 9), np.round(n[0], 3).tolist()
(1.0, [0.098, -0.995])
"""
import importlib

from slicer.contact import BACKENDS
from slicer.contact.trimesh_ray import TrimeshContact
from slicer.degenerate import mesh_scale, nudge_planes, nudge_report
from slicer.planes import SlicePlane, frame_for_normal, make_planes, parse_axis
from slicer.section import Section, sections
from slicer.slices import Slice, slice_mesh

__all__ = [
    "SlicePlane",
    "parse_axis",
    "frame_for_normal",
    "make_planes",
    "nudge_planes",
    "nudge_report",
    "mesh_scale",
    "Section",
    "sections",
    "BACKENDS",
    "Slice",
    "slice_mesh",
    "ExactContact",
    "TrimeshContact",
]


def __getattr__(name: str):
    """``ExactContact`` on first use (its module compiles with numba, which the command
    line's parser must not load)."""
    if name == "ExactContact":
        value = importlib.import_module("slicer.contact.exact").ExactContact
        globals()[name] = value
        return value
    raise AttributeError(f"module 'slicer' has no attribute {name!r}")
