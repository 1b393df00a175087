"""Adaptive slicing (``recon3d run --slices auto``): slices where the section changes.

Model no more than the scene needs. Per family, the candidate planes are the
``max_slices`` evenly spaced planes of a uniform run (so an adaptive run is a
subset of the uniform one and spans the same slab):

1. **Start coarse**: ``initial`` planes spread over the candidates (the first
   and the last among them; 3 below 16 candidates, else 5). The middle one
   is sensed first at the coarse eps (2 x eps); the others at the eps it
   asks for (step 2), so a scene with narrow features pays one coarse pass,
   not one per slice.
2. **Adapt eps to the feature size the slice shows**: the sensed region of a
   slice (:func:`recon3d.surface.closure.slice_region`) is opened and closed with
   discs of dyadic widths w; the smallest w for which the boundary moves by
   more than w / 2 (a part or a pocket narrower than w, deeper than w / 2) is
   the slice's feature width, and a slice whose feature width is at most
   2 x the coarse eps is sensed again at eps_i = max(w / 4, eps)
   (snapped to coarse eps / 2^k): never finer than the eps of the uniform
   run it replaces, so a slice never costs more than a uniform one. Features
   the coarse pass bridged (narrower than the coarse eps) stay invisible: a
   slice can only show what it sensed.
3. **Refine where neighbours differ**: between two neighbouring sensed
   slices whose regions differ by more than ``tol`` (symmetric Hausdorff
   distance of their boundaries, in the shared 2D frame of the family) and
   that have a candidate between them, the middle candidate is added, sensed
   at the finer of the two neighbours' eps; a slice sensed coarser than its
   own feature width asks for is sensed again (step 2). Repeat until no pair
   differs or no candidate is left between differing neighbours.

Everything is decided from the sensed curves (the robot's own data), never
from the mesh. The cost of the coarse passes that were sensed again is not
lost: it is reported in ``MeshRun.adaptive`` (and ``metrics.json`` ->
``adaptive``) and counted in the robot time there.

:func:`sense_adaptive` decides which slices to sense at which eps; the
sensing itself and the assembly of the run are
:func:`recon3d.sensing.mesh.sense_mesh`'s, as for a uniform run.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import shapely

from recon3d.config import COARSE
from recon3d.records import SliceRun, robot_time
from recon3d.surface.closure import slice_region

__all__ = ["AdaptivePlan", "region_difference", "feature_width", "sense_adaptive",
           "refine_pairs"]


@dataclass(frozen=True)
class AdaptivePlan:
    """Parameters of adaptive slicing.

    max_slices : int -- candidate planes per family (the uniform run it replaces).
    initial : int -- planes of the coarse start (>= 2).
    tol : float -- neighbours whose regions differ by more than this get a
        slice between them (mesh units).
    eps : float -- the eps of the uniform run it replaces; slices use eps or 2 x eps.
    """

    max_slices: int
    initial: int
    tol: float
    eps: float

    @property
    def coarse(self) -> float:
        return COARSE * self.eps

    @property
    def fine(self) -> float:
        return self.eps


def region_difference(a, b) -> float:
    """Symmetric Hausdorff distance between the boundaries of two regions.

    ``inf`` when exactly one is empty, 0 when both are.

    >>> from shapely.geometry import box
    >>> region_difference(box(0, 0, 2, 2), box(0, 0, 2, 3))
    1.0
    """
    if a.is_empty and b.is_empty:
        return 0.0
    if a.is_empty or b.is_empty:
        return float("inf")
    return float(shapely.hausdorff_distance(a.boundary, b.boundary, densify=0.25))


def feature_width(region, widths) -> float | None:
    """Smallest width w (of ``widths``, ascending) a region shows, or None.

    A width shows when opening or closing the region with a disc of
    diameter w moves its boundary by more than w / 2: a part or a pocket
    narrower than w and deeper than w / 2 (a corner moves it by < 0.21 w).

    >>> from shapely.geometry import box
    >>> comb = box(0, 0, 10, 10).difference(box(4, 2, 5, 11))  # a slot 1 wide, 8 deep
    >>> feature_width(comb, [0.5, 1.5, 3.0])
    1.5
    """
    if region.is_empty:
        return None
    for w in widths:
        r = w / 2
        closed = region.buffer(r, quad_segs=4).buffer(-r, quad_segs=4)
        opened = region.buffer(-r, quad_segs=4).buffer(r, quad_segs=4)
        for other in (closed, opened):
            if region_difference(region, other) > w / 2:
                return float(w)
    return None


def _eps_for(region, plan: AdaptivePlan) -> float:
    """The slice's eps from its feature width (see the module doc)."""
    levels = [plan.coarse / 2 ** k for k in range(8) if plan.coarse / 2 ** k >= plan.fine * 0.999]
    widths = sorted(4 * e for e in levels)
    w = feature_width(region, widths)
    if w is None:
        return plan.coarse
    return max(e for e in levels if e <= max(w / 4, plan.fine))


