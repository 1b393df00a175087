"""The planner with real sensors: noise and taxels, per scene group and level.

Every case is sensed once with the paper's perfect sensing and once per
sensor level (:class:`core2d.SensorModel`: contact and joint-reading noise
S x eps, taxels T x eps, seeded per case), and scored against the true
contour with :func:`core2d.truth.metrics.slice_metrics` (tolerance eps / 2)
and :func:`core2d.truth.metrics.sensor_metrics` (eps / 2 + 2 S x eps). One
row per group and level: slices, reachable coverage and precision at both
tolerances (length weighted, and the worst slice at the sensor's), coverage at the
sensor's tolerance over the part eps resolves (:mod:`core2d.truth.resolvable`: openings
narrower than eps left out, which §3.1 closes by W2 by design) and over the part eps +
jitter resolves (the sensor's stated W2 distance: openings that read narrower are W2 by the
planner's rule), W3 lids and unsound ones at
both tolerances, motions and their ratio to the noiseless run (total, and the worst slice),
budget hits. Then, per case (a scene or mesh over its slices, an outline), which meet the
issue's targets at each level: coverage within eps/2 + 2 sigma (over the reachable contour
and over the part eps resolves), precision >= 0.98, motions <= 2 x noiseless, no budget hit.

One seed's coverage is a lottery at +-0.01 (and a slot's worth on the ``comb`` outlines):
``--seeds K`` runs every noisy level K times per case, with sensor seeds seed, seed + 1000,
..., seed + 1000 (K - 1) (the noiseless run once). The summary's ``slices`` then counts
slice runs, and each case is judged once per sensor seed ("comb-0 (sensor seed +1000)").

    python -m bench.sensor_study                       # every group, every level
    python -m bench.sensor_study --groups scenes --levels 0.3:0.25 --jobs 2
    python -m bench.sensor_study --groups scenes --slices 8 --levels 0.1:0 --only comb
    python -m bench.sensor_study --groups outlines,scenes --levels 0.1:0 --seeds 3
    python -m bench.sensor_study --groups outlines --first-outline 2 --per-kind 4   # unseen

Groups: ``outlines`` (``--per-kind`` seeded outlines of each kind of
``tests/outlines.py``, exact backend, eps 1), ``scenes`` (the middle z-slice
of every built-in scene, Embree, eps = diagonal / 200; ``--slices N``: N
z-slices each), ``meshes`` (``../shared/meshes`` alike, skipped when
absent). Nothing is asserted: it measures.
"""
from __future__ import annotations

import argparse
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

from bench.sensor_report import coverage_target, markdown, per_case, summarise, verdicts

ROOT = Path(__file__).resolve().parents[1]
SHARED = ROOT.parent / "shared"
sys.path.insert(0, str(ROOT / "tests"))

LEVELS = ((0.03, 0.0), (0.1, 0.0), (0.3, 0.0), (1.0, 0.0), (0.0, 0.25), (0.3, 0.25))
"""(noise, taxel) in eps, besides the noiseless run every level is compared with."""
GROUPS = ("outlines", "scenes", "meshes")


def _score(loops, contact, ws, eps, levels, seed, budget, seeds=1, keyed=False,
           reads="auto") -> list[dict]:
    """Rows of one slice: the noiseless run, then every level once per sensor seed
    ``seed + 1000 j`` (j < ``seeds``; j = 0 is the case's own seed), each with its
    ``sensor_seed`` and ``ratio`` (motions over the noiseless run's); ``keyed``: the
    sensor's draws keyed by reading (:class:`core2d.SensorModel`'s common random numbers);
    ``reads``: reads averaged per reading point, 'auto' as ``recon3d run``
    (:func:`core2d.resolution.repeated_reads`), recorded in each row."""
    from core2d import SensorModel, sense_slice
    from core2d.resolution import Resolution, repeated_reads
    from core2d.truth.metrics import sensor_metrics, slice_metrics
    from core2d.truth.reachability import reachable_samples
    from core2d.truth.resolvable import resolvable

    samples = reachable_samples(loops, eps / 4)
    resolved = resolvable(loops, samples[0].points, eps)
    weights, reach = samples[0].lengths, samples[1]
    bands = {}  # the sensor's W2 distance -> the contour a disc that wide resolves
    rows = []
    runs = [(0.0, 0.0, 0)] + [(n, t, j) for n, t in levels for j in range(seeds)]
    for noise, taxel, j in runs:
        n = repeated_reads(1.0, noise, taxel) if reads == "auto" else int(reads)
        sensor = SensorModel.of_eps(eps, noise, taxel, seed + 1000 * j, keyed=keyed, reads=n)
        res = sense_slice(contact, ws, eps, max_motions=budget, sensor=sensor)
        m = slice_metrics(loops, res, eps, spacing=eps / 4, samples=samples, resolved=resolved)
        m.update(sensor_metrics(loops, res, eps, sensor.noise, spacing=eps / 4, samples=samples,
                                resolved=resolved))
        w2 = Resolution.of(eps, noise=sensor.read_noise, taxel=sensor.taxel).w2_dist
        if w2 == eps:  # no jitter: the part eps resolves
            band, covered = resolved, m["covered_resolvable_length_sensor"]
        else:
            if w2 not in bands:
                bands[w2] = resolvable(loops, samples[0].points, w2)
            band = bands[w2]
            covered = sensor_metrics(loops, res, eps, sensor.noise, spacing=eps / 4,
                                     samples=samples,
                                     resolved=band)["covered_resolvable_length_sensor"]
        rows.append({"noise": noise, "taxel": taxel, "sensor_seed": seed + 1000 * j,
                     "repeat": j, "keyed": keyed, "reads": n, "band_length": float(weights[reach & band].sum()),
                     "covered_band_length_sensor": covered, **{k: m[k] for k in (
            "coverage", "covered_length", "coverage_sensor", "covered_length_sensor",
            "w2_credit_length_sensor", "w2_material_arcs_sensor",
            "coverage_resolvable_sensor", "covered_resolvable_length_sensor",
            "resolvable_length",
            "reachable_length", "precision", "precise_length", "precision_sensor",
            "precise_length_sensor", "detected_length", "w3_count", "w3_unsound_count",
            "w3_unsound_count_sensor", "motions", "budget_hit")}})
    base = rows[0]["motions"]
    for r in rows:
        r["ratio"] = r["motions"] / max(base, 1)
    return rows


