"""Write the outputs of ``recon3d run`` into a directory, all or nothing (:class:`Staged`).

A machine without OpenGL cannot render ``coverage.png``: the other files
are still written and a ``RuntimeWarning`` says why the picture is missing.
``slices.png`` (every slice in 2D, :mod:`recon3d.viz.multiples`) needs no
OpenGL: matplotlib's Agg draws it.

Where the process can fork (:func:`recon3d.io.side.can_fork`), both pictures
are drawn by a child (:class:`recon3d.io.side.Side`) forked once the scene is
built: it loads pyvista's plotting, draws ``slices.png`` and renders the scene
it inherited while this process writes ``scene.vtm`` and the other files: the
slow libraries load and draw on one core, the files are written on the other.
Without pictures, the child writes ``scene.vtm`` while this process writes the rest.
"""
from __future__ import annotations

import io
import json
import warnings
from pathlib import Path

import numpy as np
import trimesh

from recon3d.io import ply
from recon3d.io.motions import write_motions
from recon3d.io.side import Side, can_fork
from recon3d.io.staged import Staged
from recon3d.viz import libs, plot
from recon3d.viz.multiples import save_multiples
from recon3d.viz.sliceview import slice_views

__all__ = ["OUTPUTS", "write_outputs", "write_json", "write_slices_png", "slices_png_bytes"]

OUTPUTS = ("sensing.json", "metrics.json", "motions.csv", "surface.ply", "scene.vtm",
           "coverage.png", "slices.png")
"""Files of a complete run (``scene.vtm`` comes with its ``scene/`` folder)."""


def write_json(path, obj, indent=1) -> None:
    """Write ``obj``; ``indent=None`` writes compact JSON through the C encoder
    (``json.dump`` and any indent take the pure-Python one: ~10x slower on
    the 10+ MB sensing document of a large run)."""
    text = json.dumps(obj, indent=indent, allow_nan=False)
    with open(path, "w") as fh:
        fh.write(text)


def _render(blocks, path, title) -> None:
    try:
        plot.save_png(blocks, path, title=title)
    except Exception as exc:  # VTK raises many kinds when OpenGL is missing
        msg = " ".join(str(exc).split())[:200]
        warnings.warn(f"coverage.png not written: {type(exc).__name__}: {msg} (needs OpenGL: "
                      f"EGL or a display; --no-png skips it)", RuntimeWarning, stacklevel=3)


def write_slices_png(path, sensing: dict, metrics: dict, slices=(), title: str = "") -> None:
    """Draw ``slices.png``: one small 2D panel per slice (:mod:`recon3d.viz.multiples`).

    path : path or binary file -- where the PNG goes.
    metrics : dict -- the ``metrics.json`` document, or any dict with its ``method`` and
        ``slices`` (all the picture reads: the per-slice coverage).
    slices : list of recon3d.records.SliceRun -- their reference loops are the true
        sections drawn in grey (slice frame); none without them.
    """
    loops = {(int(s.family), int(s.index)): [np.asarray(lp, float) for lp in s.slice.loops]
             for s in slices if s.slice is not None}
    views = slice_views(sensing, metrics)
    for view in views:
        view.section = loops.get((view.family, view.index))
    method = metrics.get("method", "pulling")
    sensor = metrics.get("sensor")
    noisy = (f"  ·  sensor noise {sensor.get('noise', 0):g} eps, taxel {sensor.get('taxel', 0):g}"
             f" eps" if sensor else "")
    save_multiples(views, path, title=f"{title}  ·  method {method}{noisy}".strip(" ·"))


def slices_png_bytes(sensing: dict, metrics: dict, slices=(), title: str = "") -> bytes:
    """``slices.png`` as bytes (:func:`write_slices_png`): drawn before the run's directory
    exists, e.g. in a side process while the surface is rebuilt."""
    buf = io.BytesIO()
    write_slices_png(buf, sensing, metrics, slices, title)
    return buf.getvalue()


