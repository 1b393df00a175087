"""Python API: ``recon3d.run(...) -> Result`` (the whole job, for notebooks).

Example::

    import recon3d
    res = recon3d.run("fig17_pocket", axis="z", slices=4, jobs=2)
    res.metrics["total"]["surface"]["fscore"]["1%"]
    res.surface.is_watertight, len(res.slices)
    res.save("out/pocket"); res.plot()
"""
from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np

from recon3d.checks import (InputError, at_least, check_eps, check_out_dir, check_tol,
                            positive)

__all__ = ["Result", "run", "make_config", "load_input", "validate", "execute"]


@dataclass
class Result:
    """Everything a run produced.

    mesh : trimesh.Trimesh -- the ground truth.
    sensing : recon3d.pipeline.MeshRun -- families, slices, 2D results and metrics.
    recon : recon3d.reconstruct.Reconstruction -- surface, slice regions, solids.
    metrics : dict -- the ``metrics.json`` document.
    warnings : list of str -- notes for the user (coarse eps, moved planes, ...).
    """

    mesh: object
    sensing: object
    recon: object
    metrics: dict
    warnings: list

    @property
    def slices(self) -> list:
        """Every :class:`recon3d.pipeline.SliceRun`, family by family."""
        return self.sensing.slices

    @property
    def surface(self):
        """The reconstructed surface (trimesh, ``face_attributes['label']``)."""
        return self.recon.surface

    def sensing_document(self) -> dict:
        """The ``sensing.json`` object."""
        from recon3d.output import sensing_document

        return sensing_document(self.sensing)

    def blocks(self):
        """The ``scene.vtm`` multiblock (ground truth, surface, curves)."""
        from recon3d.evaluate import contour_cloud, coverage_mesh
        from recon3d.scene import scene_blocks

        gt = coverage_mesh(self.mesh, contour_cloud(self.sensing.families), 2 * self.recon.step)
        return scene_blocks(gt, self.surface, self.slices)

    def plot(self, off_screen: bool | None = None, screenshot=None, **show_kwargs):
        """Show the two coverage panels (pyvista); see :mod:`recon3d.plot`."""
        from recon3d.plot import coverage_plotter, has_display, prepare_offscreen

        if off_screen is None:
            off_screen = not has_display()
        if off_screen:
            prepare_offscreen()
        p = coverage_plotter(self.blocks(), title=self.sensing.name, off_screen=off_screen)
        return p.show(screenshot=screenshot, **show_kwargs)

    def save(self, out, png: bool = True) -> list:
        """Write sensing.json, metrics.json, surface.ply, scene.vtm, coverage.png into ``out``."""
        from recon3d.save import write_outputs

        check_out_dir(out, "out")
        return write_outputs(out, self.sensing_document(), self.metrics, self.surface,
                             self.blocks(), title=self.sensing.name, png=png)


def load_input(source):
    """A trimesh, a scene name or a mesh path -> (trimesh, name, warnings)."""
    import warnings

    import meshes
    import trimesh

    if isinstance(source, trimesh.Trimesh):
        if len(source.faces) == 0:
            raise InputError("the mesh has no faces")
        from meshes.loading import open_edge_count

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


def validate(mesh, config, names=None) -> list[str]:
    """Check a :class:`recon3d.pipeline.RunConfig` against ``mesh``; return warnings.

    ``names`` maps parameter names to how the caller spells them (CLI flags).
    """
    from slicer import parse_axis

    n = {k: k for k in ("eps", "tol", "slices", "axis", "jobs", "max_motions",
                        "probe_speed", "motion_overhead", "max_slices", "slice_tol")}
    n.update(names or {})
    if config.slices == "auto":
        at_least(config.max_slices, n["max_slices"], low=3)
        if not 0 < positive(config.slice_tol, n["slice_tol"]) < 0.5:
            raise InputError(f"{n['slice_tol']} is a share of the diagonal in (0, 0.5) "
                             f"(got {config.slice_tol})")
    else:
        at_least(config.slices, n["slices"])
    at_least(config.max_motions, n["max_motions"])
    if config.jobs is not None:
        at_least(config.jobs, n["jobs"])
    positive(config.probe_speed, n["probe_speed"])
    positive(config.motion_overhead, n["motion_overhead"], allow_zero=True)
    if not config.axes:
        raise InputError(f"give at least one {n['axis']}")
    for a in config.axes:
        try:
            parse_axis(a)
        except ValueError as exc:
            raise InputError(f"{n['axis']}: {exc}") from None
    diag = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)))
    if not np.isfinite(diag) or diag <= 0:
        raise InputError("the mesh has no extent")
    eps = diag / 200.0 if config.eps is None else positive(config.eps, n["eps"])
    note = check_eps(eps, diag, n["eps"])
    if config.tol is not None:
        check_tol(positive(config.tol, n["tol"]), eps, n["tol"])
    return [note] if note else []