def _outline_case(kind, seed, levels, budget, seeds=1, keyed=False, reads="auto"):
    from outlines import outline

    from slicer import ExactContact

    loops = outline(kind, np.random.default_rng(seed), 1.0)
    pts = np.concatenate(loops)
    lo, hi = pts.min(0), pts.max(0)
    ws = ((lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2 + 1.0))
    return _score(loops, ExactContact(loops), ws, 1.0, levels, seed, budget, seeds, keyed,
                  reads)


def _mesh_case(source, count, index, levels, budget, seeds=1, keyed=False, reads="auto"):
    import meshes
    import slicer

    mesh = meshes.load(source)
    eps = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)) / 200)
    cut = slicer.slice_mesh(mesh, axis="z", count=count)[index]
    if not cut.loops or cut.open_chains:
        return []
    center, radius = cut.bounding_circle()
    loops = [np.asarray(lp) for lp in cut.loops]
    return _score(loops, cut.contact("embree"), (center, radius + eps), eps, levels, index,
                  budget, seeds, keyed, reads)


def cases(args):
    """(group, name, function, arguments) of every case."""
    import meshes
    from outlines import KINDS

    if "outlines" in args.groups:
        for kind in KINDS:
            for seed in range(args.first_outline, args.first_outline + args.per_kind):
                yield "outlines", f"{kind}-{seed}", _outline_case, (kind, seed)
    picks = [args.slices // 2] if args.slices == 1 else range(args.slices)
    count = 8 if args.slices == 1 else args.slices  # the middle of 8 (the slice)
    if "scenes" in args.groups:
        for name in meshes.names():
            for i in ([count // 2] if args.slices == 1 else picks):
                yield "scenes", f"{name}:z{i}", _mesh_case, (name, count, i)
    if "meshes" in args.groups and (SHARED / "meshes").is_dir():
        for path in sorted((SHARED / "meshes").glob("*.*")):
            if path.suffix.lower() in (".stl", ".obj", ".ply", ".off", ".glb"):
                for i in ([count // 2] if args.slices == 1 else picks):
                    yield "meshes", f"{path.stem}:z{i}", _mesh_case, (str(path), count, i)


def _quiet_repeats() -> None:
    """Pool initializer: each distinct warning or log message once per worker process.

    Every case of a mesh loads and slices it again, so its load warning (an open mesh) and
    its nudged degenerate planes would be printed once per slice."""
    import logging
    import warnings

    seen: set[str] = set()
    show = warnings.showwarning

    def once(message, category, filename, lineno, file=None, line=None):
        key = f"{category.__name__}: {message}"
        if key not in seen:
            seen.add(key)
            show(message, category, filename, lineno, file, line)

    def first(record: logging.LogRecord) -> bool:
        key = record.getMessage()
        if key in seen:
            return False
        seen.add(key)
        return True

    warnings.showwarning = once
    logging.getLogger().addFilter(first)
    for handler in logging.getLogger().handlers:
        handler.addFilter(first)
    logging.lastResort.addFilter(first)


def _run(job):
    group, name, fn, a, levels, budget, seeds, keyed, reads = job
    t0 = time.perf_counter()
    try:
        rows = fn(*a, levels, budget, seeds, keyed, reads)
    except Exception as exc:  # a crash is a finding, reported, not fatal
        return [{"group": group, "name": name, "error": f"{type(exc).__name__}: {exc}"[:200]}]
    for r in rows:
        r.update(group=group, name=name, wall=time.perf_counter() - t0)
    return rows


def write_csv(path: Path, rows) -> None:
    """One line per case and level (the crashed cases with their error)."""
    import csv

    keys = sorted({k for r in rows for k in r})
    head = ["group", "name", "noise", "taxel"]
    keys = head + [k for k in keys if k not in head]
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, keys)
        w.writeheader()
        w.writerows(rows)


def _levels(text):
    try:
        return tuple(tuple(float(x) for x in item.split(":")) for item in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"levels are NOISE:TAXEL,... in eps (got {text!r})")


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m bench.sensor_study",
                                description=__doc__.splitlines()[0])
    p.add_argument("--groups", default=",".join(GROUPS),
                   help=f"comma-separated subset of {', '.join(GROUPS)} (default all)")
    p.add_argument("--levels", type=_levels, default=LEVELS, metavar="S:T,...",
                   help="sensor levels NOISE:TAXEL in eps (default "
                   + ",".join(f"{a:g}:{b:g}" for a, b in LEVELS) + "); 0:0 always runs")
    p.add_argument("--per-kind", type=int, default=2, help="outlines per kind (default 2)")
    p.add_argument("--first-outline", type=int, default=0, metavar="SEED",
                   help="seed of each kind's first outline (default 0; the planner's rules "
                   "were measured on seeds 0 and 1, so --first-outline 2 gives outlines "
                   "they never saw)")
    p.add_argument("--slices", type=int, default=1,
                   help="z-slices per mesh (default 1: the middle of 8)")
    p.add_argument("--only", default="",
                   help="comma-separated case names (before ':z', e.g. comb,deep_slot) to keep")
    p.add_argument("--budget", type=int, default=20000, help="motion budget per slice")
    p.add_argument("--seeds", type=int, default=1,
                   help="sensor seeds per case and level (default 1: the case's seed; "
                   "more: + 1000, + 2000, ...; the noiseless run once)")
    p.add_argument("--keyed-noise", action="store_true",
                   help="each reading's noise keyed by its true posture (common random "
                   "numbers: two planners compared with it differ only where their motions "
                   "do; see core2d.sim.sensor)")
    p.add_argument("--reads", default="auto", metavar="N",
                   help="sensor reads averaged at each reading point: 'auto' (default, as "
                   "recon3d run: core2d.resolution.repeated_reads) or a number")
    p.add_argument("--jobs", type=int, default=2, help="processes (default 2)")
    p.add_argument("--csv", type=Path, default=None,
                   help="also write one row per case and level to this CSV file")
    p.add_argument("--chart", type=Path, default=None,
                   help="also chart motions, budget hits and coverage per group and level (PNG)")
    args = p.parse_args(argv)
    args.groups = [g.strip() for g in args.groups.split(",") if g.strip()]
    unknown = [g for g in args.groups if g not in GROUPS]
    if unknown or any(len(lv) != 2 or min(lv) < 0 for lv in args.levels):
        p.error(f"unknown groups {unknown}" if unknown else "levels are NOISE:TAXEL >= 0")
    levels = tuple(lv for lv in args.levels if lv != (0.0, 0.0))
    only = {x.strip() for x in args.only.split(",") if x.strip()}
    if args.seeds < 1:
        p.error("--seeds is at least 1")
    if args.reads != "auto" and not (args.reads.isdigit() and int(args.reads) >= 1):
        p.error(f"--reads is 'auto' or a number >= 1 (got {args.reads!r})")
    jobs = [(g, n, fn, a, levels, args.budget, args.seeds, args.keyed_noise, args.reads)
            for g, n, fn, a in cases(args)
            if not only or n.split(":")[0] in only]
    print(f"sensor study: {len(jobs)} cases x {len(levels) * args.seeds + 1} runs, "
          f"{args.jobs} jobs, reads {args.reads}" + (", keyed noise" if args.keyed_noise else ""),
          file=sys.stderr)
    t0 = time.perf_counter()
    rows = []
    with ProcessPoolExecutor(args.jobs, initializer=_quiet_repeats) as ex:
        for k, got in enumerate(ex.map(_run, jobs, chunksize=1)):
            rows += got
            print(f"  [{k + 1}/{len(jobs)}] {jobs[k][1]}", file=sys.stderr, flush=True)
    for r in rows:
        if "error" in r:
            print("CRASH", r["group"], r["name"], r["error"])
    if args.csv is not None:
        write_csv(args.csv, rows)
    summary = summarise(rows)
    if args.chart is not None:
        from bench.sensor_study_chart import chart

        chart(summary, args.chart, coverage_target)
    print(markdown(summary))
    print()
    print(verdicts(rows))
    print(f"\n{len(jobs)} cases in {time.perf_counter() - t0:.0f} s", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
