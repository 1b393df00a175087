"""Python API: ``recon3d.run(...) -> Result`` (the whole job, for notebooks).

Example::

    import recon3d
    res = recon3d.run("fig17_pocket", axis="z", slices=4, jobs=2)
    res.metrics["total"]["surface"]["fscore"]["1%"]
    res.surface.is_watertight, len(res.slices)
    res.save("out/pocket"); res.plot()
"""
from __future__ import annotations

import inspect
import os
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import trimesh

import meshes
from meshes.loading import open_edge_count
from recon3d.checks import InputError, check_flag, check_out_dir
from recon3d.config import RunConfig, diagonal, package_version, resolve, validate
from recon3d.spellings import make_config, number, numpydoc_params, run_signature
from recon3d.io.documents import metrics_document, sensing_document
from recon3d.io.outputs import slices_png_bytes, write_outputs
from recon3d.io.side import Side, can_fork
from recon3d.records import MeshRun, SliceRun
from recon3d.score import score
from recon3d.score.evaluate import (classified_ground_truth, contour_cloud, coverage_mesh,
                                    surface_distances)
from recon3d.score.report import chord_lines, slicing_text, surface_lines
from recon3d.score.unknowns import unknown_chords
from recon3d.sensing import COMPILE_NOTICE, WorkerDied, cold_kernels, sense_mesh
from recon3d.sensing.regions import RegionsAsSensed
from recon3d.sensing.worker import resolved_reads
from recon3d.surface import Reconstruction, reconstruct
from recon3d.surface.closure import closure_lengths
from recon3d.surface.field import grid_step
from recon3d.viz import blocks as scene, libs, plot

__all__ = ["Result", "run", "load_input", "execute", "Source", "WorkerDied", "cold_kernels",
           "COMPILE_NOTICE", "__version__"]

Source = trimesh.Trimesh | str | os.PathLike
"""What :func:`run` senses: a trimesh, a built-in scene name or a mesh file path."""


__version__ = package_version()
"""The version of the installed distribution ``pulling-probe-3d``."""


