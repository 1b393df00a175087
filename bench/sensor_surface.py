"""The 3D result with real sensors: F@1 % of whole runs, noiseless against noisy.

:mod:`bench.sensor_study` scores the slices in 2D; this runs :func:`recon3d.run` (8
z-slices, Embree, the defaults otherwise, sensor seed 0) on every built-in scene at each
sensor level and prints, per scene and level, the surface's F@1 % over the slab, the
reachable coverage within eps/2 + 2 sigma (eps/2 noiseless) and the run's unknown chords
and bridges (the closure's unsensed pieces, :mod:`recon3d.surface.closure`), then the
median and the worst drop of F@1 % from the noiseless run. Nothing is asserted: it measures
where the 3D result loses what the 2D coverage keeps.

    python -m bench.sensor_surface [--scenes a,b] [--levels 0.1:0,0.3:0.25] [--slices 8]
                                   [--csv FILE]
"""
from __future__ import annotations

import argparse
import csv
import statistics
import subprocess
import sys
import time

LEVELS = ((0.1, 0.0), (0.3, 0.25))
"""(noise, taxel) in eps, besides the noiseless run."""


def _row(scene: str, slices: int, noise: float, taxel: float) -> dict:
    import recon3d

    res = recon3d.run(scene, slices=slices, jobs=2, noise=noise, taxel=taxel, seed=0)
    tot = res.metrics["total"]
    surf = tot.get("surface") or {}
    pieces = [p for fam in res.recon.regions for reg in fam for p in reg.pieces]
    return {"scene": scene, "noise": noise, "taxel": taxel,
            "fscore_1%": (surf.get("fscore") or {}).get("1%"),
            "coverage": tot.get("coverage_sensor", tot.get("coverage")),
            "unknown": sum(p.kind == "unknown" for p in pieces),
            "bridges": sum(p.kind == "bridge" for p in pieces),
            "motions": tot.get("motions")}


def _levels(text: str) -> tuple:
    return tuple(tuple(float(x) for x in part.split(":")) for part in text.split(","))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.sensor_surface", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", help="comma-separated built-in scenes (default: all)")
    ap.add_argument("--levels", type=_levels, default=LEVELS,
                    help="noise:taxel pairs in eps (default 0.1:0,0.3:0.25)")
    ap.add_argument("--slices", type=int, default=8, help="z-slices per run (8)")
    ap.add_argument("--csv", help="write the rows here too")
    args = ap.parse_args(argv)
    import meshes

    scenes = args.scenes.split(",") if args.scenes else list(meshes.names())
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip() or "unknown"
    if subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                      capture_output=True, text=True).stdout.strip():
        commit += " with uncommitted changes"
    print(f"commit {commit}; {args.slices} z-slices, Embree, sensor seed 0", flush=True)
    t0, rows = time.perf_counter(), []
    print("each cell: F@1 % over the slab (reachable coverage, within eps/2 + 2 sigma with a "
          "sensor; unknown chords / bridges in the slices' closed regions)")
    head = " | ".join(f"sigma {n:g} T {t:g}" for n, t in args.levels)
    print(f"{'scene':18s} noiseless | {head}", flush=True)
    for scene in scenes:
        mine = [_row(scene, args.slices, 0.0, 0.0)]
        mine += [_row(scene, args.slices, n, t) for n, t in args.levels]
        rows += mine
        print(f"{scene:18s} " + " | ".join(
            f"{r['fscore_1%']:.3f} ({r['coverage']:.3f}; {r['unknown']} / {r['bridges']})"
            for r in mine), flush=True)
    for n, t in args.levels:
        drops = [b["fscore_1%"] - a["fscore_1%"] for a, b in
                 zip(rows[::len(args.levels) + 1],
                     [r for r in rows if (r["noise"], r["taxel"]) == (n, t)])]
        print(f"sigma {n:g} eps, taxel {t:g} eps: F@1 % change from noiseless median "
              f"{statistics.median(drops):+.3f}, worst {min(drops):+.3f}")
    if args.csv:
        with open(args.csv, "w", newline="") as fh:
            w = csv.DictWriter(fh, list(rows[0]))
            w.writeheader()
            w.writerows(rows)
    print(f"{len(rows)} runs in {time.perf_counter() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
