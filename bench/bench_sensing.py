"""Sensing speed per slice: this checkout against an earlier commit and against raw Embree.

For every built-in scene (``--slices`` z-slices, eps = diagonal / 200, the
Embree backend) it prints, measured in one run:

* ``before s`` / ``after s`` -- CPU seconds of ``core2d.sense_slice`` per
  slice for the commit ``--before`` (default ``c95dda6``, exported with
  ``git archive`` into a temporary directory; an untimed run on 2 slices of
  ``fig18_overhangs`` first compiles its numba kernels into their cache) and
  for this checkout, each scene's runs alternating before / after
  ``--repeat`` times (median);
* ``speed-up`` -- before / after;
* ``x large`` -- sensing CPU over the CPU embreex alone needs for the same
  rays in calls of 65,536 (Embree's throughput), and ``x cast`` -- over
  embreex on the same rays in the casts as issued: every ray this checkout
  cast, logged ray by ray (:mod:`bench.ray_log`) and replayed on the same
  scene (``before->after`` with ``--raw-before``);
* ``rays``, ``casts``, ``motions`` per slice (before -> after when they differ);
* ``same`` -- whether this checkout gives the same result as the commit
  ``--reference`` (default: ``--before``; give the last commit that changed
  the planner's rules when it came after ``--before``), per slice: ``=``
  identical geometry; else the share of contour samples (every eps/4)
  whose class differs (W1 within eps/2 of a traced polyline, W2 within
  eps/2 of or behind a chord, W3 behind a lid, or none), and the coverage,
  precision and W3-soundness of both;
* ``peak MiB`` -- peak resident memory of the process that sensed the slices
  (after), and what it held before sensing (imports, mesh, slices).

``--noise S --taxel T [--keyed-noise]`` senses both sides through a sensor (noise and
taxel spacing in eps, the reads averaged as ``recon3d run`` averages them, sensor seed =
the slice's index): what a noisy run costs, and whether a change keeps its results.

``--tols`` adds a table of peak memory and time against the contact
resolution (tol = eps x share), which the windows of the simulator keep
bounded. Times are CPU seconds: the machine may be shared; compare the
ratios, which are measured side by side.

    python -m bench.bench_sensing [--slices 4] [--repeat 1] [--scenes a,b] [--before REV]
                                  [--reference REV] [--no-before] [--raw-before]
                                  [--tols 0.05,0.005] [--json out.json]
                                  [--noise S] [--taxel T] [--keyed-noise]

The first line printed names both commits (``+dirty``: uncommitted changes).
"""
from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
WORKER = Path(__file__).resolve().with_name("sensing_worker.py")
FIGURES = ("fig17_pocket", "fig18_overhangs")


def export(rev: str, into: Path) -> Path:
    """Files of commit ``rev`` of this repository, unpacked under ``into``."""
    tar = into / "before.tar"
    with open(tar, "wb") as fh:
        subprocess.run(["git", "-C", str(ROOT), "archive", rev], stdout=fh, check=True)
    dest = into / "before"
    with tarfile.open(tar) as tf:
        tf.extractall(dest, filter="data")
    return dest


def sense(root: Path, scene: str, slices: int, out: Path, raw=False, tol_share=None,
          sensor=None) -> dict:
    """Run the worker for one checkout and scene; its JSON document. ``sensor``:
    ``"NOISE,TAXEL,KEYED"`` (module doc)."""
    cmd = [sys.executable, str(WORKER), str(root), scene, str(slices), str(out)]
    cmd += ["--raw"] * raw + (["--tol-share", str(tol_share)] if tol_share else [])
    cmd += ["--sensor", sensor] if sensor else []
    subprocess.run(cmd, check=True, cwd=str(root))
    return json.loads(out.read_text())


