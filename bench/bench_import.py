"""Import times of the packages, each in a fresh interpreter (issue 20: ``import recon3d`` <= 0.5 s).

For each package, ``python -X importtime -c "import PKG"`` runs ``--repeat`` times (default 5)
in a new process, after one untimed run (so the ``.pyc`` files exist); the median of the
cumulative import time of the package (from ``-X importtime``, the interpreter's own
start-up excluded) and of the process's wall time are printed, with the heavy libraries
the import loaded. Nothing is asserted: it measures.

    python -m bench.bench_import
    python -m bench.bench_import --repeat 9 recon3d
"""
from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("recon3d", "core2d", "slicer")
HEAVY = ("trimesh", "scipy", "numba", "shapely", "embreex", "manifold3d", "pyvista",
         "matplotlib", "vtkmodules", "dask")
TARGET = {"recon3d": 0.5}
"""Seconds: the targets of issue 20."""


def _once(pkg: str) -> tuple[float, float, list[str]]:
    """(import seconds, process wall seconds, heavy libraries loaded) of one fresh import."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
    code = (f"import sys, {pkg}; "
            f"print(' '.join(sorted({{m.split('.')[0] for m in sys.modules}} & {set(HEAVY)!r})))")
    t0 = time.perf_counter()
    out = subprocess.run([sys.executable, "-X", "importtime", "-c", code], cwd=ROOT, env=env,
                         capture_output=True, text=True, check=True)
    wall = time.perf_counter() - t0
    line = [ln for ln in out.stderr.splitlines() if ln.rstrip().endswith(f"| {pkg}")][-1]
    return int(line.split("|")[1]) / 1e6, wall, out.stdout.split()


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("packages", nargs="*", default=list(PACKAGES))
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    print(f"{'package':10s} {'import s':>9s} {'process s':>10s} {'target':>7s}  heavy loaded")
    for pkg in args.packages:
        _once(pkg)  # untimed: writes the .pyc files
        runs = [_once(pkg) for _ in range(args.repeat)]
        imp = statistics.median(r[0] for r in runs)
        wall = statistics.median(r[1] for r in runs)
        target = f"{TARGET[pkg]:.1f}" if pkg in TARGET else "-"
        print(f"{pkg:10s} {imp:9.3f} {wall:10.3f} {target:>7s}  {' '.join(runs[-1][2]) or '-'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
