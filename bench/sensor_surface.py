"""The 3D result with real sensors: F@1 % of whole runs, noiseless against noisy.

:mod:`bench.sensor_study` scores the slices in 2D; this runs :func:`recon3d.run` (8
z-slices, Embree, the defaults otherwise) on every built-in scene at each sensor level and
prints, per scene and level, the surface's F@1 % over the slab, the reachable coverage
within eps/2 + 2 sigma (eps/2 noiseless) and the run's unknown chords and bridges (the
closure's unsensed pieces, :mod:`recon3d.surface.closure`), then the median and the worst
drop of F@1 % from the noiseless run. Nothing is asserted: it measures where the 3D result
loses what the 2D coverage keeps.

``--seeds K`` runs every noisy level with sensor seeds 0 .. K - 1 (the noiseless run once);
``--keyed-noise`` keys each reading's draws by its posture (``recon3d run --keyed-noise``),
so two planners read the same draws where they make the same motion. ``--before CSV``
pairs this study's noisy runs with an earlier one's (same scene, level and seed) and prints
the mean F@1 % change with its 95 % paired-bootstrap interval and the sign test
(:mod:`bench.paired`): is a planner change more than the sensor's lottery in 3D?
``--reads N`` averages N reads at each reading point (``recon3d run --reads``; default
``auto``, as a run takes them), so two reads rules compare the same way.

    python -m bench.sensor_surface [--scenes a,b] [--levels 0.1:0,0.3:0.25] [--slices 8]
                                   [--seeds K] [--keyed-noise] [--reads N] [--csv FILE]
                                   [--before CSV]
"""
from __future__ import annotations

import argparse
import csv
import math
import statistics
import subprocess
import sys
import time

__all__ = ["LEVELS", "paired_lines", "main"]

LEVELS = ((0.1, 0.0), (0.3, 0.25))
"""(noise, taxel) in eps, besides the noiseless run."""


def _row(scene: str, slices: int, noise: float, taxel: float, seed: int = 0,
         keyed: bool = False, reads: int | str = "auto") -> dict:
    import recon3d

    res = recon3d.run(scene, slices=slices, jobs=2, noise=noise, taxel=taxel, seed=seed,
                      keyed_noise=keyed, reads=reads)
    tot = res.metrics["total"]
    surf = tot.get("surface") or {}
    pieces = [p for fam in res.recon.regions for reg in fam for p in reg.pieces]
    return {"scene": scene, "noise": noise, "taxel": taxel, "seed": seed,
            "keyed": bool(keyed and noise),  # taxels alone draw nothing to key
            "reads": (res.metrics.get("sensor") or {}).get("reads", 1),
            "fscore_1%": (surf.get("fscore") or {}).get("1%"),
            "coverage": tot.get("coverage_sensor", tot.get("coverage")),
            "unknown": sum(p.kind == "unknown" for p in pieces),
            "bridges": sum(p.kind == "bridge" for p in pieces),
            "motions": tot.get("motions")}


def _levels(text: str) -> tuple:
    return tuple(tuple(float(x) for x in part.split(":")) for part in text.split(","))


def _key(row: dict) -> tuple:
    return (row["scene"], float(row["noise"]), float(row["taxel"]), int(row.get("seed") or 0))


