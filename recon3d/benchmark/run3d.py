"""``recon3d bench``: every sweep of the 3D benchmark on Dask, CSV + PNG + a short table.

Parts (``--parts``; all by default):

* ``pareto`` -- :mod:`.pareto`: pareto.csv / pareto.png, adaptive.csv;
* ``backends`` -- :mod:`.backends`: backends.csv;
* ``baseline`` -- :mod:`.baseline`: baseline.csv / baseline.png;
* ``stability`` -- :mod:`.stability`: stability.csv / stability.png, breaks.csv,
  sensor.png (motions and coverage against the sensor's noise and taxel spacing);
* ``claims`` -- :mod:`.claims`: claims.csv / claims.png, claims_summary.csv (pulling
  against pushing under tip friction).

All tasks of all parts go to one Dask cluster (:func:`recon3d.jobs.cluster.run_tasks`),
longest first. Files are written at the end, all together (:class:`recon3d.io.staged.Staged`).
"""
from __future__ import annotations

import csv
import logging
import math
import time

from recon3d.benchmark import (PARTS, backends, baseline, charts, claims, pareto, stability,
                                stability_charts)
from recon3d.io.staged import Staged
from recon3d.jobs.cluster import run_tasks

__all__ = ["PARTS", "run_bench", "write_outputs", "dispatch", "write_csv"]


def dispatch(task: dict) -> dict:
    """Run one task of any part (the function Dask workers call): its rows and seconds."""
    logging.getLogger("slicer").setLevel(logging.ERROR)  # planes near vertices: on purpose
    fn = {"pareto": pareto.run_case, "backends": backends.compare_slice,
          "baseline": baseline.compare_probing, "stability": stability.run_factor,
          "claims": claims.run_claims}[task["part"]]
    t0 = time.perf_counter()
    try:
        rows = fn(task)
    except Exception as exc:  # one failed task is reported, the sweep goes on
        return {"rows": [], "seconds": time.perf_counter() - t0,
                "error": f"{type(exc).__name__}: {exc}"[:200]}
    return {"rows": rows if isinstance(rows, list) else [rows],
            "seconds": time.perf_counter() - t0, "error": ""}


def _tasks(parts, quick):
    plan = pareto.QUICK if quick else pareto.FULL
    made = {"pareto": lambda: pareto.pareto_tasks(plan),
            "backends": lambda: backends.backend_tasks(quick),
            "baseline": lambda: baseline.baseline_tasks(quick),
            "stability": lambda: stability.stability_tasks(quick),
            "claims": lambda: claims.claims_tasks(quick)}
    tasks = []
    for part in parts:
        tasks += [dict(t, part=part) for t in made[part]()]

    def weight(t):  # rough cost, for longest-first scheduling
        if t["part"] == "pareto":
            n = t.get("max_slices") if t["slices"] == "auto" else t["slices"]
            return n / t["eps_share"] / 200
        return {"backends": 60, "baseline": 30, "stability": 10, "claims": 20}[t["part"]]

    return sorted(tasks, key=weight, reverse=True), plan


def write_csv(path, rows) -> None:
    """Rows (dicts) to CSV; columns in first-seen order, NaN written empty."""
    cols = list(dict.fromkeys(k for r in rows for k in r))
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, cols)
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if isinstance(v, float) and math.isnan(v) else v)
                        for k, v in r.items()})


def _fmt(v, f=".3f"):
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "n/a"
    return format(v, f) if isinstance(v, (int, float)) and not isinstance(v, bool) else str(v)


def _table(lines, head, rows, keys, fmts):
    lines.append("  ".join(head))
    for r in rows:
        lines.append("  ".join(_fmt(r[k], f) for k, f in zip(keys, fmts)))


def _claims(lines, stage, rows) -> None:
    """claims.csv, claims_summary.csv, claims.png and the table's lines."""
    rows = sorted(rows, key=lambda r: (r["case"], claims.METHODS.index(r["method"]), r["mu"]))
    write_csv(stage / "claims.csv", rows)
    summ = claims.summary(rows)
    write_csv(stage / "claims_summary.csv", summ)
    charts.claims_chart(rows, stage / "claims.png")
    lines.append("\npulling against pushing under tip friction mu (middle z-slice per case; "
                 "coverage: mean over the cases, jams / pushes / motions: sums):")
    _table(lines, ["method", "mu", "cases", "coverage", "jams", "pushes", "motions",
                   "robot time s"], summ,
           ["method", "mu", "cases", "coverage", "jams", "pushes", "motions", "robot_time_s"],
           ["", "g", "d", ".3f", "d", "d", "d", ".0f"])


def run_bench(out, quick: bool = False, scheduler=None, workers=None, parts=PARTS,
              quiet: bool = False) -> list[str]:
    """Run the parts, write their files into ``out``; the printed table's lines."""
    tasks, plan = _tasks(parts, quick)
    results = run_tasks(dispatch, tasks, scheduler, workers, desc="bench", quiet=quiet)
    by = {p: [] for p in PARTS}
    timing = []
    for t, r in zip(tasks, results):
        by[t["part"]] += r["rows"]
        timing.append({"part": t["part"], **{k: t.get(k) for k in (
            "case", "factor", "value", "slices", "eps_share")}, "seconds": r["seconds"],
            "error": r["error"]})
    return write_outputs(out, by, timing, plan, quick)