def _classes(loops, geometry, eps):
    """Class per contour sample (0 none, 1 W1, 2 W2, 3 W3) and the samples."""
    import shapely

    from core2d.truth.metrics import lid_arcs
    from core2d.truth.reachability import sample_contour

    samp = sample_contour(loops, eps / 4)
    cls = np.zeros(len(samp.points), dtype=np.int8)
    pts = shapely.points(samp.points)
    for code, key in ((3, "w3"), (2, "w2"), (1, "w1")):  # W1 over W2 over W3
        parts = [np.asarray(p, float) for p in geometry[key] if len(p) >= 2]
        if not parts:
            continue
        mask = np.zeros(len(cls), dtype=bool)
        if code < 3:
            mask |= shapely.distance(shapely.MultiLineString(parts), pts) <= eps / 2
        if code > 1:
            mask |= lid_arcs(loops, parts, samp, resolution=eps / 4)["mask"]
        cls[mask] = code
    return cls


def _metrics(loops, geometry, eps) -> dict:
    from core2d.result import SliceResult
    from core2d.truth.metrics import slice_metrics

    res = SliceResult(**{k: [np.asarray(a, float) for a in v] for k, v in geometry.items()})
    m = slice_metrics(loops, res, eps)
    return {k: m[k] for k in ("coverage", "precision", "w3_count", "w3_unsound_count")}


def compare(scene: str, before: dict, after: dict, slices: int) -> list[dict]:
    """Per slice: identical geometry, differing sample classes, metrics of both."""
    import meshes
    import slicer

    cuts = [c for c in slicer.slice_mesh(meshes.load(scene), axis="z", count=slices) if c.loops]
    out = []
    for cut, b, a in zip(cuts, before["slices"], after["slices"]):
        loops = [np.asarray(lp) for lp in cut.loops]
        row = {"identical": b["geometry"] == a["geometry"], "class_diff": 0.0}
        if not row["identical"]:
            cb, ca = (_classes(loops, s["geometry"], s["eps"]) for s in (b, a))
            row["class_diff"] = float(np.mean(cb != ca))
        row["before"], row["after"] = (_metrics(loops, s["geometry"], s["eps"]) for s in (b, a))
        out.append(row)
    return out


def _fmt_counts(b, a) -> str:
    return f"{b:.0f}" if round(b) == round(a) else f"{b:.0f}->{a:.0f}"


def _same(rows) -> str:
    if all(r["identical"] for r in rows):
        return "="
    worst = max(r["class_diff"] for r in rows)
    keys = ("coverage", "precision", "w3_count", "w3_unsound_count")
    metrics = all(abs(r["before"][k] - r["after"][k]) <= 1e-3 for r in rows for k in keys)
    return f"{worst:.1%} of samples" + ("" if metrics else " (metrics differ)")


def scene_row(scene, runs_b, runs_a, cmp_rows) -> dict:
    """Summary of one scene (per slice: seconds, counts; whole: ratios). The first run
    of each side carries its raw-Embree replay (``raw_seconds``, ``large_seconds``)."""
    n = len(runs_a[0]["slices"])
    per = lambda doc, key: sum(s[key] for s in doc["slices"]) / max(n, 1)  # noqa: E731
    after = statistics.median(per(d, "seconds") for d in runs_a)
    before = statistics.median(per(d, "seconds") for d in runs_b) if runs_b else None

    def raw(docs, key):
        return docs[0][key] / max(n, 1) if docs and key in docs[0] else None

    return dict(scene=scene, slices=n, before=before, after=after,
                speedup=before / after if before else None,
                raw=raw(runs_a, "raw_seconds"), large=raw(runs_a, "large_seconds"),
                raw_before=raw(runs_b, "raw_seconds"), large_before=raw(runs_b, "large_seconds"),
                rays=per(runs_a[0], "rays"),
                casts=per(runs_a[0], "casts"), motions=per(runs_a[0], "motions"),
                rays_before=per(runs_b[0], "rays") if runs_b else None,
                casts_before=per(runs_b[0], "casts") if runs_b else None,
                motions_before=per(runs_b[0], "motions") if runs_b else None,
                peak=max(d["peak_mib"] for d in runs_a), base=max(d["base_mib"] for d in runs_a),
                same=_same(cmp_rows) if cmp_rows else "", compare=cmp_rows)