@dataclass
class Result:
    """Everything a run produced.

    mesh : trimesh.Trimesh -- the ground truth.
    sensing : recon3d.records.MeshRun -- families, slices, 2D results and metrics.
    recon : recon3d.surface.Reconstruction -- surface, slice regions, solids.
    metrics : dict -- the ``metrics.json`` document.
    warnings : list of str -- notes for the user (coarse eps, moved planes, ...).
    """

    mesh: trimesh.Trimesh
    sensing: MeshRun
    recon: Reconstruction
    metrics: dict
    warnings: list[str]
    _blocks: Any = field(default=None, init=False, repr=False, compare=False)
    _coverage: trimesh.Trimesh | None = field(default=None, repr=False, compare=False)
    _slices_png: bytes | None = field(default=None, repr=False, compare=False)

    @property
    def slices(self) -> list[SliceRun]:
        """Every :class:`recon3d.records.SliceRun`, family by family."""
        return self.sensing.slices

    @property
    def surface(self) -> trimesh.Trimesh:
        """The reconstructed surface (trimesh, ``face_attributes['label']``)."""
        return self.recon.surface

    def sensing_document(self) -> dict:
        """The ``sensing.json`` object."""
        return sensing_document(self.sensing)

    def __repr__(self) -> str:
        fams = ", ".join(f"{f.label} x{len(f.slices)}" for f in self.sensing.families)
        t, ev = self.metrics.get("total", {}), self.metrics.get("surface_eval", {})
        surf = t.get("surface") or {}
        f1 = (surf.get("fscore") or {}).get("1%")
        f1r = ((surf.get("reachable") or {}).get("fscore") or {}).get("1%")
        slab = ev.get("slab_share")
        return (f"<recon3d.Result mesh={self.sensing.name!r} families=[{fams}] "
                f"slices={len(self.slices)} eps={number(self.sensing.eps, '.4g')} "
                f"slab={number(slab)} F@1%={number(f1)} reachable_F@1%={number(f1r)} "
                f"coverage_2D={number(t.get('coverage'))} "
                f"unknown_chords={t.get('unknown_chords', 0)} "
                f"warnings={len(self.warnings)}>")[:399]

    def headline(self, shown: int = 4) -> tuple[list[str], list[str]]:
        """Text lines of the 3D scores and of the unknown chords (``shown`` of them located):
        :func:`recon3d.score.report.surface_lines`, :func:`~recon3d.score.report.chord_lines`."""
        return surface_lines(self.metrics), chord_lines(self.metrics, shown)

    def blocks(self) -> Any:
        """The ``scene.vtm`` multiblock (ground truth, surface, curves, headline), built on
        the first call and kept (``save`` and ``plot`` draw the same scene)."""
        if self._blocks is None:
            self._blocks = self._build_blocks()
        return self._blocks

    def _build_blocks(self) -> Any:
        gt = self._coverage if self._coverage is not None else _coverage(self.mesh, self.sensing,
                                                                         self.recon)
        return scene.scene_blocks(gt, self.surface, self.slices,
                                  headline=[f"{self.sensing.name}: slices "
                                            f"{slicing_text(self.metrics)}"] + sum(self.headline(2), []),
                                  normals=[f.normal for f in self.sensing.families],
                                  axes=[f.label for f in self.sensing.families])

    def plot(self, off_screen: bool | None = None, screenshot: str | os.PathLike | None = None,
             **show_kwargs: Any) -> Any:
        """The two coverage panels (see :mod:`recon3d.viz.plot`): a window, a file or a plotter.

        Parameters
        ----------
        off_screen : bool, optional
            Render without a window (default: when there is no display, or when
            ``screenshot`` is given).
        screenshot : str or path-like, optional
            Write the picture to this PNG file.
        **show_kwargs
            Passed to ``pyvista.Plotter.show`` (on screen only).

        Returns
        -------
        pathlib.Path or pyvista.Plotter
            With ``screenshot``: the path written (the plotter is closed). Otherwise
            the plotter: shown in a window first when on screen, or, off screen,
            ready to render (``.screenshot(...)``, ``.show()``) -- nothing is drawn yet.
        """
        if off_screen is None:
            off_screen = screenshot is not None or not plot.has_display()
        if off_screen:
            plot.prepare_offscreen()
        p = plot.coverage_plotter(self.blocks(), title=self.sensing.name, off_screen=off_screen)
        if screenshot is not None:
            path = Path(screenshot)
            try:
                if off_screen:
                    p.screenshot(str(path))
                else:
                    p.show(screenshot=str(path), **show_kwargs)
            finally:
                p.close()
            return path
        if not off_screen:
            p.show(**show_kwargs)
        return p

    def save(self, out: str | os.PathLike, png: bool = True) -> list[Path]:
        """Write sensing.json, metrics.json, motions.csv, surface.ply, scene.vtm,
        coverage.png and slices.png into ``out`` (``png=False``: neither picture)."""
        check_out_dir(out, "out")
        return write_outputs(out, self.sensing_document(), self.metrics, self.surface,
                             self.blocks, title=self.sensing.name, png=png,
                             slices=self.slices, slices_png=self._slices_png)


def _checked(mesh: trimesh.Trimesh, name: str, drop_nonfinite: bool) -> trimesh.Trimesh:
    """A given trimesh through the checks a loaded file gets (:mod:`meshes.validate`)."""
    mesh = meshes.check_finite(mesh, name, drop=drop_nonfinite)
    meshes.check_solid(mesh, name)
    meshes.check_overlap(mesh, name)
    return mesh