def write_outputs(out, sensing: dict, metrics: dict, surface: trimesh.Trimesh, blocks,
                  title: str = "", png: bool = True, slices=(),
                  slices_png: bytes | None = None) -> list[Path]:
    """Write the outputs of one run into ``out``.

    Parameters
    ----------
    out : path -- created if missing (and removed again if writing fails).
    sensing, metrics : dict -- the JSON documents.
    surface : trimesh.Trimesh with ``face_attributes['label']``.
    blocks : pyvista.MultiBlock, or a callable returning one --
        :func:`recon3d.viz.blocks.scene_blocks` (a callable is called once, here).
    png : bool -- render ``coverage.png`` (needs an OpenGL context; see module doc) and
        ``slices.png``.
    slices : list of recon3d.records.SliceRun -- their motion logs make ``motions.csv``,
        their true sections go into ``slices.png``.
    slices_png : bytes, optional -- ``slices.png`` already drawn (:func:`slices_png_bytes`):
        written as it is instead of drawn again.

    Returns
    -------
    list of Path -- the files written (the ``scene/`` folder included).
    """
    staged = Staged(out, replaces=OUTPUTS)
    with staged as stage:
        scene = blocks() if callable(blocks) else blocks
        # the pictures in a forked child: it loads pyvista's plotting, draws slices.png and
        # renders the scene it inherited as coverage.png while this process writes
        # scene.vtm and the rest; without fork, all of it here, one after the other
        # (without pictures the child writes scene.vtm, the slowest file, instead)
        side = None
        if can_fork():
            side = (Side(_pictures, stage, title, sensing, metrics, slices, scene, slices_png)
                    if png else Side(_save_scene, scene, stage))
        try:
            if png or side is None:
                _save_scene(scene, stage)
            write_json(stage / "sensing.json", sensing, indent=None)  # machine data: compact
            write_json(stage / "metrics.json", metrics)
            write_motions(stage / "motions.csv", slices)
            ply.write_ply(stage / "surface.ply", surface.vertices, surface.faces,
                          np.asarray(surface.face_attributes["label"]))
            if png and side is None:
                _pictures(stage, title, sensing, metrics, slices, scene, slices_png)
            elif side is not None:
                side.result()
                side = None
        finally:
            if side is not None:  # an error here: the child's picture is thrown away too
                side.stop()
    return staged.written


def _save_scene(scene, stage: Path) -> None:
    """Write ``scene.vtm`` (and its ``scene/`` folder) into ``stage``.

    VTK XML with the arrays compressed by zlib at level 1 in an appended section, raw
    (read by VTK, ParaView and pyvista alike), not at VTK's level 5 inline in base64 as
    ``MultiBlock.save`` writes them. The large mesh's scene (64 slices, 360k + 159k
    triangles): 0.53 -> 0.21 CPU s, 11.3 -> 8.5 MB (level 5 raw: 0.48 s, 8.2 MB); the
    same arrays read back (``tests/test_outputs_scene.py``)."""
    writer = libs.vtm_writer()
    writer.SetFileName(str(stage / "scene.vtm"))
    writer.SetInputData(scene)
    writer.SetDataModeToAppended()
    writer.EncodeAppendedDataOff()
    writer.SetCompressorTypeToZLib()
    writer.GetCompressor().SetCompressionLevel(1)
    if writer.Write() != 1:
        raise OSError(f"VTK could not write {stage / 'scene.vtm'}")


def _pictures(stage: Path, title: str, sensing: dict, metrics: dict, slices, scene,
              slices_png: bytes | None = None) -> None:
    """Load pyvista's plotting, draw ``slices.png`` (or write the one drawn already), render
    ``scene`` as ``coverage.png`` (in the child, or here)."""
    plot.load_plotting()
    if slices_png is None:
        write_slices_png(stage / "slices.png", sensing, metrics, slices, title)
    else:
        (stage / "slices.png").write_bytes(slices_png)
    _render(scene, stage / "coverage.png", title)
