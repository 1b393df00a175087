"""``recon3d run INPUT --out DIR``: sense every slice, write the outputs."""
from __future__ import annotations

import sys
from pathlib import Path

__all__ = ["add_run_parser", "config_from_args"]


def add_run_parser(sub) -> None:
    p = sub.add_parser(
        "run", help="sense every slice of a mesh with the pulling-motion algorithm",
        description="Slice INPUT, run the paper's 2D algorithm on every slice against "
        "a simulated probe, and write DIR/sensing.json and DIR/metrics.json.",
    )
    p.add_argument("input", help="built-in scene name (see 'recon3d scenes') or mesh file")
    p.add_argument("--out", required=True, help="output directory (created if missing)")
    p.add_argument("--axis", default="z", help="slice normal: x, y, z or nx,ny,nz (default z)")
    p.add_argument("--slices", type=int, default=8, help="number of slices (default 8)")
    p.add_argument("--eps", type=float, default=None,
                   help="the paper's epsilon (default: bounding-box diagonal / 200)")
    p.add_argument("--backend", choices=("embree", "exact"), default="embree",
                   help="contact backend (default embree)")
    p.add_argument("--tol", type=float, default=None, help="contact resolution (default eps/20)")
    p.add_argument("--max-motions", type=int, default=20000,
                   help="motion budget per slice (default 20000)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=_run)


def config_from_args(args):
    from recon3d.cli import UsageError
    from recon3d.pipeline import RunConfig
    from slicer import parse_axis

    if args.slices < 1:
        raise UsageError(f"--slices must be at least 1 (got {args.slices})")
    for flag in ("eps", "tol"):
        value = getattr(args, flag)
        if value is not None and not value > 0:
            raise UsageError(f"--{flag} must be a positive number (got {value})")
    if args.max_motions < 1:
        raise UsageError(f"--max-motions must be at least 1 (got {args.max_motions})")
    try:
        axis = parse_axis(args.axis)
    except ValueError as exc:
        raise UsageError(f"--axis: {exc}") from None
    return RunConfig(axis=axis, slices=args.slices, eps=args.eps, backend=args.backend,
                     tol=args.tol, max_motions=args.max_motions)


def _run(args) -> int:
    from recon3d.cli import UsageError

    config = config_from_args(args)
    import meshes
    from recon3d.output import metrics_document, sensing_document, write_json
    from recon3d.pipeline import sense_mesh

    try:
        mesh = meshes.load(args.input)
    except meshes.MeshError as exc:
        raise UsageError(str(exc)) from None
    if Path(args.input).exists() and not args.quiet:
        print(meshes.format_report(meshes.mesh_report(mesh)), file=sys.stderr)
    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise UsageError(f"--out {out} exists and is not a directory")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise UsageError(f"cannot create --out {out}: {exc.strerror}") from None
    name = Path(args.input).name if Path(args.input).exists() else args.input
    bar = None
    if not args.quiet:
        from tqdm import tqdm

        bar = tqdm(total=config.slices, desc=f"sensing {name}", unit="slice", file=sys.stderr)

    def progress(srun):
        if bar is not None:
            bar.update(1)
            bar.set_postfix(motions=srun.result.stats.motions,
                            coverage=f"{srun.metrics.get('coverage', float('nan')):.3f}")

    try:
        run = sense_mesh(mesh, name, config, progress)
    finally:
        if bar is not None:
            bar.close()
    write_json(out / "sensing.json", sensing_document(run))
    write_json(out / "metrics.json", metrics_document(run))
    _summary(run, out)
    return 0


def _summary(run, out) -> None:
    t = run.totals
    hits = sum(s.result.stats.budget_hit for s in run.slices)
    print(f"{run.name}: {len(run.slices)} slices, eps {run.eps:.4g}, "
          f"{run.seconds:.1f} s")
    print(f"  reachable coverage {t.get('coverage', float('nan')):.4f}  "
          f"precision {t.get('precision', float('nan')):.4f}  "
          f"W3 soundness {t.get('w3_soundness', float('nan')):.4f}")
    print(f"  motions {t.get('motions', 0)}  rays {t.get('rays', 0)}  "
          f"pushes {t.get('pushes', 0)}  budget hits {hits}")
    print(f"  wrote {out / 'sensing.json'} and {out / 'metrics.json'}")