def refine_pairs(indices, regions, tol) -> list:
    """Candidates to add: the middle index of each neighbouring pair that differs.

    Parameters
    ----------
    indices : sorted list of int -- sensed candidate indices.
    regions : dict int -> shapely geometry -- their sensed regions.
    tol : float

    >>> from shapely.geometry import box
    >>> regs = {0: box(0, 0, 1, 1), 4: box(0, 0, 1, 1), 8: box(0, 0, 3, 1)}
    >>> refine_pairs([0, 4, 8], regs, 0.5)
    [6]
    """
    out = []
    for a, b in zip(indices[:-1], indices[1:]):
        if b - a > 1 and region_difference(regions[a], regions[b]) > tol:
            out.append((a + b) // 2)
    return out


def _region(srun: SliceRun, tol: float):
    r = srun.result  # its pieces alone: the plan compares sections, not what the probe swept
    return slice_region(r.w1, r.w2, r.w3, r.unknown, 2.0 * tol).geometry


def sense_adaptive(plan: AdaptivePlan, sense: Callable[[list], list[SliceRun]], families: int,
                   tol_share: float, probe_speed: float, motion_overhead: float,
                   read_time: float = 0.0):
    """Choose, round by round, which slices to sense at which eps (module doc).

    Parameters
    ----------
    plan : AdaptivePlan
    sense : callable(list of (family, index, eps)) -> list of SliceRun, in task order.
    families : int -- number of slice families.
    tol_share : float -- contact resolution as a share of each slice's eps.
    probe_speed, motion_overhead, read_time : float -- robot time of the passes sensed again
        (speed in mesh units per second; :func:`recon3d.records.robot_time`).

    Returns
    -------
    got : list of dict index -> (SliceRun, eps) -- per family, the slices kept.
    eps, tol : float -- the finest eps sensed and its contact resolution.
    info : dict -- the ``adaptive`` block of metrics.json.
    """
    n = plan.max_slices
    got = [dict() for _ in range(families)]  # family -> index -> (SliceRun, eps)
    regions = [dict() for _ in range(families)]
    discarded = {"motions": 0, "joint_path": 0.0, "robot_time_s": 0.0, "slices": 0}

    def run(tasks):
        for out, (f, i, e) in zip(sense(tasks), tasks):
            if i in got[f]:  # sensed again at a finer eps: the coarse pass still cost
                st = got[f][i][0].result.stats.as_dict()
                discarded["motions"] += st["motions"]
                discarded["joint_path"] += st["joint_path"]
                discarded["robot_time_s"] += robot_time(st, probe_speed, motion_overhead,
                                                        read_time)
                discarded["slices"] += 1
            got[f][i] = (out, e)
            regions[f][i] = _region(out, tol_share * e)

    def finer(fi):  # sensed slices whose feature width asks for a finer eps than they got
        return [(f, i, e) for f, i in fi if (e := _eps_for(regions[f][i], plan)) < got[f][i][1]]

    fams = range(families)
    start = sorted(set(np.round(np.linspace(0, n - 1, plan.initial)).astype(int).tolist()))
    mid = start[len(start) // 2]
    run([(f, mid, plan.coarse) for f in fams])  # one probe slice per family first
    first = {f: min(_eps_for(regions[f][mid], plan), plan.coarse) for f in fams}
    run([(f, mid, first[f]) for f in fams if first[f] < plan.coarse]
        + [(f, i, first[f]) for f in fams for i in start if i != mid])
    new = [(f, i) for f in fams for i in start if i != mid]
    rounds = 1
    while True:
        again = finer(new)  # a feature the neighbours did not show: sense it again, finer
        if again:
            run(again)
        tasks = []
        for f in fams:
            idx = sorted(got[f])
            for m in refine_pairs(idx, regions[f], plan.tol):
                lo = max(i for i in idx if i < m)
                hi = min(i for i in idx if i > m)
                tasks.append((f, m, min(got[f][lo][1], got[f][hi][1])))
        if not tasks:
            break
        rounds += 1
        run(tasks)
        new = [(f, m) for f, m, _ in tasks]
    used = [e for g in got for _, e in (g[i] for i in sorted(g))]
    eps = min(used)
    info = {"max_slices": n, "initial": plan.initial, "tol": plan.tol,
            "rounds": rounds, "slices": [len(g) for g in got],
            "eps": {"coarse": plan.coarse, "fine": plan.fine, "per_slice": used},
            "resensed": discarded}
    return got, eps, tol_share * eps, info
