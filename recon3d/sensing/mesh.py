"""Run the 2D algorithm on every slice of every family (meshes -> slicer -> core2d).

:func:`sense_mesh` cuts the mesh once, resolves the run's defaults
(:func:`recon3d.config.resolve`), lets a plan of planes choose what to
sense -- every plane at eps (uniform) or, for ``slices='auto'``, the rounds
of :func:`recon3d.sensing.adaptive.sense_adaptive` -- senses it
(:func:`recon3d.sensing.pool.sense_all`) and assembles the
:class:`recon3d.records.MeshRun`. Each slice gets its own contact backend,
probe, planner and budget, so a run always ends. Metrics against the
reference contour are computed after sensing and never fed back to the
planner.
"""
from __future__ import annotations

import time
from collections.abc import Callable

import trimesh

import slicer
from recon3d.config import Resolved, RunConfig, diagonal, resolve
from recon3d.records import Family, MeshRun, SliceRun, robot_time
from recon3d.sensing.adaptive import AdaptivePlan, sense_adaptive
from recon3d.sensing.pool import sense_all
from recon3d.sensing.worker import SenseSettings, family_slices, resolved_reads

__all__ = ["sense_mesh"]


def _sense_uniform(sense, cuts: list, res: Resolved):
    """Every plane of every family at the run's eps (the uniform plan; returns as
    :func:`recon3d.sensing.adaptive.sense_adaptive` does, without its ``info``)."""
    got = [dict() for _ in cuts]
    tasks = [(f, i) for f, fam in enumerate(cuts) for i in range(len(fam))]
    for out in sense(tasks):
        got[out.family][out.index] = (out, res.eps)
    return got, res.eps, res.tol, None


def sense_mesh(mesh: trimesh.Trimesh, name: str, config: RunConfig,
               progress: Callable[[SliceRun], None] | None = None,
               beside: Callable[[], object] | None = None) -> MeshRun:
    """Slice ``mesh`` along every axis of ``config`` and sense the planes its plan picks.

    Parameters
    ----------
    mesh : trimesh.Trimesh
    name : str -- label written to the output.
    config : RunConfig -- checked (:func:`recon3d.config.validate`).
    progress : callable(SliceRun) or None -- called as each slice finishes.
    beside : callable() or None -- run in a thread of this process while worker processes
        sense (:func:`recon3d.sensing.pool.sense_all`).

    Returns
    -------
    MeshRun -- families in ``config.axes`` order, slices in plane order.
    """
    t0 = time.perf_counter()
    auto = config.slices == "auto"
    count = int(config.max_slices) if auto else config.slices
    normals = tuple(slicer.parse_axis(a) for a in config.axes)
    cuts = [family_slices(mesh, n, count) for n in normals]
    res = resolve(config, diagonal(mesh), cuts)
    tol = res.tol_share * res.first_eps if auto else res.tol
    settings = SenseSettings(normals, count, res.first_eps, tol, config.backend,
                             config.max_motions, config.bootstrap, config.method,
                             float(config.noise), float(config.taxel), int(config.seed),
                             float(config.friction), float(config.torque_threshold),
                             float(config.torque_noise), bool(config.keyed_noise),
                             resolved_reads(config, tol / res.first_eps))

    def sense(tasks):
        return sense_all(mesh, cuts, settings, tasks, res.jobs, progress=progress,
                         beside=beside)

    if auto:
        n = int(config.max_slices)
        plan = AdaptivePlan(n, 3 if n < 16 else 5, float(config.slice_tol) * res.diagonal,
                            res.eps)
        got, eps, tol, info = sense_adaptive(plan, sense, len(normals), res.tol_share,
                                             config.speed, config.motion_overhead,
                                             config.read_time)
    else:
        got, eps, tol, info = _sense_uniform(sense, cuts, res)
    run = MeshRun(name, mesh, config, eps, tol, probe_length=res.probe_length, jobs=res.jobs,
                  families=[Family(n) for n in normals], adaptive=info, reads=settings.reads)
    for f, fam in enumerate(run.families):
        for i in sorted(got[f]):
            out = got[f][i][0]
            out.slice = cuts[f][i]
            out.metrics["robot_time_s"] = robot_time(out.result.stats.as_dict(), config.speed,
                                                     config.motion_overhead, config.read_time)
            fam.slices.append(out)
    run.seconds = time.perf_counter() - t0
    return run
