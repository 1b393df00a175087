"""``recon3d batch MANIFEST --out DIR [--scheduler ADDRESS]``: run a manifest on Dask.

Run every mesh of MANIFEST with every combination of its [params] (see
README 'recon3d batch'), one job per Dask task: a local cluster with one
worker per core by default, an existing cluster with --scheduler. Writes
DIR/batch.csv and DIR/runs/NNN_<mesh>/{metrics.json,sensing.json,surface.ply};
DIR is locked while the batch lasts, and a DIR holding an earlier batch is
refused unless --overwrite.
"""
from __future__ import annotations

from pathlib import Path

from recon3d.checks import InputError, at_least, check_out_dir
from recon3d.spellings import manifest_doc

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
    p.add_argument("--overwrite", action="store_true",
                   help="replace the batch.csv and runs/ of an earlier batch in --out "
                   "(without it, such an --out is refused)")
    p.epilog = manifest_doc()
    add_cluster_flags(p, "Dask scheduler address (tcp://host:8786), or 'serial' to run in "
                      "this process; default: a local cluster")


def command(args) -> int:
    # the batch's libraries (the runs, Dask): `recon3d --help` loads none of them
    from recon3d.io.lock import OutputLock  # lazy: recon3d.io loads the records (core2d)
    from recon3d.jobs.batch import read_manifest  # lazy: see above

    if args.workers is not None:
        at_least(args.workers, "--workers")
    check_out_dir(args.out, "--out")
    jobs = read_manifest(args.manifest)
    with OutputLock(args.out, "--out"):  # a second run into --out is refused from here on
        _refuse_earlier_batch(args.out, args.overwrite)
        results = _run(args, jobs)
    for r in results:  # printed once the outputs are complete and --out is free
        row = r["row"]
        f1 = row["fscore_1%"]
        print(f"{row['job']:3d} {row['mesh']:28s} slices {str(row['slices']):>4s} "
              f"eps {row['eps']:.4g}  F@1% {'n/a' if f1 is None else format(f1, '.3f')}  "
              f"robot {row['robot_time_s']:.0f}s  wall {row['seconds']:.1f}s")
    print(f"wrote {Path(args.out) / 'batch.csv'} and {len(jobs)} runs in {Path(args.out) / 'runs'}")
    return 0


def _refuse_earlier_batch(out, overwrite: bool) -> None:
    """An --out holding an earlier batch (batch.csv or runs/) needs --overwrite."""
    held = [n for n in ("batch.csv", "runs") if (Path(out) / n).exists()]
    if held and not overwrite:
        raise InputError(f"--out {out} holds an earlier batch ({' and '.join(held)}); "
                         f"give --overwrite to replace it, or choose another --out")


def _run(args, jobs) -> list[dict]:
    """Run the jobs and write their outputs (``--out`` held); the results."""
    from recon3d.jobs.batch import run_job, write_batch  # lazy: as in command
    from recon3d.jobs.cluster import run_tasks  # lazy: Dask

    try:
        results = run_tasks(run_job, jobs, args.scheduler, args.workers, desc="batch",
                            quiet=args.quiet)
    except OSError as exc:  # no scheduler at that address
        raise InputError(f"--scheduler {args.scheduler}: {exc}") from None
    write_batch(args.out, jobs, results)
    return results