def load_input(source: Source, drop_nonfinite: bool = False
               ) -> tuple[trimesh.Trimesh, str, list[str]]:
    """A trimesh, a scene name or a mesh path -> (trimesh, name, warnings).

    Non-finite vertices, a flat mesh or one without faces raise :class:`InputError`;
    ``drop_nonfinite`` drops non-finite vertices and their faces (with a warning).
    """
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", meshes.MeshWarning)
        try:
            if isinstance(source, trimesh.Trimesh):
                name = str(source.metadata.get("scene") or source.metadata.get("file_name")
                           or "mesh")
                mesh = _checked(source, name, drop_nonfinite)
            else:
                mesh = meshes.load(source, drop_nonfinite=drop_nonfinite)
        except meshes.MeshError as exc:
            raise InputError(str(exc)) from None
    notes = [str(w.message) for w in caught if issubclass(w.category, meshes.MeshWarning)]
    if isinstance(source, trimesh.Trimesh):
        if not mesh.is_watertight:
            notes.append(f"{name}: mesh is not watertight ({open_edge_count(mesh)} boundary "
                         f"edges); slices may give open or broken contours")
        return mesh, name, notes
    path = os.fspath(source)
    name = os.path.basename(path) if os.path.exists(path) else path
    return mesh, name, notes


def _coverage(mesh: trimesh.Trimesh, sensed: MeshRun, recon: Reconstruction) -> trimesh.Trimesh:
    """The ground truth of the scene, coloured (:func:`recon3d.score.evaluate.coverage_mesh`)."""
    return coverage_mesh(mesh, contour_cloud(sensed.families), 2 * recon.step, recon.surface)


def _classified_arrays(mesh: trimesh.Trimesh, sensed: MeshRun) -> tuple:
    """The ground truth subdivided and classified (:func:`classified_ground_truth`), as plain
    arrays (what a side process sends back): vertices, faces, coverage class per face. Its
    edge length is the one :func:`_coverage` uses (twice the reconstruction's grid step),
    known before the reconstruction."""
    step = grid_step(sensed.eps, diagonal(mesh))
    gt = classified_ground_truth(mesh, contour_cloud(sensed.families), 2 * step)
    return gt.vertices, gt.faces, gt.face_attributes["coverage"]


def _slices_png(sensed: MeshRun) -> bytes:
    """``slices.png`` of a sensed run (:func:`recon3d.io.outputs.slices_png_bytes`): it
    reads the per-slice metrics only, known once the slices are sensed (the per-slice part
    of the ``metrics.json`` document is the same before and after the scores)."""
    return slices_png_bytes(sensing_document(sensed), metrics_document(sensed, None, {}),
                            sensed.slices, title=sensed.name)


def _side_by_side(first: Callable[[], Any], second: Callable[[], Any]) -> tuple[Any, Any]:
    """``(first(), second())`` with ``first`` in a forked child (:class:`recon3d.io.side.Side`)
    while this process runs ``second``: the two halves of each family's field (the
    reconstruction) and the scores' two distance calls, on two cores."""
    if not can_fork():
        return first(), second()
    side = Side(first)
    try:
        b = second()
        a, side = side.result(), None
    finally:
        if side is not None:
            side.stop()
    return a, b


