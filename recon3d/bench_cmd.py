"""``recon3d bench --out DIR [--quick] [--scheduler ADDRESS]``: the 3D benchmark (recon3d.benchmark.run3d)."""
from __future__ import annotations

__all__ = ["add_bench_parser", "bench_command"]


def add_bench_parser(sub) -> None:
    p = sub.add_parser(
        "bench", help="speed against accuracy, finger-probing baseline, backends, stability",
        description="Sweep eps x slices (uniform and --slices auto), compare the contact "
        "backends, dense finger probing against pulling, and the stability of each method; "
        "write CSV + PNG into DIR and print a short table (README 'recon3d bench'). Runs on "
        "Dask: a local cluster by default, an existing one with --scheduler.")
    p.add_argument("--out", required=True, help="output directory (created if missing)")
    p.add_argument("--quick", action="store_true",
                   help="small sweeps (about 10 minutes on 2 cores)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="Dask scheduler address, or 'serial' (this process); default: a local "
                   "cluster")
    p.add_argument("--workers", type=int, default=None,
                   help="local cluster worker processes (default: number of cores)")
    p.add_argument("--parts", default=None,
                   help="comma-separated subset of pareto,backends,baseline,stability")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=bench_command)


def bench_command(args) -> int:
    from recon3d.checks import InputError, at_least, check_out_dir
    from recon3d.usage import UsageError

    from recon3d.benchmark.run3d import PARTS, run_bench
    parts = PARTS if not args.parts else tuple(p.strip() for p in args.parts.split(","))
    try:
        bad = [p for p in parts if p not in PARTS]
        if bad or not parts:
            raise InputError(f"--parts: unknown {bad} (choose from {', '.join(PARTS)})")
        if args.workers is not None:
            at_least(args.workers, "--workers")
        check_out_dir(args.out, "--out")
    except InputError as exc:
        raise UsageError(str(exc)) from None
    try:
        lines = run_bench(args.out, args.quick, args.scheduler, args.workers, parts, args.quiet)
    except OSError as exc:
        raise UsageError(f"--scheduler {args.scheduler}: {exc}") from None
    print("\n".join(lines))
    return 0