def make_config(axis="z", slices: int = 8, eps: float | None = None, tol: float | None = None,
                backend: str = "embree", jobs: int | None = None, max_motions: int = 20000,
                probe_speed: float = 20.0, motion_overhead: float = 0.2, max_slices: int = 32,
                slice_tol: float = 0.005):
    """A :class:`recon3d.pipeline.RunConfig` from :func:`run`'s keywords."""
    from recon3d.pipeline import RunConfig
    from slicer import BACKENDS

    if backend not in BACKENDS:
        raise InputError(f"backend must be one of {', '.join(BACKENDS)} (got {backend!r})")
    if isinstance(slices, str) and slices != "auto":
        raise InputError(f"slices must be an integer or 'auto' (got {slices!r})")
    axes = tuple(axis) if isinstance(axis, (list, tuple)) else (axis,)
    if axes and all(isinstance(a, (int, float, np.number)) for a in axes):
        axes = (np.asarray(axes, dtype=float),)  # one vector given as a list
    return RunConfig(axes=axes, slices=slices, eps=eps, backend=backend, tol=tol,
                     max_motions=max_motions, jobs=jobs, probe_speed=probe_speed,
                     motion_overhead=motion_overhead, max_slices=max_slices,
                     slice_tol=slice_tol)


def execute(mesh, name: str, config, notes=(), progress=None, stage=None) -> Result:
    """Sense, reconstruct and score a checked mesh and config (see :func:`run`).

    stage : callable(str), optional -- told when reconstruction and scoring start.
    """
    from recon3d.adaptive import sense_adaptive
    from recon3d.output import metrics_document
    from recon3d.pipeline import sense_mesh
    from recon3d.reconstruct import reconstruct, score

    notes = list(notes)
    sense = sense_adaptive if config.slices == "auto" else sense_mesh
    sensed = sense(mesh, name, config, progress)
    notes += sensed.nudge_notes
    if stage is not None:
        stage("reconstructing")
    recon = reconstruct(sensed)
    if stage is not None:
        stage("scoring")
    surface, info = score(sensed, recon)
    metrics = metrics_document(sensed, surface, info)
    if sensed.adaptive is not None:
        metrics["adaptive"] = sensed.adaptive
    return Result(mesh, sensed, recon, metrics, notes)


def run(source, axis="z", slices: int = 8, eps: float | None = None, tol: float | None = None,
        backend: str = "embree", jobs: int | None = None, max_motions: int = 20000,
        probe_speed: float = 20.0, motion_overhead: float = 0.2, max_slices: int = 32,
        slice_tol: float = 0.005, progress=None) -> Result:
    """Sense, reconstruct and score a mesh.

    Parameters
    ----------
    source : trimesh.Trimesh, scene name or mesh file path.
    axis : str, (3,) float, or a list of them -- one slice family per axis.
    slices : int or 'auto' -- planes per family (a surface needs at least 2);
        'auto': adaptive slicing (:mod:`recon3d.adaptive`) among ``max_slices``
        candidates, refining where neighbouring sensed regions differ by more
        than ``slice_tol`` x the diagonal.
    eps, tol : float, optional -- the paper's eps (default diagonal / 200) and
        the contact resolution (default eps / 20); bounds in :mod:`recon3d.checks`.
    backend : 'embree', 'exact' or 'trimesh'.
    jobs : int, optional -- processes (default: every core); results do not depend on it.
    max_motions : int -- motion budget per slice.
    probe_speed, motion_overhead : float -- robot time model (mesh units / s, s / motion).
    progress : callable(SliceOutcome), optional -- called as slices finish.

    Returns
    -------
    Result

    Raises
    ------
    InputError (a ValueError) -- bad input, found before any sensing.

    Warns
    -----
    UserWarning -- a mesh that is not watertight, a coarse eps (also in ``Result.warnings``).
    """
    import warnings

    config = make_config(axis, slices, eps, tol, backend, jobs, max_motions, probe_speed,
                         motion_overhead, max_slices, slice_tol)
    mesh, name, notes = load_input(source)
    notes += validate(mesh, config)
    for note in notes:  # not watertight, coarse eps: say it where the caller looks
        warnings.warn(note, UserWarning, stacklevel=2)
    return execute(mesh, name, config, notes, progress)
