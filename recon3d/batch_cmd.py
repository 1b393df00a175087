"""``recon3d batch MANIFEST --out DIR [--scheduler ADDRESS]``: run a manifest on Dask."""
from __future__ import annotations

import csv
import json
import os
import shutil
import tempfile
from pathlib import Path

__all__ = ["add_batch_parser", "batch_command", "write_batch"]


def add_batch_parser(sub) -> None:
    p = sub.add_parser(
        "batch", help="run many meshes x parameters (a TOML manifest) on Dask",
        description="Run every mesh of MANIFEST with every combination of its [params] "
        "(see README 'recon3d batch'), one job per Dask task: a local cluster with one "
        "worker per core by default, an existing cluster with --scheduler. Writes "
        "DIR/batch.csv and DIR/runs/NNN_<mesh>/{metrics.json,sensing.json,surface.ply}.")
    p.add_argument("manifest", metavar="MANIFEST", help="TOML file: meshes = [...] and [params]")
    p.add_argument("--out", required=True, help="output directory (created if missing)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="Dask scheduler address (tcp://host:8786), or 'serial' to run in "
                   "this process; default: a local cluster")
    p.add_argument("--workers", type=int, default=None,
                   help="local cluster worker processes (default: number of cores)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=batch_command)


def write_batch(out, jobs, results) -> list[Path]:
    """Write batch.csv and the per-job files into ``out``, all or nothing."""
    from recon3d.batch import COLUMNS
    from recon3d.save import write_ply

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    stage = Path(tempfile.mkdtemp(prefix=".recon3d-batch-", dir=out))
    try:
        runs = stage / "runs"
        runs.mkdir()
        for job, res in zip(jobs, results):
            d = runs / job.name
            d.mkdir()
            for key in ("metrics", "sensing"):
                with open(d / f"{key}.json", "w") as fh:
                    json.dump(res[key], fh, indent=1, allow_nan=False)
            write_ply(d / "surface.ply", _Surface(*res["surface"]))
        with open(stage / "batch.csv", "w", newline="") as fh:
            w = csv.DictWriter(fh, COLUMNS)
            w.writeheader()
            w.writerows(r["row"] for r in results)
        for name in ("runs", "batch.csv"):
            target = out / name
            if target.is_dir():
                shutil.rmtree(target)
            os.replace(stage / name, target)
        stage.rmdir()
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        raise
    return [out / "batch.csv", out / "runs"]


class _Surface:
    """vertices, faces, labels -> what :func:`recon3d.save.write_ply` reads."""

    def __init__(self, vertices, faces, labels):
        self.vertices, self.faces = vertices, faces
        self.face_attributes = {"label": labels}


def batch_command(args) -> int:
    from recon3d.batch import read_manifest, run_job
    from recon3d.checks import InputError, at_least, check_out_dir
    from recon3d.usage import UsageError
    from recon3d.distributed import run_tasks

    try:
        if args.workers is not None:
            at_least(args.workers, "--workers")
        check_out_dir(args.out, "--out")
        jobs = read_manifest(args.manifest)
    except InputError as exc:
        raise UsageError(str(exc)) from None
    try:
        results = run_tasks(run_job, jobs, args.scheduler, args.workers, desc="batch",
                            quiet=args.quiet)
    except OSError as exc:  # no scheduler at that address
        raise UsageError(f"--scheduler {args.scheduler}: {exc}") from None
    write_batch(args.out, jobs, results)
    for r in results:
        row = r["row"]
        f1 = row["fscore_1%"]
        print(f"{row['job']:3d} {row['mesh']:28s} slices {str(row['slices']):>4s} "
              f"eps {row['eps']:.4g}  F@1% {'n/a' if f1 is None else format(f1, '.3f')}  "
              f"robot {row['robot_time_s']:.0f}s  wall {row['seconds']:.1f}s")
    print(f"wrote {Path(args.out) / 'batch.csv'} and {len(jobs)} runs in {Path(args.out) / 'runs'}")
    return 0
