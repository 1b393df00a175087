"""The baseline users would pick instead: dense finger probing against pulling.

One task per slice (:func:`compare_probing`): the pulling planner once, then
finger probing (:mod:`core2d.planner.finger`, straight insertions on a grid
of directions x line spacing) swept in density; the same Embree contact,
the same metrics (2D reachable coverage) and the same robot-time model as
``metrics.json`` (joint path / probe speed + motions x overhead).
:func:`equal_coverage` compares the two at equal reachable coverage: the
cheapest finger density that covers at least as much as pulling does.
"""
from __future__ import annotations

import numpy as np

from core2d import sense_slice
from core2d.truth.metrics import slice_metrics
from recon3d.benchmark.cases import case_list, middle_slice, workspace
from recon3d.config import RunConfig
from recon3d.records import robot_time

__all__ = ["baseline_tasks", "compare_probing", "equal_coverage", "DENSITIES"]

SPEED, OVERHEAD = RunConfig.probe_speed, RunConfig.motion_overhead  # recon3d run's defaults
DENSITIES = {"full": ((4, 6, 8, 12, 16, 24, 32, 48), (2.0, 1.5, 1.0, 0.75, 0.5)),
             "quick": ((4, 8, 12, 16, 24, 32), (2.0, 1.0, 0.5))}
"""Finger densities: directions x line spacing (in eps). Steps of at most 1.5x
in each, so the cheapest density reaching a coverage is found within 1.5x
(a coarse grid would overstate what finger probing needs)."""


def baseline_tasks(quick: bool) -> list[dict]:
    """Middle z-slices of the scenes that satisfy the paper's assumptions (and real meshes)."""
    scenes = ("fig17_pocket", "fig18_overhangs", "stepped_pyramid") if quick else (
        "fig17_pocket", "fig18_overhangs", "stepped_pyramid", "mushroom", "gear", "dovetail")
    share = 1 / 100 if quick else 1 / 200
    return [{"case": n, "source": s, "eps_share": share, "quick": quick}
            for n, s in case_list(scenes, real=not quick)]


def _row(case, method, res, loops, eps, **extra):
    st = res.stats.as_dict()
    m = slice_metrics(loops, res, eps)
    return {"case": case, "method": method, **extra, "coverage": m["coverage"],
            "precision": m["precision"], "motions": st["motions"],
            "joint_path": st["joint_path"], "robot_time_s": robot_time(st, SPEED, OVERHEAD),
            "budget_hit": st["budget_hit"], "seconds": st["seconds"]}


def compare_probing(task: dict) -> list[dict]:
    """Pulling once and finger probing at every density on one slice."""
    _, diag, slc = middle_slice(task["source"])
    eps = task["eps_share"] * diag
    loops = [np.asarray(lp) for lp in slc.loops]
    model, ws = slc.contact("embree"), workspace(slc, eps)
    rows = [_row(task["case"], "pulling", sense_slice(model, ws, eps), loops, eps,
                 directions=0, spacing_eps=0.0)]
    dirs, spacings = DENSITIES["quick" if task["quick"] else "full"]
    for n in dirs:
        for s in spacings:
            res = sense_slice(model, ws, eps, method="finger", directions=n, spacing=s * eps,
                              max_motions=10 ** 7)
            rows.append(_row(task["case"], "finger", res, loops, eps, directions=n,
                             spacing_eps=s))
    return rows


def equal_coverage(rows) -> list[dict]:
    """Per case: pulling against the cheapest finger density covering as much.

    When no density reaches pulling's coverage, the best-covering one is
    given (``reached`` False)."""
    out = []
    for case in dict.fromkeys(r["case"] for r in rows):
        pull = next(r for r in rows if r["case"] == case and r["method"] == "pulling")
        fingers = [r for r in rows if r["case"] == case and r["method"] == "finger"]
        ok = [r for r in fingers if r["coverage"] >= pull["coverage"] - 1e-9]
        best = min(ok, key=lambda r: r["robot_time_s"]) if ok else max(
            fingers, key=lambda r: (r["coverage"], -r["robot_time_s"]))
        at99 = [r for r in fingers if r["coverage"] >= 0.99]
        cheap99 = min(at99, key=lambda r: r["robot_time_s"]) if at99 else None
        out.append({"case": case, "pulling_coverage": pull["coverage"],
                    "robot_time_ratio_at_99": None if cheap99 is None or pull["coverage"] < 0.99
                    else cheap99["robot_time_s"] / pull["robot_time_s"],
                    "finger_coverage": best["coverage"], "reached": bool(ok),
                    "finger_density": f"{best['directions']} dirs x {best['spacing_eps']:g} eps",
                    "motions_ratio": best["motions"] / pull["motions"],
                    "joint_path_ratio": best["joint_path"] / pull["joint_path"],
                    "robot_time_ratio": best["robot_time_s"] / pull["robot_time_s"],
                    "pulling_robot_time_s": pull["robot_time_s"],
                    "finger_robot_time_s": best["robot_time_s"]})
    return out
