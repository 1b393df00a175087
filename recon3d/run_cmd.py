"""``recon3d run INPUT --out DIR``: sense, reconstruct, score, write the outputs."""
from __future__ import annotations

import argparse
import os
import sys

from recon3d.checks import EPS_SHARE, TOL_SHARE

__all__ = ["add_run_parser", "run_command"]

FLAGS = {"eps": "--eps", "tol": "--tol", "slices": "--slices", "axis": "--axis",
         "jobs": "--jobs", "max_motions": "--max-motions", "probe_speed": "--probe-speed",
         "motion_overhead": "--motion-overhead", "max_slices": "--max-slices",
         "slice_tol": "--slice-tol"}


def _slices(text):
    """``--slices``: a positive integer or 'auto'."""
    if text == "auto":
        return text
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an integer or 'auto', got {text!r}") from None


def add_run_parser(sub) -> None:
    lo, hi = EPS_SHARE
    p = sub.add_parser(
        "run", help="sense every slice of a mesh, rebuild its surface and score it",
        description="Slice INPUT along one or more axes, run the paper's 2D algorithm on "
        "every slice against a simulated probe, rebuild a watertight surface and score it "
        "against the mesh. Writes DIR/sensing.json, metrics.json, surface.ply, scene.vtm "
        "(+ scene/) and coverage.png.",
    )
    p.add_argument("input", help="built-in scene name (see 'recon3d scenes') or mesh file")
    p.add_argument("--out", required=True, help="output directory (created if missing)")
    p.add_argument("--axis", action="append", default=None, metavar="AXIS",
                   help="slice normal: x, y, z, -x, ... or nx,ny,nz; repeat for several "
                   "families fused into one surface (default z)")
    p.add_argument("--slices", type=_slices, default=8,
                   help="slices per axis (default 8), or 'auto': adaptive slicing -- start "
                   "coarse, add slices where neighbouring sensed sections differ, eps per "
                   "slice from the features it shows")
    p.add_argument("--max-slices", type=int, default=32,
                   help="--slices auto: candidate planes per axis (default 32)")
    p.add_argument("--slice-tol", type=float, default=0.005,
                   help="--slices auto: refine between neighbours whose sensed sections "
                   "differ by more than this share of the diagonal (default 0.005)")
    p.add_argument("--eps", type=float, default=None,
                   help=f"the paper's epsilon, in mesh units (default: bounding-box diagonal "
                   f"/ 200; allowed: {lo:g} to {hi:g} x diagonal)")
    p.add_argument("--tol", type=float, default=None,
                   help=f"contact resolution (default eps/20; allowed: eps*{TOL_SHARE:g} "
                   f"up to, not including, eps)")
    p.add_argument("--backend", choices=("embree", "exact", "trimesh"), default="embree",
                   help="contact backend (default embree; trimesh: its generic ray engine, slow)")
    p.add_argument("--max-motions", type=int, default=20000,
                   help="motion budget per slice (default 20000)")
    p.add_argument("--jobs", type=int, default=None,
                   help="parallel processes (default: number of cores; results do not "
                   "depend on it)")
    p.add_argument("--probe-speed", type=float, default=20.0,
                   help="joint speed for the robot time, mesh units per second (default 20; "
                   "scenes are in mm)")
    p.add_argument("--motion-overhead", type=float, default=0.2,
                   help="seconds per motion for the robot time (default 0.2)")
    p.add_argument("--no-png", action="store_true", help="skip coverage.png (no OpenGL)")
    p.add_argument("--quiet", action="store_true",
                   help="no progress bar, mesh report or notes (warnings still print)")
    p.set_defaults(func=run_command)


def _progress_bar(total, name, quiet):
    if quiet:
        return None
    from tqdm import tqdm

    return tqdm(total=total, desc=f"sensing {name}", unit="slice", file=sys.stderr)


def run_command(args) -> int:
    from recon3d.api import execute, load_input, make_config, validate
    from recon3d.checks import InputError, check_out_dir
    from recon3d.usage import UsageError, warn
    from recon3d.summary import summary_lines

    try:
        config = make_config(args.axis or ["z"], args.slices, args.eps, args.tol, args.backend,
                             args.jobs, args.max_motions, args.probe_speed,
                             args.motion_overhead, args.max_slices, args.slice_tol)
        mesh, name, notes = load_input(args.input)
        notes += validate(mesh, config, FLAGS)
        check_out_dir(args.out, "--out")
    except InputError as exc:
        raise UsageError(str(exc)) from None
    import meshes

    if os.path.exists(args.input) and not args.quiet:  # a file: one-line report (units, scale)
        print(meshes.format_report(meshes.mesh_report(mesh)), file=sys.stderr)
    for note in notes:
        warn(note)
    per_axis = config.max_slices if config.slices == "auto" else config.slices
    bar = _progress_bar(per_axis * len(config.axes), name, args.quiet)

    def progress(outcome):
        if bar is not None:
            bar.update(1)
            cov = outcome.metrics.get("coverage")
            bar.set_postfix(motions=outcome.result.stats.motions,
                            coverage="n/a" if cov is None else f"{cov:.3f}")

    def stage(what):
        if bar is not None:
            bar.set_description(f"{what} {name}")

    try:
        result = execute(mesh, name, config, progress=progress, stage=stage)
        if bar is not None:
            bar.set_description(f"writing {name}")
        files = result.save(args.out, png=not args.no_png)
    finally:
        if bar is not None:
            bar.close()
    for note in result.warnings:
        if not args.quiet:
            print(f"recon3d: note: {note}", file=sys.stderr)
    print("\n".join(summary_lines(result, files)))
    return 0
