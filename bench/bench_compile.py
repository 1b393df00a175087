"""The first compile of the sensing kernels: cold (empty numba cache) and warm, per commit.

For each commit (exported with ``git archive``; ``WORKTREE`` is this checkout
as it is) it runs, in a fresh process with an empty ``NUMBA_CACHE_DIR``, the
sensing of one z-slice of ``fig18_overhangs`` (Embree backend, eps =
diagonal / 200, every compiled kernel of the planner and the simulator a
run uses), then the same process again on the filled cache. It prints the
wall seconds of both, their difference (the compile) in wall and in CPU
seconds (user + system: less sensitive to a shared machine), the numba
signatures compiled, and the 1-minute load average before the cold run.
(The compile notice is the CLI's, tested in ``tests/test_compile_notice.py``.)

    python -m bench.bench_compile [COMMIT ...] [--repeat 1]
"""
from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
WORKTREE = "WORKTREE"

_JOB = """
import logging, sys, numpy as np
logging.disable(logging.WARNING)
import core2d, meshes, slicer
mesh = meshes.load("fig18_overhangs")
eps = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)) / 200)
cut = [c for c in slicer.slice_mesh(mesh, axis="z", count=4) if c.loops][1]
center, radius = cut.bounding_circle()
core2d.sense_slice(cut.contact("embree"), (center, radius + eps), eps)
import numba.core.registry as reg
from numba.core.dispatcher import Dispatcher
found = {}  # each kernel once, however many modules import it by name
for mod in [m for name, m in list(sys.modules.items())
            if name.split(".")[0] in ("core2d", "slicer")]:
    for obj in vars(mod).values():
        if isinstance(obj, Dispatcher):
            found[id(obj)] = len(obj.signatures)
print("SIGNATURES", sum(found.values()))
"""


def _tree(commit: str, tmp: Path) -> tuple[str, Path]:
    """(label, source tree) of ``commit``."""
    if commit == WORKTREE:
        return "worktree", ROOT
    short = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", commit],
                           check=True, capture_output=True, text=True).stdout.strip()
    dest = tmp / short
    if not dest.is_dir():
        tar = tmp / f"{short}.tar"
        with open(tar, "wb") as fh:
            subprocess.run(["git", "-C", str(ROOT), "archive", commit], stdout=fh, check=True)
        with tarfile.open(tar) as tf:
            tf.extractall(dest, filter="data")
    return short, dest


def _cpu() -> float:
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def _run(src: Path, cache: Path) -> tuple[float, float, int, float]:
    """(wall s, CPU s, signatures, load) of one sensing process."""
    env = dict(os.environ, PYTHONPATH=str(src), NUMBA_CACHE_DIR=str(cache))
    load = os.getloadavg()[0]
    t0, c0 = time.perf_counter(), _cpu()
    proc = subprocess.run([sys.executable, "-c", _JOB], cwd=str(src), env=env,
                          capture_output=True, text=True)
    wall, cpu = time.perf_counter() - t0, _cpu() - c0
    if proc.returncode:
        raise SystemExit(f"sensing failed in {src}: {proc.stderr.strip().splitlines()[-1]}")
    sigs = int(proc.stdout.split("SIGNATURES")[1].split()[0])
    return wall, cpu, sigs, load


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("commits", nargs="*", default=[WORKTREE],
                   help="commits to measure (default: this checkout, WORKTREE)")
    p.add_argument("--repeat", type=int, default=1, help="cold runs per commit")
    args = p.parse_args(argv)
    if args.repeat < 1:
        p.error("--repeat must be >= 1")
    print(f"{'commit':10s} {'cold s':>7s} {'warm s':>7s} {'compile s':>9s} "
          f"{'compile CPU s':>13s} {'signatures':>10s} {'load':>5s}")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for commit in args.commits:
            label, src = _tree(commit, tmp)
            for k in range(args.repeat):
                cache = tmp / f"cache-{label}-{k}"
                cold, cold_cpu, sigs, load = _run(src, cache)
                warm, warm_cpu, _, _ = _run(src, cache)
                print(f"{label:10s} {cold:7.1f} {warm:7.1f} {cold - warm:9.1f} "
                      f"{cold_cpu - warm_cpu:13.1f} {sigs:10d} {load:5.2f}", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