def paired_lines(before: list[dict], after: list[dict]) -> list[str]:
    """Per noisy level, the mean F@1 % of the runs both studies made (scene, level and
    sensor seed alike), before and after, with the change's 95 % paired-bootstrap interval
    and the sign test of the runs that moved; a line more when one study's noise is keyed
    and the other's is not (their runs then share no draws).

    >>> a = [{"scene": "s", "noise": 0.3, "taxel": 0.0, "seed": 0, "fscore_1%": 0.9}]
    >>> paired_lines(a, [dict(a[0], **{"fscore_1%": 0.95})])[0]
    'sigma 0.3 eps, taxel 0 eps: 1 paired runs, mean F@1 % 0.9000 -> 0.9500 (+0.0500, too few runs for an interval); up 1, down 0, sign test p = 1'
    """
    from bench.paired import pooled_change, sign_test

    old = {_key(r): r for r in before if float(r["noise"]) or float(r["taxel"])}
    lines = []
    if {str(r.get("keyed")) == "True" for r in old.values()} != {
            str(r.get("keyed")) == "True" for r in after if _key(r) in old}:
        lines.append("warning: one study's noise is keyed and the other's is not: "
                     "their runs share no draws")
    for level in sorted({k[1:3] for k in old}):
        pairs = [(float(old[_key(r)]["fscore_1%"]), float(r["fscore_1%"])) for r in after
                 if _key(r) in old and _key(r)[1:3] == level
                 and str(r["fscore_1%"]) not in ("", "None")
                 and str(old[_key(r)]["fscore_1%"]) not in ("", "None")]
        if not pairs:
            continue
        x, y = zip(*pairs)
        c = pooled_change(list(x), list(y), weight=[1.0] * len(x))
        up = sum(b > a + 1e-12 for a, b in pairs)
        down = sum(b < a - 1e-12 for a, b in pairs)
        ci = ("too few runs for an interval" if math.isnan(c.low)
              else f"95 % interval {c.low:+.4f} .. {c.high:+.4f}")
        lines.append(f"sigma {level[0]:g} eps, taxel {level[1]:g} eps: {len(pairs)} paired runs, "
                     f"mean F@1 % {c.before:.4f} -> {c.after:.4f} ({c.change:+.4f}, {ci}); "
                     f"up {up}, down {down}, sign test p = {sign_test(up, down):.3g}")
    return lines


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.sensor_surface", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", help="comma-separated built-in scenes (default: all)")
    ap.add_argument("--levels", type=_levels, default=LEVELS,
                    help="noise:taxel pairs in eps (default 0.1:0,0.3:0.25)")
    ap.add_argument("--slices", type=int, default=8, help="z-slices per run (8)")
    ap.add_argument("--seeds", type=int, default=1,
                    help="sensor seeds 0 .. K-1 per noisy level (default 1)")
    ap.add_argument("--keyed-noise", action="store_true",
                    help="key each reading's noise by its posture (recon3d run --keyed-noise)")
    ap.add_argument("--reads", default="auto", metavar="N",
                    help="sensor reads averaged at each reading point: 'auto' (default, as "
                    "recon3d run) or a number (recon3d run --reads)")
    ap.add_argument("--csv", help="write the rows here too")
    ap.add_argument("--before", help="an earlier study's CSV: print the paired change")
    args = ap.parse_args(argv)
    import meshes

    if args.seeds < 1:
        ap.error("--seeds must be at least 1")
    if args.reads != "auto" and not (args.reads.isdigit() and int(args.reads) >= 1):
        ap.error(f"--reads is 'auto' or a number >= 1 (got {args.reads!r})")
    reads = args.reads if args.reads == "auto" else int(args.reads)
    before = None
    if args.before:
        try:
            with open(args.before, newline="") as fh:
                before = list(csv.DictReader(fh))
        except OSError as exc:
            ap.error(f"--before: cannot read {args.before}: {exc.strerror}")
    scenes = args.scenes.split(",") if args.scenes else list(meshes.names())
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip() or "unknown"
    if subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                      capture_output=True, text=True).stdout.strip():
        commit += " with uncommitted changes"
    seeds = range(args.seeds)
    print(f"commit {commit}; {args.slices} z-slices, Embree, sensor seeds "
          f"{', '.join(map(str, seeds))}{', keyed' if args.keyed_noise else ''}, reads {reads}",
          flush=True)
    t0, rows = time.perf_counter(), []
    print("each cell: F@1 % over the slab (reachable coverage, within eps/2 + 2 sigma with a "
          "sensor; unknown chords / bridges in the slices' closed regions)")
    head = " | ".join(f"sigma {n:g} T {t:g}" + (f" seed {s}" if args.seeds > 1 else "")
                      for n, t in args.levels for s in seeds)
    print(f"{'scene':18s} noiseless | {head}", flush=True)
    for scene in scenes:
        mine = [_row(scene, args.slices, 0.0, 0.0)]
        mine += [_row(scene, args.slices, n, t, s, args.keyed_noise, reads)
                 for n, t in args.levels for s in seeds]
        rows += mine
        print(f"{scene:18s} " + " | ".join(
            f"{r['fscore_1%']:.3f} ({r['coverage']:.3f}; {r['unknown']} / {r['bridges']})"
            for r in mine), flush=True)
    base = {r["scene"]: r["fscore_1%"] for r in rows if not (r["noise"] or r["taxel"])}
    for n, t in args.levels:
        drops = [r["fscore_1%"] - base[r["scene"]] for r in rows
                 if (r["noise"], r["taxel"]) == (n, t)]
        print(f"sigma {n:g} eps, taxel {t:g} eps: F@1 % change from noiseless median "
              f"{statistics.median(drops):+.3f}, worst {min(drops):+.3f}"
              + (f" (over {len(drops)} runs: {len(scenes)} scenes x {args.seeds} seeds)"
                 if args.seeds > 1 else ""))
    if before is not None:
        print(f"against {args.before}:")
        for line in paired_lines(before, rows):
            print("  " + line)
    if args.csv:
        with open(args.csv, "w", newline="") as fh:
            w = csv.DictWriter(fh, list(rows[0]))
            w.writeheader()
            w.writerows(rows)
    print(f"{len(rows)} runs in {time.perf_counter() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
