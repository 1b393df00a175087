"""Speed against accuracy: eps x slice count per case, uniform and adaptive slicing.

One task per run (:func:`run_case`, ``recon3d.run`` with ``jobs=1`` and
``force``: the sweep keeps slice counts above extent / eps, where slices
closer than eps add time, not detail):
wall and CPU seconds of the whole job, Chamfer-L1 / diagonal, F@1%, 2D
reachable coverage, robot time. :func:`pareto_front` marks the runs no
other run of the same case beats in both time and error; ``recon3d bench``
uses CPU seconds (each run is one process, so this is its wall time on an
idle core; the wall time on a shared machine also counts the waiting).
"""
from __future__ import annotations

import time
import warnings

import numpy as np

import meshes
import recon3d
from recon3d.benchmark.cases import case_list
from recon3d.config import diagonal

__all__ = ["FULL", "QUICK", "pareto_tasks", "run_case", "pareto_front", "adaptive_summary"]

FULL = {"scenes": ("fig17_pocket", "fig18_overhangs", "stepped_pyramid", "bowl"),
        "eps_shares": (1 / 25, 1 / 50, 1 / 100, 1 / 150), "slices": (4, 8, 16, 32),
        "auto_max": 32, "auto_share": 1 / 100, "real": True}
QUICK = {"scenes": ("fig17_pocket", "fig18_overhangs", "stepped_pyramid", "bowl"),
         "eps_shares": (1 / 25, 1 / 40, 1 / 60, 1 / 100), "slices": (2, 4, 6, 8),
         "auto_max": 8, "auto_share": 1 / 100, "real": False}
"""The sweeps: ``auto_share`` is one of ``eps_shares`` and ``auto_max`` one of
``slices``, so the adaptive run has a uniform run to be compared with (the
full sweep is sized to finish within ~45 minutes on 2 shared cores)."""


def pareto_tasks(plan: dict) -> list[dict]:
    """Every (case, slices, eps share) of ``plan`` plus one adaptive run per case."""
    tasks = []
    for name, source in case_list(plan["scenes"], plan["real"]):
        for share in plan["eps_shares"]:
            for n in plan["slices"]:
                tasks.append({"case": name, "source": source, "method": "uniform",
                              "slices": n, "eps_share": share})
        tasks.append({"case": name, "source": source, "method": "adaptive", "slices": "auto",
                      "max_slices": plan["auto_max"], "eps_share": plan["auto_share"]})
    return tasks


def run_case(task: dict) -> dict:
    """Run one task; its row of ``pareto.csv``."""
    mesh = meshes.load(task["source"])
    diag = diagonal(mesh)
    kw = {"max_slices": task["max_slices"]} if task["method"] == "adaptive" else {}
    t0, c0 = time.perf_counter(), time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        # force: the sweep's point is that slices closer than eps add time, not detail
        res = recon3d.run(mesh, slices=task["slices"], eps=task["eps_share"] * diag, jobs=1,
                          force=True, **kw)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    tot = res.metrics["total"]
    s = tot.get("surface") or {}
    extra = res.metrics.get("adaptive", {}).get("resensed", {})
    return {**{k: task[k] for k in ("case", "method", "eps_share")},
            "slices": len(res.slices), "eps": res.sensing.eps, "wall_s": wall, "cpu_s": cpu,
            "chamfer_l1_diag": np.nan if s.get("chamfer_l1") is None else s["chamfer_l1"] / diag,
            "fscore_1": (s.get("fscore") or {}).get("1%", np.nan),
            "coverage": tot.get("coverage", np.nan),
            "robot_time_s": tot["robot_time_s"] + extra.get("robot_time_s", 0.0),
            "motions": tot["motions"] + extra.get("motions", 0),
            "budget_hits": tot.get("budget_hits", 0)}


def pareto_front(rows, x: str = "wall_s", y: str = "chamfer_l1_diag",
                 lower_is_better: bool = True) -> np.ndarray:
    """(n,) bool: rows not dominated within their case (less ``x`` and better ``y``).

    >>> rows = [{"case": "a", "wall_s": 1, "e": 3}, {"case": "a", "wall_s": 2, "e": 1},
    ...         {"case": "a", "wall_s": 3, "e": 2}]
    >>> pareto_front(rows, y="e").tolist()
    [True, True, False]
    """
    out = np.zeros(len(rows), dtype=bool)
    sign = 1.0 if lower_is_better else -1.0
    for i, r in enumerate(rows):
        if not np.isfinite(r[y]):
            continue
        out[i] = not any(o["case"] == r["case"] and np.isfinite(o[y]) and o[x] <= r[x]
                         and sign * o[y] <= sign * r[y] and (o[x] < r[x] or sign * o[y] < sign * r[y])
                         for o in rows)
    return out


def adaptive_summary(rows, plan: dict) -> list[dict]:
    """Per case: adaptive against uniform at ``auto_max`` slices and the same eps.

    The target: F@1% within 0.005 of the uniform run's with at most half its
    slices and half its CPU time."""
    out = []
    for case in dict.fromkeys(r["case"] for r in rows):
        uni = [r for r in rows if r["case"] == case and r["method"] == "uniform"
               and r["slices"] == plan["auto_max"] and np.isclose(r["eps_share"], plan["auto_share"])]
        ada = [r for r in rows if r["case"] == case and r["method"] == "adaptive"]
        if not uni or not ada:
            continue
        u, a = uni[0], ada[0]
        out.append({"case": case, "uniform_slices": u["slices"], "adaptive_slices": a["slices"],
                    "uniform_f1": u["fscore_1"], "adaptive_f1": a["fscore_1"],
                    "slice_ratio": a["slices"] / u["slices"], "time_ratio": a["wall_s"] / u["wall_s"],
                    "cpu_ratio": a["cpu_s"] / u["cpu_s"],
                    "robot_ratio": a["robot_time_s"] / u["robot_time_s"],
                    "target_met": bool(a["fscore_1"] >= u["fscore_1"] - 0.005
                                       and a["slices"] <= u["slices"] / 2
                                       and a["cpu_s"] <= u["cpu_s"] / 2)})
    return out
