"""``recon3d run INPUT --out DIR``: sense, reconstruct, score, write the outputs.

Slice INPUT along one or more axes, run the paper's 2D algorithm on every
slice against a simulated probe, rebuild a watertight surface and score it
against the mesh. Writes DIR/sensing.json, metrics.json, surface.ply,
scene.vtm (+ scene/), coverage.png and slices.png (every slice in 2D). DIR is locked while the run lasts: a
second run into it is refused. A long run says about how long it will take
once its first slices are sensed, and the first run on a machine says first that it
compiles the sensing kernels (:func:`recon3d.sensing.cold_kernels`).

The flags of the run parameters are generated from :data:`recon3d.config.PARAMS`;
the command's own flags (``--out``, ``--no-png``, ``--quiet``) are here.
"""
from __future__ import annotations

import argparse
import os
import sys
import time

from tqdm import tqdm

from recon3d.checks import check_out_dir
from recon3d.cli.printing import estimate_note, summary_lines, warn
from recon3d.config import PARAMS, default_jobs, validate
from recon3d.io.side import paused_collector
from recon3d.spellings import make_config

__all__ = ["HELP", "add_arguments", "command", "COMMAND_FLAGS"]

HELP = "sense every slice of a mesh, rebuild its surface and score it"

COMMAND_FLAGS = (
    ("--no-png", "skip coverage.png and slices.png (no OpenGL, no matplotlib)",
     "skip `coverage.png` and `slices.png`; without OpenGL (no EGL, no display) `coverage.png` "
     "is skipped anyway, with a one-line warning, and the other outputs are written"),
    ("--quiet", "no progress bar, mesh report or notes (warnings still print)",
     "no progress bar, mesh report or notes; warnings still print (one line each)"),
)
"""The flags of ``recon3d run`` that are not run parameters: (flag, help, README meaning)."""


def add_run_arguments(p: argparse.ArgumentParser) -> None:
    """One flag per run parameter, spelled, parsed and explained as its :class:`Param` says."""
    for prm in PARAMS:
        if prm.switch:  # on/off: absent is None, like every other parameter
            p.add_argument(prm.flag, action="store_const", const=True, default=None,
                           help=prm.help)
        elif prm.repeat:
            p.add_argument(prm.flag, action="append", default=None,
                           metavar=prm.key.upper(), help=prm.help)
        else:
            p.add_argument(prm.flag, type=prm.parse, choices=prm.choices, default=None,
                           help=prm.help)


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("input", help="built-in scene name (see 'recon3d scenes') or mesh file")
    p.add_argument("--out", required=True, help="output directory (created if missing)")
    add_run_arguments(p)
    for flag, text, _ in COMMAND_FLAGS:
        p.add_argument(flag, action="store_true", help=text)


def _progress_bar(total, name, quiet):
    if quiet:
        return None
    return tqdm(total=total, desc=f"sensing {name}", unit="slice", file=sys.stderr)


def libraries() -> tuple:
    """Import the run's libraries (trimesh, the sensing, VTK: ``recon3d --help`` loads none
    of them) with the cyclic collector paused (:func:`recon3d.io.side.paused_collector`:
    their ~280 collections, 0.09 - 0.13 s of the run's serial start, free nothing);
    ``(load_input, OutputLock)``."""
    with paused_collector():
        from recon3d.api import load_input  # lazy: see above
        from recon3d.io.lock import OutputLock  # lazy: as recon3d.api
    return load_input, OutputLock


def command(args) -> int:
    load_input, OutputLock = libraries()

    given = {p.key: v for p in PARAMS if (v := getattr(args, p.key)) is not None}
    config = make_config(**given)
    mesh, name, notes = load_input(args.input, config.drop_nonfinite)
    notes += validate(mesh, config, spelling="flag")
    check_out_dir(args.out, "--out")
    with OutputLock(args.out, "--out"):  # a second run into --out is refused from here on
        result, files = _run(args, config, mesh, name, notes)
    for note in result.warnings:  # printed once the outputs are complete and --out is free
        if not args.quiet:
            print(f"recon3d: note: {note}", file=sys.stderr)
    print("\n".join(summary_lines(result, files)))
    return 0


def _run(args, config, mesh, name, notes):
    """Sense, reconstruct, score and write (``--out`` held); the Result and its files."""
    import meshes  # lazy: with the run's libraries (command)
    from recon3d.api import COMPILE_NOTICE, cold_kernels, execute  # lazy: as meshes

    if os.path.exists(args.input) and not args.quiet:  # a file: one-line report (units, scale)
        print(meshes.format_report(meshes.mesh_report(mesh)), file=sys.stderr)
    for note in notes:
        warn(note)
    # the first run on a machine compiles about 10 s before its first slice, in the main
    # process (recon3d.sensing.pool._compile_here; the kernels asked about are the
    # backend's: Embree's or the exact backend's; trimesh's runs the Python engine)
    if not args.quiet and cold_kernels(config.backend):
        print(COMPILE_NOTICE, file=sys.stderr, flush=True)
    per_axis = config.max_slices if config.slices == "auto" else config.slices
    total = per_axis * len(config.axes)
    bar = _progress_bar(total, name, args.quiet)
    jobs = default_jobs() if config.jobs is None else int(config.jobs)
    # the estimate of a long uniform run (an adaptive one senses fewer, at several eps):
    # once the first slice (start-up included) and then one slice per worker are done
    t0, done, need = time.perf_counter(), [], 1 if total <= jobs else jobs + 1

    def progress(srun):
        if bar is None:
            return
        if len(done) < need and config.slices != "auto":
            done.append(time.perf_counter() - t0)
            if len(done) == need:
                note = estimate_note(total, done[0], done[-1] - done[0] or done[0], jobs)
                if note is not None:
                    bar.write(f"recon3d: note: {note}", file=sys.stderr)
        bar.update(1)
        cov = srun.metrics.get("coverage_sensor", srun.metrics.get("coverage"))
        key = "coverage" if "coverage_sensor" not in srun.metrics else "coverage (eps/2+2σ)"
        bar.set_postfix({"motions": srun.result.stats.motions,
                         key: "n/a" if cov is None else f"{cov:.3f}"})

    def stage(what):
        if bar is not None:
            bar.set_description(f"{what} {name}")

    try:
        result = execute(mesh, name, config, progress=progress, stage=stage, scene=True,
                         pictures=not args.no_png)
        if bar is not None:
            bar.set_description(f"writing {name}")
        files = result.save(args.out, png=not args.no_png)
    finally:
        if bar is not None:
            bar.close()
    return result, files
