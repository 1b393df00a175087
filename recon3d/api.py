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
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import trimesh

import meshes
from meshes.loading import open_edge_count
from recon3d.checks import InputError, check_out_dir
from recon3d.config import RunConfig, make_config, numpydoc_params, run_signature, validate
from recon3d.io.documents import metrics_document, sensing_document
from recon3d.io.outputs import write_outputs
from recon3d.records import MeshRun, SliceRun
from recon3d.score import score
from recon3d.score.evaluate import contour_cloud, coverage_mesh
from recon3d.sensing import WorkerDied, sense_mesh
from recon3d.surface import Reconstruction, reconstruct
from recon3d.viz import blocks as scene, plot

__all__ = ["Result", "run", "load_input", "execute", "WorkerDied"]


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

    def blocks(self):
        """The ``scene.vtm`` multiblock (ground truth, surface, curves)."""
        gt = coverage_mesh(self.mesh, contour_cloud(self.sensing.families), 2 * self.recon.step)
        return scene.scene_blocks(gt, self.surface, self.slices)

    def plot(self, off_screen: bool | None = None, screenshot=None, **show_kwargs):
        """Show the two coverage panels (pyvista); see :mod:`recon3d.viz.plot`."""
        if off_screen is None:
            off_screen = not plot.has_display()
        if off_screen:
            plot.prepare_offscreen()
        p = plot.coverage_plotter(self.blocks(), title=self.sensing.name, off_screen=off_screen)
        return p.show(screenshot=screenshot, **show_kwargs)

    def save(self, out, png: bool = True) -> list[Path]:
        """Write sensing.json, metrics.json, surface.ply, scene.vtm, coverage.png into ``out``."""
        check_out_dir(out, "out")
        return write_outputs(out, self.sensing_document(), self.metrics, self.surface,
                             self.blocks(), title=self.sensing.name, png=png)


def load_input(source) -> tuple[trimesh.Trimesh, str, list[str]]:
    """A trimesh, a scene name or a mesh path -> (trimesh, name, warnings)."""
    if isinstance(source, trimesh.Trimesh):
        if len(source.faces) == 0:
            raise InputError("the mesh has no faces")
        name = str(source.metadata.get("scene") or source.metadata.get("file_name") or "mesh")
        notes = [] if source.is_watertight else [
            f"{name}: mesh is not watertight ({open_edge_count(source)} boundary edges); "
            f"slices may give open or broken contours"]
        return source, name, notes
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", meshes.MeshWarning)
        try:
            mesh = meshes.load(source)
        except meshes.MeshError as exc:
            raise InputError(str(exc)) from None
    notes = [str(w.message) for w in caught if issubclass(w.category, meshes.MeshWarning)]
    path = os.fspath(source)
    name = os.path.basename(path) if os.path.exists(path) else path
    return mesh, name, notes


def execute(mesh: trimesh.Trimesh, name: str, config: RunConfig, notes=(),
            progress: Callable[[SliceRun], None] | None = None,
            stage: Callable[[str], None] | None = None) -> Result:
    """Sense, reconstruct and score a checked mesh and config (see :func:`run`).

    stage : callable(str), optional -- told when reconstruction and scoring start.
    """
    notes = list(notes)
    sensed = sense_mesh(mesh, name, config, progress)
    notes += sensed.nudge_notes
    if stage is not None:
        stage("reconstructing")
    recon = reconstruct(sensed)
    if stage is not None:
        stage("scoring")
    surface, info = score(sensed, recon)
    return Result(mesh, sensed, recon, metrics_document(sensed, surface, info), notes)


def run(source, *, progress: Callable[[SliceRun], None] | None = None, **params) -> Result:
    """Sense, reconstruct and score a mesh.

    Parameters
    ----------
    source : trimesh.Trimesh, scene name or mesh file path.
    progress : callable(SliceRun), optional -- called as slices finish.
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
    mesh, name, notes = load_input(source)
    notes += validate(mesh, config)
    for note in notes:  # not watertight, coarse eps: say it where the caller looks
        warnings.warn(note, UserWarning, stacklevel=2)
    return execute(mesh, name, config, notes, progress)


# the keywords and their documentation come from RunConfig (recon3d.config)
run.__doc__ = run.__doc__.replace("{params}", numpydoc_params().replace("\n", "\n    "))
run.__signature__ = run_signature(
    first=[inspect.Parameter("source", inspect.Parameter.POSITIONAL_OR_KEYWORD)],
    last=[inspect.Parameter("progress", inspect.Parameter.KEYWORD_ONLY, default=None)])
