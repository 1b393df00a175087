"""``recon3d batch MANIFEST --out DIR [--scheduler ADDRESS]``: run a manifest on Dask.

Run every mesh of MANIFEST with every combination of its [params] (see
README 'recon3d batch'), one job per Dask task: a local cluster with one
worker per core by default, an existing cluster with --scheduler. Writes
DIR/batch.csv and DIR/runs/NNN_<mesh>/{metrics.json,sensing.json,surface.ply}.
"""
from __future__ import annotations

from pathlib import Path

from recon3d.checks import InputError, at_least, check_out_dir
from recon3d.config import manifest_doc
from recon3d.jobs.batch import read_manifest, run_job, write_batch
from recon3d.jobs.cluster import run_tasks

__all__ = ["HELP", "add_arguments", "command", "add_cluster_flags"]

HELP = "run many meshes x parameters (a TOML manifest) on Dask"


def add_cluster_flags(p, scheduler_help: str) -> None:
    """``--out``, ``--scheduler``, ``--workers`` and ``--quiet`` (batch and bench)."""
    p.add_argument("--out", required=True, help="output directory (created if missing)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS", help=scheduler_help)
    p.add_argument("--workers", type=int, default=None,
                   help="local cluster worker processes (default: number of cores)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")


def add_arguments(p) -> None:
    p.add_argument("manifest", metavar="MANIFEST", help="TOML file: meshes = [...] and [params]")
    p.epilog = manifest_doc()
    add_cluster_flags(p, "Dask scheduler address (tcp://host:8786), or 'serial' to run in "
                      "this process; default: a local cluster")


def command(args) -> int:
    if args.workers is not None:
        at_least(args.workers, "--workers")
    check_out_dir(args.out, "--out")
    jobs = read_manifest(args.manifest)
    try:
        results = run_tasks(run_job, jobs, args.scheduler, args.workers, desc="batch",
                            quiet=args.quiet)
    except OSError as exc:  # no scheduler at that address
        raise InputError(f"--scheduler {args.scheduler}: {exc}") from None
    write_batch(args.out, jobs, results)
    for r in results:
        row = r["row"]
        f1 = row["fscore_1%"]
        print(f"{row['job']:3d} {row['mesh']:28s} slices {str(row['slices']):>4s} "
              f"eps {row['eps']:.4g}  F@1% {'n/a' if f1 is None else format(f1, '.3f')}  "
              f"robot {row['robot_time_s']:.0f}s  wall {row['seconds']:.1f}s")
    print(f"wrote {Path(args.out) / 'batch.csv'} and {len(jobs)} runs in {Path(args.out) / 'runs'}")
    return 0