def _ratio(t, ref) -> str:
    return f"{t / ref:.1f}" if t is not None and ref else "-"


def print_table(rows, commits) -> None:
    """The table: seconds per slice, ratios to raw Embree, counts, memory, results."""
    print(f"before = {commits[0]}, after = {commits[1]}; CPU s per slice; x large: sensing / "
          f"embreex on the same rays in calls of 65,536; x cast: / embreex in the casts as "
          f"issued")
    print(f"{'scene':16s} {'before s':>8s} {'after s':>8s} {'speed-up':>8s} "
          f"{'x large':>10s} {'x cast':>9s} {'rays':>15s} {'casts':>12s} {'motions':>10s} "
          f"{'peak MiB':>13s}  same")
    for r in rows:
        b = f"{r['before']:8.3f}" if r["before"] is not None else f"{'-':>8s}"
        sp = f"{r['speedup']:7.1f}x" if r["speedup"] else f"{'-':>8s}"
        large = _ratio(r["after"], r["large"])
        if r["large_before"]:
            large = f"{_ratio(r['before'], r['large_before'])}->{large}"
        cast = _ratio(r["after"], r["raw"])
        if r["raw_before"]:
            cast = f"{_ratio(r['before'], r['raw_before'])}->{cast}"
        rays = _fmt_counts(r["rays_before"] or r["rays"], r["rays"])
        casts = _fmt_counts(r["casts_before"] or r["casts"], r["casts"])
        mot = _fmt_counts(r["motions_before"] or r["motions"], r["motions"])
        print(f"{r['scene']:16s} {b} {r['after']:8.3f} {sp} {large:>10s} {cast:>9s} "
              f"{rays:>15s} {casts:>12s} {mot:>10s} {r['peak']:6.0f} ({r['base']:4.0f})  "
              f"{r['same']}")
    sp = [r["speedup"] for r in rows if r["speedup"]]
    xl = [r["after"] / r["large"] for r in rows if r["large"]]
    xr = [r["after"] / r["raw"] for r in rows if r["raw"]]
    if sp:
        print(f"median speed-up {statistics.median(sp):.1f}x (min {min(sp):.1f}x); ", end="")
    if xl:
        print(f"after / embreex large calls: median {statistics.median(xl):.1f}, "
              f"max {max(xl):.1f}; after / embreex as cast: median "
              f"{statistics.median(xr):.1f}, max {max(xr):.1f}")


def _commit(rev: str) -> str:
    """Short hash of ``rev``."""
    short = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", rev], check=True,
                           capture_output=True, text=True).stdout.strip()
    return short


def _this_checkout() -> str:
    """Short hash of this checkout, ``+dirty`` with uncommitted changes to the code."""
    dirty = subprocess.run(["git", "-C", str(ROOT), "status", "--porcelain", "--",
                            "core2d", "slicer", "meshes", "bench"], check=True,
                           capture_output=True, text=True).stdout.strip()
    return _commit("HEAD") + ("+dirty" if dirty else "")


def tol_table(tmp, scene, slices, shares) -> list[dict]:
    """Peak memory and time of this checkout against tol = eps x share."""
    out = []
    for share in shares:
        doc = sense(ROOT, scene, slices, tmp / f"tol-{share}.json", tol_share=share)
        n = len(doc["slices"])
        out.append(dict(scene=scene, share=share, peak=doc["peak_mib"], base=doc["base_mib"],
                        seconds=sum(s["seconds"] for s in doc["slices"]) / n,
                        rays=sum(s["rays"] for s in doc["slices"]) / n))
    print(f"\n{'scene':16s} {'tol / eps':>9s} {'s/slice':>8s} {'rays/slice':>11s} {'peak MiB':>13s}")
    for r in out:
        print(f"{r['scene']:16s} {r['share']:9.4g} {r['seconds']:8.3f} {r['rays']:11.0f} "
              f"{r['peak']:6.0f} ({r['base']:4.0f})")
    return out


