"""``recon3d bench --out DIR [--quick] [--scheduler ADDRESS]``: the 3D benchmark.

Sweep eps x slices (uniform and --slices auto), compare the contact
backends, dense finger probing against pulling, the stability of each
method, and pulling against a pushing contour follower under tip friction; write CSV + PNG into DIR and print a short table (README 'recon3d
bench'). Runs on Dask: a local cluster by default, an existing one with
--scheduler. ``--redraw DIR[,DIR...]`` re-makes the files of earlier
outputs from their CSVs (no sensing; parts run apart are merged).
"""
from __future__ import annotations

from recon3d.benchmark import PARTS
from recon3d.checks import InputError, at_least, check_out_dir
from recon3d.cli.batch import add_cluster_flags

__all__ = ["HELP", "add_arguments", "command"]

HELP = ("speed against accuracy, finger-probing baseline, backends, stability, pulling "
        "against pushing under friction")


def add_arguments(p) -> None:
    add_cluster_flags(p, "Dask scheduler address, or 'serial' (this process); default: a "
                      "local cluster")
    p.add_argument("--quick", action="store_true",
                   help="small sweeps (about 3 minutes on 2 cores)")
    p.add_argument("--parts", default=None,
                   help=f"comma-separated subset of {','.join(PARTS)}")
    p.add_argument("--redraw", default=None, metavar="DIR[,DIR...]",
                   help="no sensing: re-make the CSVs, charts and table.txt of earlier bench "
                   "outputs from their CSVs into --out (several DIRs, e.g. parts run apart, "
                   "are merged; --quick and --parts are taken from them)")


def command(args) -> int:
    # the benchmark's libraries (the runs, Dask, matplotlib): `recon3d --help` loads none
    from recon3d.benchmark.redraw import redraw  # lazy: see above
    from recon3d.benchmark.run3d import run_bench  # lazy: see above

    parts = PARTS if not args.parts else tuple(p.strip() for p in args.parts.split(","))
    bad = [p for p in parts if p not in PARTS]
    if bad or not parts:
        raise InputError(f"--parts: unknown {bad} (choose from {', '.join(PARTS)})")
    if args.workers is not None:
        at_least(args.workers, "--workers")
    check_out_dir(args.out, "--out")
    if args.redraw is not None:
        try:
            lines = redraw([d.strip() for d in args.redraw.split(",") if d.strip()], args.out)
        except (ValueError, OSError) as exc:
            raise InputError(f"--redraw: {exc}") from None
        except KeyError as exc:
            raise InputError(f"--redraw: a CSV lacks the column {exc}") from None
        print("\n".join(lines))
        return 0
    try:
        lines = run_bench(args.out, args.quick, args.scheduler, args.workers, parts, args.quiet)
    except OSError as exc:
        raise InputError(f"--scheduler {args.scheduler}: {exc}") from None
    print("\n".join(lines))
    return 0
