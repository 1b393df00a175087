"""Whole-job benchmark: sense, rebuild and score every built-in scene and real meshes.

For each case, ``recon3d.run`` with ``--jobs 1`` and then ``--jobs 2`` (same
slices, same eps): Chamfer-L1 / diagonal and F@1% of the surface, 2D
reachable coverage, 3D surface coverage, wall time per jobs value, the
speed-up, and whether both runs gave identical metrics (they must).

Run from the repository root::

    python -m bench.bench_recon [--quick] [--slices 16] [--cases a,b] [--jobs 1,2]

``--quick``: 4 slices and eps = diagonal / 80 (a smoke run of a few minutes).
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

import meshes
import recon3d
from recon3d.io import without_timing

SHARED = Path(__file__).resolve().parents[2] / "shared" / "meshes"
REAL = ("trimesh_featuretype.stl", "mujoco_spot.ply", "trimesh_idler_riser.stl")


def _cases(arg):
    if arg:
        names = arg.split(",")
    else:
        names = meshes.names() + [m for m in REAL if (SHARED / m).is_file()]
    return [(n, str(SHARED / n) if (SHARED / n).is_file() else n) for n in names]




def _row(name, source, slices, share, jobs):
    mesh = meshes.load(source)
    diag = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)))
    eps = None if share is None else diag * share
    walls, docs, res = [], [], None
    for j in jobs:
        t0 = time.perf_counter()
        res = recon3d.run(source, slices=slices, eps=eps, jobs=j)
        walls.append(time.perf_counter() - t0)
        docs.append(without_timing(res.metrics))
    t, s = res.metrics["total"], res.metrics["total"]["surface"] or {}
    return {"case": name, "cd": (s.get("chamfer_l1") or np.nan) / diag,
            "f1": (s.get("fscore") or {}).get("1%", np.nan), "cov2d": t.get("coverage"),
            "cov3d": res.metrics["surface_eval"].get("coverage"), "walls": walls,
            "same": all(d == docs[0] for d in docs), "faces": len(res.surface.faces),
            "hits": t.get("budget_hits", 0)}


def _fmt(x, f):
    return "n/a" if x is None or (isinstance(x, float) and np.isnan(x)) else format(x, f)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="4 slices, eps = diagonal / 80")
    ap.add_argument("--slices", type=int, default=None, help="slices (default 16; quick 4)")
    ap.add_argument("--cases", default="", help="comma-separated scenes / mesh files")
    ap.add_argument("--jobs", default="1,2", help="jobs values to time (default 1,2)")
    args = ap.parse_args(argv)
    slices = args.slices or (4 if args.quick else 16)
    share = 1 / 80 if args.quick else None
    jobs = [int(j) for j in args.jobs.split(",")]
    print(f"{slices} z-slices, eps = diagonal / {80 if args.quick else 200}, jobs {jobs}")
    head = (f"{'case':26s} {'CD-L1/diag':>10s} {'F@1%':>6s} {'reach cov':>9s} "
            f"{'surf cov':>8s} " + " ".join(f"{'wall j' + str(j):>9s}" for j in jobs)
            + f" {'j1/j' + str(jobs[-1]):>7s} {'same':>5s} {'budget':>6s}")
    print(head)
    for name, source in _cases(args.cases):
        r = _row(name, source, slices, share, jobs)
        walls = " ".join(f"{w:8.1f}s" for w in r["walls"])
        print(f"{r['case']:26s} {_fmt(r['cd'], '10.2e')} {_fmt(r['f1'], '6.3f')} "
              f"{_fmt(r['cov2d'], '9.4f')} {_fmt(r['cov3d'], '8.3f')} {walls} "
              f"{r['walls'][0] / r['walls'][-1]:7.2f} {str(r['same']):>5s} {r['hits']:6d}",
              flush=True)


if __name__ == "__main__":
    main()