def write_outputs(out, by: dict, timing: list[dict], plan: dict, quick: bool) -> list[str]:
    """Every file of a bench run from its rows: ``by`` part -> rows (the
    CSVs' contents), ``timing`` one dict per task (tasks.csv), ``plan`` the
    pareto sweep (:data:`.pareto.FULL` or ``QUICK``). Writes CSVs, charts and
    table.txt into ``out`` (staged: all or nothing); the table's lines."""
    by = {p: by.get(p, []) for p in PARTS}
    parts = [p for p in PARTS if any(t["part"] == p for t in timing)]
    lines = [f"recon3d bench{' --quick' if quick else ''}: {len(timing)} tasks"]
    with Staged(out) as stage:
        if by["pareto"]:
            rows = sorted(by["pareto"], key=lambda r: (r["case"], r["method"], r["eps_share"],
                                                      r["slices"]))
            fronts = {k: pareto.pareto_front(rows, x="cpu_s", y=k,
                                             lower_is_better=k == "chamfer_l1_diag")
                      for k in ("chamfer_l1_diag", "fscore_1", "coverage")}
            for k, r in enumerate(rows):
                for key, flag in fronts.items():
                    r[f"pareto_{key}"] = bool(flag[k])
            write_csv(stage / "pareto.csv", rows)
            charts.pareto_chart(rows, fronts, stage / "pareto.png")
            ada = pareto.adaptive_summary(rows, plan)
            write_csv(stage / "adaptive.csv", ada)
            lines.append(f"\nadaptive (--slices auto, max {plan['auto_max']}) against "
                         f"{plan['auto_max']} uniform slices, eps = diagonal / "
                         f"{round(1 / plan['auto_share'])}:")
            _table(lines, ["case", "slices u/a", "F@1% u", "F@1% a", "slices", "wall", "cpu",
                           "robot", "target (F, slices, cpu)"], ada,
                   ["case", "adaptive_slices", "uniform_f1", "adaptive_f1", "slice_ratio",
                    "time_ratio", "cpu_ratio", "robot_ratio", "target_met"],
                   ["", "d", ".3f", ".3f", ".2f", ".2f", ".2f", ".2f", ""])
        if by["backends"]:
            write_csv(stage / "backends.csv", by["backends"])
            lines.append("\ncontact backends (same slices, one process; agreement of W classes "
                         "with exact):")
            _table(lines, ["case", "backend", "motions", "ms/motion", "x embree", "agreement"],
                   by["backends"], ["case", "backend", "motions", "ms_per_motion",
                                    "time_per_motion_vs_embree", "agreement"],
                   ["", "", "d", ".3f", ".2f", ".4f"])
        if by["baseline"]:
            write_csv(stage / "baseline.csv", by["baseline"])
            charts.baseline_chart(by["baseline"], stage / "baseline.png")
            eq = baseline.equal_coverage(by["baseline"])
            write_csv(stage / "baseline_ratios.csv", eq)
            lines.append("\nfinger probing against pulling at equal reachable coverage "
                         "(finger / pulling):")
            _table(lines, ["case", "cov pull", "cov finger", "density", "motions", "joint path",
                           "robot time", "robot@99%"], eq,
                   ["case", "pulling_coverage", "finger_coverage", "finger_density",
                    "motions_ratio", "joint_path_ratio", "robot_time_ratio",
                    "robot_time_ratio_at_99"], ["", ".4f", ".4f", "", ".1f", ".1f", ".1f", ".1f"])
        if by["stability"]:
            rows = by["stability"]
            breaks = stability.breaking_points(rows)
            write_csv(stage / "stability.csv", rows)
            write_csv(stage / "breaks.csv", breaks)
            stability_charts.stability_chart(rows, breaks, stage / "stability.png")
            if any(r["factor"] in stability.SENSOR_FACTORS for r in rows):
                stability_charts.sensor_chart(rows, stage / "sensor.png")
            lines.append("\nstability: where each method breaks (first value; none = never):")
            _table(lines, ["factor", "method", "breaks at", "why"], breaks,
                   ["factor", "method", "breaks_at", "why"], ["", "", "g", ""])
        if by["claims"]:
            _claims(lines, stage, by["claims"])
        write_csv(stage / "tasks.csv", timing)
        failed = [t for t in timing if t["error"]]
        if failed:
            lines.append(f"\n{len(failed)} tasks failed (tasks.csv has them):")
            lines += [f"  {t['part']} {t['case'] or t['factor']} {t['value'] or ''}: {t['error']}"
                      for t in failed]
        cpu = {p: sum(t["seconds"] for t in timing if t["part"] == p) for p in parts}
        lines.append("\ntask seconds per part (sum over tasks): " + ", ".join(
            f"{p} {cpu[p]:.0f}" for p in parts))
        lines.append("\nreconstruction methods: one (shape-based interpolation of the slice "
                     "regions, recon3d.surface.field); nothing to compare")
        (stage / "table.txt").write_text("\n".join(lines) + "\n")
    return lines