def main(argv=None) -> int:
    import meshes

    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--slices", type=int, default=4, help="z-slices per scene (default 4)")
    p.add_argument("--repeat", type=int, default=1, help="timed runs per side and scene")
    p.add_argument("--scenes", help="comma-separated scene names (default: all)")
    p.add_argument("--before", default="c95dda6", help="commit to compare with")
    p.add_argument("--reference", help="commit whose results must be reproduced "
                   "(default: --before)")
    p.add_argument("--no-before", dest="with_before", action="store_false")
    p.add_argument("--raw-before", action="store_true",
                   help="replay the --before commit's rays on raw embreex too")
    p.add_argument("--tols", help="tol / eps shares for the memory table, e.g. 0.05,0.005")
    p.add_argument("--tol-scene", default="deep_slot", help="scene of the memory table")
    p.add_argument("--json", help="write the rows to this file")
    p.add_argument("--noise", type=float, default=0.0, help="sensor noise sigma in eps")
    p.add_argument("--taxel", type=float, default=0.0, help="taxel spacing in eps")
    p.add_argument("--keyed-noise", action="store_true", help="keyed sensor draws")
    args = p.parse_args(argv)
    if args.noise < 0 or args.taxel < 0:
        p.error("--noise and --taxel must be >= 0")
    sensor = (f"{args.noise},{args.taxel},{int(args.keyed_noise)}"
              if args.noise or args.taxel else None)
    scenes = args.scenes.split(",") if args.scenes else meshes.names()
    unknown = sorted(set(scenes) - set(meshes.names()))
    if unknown or args.slices < 1 or args.repeat < 1:
        p.error(f"unknown scenes {unknown}" if unknown else "--slices and --repeat must be >= 1")
    rows, tols = [], []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        old = export(args.before, tmp) if args.with_before else None
        ref = old
        if args.reference and args.with_before:
            (tmp / "ref").mkdir()
            ref = export(args.reference, tmp / "ref")
        for root in {old, ref} - {None}:  # compile an exported tree's kernels, untimed
            sense(root, "fig18_overhangs", 2, tmp / "warm.json")
        for scene in scenes:
            runs_b, runs_a = [], []
            for k in range(args.repeat):
                if old is not None:
                    runs_b.append(sense(old, scene, args.slices, tmp / "b.json",
                                        raw=k == 0 and args.raw_before, sensor=sensor))
                runs_a.append(sense(ROOT, scene, args.slices, tmp / "a.json", raw=k == 0,
                                    sensor=sensor))
            cmp_rows = []
            if runs_b:
                doc_ref = runs_b[0] if ref is old else sense(ref, scene, args.slices,
                                                             tmp / "r.json", sensor=sensor)
                cmp_rows = compare(scene, doc_ref, runs_a[0], args.slices)
            rows.append(scene_row(scene, runs_b, runs_a, cmp_rows))
            print(f"  {scene}: done", file=sys.stderr, flush=True)
        commits = (_commit(args.before) if args.with_before else "-", _this_checkout())
        if sensor:
            print(f"sensor: noise {args.noise:g} eps, taxel {args.taxel:g} eps"
                  f"{', keyed draws' if args.keyed_noise else ''}, sensor seed = slice index")
        print_table(rows, commits)
        if args.tols:
            tols = tol_table(tmp, args.tol_scene, args.slices,
                             [float(x) for x in args.tols.split(",")])
    if args.json:
        Path(args.json).write_text(json.dumps({"scenes": rows, "tols": tols,
                                               "commits": commits}, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
