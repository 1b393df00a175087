"""Read a run's directory for the 2D figures: documents, motion log, true sections.

``read_views(DIR)`` gives one :class:`recon3d.viz.sliceview.SliceView` per
slice from ``sensing.json`` and ``metrics.json``; :func:`attach_log` adds the
slice's rows of ``motions.csv`` when the run wrote one, :func:`attach_sections`
the true section, recomputed with :mod:`slicer` from the mesh: the built-in
scene named in ``sensing.json``, else the ``ground_truth`` block of
``scene.vtm`` (the mesh as the run saw it). Every failure a user can cause is
an :class:`recon3d.checks.InputError` (one line).
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import trimesh

import meshes
import slicer
from recon3d.checks import InputError
from recon3d.viz import libs
from recon3d.viz.sliceview import MotionLog, SliceView, slice_views

__all__ = ["read_views", "attach_log", "attach_sections", "run_mesh"]


def _read_json(path: Path) -> dict:
    try:
        with open(path) as fh:
            return json.load(fh)
    except FileNotFoundError:
        raise InputError(f"no {path.name} in {path.parent} (write one with "
                         f"'recon3d run ... --out DIR')") from None
    except (OSError, ValueError) as exc:
        raise InputError(f"cannot read {path}: {type(exc).__name__}") from None


def read_views(run_dir) -> tuple[dict, list[SliceView]]:
    """(``sensing.json`` document, one SliceView per slice) of the run in ``run_dir``."""
    path = Path(run_dir)
    if not path.is_dir():
        raise InputError(f"{path} is not a directory (the --out DIR of 'recon3d run')")
    sensing = _read_json(path / "sensing.json")
    metrics = _read_json(path / "metrics.json") if (path / "metrics.json").is_file() else None
    try:
        return sensing, slice_views(sensing, metrics)
    except (KeyError, TypeError, ValueError, IndexError) as exc:
        raise InputError(f"{path / 'sensing.json'} is not a recon3d sensing document "
                         f"({type(exc).__name__}: {exc})") from None


def attach_log(view: SliceView, table) -> SliceView:
    """``view`` with its rows of a motion table (``log`` stays None without a table)."""
    if table is not None:
        try:
            view.log = MotionLog.from_table(table, view.family, view.index)
        except (KeyError, ValueError) as exc:
            raise InputError(f"the motion log lacks a column or a number: {exc}") from None
    return view


def run_mesh(sensing: dict, run_dir) -> trimesh.Trimesh | None:
    """The mesh of a run: the built-in scene it names, else ``scene.vtm``'s ground truth
    (None when neither is there)."""
    name = str(sensing.get("mesh", ""))
    if name in meshes.names():
        return meshes.load(name)
    vtm = Path(run_dir) / "scene.vtm"
    if not vtm.is_file():
        return None
    blocks = libs.pyvista().read(str(vtm))
    if "ground_truth" not in blocks.keys():
        return None
    gt = blocks["ground_truth"].triangulate()
    if gt.n_cells == 0:
        return None
    faces = np.asarray(gt.faces).reshape(-1, 4)[:, 1:]
    return trimesh.Trimesh(np.asarray(gt.points, float), faces, process=True)


def attach_sections(views: list[SliceView], sensing: dict, run_dir) -> list[SliceView]:
    """``views`` with ``section`` set to the true section loops, recomputed by
    :func:`slicer.sections` on the run's mesh (left None when the mesh is not found)."""
    mesh = run_mesh(sensing, run_dir)
    if mesh is None or not views:
        return views
    planes = []
    for view in views:
        origin, u, v = (np.asarray(x, float) for x in view.frame)
        normal = np.cross(u, v)
        planes.append(slicer.SlicePlane(view.index, origin, normal, u, v,
                                        float(origin @ normal)))
    for view, sec in zip(views, slicer.sections(mesh, planes)):
        view.section = [np.asarray(lp, float) for lp in (*sec.loops, *sec.open_chains)]
    return views
