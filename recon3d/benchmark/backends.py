"""Contact backends on the same slices: Embree direct, exact 2D, trimesh's ray engine.

One task per slice (:func:`compare_slice`) senses it with every backend in
turn, in one process, so the ratios come from one run on one core: seconds
per motion, casts, and the agreement of the W classes with the exact
backend -- the share of reference contour length whose class (W1, W2, W3 or
nothing: the kind of the nearest sensed piece within eps / 2) is the same.
"""
from __future__ import annotations

import time

import numpy as np
import shapely

from core2d import sense_slice
from core2d.truth.reachability import sample_contour
from recon3d.benchmark.cases import case_list, middle_slice, workspace

__all__ = ["BACKEND_NAMES", "backend_tasks", "compare_slice", "class_labels"]

BACKEND_NAMES = ("embree", "exact", "trimesh")


def backend_tasks(quick: bool) -> list[dict]:
    """Middle z-slices of a few scenes (and Spot when present)."""
    scenes = ("fig18_overhangs", "stepped_pyramid") if quick else (
        "fig18_overhangs", "stepped_pyramid", "mushroom", "gear")
    share = 1 / 50 if quick else 1 / 100
    return [{"case": n, "source": s, "eps_share": share}
            for n, s in case_list(scenes, real=not quick)[:5]]


def class_labels(loops, result, eps: float, spacing: float):
    """Per reference sample: 0 nothing, 1 W1, 2 W2, 3 W3 (nearest piece within eps / 2).

    Returns
    -------
    labels : (m,) int, lengths : (m,) float
    """
    samp = sample_contour(loops, spacing)
    pieces, kinds = [], []
    for kind, parts in ((1, result.w1), (2, result.w2), (3, result.w3)):
        for p in parts:
            p = np.asarray(p, float).reshape(-1, 2)
            pieces.append(shapely.linestrings(np.vstack([p, p]) if len(p) == 1 else p))
            kinds.append(kind)
    labels = np.zeros(len(samp.points), dtype=int)
    if pieces:
        tree = shapely.STRtree(pieces)
        (i, j), d = tree.query_nearest(shapely.points(samp.points), return_distance=True,
                                       all_matches=False)
        near = d <= eps / 2
        labels[i[near]] = np.asarray(kinds)[j[near]]
    return labels, samp.lengths


def _warm(model, ws, eps) -> None:
    """Load (or compile) the numba kernels a backend, the simulator and the
    planner use, so that no timing pays for them: a cast of 40 rays and a
    short sensing run (200 motions) on the slice."""
    model.cast(np.zeros((40, 2)), np.tile([1.0, 0.0], (40, 1)), 1.0)
    sense_slice(model, ws, eps, max_motions=200)


def compare_slice(task: dict) -> list[dict]:
    """Sense one slice with every backend; one row per backend."""
    mesh, diag, slc = middle_slice(task["source"])
    eps = task["eps_share"] * diag
    loops = [np.asarray(lp) for lp in slc.loops]
    ref = None
    rows = []
    for b in ("exact",) + tuple(n for n in BACKEND_NAMES if n != "exact"):
        model = slc.contact(b)
        _warm(model, workspace(slc, eps), eps)
        t0 = time.perf_counter()
        res = sense_slice(model, workspace(slc, eps), eps)
        sec = time.perf_counter() - t0
        labels, lengths = class_labels(loops, res, eps, eps / 4)
        if ref is None:
            ref = labels
        st = res.stats
        rows.append({"case": task["case"], "backend": b, "eps": eps, "motions": st.motions,
                     "casts": st.casts, "seconds": sec, "s_per_motion": sec / max(st.motions, 1),
                     "ms_per_motion": 1000 * sec / max(st.motions, 1),
                     "cast_share": st.cast_seconds / sec if sec > 0 else np.nan,
                     "agreement": float(lengths[labels == ref].sum() / lengths.sum()),
                     "budget_hit": st.budget_hit})
    emb = next(r for r in rows if r["backend"] == "embree")
    for r in rows:
        r["time_per_motion_vs_embree"] = r["s_per_motion"] / emb["s_per_motion"]
    return rows