def execute(mesh: trimesh.Trimesh, name: str, config: RunConfig, notes: Sequence[str] = (),
            progress: Callable[[SliceRun], None] | None = None,
            stage: Callable[[str], None] | None = None, scene: bool = False,
            pictures: bool = False) -> Result:
    """Sense, reconstruct and score a checked mesh and config (see :func:`run`).

    stage : callable(str), optional -- told when reconstruction and scoring start.
    scene : bool -- the scene's coloured ground truth will be wanted (``save``): where a
        process can fork, it is computed beside the reconstruction and the scores, on
        another core.
    pictures : bool -- the pictures will be drawn (``save(png=True)``): pyvista's plotting
        is loaded while the workers sense, so the picture child forked by ``save``
        inherits it instead of loading it after the scores (no render window is made, so
        this process can still fork), and ``slices.png`` is drawn by a side process while
        this one reconstructs and scores.
    """
    notes = list(notes)
    # each slice's filled region is closed in this process as the slice comes back (it only
    # waits for the workers); the reconstruction takes them as they are
    plan = resolve(config, diagonal(mesh))
    reads = resolved_reads(config, plan.tol / plan.eps)  # the closure sees the means' scatter
    lengths = closure_lengths(plan.eps, plan.tol, config.noise / reads ** 0.5, config.taxel)
    regions = RegionsAsSensed(None if config.slices == "auto" else lengths)

    def sensed_one(srun: SliceRun) -> None:
        regions.add(srun)
        if progress is not None:
            progress(srun)

    # pyvista (the reconstruction's flying edges, the scores' distances) and, for pictures,
    # its plotting are imported while the workers sense
    sensed = sense_mesh(mesh, name, config, sensed_one,
                        beside=plot.load_plotting if pictures else libs.pyvista)
    notes += sensed.nudge_notes
    drawing = side = None
    halves: tuple[Side, ...] = ()
    try:
        if pictures and can_fork():  # slices.png needs the sensing only
            drawing = Side(_slices_png, sensed)
        # the scene's coloured ground truth beside the rest: subdivided and classified while
        # this process reconstructs, its distances to the surface taken while this one scores
        if scene and can_fork():
            side = Side(_classified_arrays, mesh, sensed)
        if stage is not None:
            stage("reconstructing")
        recon = reconstruct(sensed, regions=regions.for_run(sensed), pair=_side_by_side)
        if stage is not None:
            stage("scoring")
        gt = None
        if side is not None:
            v, f, cov = side.result()
            gt = trimesh.Trimesh(v, f, process=False)
            gt.face_attributes["coverage"] = cov
            side = None
            # its vertices' distances (10^5 - 10^6 of them: the longest call after the
            # sensing) in two halves, each in a child, while this process scores
            cut = len(v) // 2
            halves = (Side(surface_distances, v[:cut], recon.surface, diagonal(mesh)),
                      Side(surface_distances, v[cut:], recon.surface, diagonal(mesh)))
        surface, info = score(sensed, recon, pair=_side_by_side)
        doc = metrics_document(sensed, surface, info, unknown_chords(sensed))
        if halves:
            gt.vertex_attributes["distance"] = np.concatenate([h.result() for h in halves])
            halves = ()
        png = None
        if drawing is not None:
            try:
                png = drawing.result()
            except RuntimeError:  # drawn again by save, where its error is reported
                png = None
            drawing = None
    finally:
        for child in (side, drawing, *halves):
            if child is not None:
                child.stop()
    return Result(mesh, sensed, recon, doc, notes, _coverage=gt, _slices_png=png)


def run(source: Source, *, progress: Callable[[SliceRun], None] | None = None,
        **params: Any) -> Result:
    """Sense, reconstruct and score a mesh.

    Parameters
    ----------
    source : trimesh.Trimesh, scene name or mesh file path.
    progress : callable(SliceRun), optional -- called as slices finish (with worker
        processes, while the cyclic collector is paused: a garbage cycle it makes is
        collected once the sensing ends).
    {params}

    Returns
    -------
    Result

    Raises
    ------
    InputError (a ValueError) -- bad input, found before any sensing.
    WorkerDied (a RuntimeError) -- a sensing worker process died (killed, a crash);
        the other workers are stopped, nothing is returned.

    Warns
    -----
    UserWarning -- a mesh that is not watertight, a coarse eps (also in ``Result.warnings``).
    """
    config = make_config(**params)
    check_flag(config.drop_nonfinite, "drop_nonfinite")
    mesh, name, notes = load_input(source, config.drop_nonfinite)
    notes += validate(mesh, config)
    for note in notes:  # not watertight, coarse eps: say it where the caller looks
        warnings.warn(note, UserWarning, stacklevel=2)
    return execute(mesh, name, config, notes, progress)


# the keywords and their documentation come from RunConfig (recon3d.config)
run.__doc__ = run.__doc__.replace("{params}", numpydoc_params().replace("\n", "\n    "))
run.__signature__ = run_signature(
    first=[inspect.Parameter("source", inspect.Parameter.POSITIONAL_OR_KEYWORD,
                             annotation="trimesh.Trimesh | str | os.PathLike")],
    last=[inspect.Parameter("progress", inspect.Parameter.KEYWORD_ONLY, default=None,
                            annotation="Callable[[SliceRun], None] | None")])
run.__signature__ = run.__signature__.replace(return_annotation="Result")
