"""The first compile of the sensing kernels: cold (empty numba cache) and warm, per commit.

For each commit (exported with ``git archive``; ``WORKTREE`` is this checkout
as it is) it runs, in a fresh process with an empty ``NUMBA_CACHE_DIR``, the
sensing of one z-slice of ``fig18_overhangs`` (Embree backend, eps =
diagonal / 200, every compiled kernel of the planner and the simulator a
run uses), then the same process again on the filled cache. It prints the
wall seconds of both, their difference (the compile), the numba
signatures compiled, whether the compile announcement appeared on stderr,
and the 1-minute load average before each run (the machine may be shared).

    python -m bench.bench_compile [COMMIT ...] [--repeat 1]
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
WORKTREE = "WORKTREE"
ANNOUNCEMENT = "compiling sensing kernels"

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
n = 0
for mod in [m for name, m in list(sys.modules.items())
            if name.split(".")[0] in ("core2d", "slicer")]:
    for obj in vars(mod).values():
        if isinstance(obj, Dispatcher):
            n += len(obj.signatures)
print("SIGNATURES", n)
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


def _run(src: Path, cache: Path) -> tuple[float, int, bool, float]:
    """(wall s, signatures, announced, load) of one sensing process."""
    env = dict(os.environ, PYTHONPATH=str(src), NUMBA_CACHE_DIR=str(cache))
    load = os.getloadavg()[0]
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", _JOB], cwd=str(src), env=env,
                          capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if proc.returncode:
        raise SystemExit(f"sensing failed in {src}: {proc.stderr.strip().splitlines()[-1]}")
    sigs = int(proc.stdout.split("SIGNATURES")[1].split()[0])
    return wall, sigs, ANNOUNCEMENT in proc.stderr, load


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("commits", nargs="*", default=[WORKTREE],
                   help="commits to measure (default: this checkout, WORKTREE)")
    p.add_argument("--repeat", type=int, default=1, help="cold runs per commit")
    args = p.parse_args(argv)
    if args.repeat < 1:
        p.error("--repeat must be >= 1")
    print(f"{'commit':10s} {'cold s':>7s} {'warm s':>7s} {'compile s':>9s} {'signatures':>10s} "
          f"{'announced':>9s} {'load':>5s}")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for commit in args.commits:
            label, src = _tree(commit, tmp)
            for k in range(args.repeat):
                cache = tmp / f"cache-{label}-{k}"
                cold, sigs, said, load = _run(src, cache)
                warm, _, said_warm, _ = _run(src, cache)
                print(f"{label:10s} {cold:7.1f} {warm:7.1f} {cold - warm:9.1f} {sigs:10d} "
                      f"{'yes' if said and not said_warm else 'no':>9s} {load:5.2f}",
                      flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
