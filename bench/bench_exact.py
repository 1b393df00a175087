"""The exact 2D backend's sensing time, this checkout against another commit, in one run.

Senses a fixed set of 2D slices through :class:`slicer.contact.exact.ExactContact`: the five
blocks of the paper's figures (``tests/figure_scenes.py``) noiseless and at sigma 0.3 eps +
taxels 0.25 eps (sensor seed 0), and one seeded outline of each kind of ``tests/outlines.py``
(seed 2) noiseless and at sigma 0.1 eps. Each checkout runs the whole set in a fresh
interpreter (after one warm-up run that builds its compiled kernels; each run loads them
before its timed slices), the two
alternating run by run (``--repeat`` each); printed per case: the median seconds of both,
their ratio, and whether the two runs are the same (motions, casts, pushes and the W1 / W2 /
W3 / unknown polylines to the bit).

    python -m bench.bench_exact --before REV [--repeat 3]
"""
from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

from bench.compare_commits import export

ROOT = Path(__file__).resolve().parents[1]

_DRIVER = r"""
import hashlib, json, sys, time
import numpy as np
import figure_scenes as F, outlines
from core2d import SensorModel, sense_slice
from slicer.contact.exact import ExactContact

def digest(res):
    h = hashlib.sha256()
    for key in ("w1", "w2", "w3", "unknown"):
        for a in getattr(res, key):
            h.update(np.ascontiguousarray(a, dtype=np.float64).tobytes())
        h.update(b"|")
    s = res.stats
    return f"{h.hexdigest()[:16]} {s.motions} {s.casts} {s.pushes}"

cases = []
for name in ("V_POCKET", "SLOPE_RIGHT", "OVERHANG_LEFT", "OVERHANG_RIGHT", "HILL"):
    for noise, taxel in ((0.0, 0.0), (0.3, 0.25)):
        cases.append((f"{name} s{noise}", F.block(getattr(F, name)), F.WORKSPACE, noise, taxel))
for kind in outlines.KINDS:
    loops = outlines.outline(kind, np.random.default_rng(2), eps=1.0)
    pts = np.concatenate(loops)
    lo, hi = pts.min(0), pts.max(0)
    ws = ((lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2 + 1.0))  # as bench.sensor_study
    for noise in (0.0, 0.1):
        cases.append((f"{kind}-2 s{noise}", loops, ws, noise, 0.0))
# loaded before timing: the compiled kernels (from numba's cache) and the lazy imports
sense_slice(ExactContact(F.block(F.HILL)), F.WORKSPACE, 1.0, max_motions=20)
out = {}
for name, loops, ws, noise, taxel in cases:
    sensor = SensorModel.of_eps(1.0, noise, taxel, 0) if noise or taxel else None
    t0 = time.perf_counter()
    res = sense_slice(ExactContact(loops), ws, 1.0, sensor=sensor)
    out[name] = (time.perf_counter() - t0, digest(res), res.stats.motions)
print(json.dumps(out))
"""


def _run(root: Path) -> dict:
    env = dict(os.environ, PYTHONPATH=f"{root}{os.pathsep}{root / 'tests'}")
    proc = subprocess.run([sys.executable, "-c", _DRIVER], cwd=root, env=env,
                          capture_output=True, text=True, check=False)
    if proc.returncode:
        sys.exit(f"bench_exact: the driver failed in {root}:\n{proc.stderr[-2000:]}")
    return json.loads(proc.stdout)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--before", required=True, help="commit to measure against")
    ap.add_argument("--repeat", type=int, default=3, help="runs per checkout (default 3)")
    args = ap.parse_args(argv)
    short, src = export(args.before, ROOT / "out" / "compare")
    here = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, text=True,
                          capture_output=True).stdout.strip()
    trees = ((f"before {short}", src), (f"after {here}+worktree", ROOT))
    for _, root in trees:  # warm-up: kernels loaded (or compiled) outside the timed runs
        _run(root)
    runs = {tag: [] for tag, _ in trees}
    for _ in range(args.repeat):
        for tag, root in trees:
            runs[tag].append(_run(root))
    (bt, _), (at, _) = trees
    print(f"exact backend, {len(runs[bt][0])} slices, medians of {args.repeat}; {bt} -> {at}")
    print(f"{'case':24s} {'before s':>9s} {'after s':>8s} {'ratio':>6s} {'motions':>8s}  same")
    total_b = total_a = 0.0
    same_all = 0
    for case in runs[bt][0]:
        b = statistics.median(r[case][0] for r in runs[bt])
        a = statistics.median(r[case][0] for r in runs[at])
        same = runs[bt][0][case][1] == runs[at][0][case][1]
        total_b, total_a, same_all = total_b + b, total_a + a, same_all + same
        print(f"{case:24s} {b:9.3f} {a:8.3f} {a / b:6.3f} {runs[at][0][case][2]:8d}  "
              f"{'same' if same else 'differ'}")
    print(f"{'all':24s} {total_b:9.3f} {total_a:8.3f} {total_a / total_b:6.3f}  "
          f"{same_all} of {len(runs[bt][0])} the same")
    return 0


if __name__ == "__main__":
    sys.exit(main())
