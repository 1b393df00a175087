"""The paper's claim, measured: pulling against pushing under tip friction (``claims``).

§1 and Figs. 1-2 argue that a probe pushed along a frictional surface sticks
or is blocked by small irregularities while a pulled one slides, so a trace
should start at a local concave point, where both directions pull. This
part runs, on the middle z-slice of each case, every method at every
friction coefficient mu of :data:`MUS` (:mod:`core2d.sim.friction`):

* ``pulling`` -- the default planner (the paper's algorithm and its additions);
* ``paper`` -- the paper's Fig. 16 flow alone;
* ``follow`` -- the pushing contour follower from the first contacts
  (:mod:`core2d.planner.follow`, Fig. 2(a));
* ``finger`` -- finger probing (:mod:`core2d.planner.finger`): insertions
  along t that stop at the first touch never slide, so friction cannot act
  on them (:mod:`core2d.sim.friction`); it is run at every mu all the same,
  and the ``same_as_mu0`` column says whether each run equals the mu = 0 one.

A row per (case, method, mu): 2D reachable coverage, jams, executed pushes,
push attempts stopped by the Case 3 guard, motions, robot time (the model
of ``metrics.json``), budget hit. One task per case.
"""
from __future__ import annotations

import numpy as np

from core2d import sense_slice
from core2d.truth.metrics import slice_metrics
from recon3d.benchmark.baseline import OVERHEAD, SPEED
from recon3d.benchmark.cases import case_list, middle_slice, workspace
from recon3d.records import robot_time

__all__ = ["claims_tasks", "run_claims", "summary", "MUS", "METHODS", "SCENES", "FINGER"]

MUS = (0.0, 0.1, 0.3, 0.6, 1.0)
"""Friction coefficients of the full run (``--quick``: the first and the last)."""
METHODS = ("pulling", "paper", "follow", "finger")
SCENES = ("fig17_pocket", "fig18_overhangs", "textured_pocket", "knurled_pocket")
"""The figure scenes and two with fine surface texture (teeth of a few tol)."""
FINGER = {"directions": 16, "spacing": 1.0}
"""Finger probing density: directions x line spacing in eps (about the
density that matches pulling's coverage on the figure scenes, baseline.csv)."""


def claims_tasks(quick: bool) -> list[dict]:
    """One task per case: the scenes (quick: two), then the real meshes found."""
    scenes = ("fig17_pocket", "textured_pocket") if quick else SCENES
    mus = (MUS[0], MUS[-1]) if quick else MUS
    return [{"case": n, "source": s, "eps_share": 1 / 200, "mus": mus}
            for n, s in case_list(scenes, real=not quick)]


def _row(case, method, mu, res, loops, eps) -> dict:
    st = res.stats.as_dict()
    m = slice_metrics(loops, res, eps)
    return {"case": case, "method": method, "mu": mu, "coverage": m["coverage"],
            "jams": st["jams"], "pushes": st["pushes"], "push_attempts": st["push_attempts"],
            "motions": st["motions"], "robot_time_s": robot_time(st, SPEED, OVERHEAD),
            "budget_hit": st["budget_hit"], "seconds": st["seconds"]}


def run_claims(task: dict) -> list[dict]:
    """Every method at every mu of the task on the case's middle z-slice."""
    _, diag, slc = middle_slice(task["source"])
    eps = task["eps_share"] * diag
    loops = [np.asarray(lp) for lp in slc.loops]
    model, ws = slc.contact("embree"), workspace(slc, eps)
    rows = []
    for method in METHODS:
        kw = {} if method != "finger" else dict(
            directions=FINGER["directions"], spacing=FINGER["spacing"] * eps, max_motions=10 ** 6)
        for mu in task["mus"]:
            res = sense_slice(model, ws, eps, method=method, friction=mu, **kw)
            rows.append(_row(task["case"], method, mu, res, loops, eps))
    for r in rows:
        if r["method"] == "finger":
            zero = next(q for q in rows if q["method"] == "finger" and q["mu"] == task["mus"][0])
            r["same_as_mu0"] = all(r[k] == zero[k] for k in ("coverage", "jams", "pushes",
                                                              "motions", "robot_time_s"))
    return rows


def summary(rows) -> list[dict]:
    """Per (method, mu): mean coverage, total jams and pushes over the cases."""
    out = []
    keys = list(dict.fromkeys((r["method"], r["mu"]) for r in rows))
    for method, mu in keys:
        sel = [r for r in rows if r["method"] == method and r["mu"] == mu]
        out.append({"method": method, "mu": mu, "cases": len(sel),
                    "coverage": float(np.mean([r["coverage"] for r in sel])),
                    "jams": int(sum(r["jams"] for r in sel)),
                    "pushes": int(sum(r["pushes"] for r in sel)),
                    "motions": int(sum(r["motions"] for r in sel)),
                    "robot_time_s": float(sum(r["robot_time_s"] for r in sel))})
    return out
