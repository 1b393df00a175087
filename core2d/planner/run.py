"""The pulling-motion sensing algorithm on one closed slice (§4, Fig. 16).

The planner decides motions from sensor readings and from what it has
recorded itself; it never sees the contour. Per unknown area A_iB_i:

1. Dist(A_i, B_i) < eps  ->  W2 (§3.1, §4.4).
2. Single probe detection (Fig. 6, :mod:`core2d.planner.detection`): G_i by
   rotating about the tip; Area(G_i) = 0  ->  W3 (§4.2.1). This and the
   proof of :mod:`core2d.planner.revisit` are the only ways to W3.
3. Initial pass planning (Theorem 1) to a new contact C on Int(A_iB_i).
4. Bisection local concave point search (Theorems 2, 3) to D_i. Infinite
   loop escape (§4.4) splits A_iB_i at C when the area repeats an ancestor's
   A and B, when generations in a row trace no new contour, or when the
   bisection fails.
5. Tracing motion planning (Theorem 4) from D_i on one or both sides; the
   events Case 1 - 4 register new areas by the rule of §4.3.3 (and the
   Fig. 12(c) split for a one-sided start).

An area whose contour C_A^B has meanwhile been traced through other areas
(:meth:`KnownContour.covers`) is closed as traced; an end A_i or B_i farther than
eps from the recorded contour is joined to it by a W2 chord
(:func:`~core2d.planner.mouths.traced_gaps`). A dead end -- no pass, or
a pass that finds no new contact -- never makes W3: the area is deferred,
and once nothing else is left :func:`core2d.planner.revisit.revisit` looks at
it again with everything the robot has recorded (another pass, another side).
Finally :func:`core2d.planner.audit.audit` registers the contour that no area
holds any more (loose ends of the recorded contour: islands, §3.2, and the
contour behind the ends of a lid that opens to F between two objects), an
object met once far from everything recorded is bootstrapped again
(:func:`core2d.planner.orphans.seek`), and what is left is reported unknown
(:func:`~core2d.planner.audit.report_leftovers`).
Areas are processed breadth first until none is left or a budget is hit.

The map, the deferral, the proof for W3, the revisit and the audit are the
planner's additions to Fig. 16; with the ``paper`` flow
(:mod:`core2d.planner.flow`) they are off and the paper's flow runs alone:
a dead end and Area(G_i) = 0 become W3 at once (§4.2.1).
"""
from __future__ import annotations

import time
from collections import deque

import numpy as np

from core2d.planar import magnitude
from core2d.planner.denoise import smooth
from core2d.planner.areas import Area, register
from core2d.planner.audit import audit, report_leftovers
from core2d.planner.bootstrap import bootstrap
from core2d.planner.budget import Budget
from core2d.planner.detection import single_detection, single_posture
from core2d.planner.flow import PULLING, Flow
from core2d.planner.grazing import beyond_ends, end_radius, resolves_half_eps
from core2d.planner.known import KnownContour
from core2d.planner.local_search import bisection, initial_pass
from core2d.planner.mouths import close_unresolved, is_mouth, traced_gaps
from core2d.planner.openings import SweptRobot
from core2d.planner.orphans import Orphans, seek
from core2d.planner.other_side import second_side
from core2d.planner.regions import Posture
from core2d.planner.revisit import finish, lid_like, proof_lines, revisit
from core2d.planner.robot import PlannerCounters, Robot, final_stats
from core2d.planner.thin_walls import touched_from_behind
from core2d.planner.tracing import (attach_pivot_G, plan_sides, reread_pass, split_contact,
                                    trace_side)
from core2d.planner.w3_checks import closes_loop
from core2d.result import AreaRecord, SliceResult

__all__ = ["explore", "Exploration", "Budget"]

#: generations in a row without new traced contour before §4.4 escape
STALE = 3


def _same(p, q, tol):
    return magnitude(np.asarray(p, float) - np.asarray(q, float)) <= tol


class Exploration:
    """The planner's state on one slice, and the steps of Fig. 16 on it.

    :func:`explore` drives it; :mod:`core2d.planner.revisit` and
    :mod:`core2d.planner.audit` work on it too, and tests drive single
    areas through :meth:`add` and :meth:`process`.

    Attributes
    ----------
    probe : Robot -- the probe commanded.
    eps : float -- the paper's epsilon.
    res : Resolution -- the probe's stated resolution (same-point radius
        ``res.tip_zone``, ...); ``angle_tol`` its angular resolution.
    budget : Budget
    result : SliceResult -- W1, W2, W3, unknown and the A_iB_i log so far.
    queue : deque of Area -- areas waiting, breadth first.
    deferred : list of Area -- dead ends, looked at again by ``revisit``.
    waiting : list of (Area, str) -- lids ready for W3, waiting to close a loop.
    audits : int -- rounds of :func:`~core2d.planner.audit.audit` made.
    known : KnownContour or None -- the robot's own map of what it has
        recorded (None when ``flow.map`` is off).
    flow : Flow -- which additions to Fig. 16 are on.
    counters : PlannerCounters -- what the planner counts itself.
    """

    def __init__(self, probe: Robot, eps: float, budget: Budget, flow: Flow = PULLING):
        self.res = probe.resolution
        # a fine noisy sensor: its insertions' sweeps tell openings (core2d.planner.openings)
        probe = SweptRobot(probe) if resolves_half_eps(self.res) else probe
        self.probe, self.eps, self.budget, self.flow = probe, eps, budget, flow
        self.same = self.res.tip_zone * flow.same  # contacts this close are one contact
        self.angle_tol = self.res.angle_tol(probe.length)
        self.counters = PlannerCounters()
        self.result = SliceResult()
        self.queue = deque()
        self.deferred = []
        self.waiting = []  # (area, reason): lids ready for W3, waiting to close a loop
        self.openings = []  # (A_i, B_i): lids the revisit closed open (core2d.planner.repeats)
        self.audits = 0
        self.orphans = Orphans()  # contacts met far from the record (core2d.planner.orphans)
        self.mouths = []  # areas processed as mouths (core2d.planner.mouths)
        self.band_w2 = []  # [map piece, sweeps seen]: W2 chords longer than eps (openings)
        # the robot's map; gaps narrower than eps (+ the sensor's jitter) are W2 (§3.1)
        self.known = KnownContour(join=self.res.w2_dist) if flow.map else None

    def add(self, area):
        area.index = len(self.result.areas)
        self.budget.areas += 1
        self.result.areas.append(AreaRecord(area.index, area.a.copy(), area.b.copy(),
                                             area.parent, area.rule))
        self.queue.append(area)

    def close(self, area, outcome, note="", pieces=None):
        """Record ``area``'s outcome; a W2, W3 or unknown area writes its lid, or
        ``pieces`` ({"W2" / "unknown": list of (2, 2) float}: a lid the revisit's passes
        touched, :mod:`core2d.planner.touched`; the gaps of a contour traced through
        other areas, :func:`~core2d.planner.mouths.traced_gaps`), which the map leaves
        out as it leaves an unknown lid."""
        rec = self.result.areas[area.index]
        rec.outcome, rec.note = outcome, note
        if outcome in ("W2", "W3", "unknown") or pieces:
            lid = np.stack([area.a, area.b])
            for kind, segments in (pieces or {outcome: [lid]}).items():
                for seg in segments:
                    getattr(self.result, kind.lower()).append(np.array(seg, dtype=float))
                    if kind != "unknown":
                        self.result.known_at[kind.lower()].append(self.probe.motions - 1)
            if outcome != "unknown" and self.known is not None and pieces is None:
                self.known.add(lid, area.pose_a, area.pose_b)
                if isinstance(self.probe, SweptRobot) and outcome == "W2" and area.dist > self.eps:
                    self.band_w2.append([len(self.known.pieces) - 1, 0])  # the noisy W2 band

    def defer(self, area, why):
        """A dead end: the area stays unknown and is looked at again later
        (``flow.defer``); in the paper's flow it is W3 at once (§4.2.1)."""
        if not self.flow.defer:
            return self.close(area, "W3", why + " (§4.2.1)")
        if area.mouth:  # reads no wider than eps + jitter (core2d.planner.mouths)
            return self.close(area, "W2", why + "; Dist(A,B) < eps + the sensor's jitter")
        rec = self.result.areas[area.index]
        rec.outcome, rec.note = "deferred", why
        self.deferred.append(area)

    def traced(self, polylines, ends) -> float:
        """Record W1 polylines (material on the right) and the postures that
        touched their ends; their total length. Noisy readings are smoothed
        over the sensor's jitter first (:func:`core2d.planner.denoise.smooth`)."""
        polylines = [smooth(pl, self.res) for pl in polylines]
        self.result.w1.extend(polylines)
        self.result.known_at["w1"].extend([self.probe.motions - 1] * len(polylines))
        for pl, (pose_first, pose_last) in zip(polylines, ends):
            if self.known is not None:
                self.known.add(pl, pose_first, pose_last)
        return float(sum(np.hypot(*np.diff(pl, axis=0).T).sum() for pl in polylines))

    def children(self, area, kids, traced=0.0):
        """Register ``kids`` of ``area``; §4.4 over the whole ancestry: a kid
        repeating the A and B of any ancestor, or the STALE-th generation in
        a row that traced less than eps of new contour, requests the escape.
        Without ``flow.escape``, §4.4 as worded: a kid repeating its parent's
        A and B (the same contact points found again)."""
        same = self.same  # contacts closer than eps/2 are one contact
        lineage = area.lineage + ((area.a, area.b),)
        stale = 0 if traced >= self.eps else area.stale + 1
        asked = lineage if self.flow.escape else lineage[-1:]
        for kid in kids:
            kid.lineage, kid.stale = lineage, stale
            if (stale >= STALE and self.flow.escape) or any(
                    _same(kid.a, a, same) and _same(kid.b, b, same) for a, b in asked):
                kid.escape = True
            self.add(kid)
        self.close(area, "split" if kids else "traced")

    def process(self, area):
        probe, eps = self.probe, self.eps
        if area.dist < self.res.w2_dist:  # eps (+ the sensor's jitter, Resolution.w2_dist)
            if not (self.flow.map and is_mouth(self.res, area.dist, area.rule)):
                return self.close(area, "W2", "Dist(A,B) < eps")
            area.mouth = True  # reads >= eps: processed, W2 at a dead end
            self.mouths.append(area)
        same = self.same
        # no hop across a mouth (a gap that reads >= eps) counts (core2d.planner.mouths)
        gaps = traced_gaps(self.known, area.a, area.b, same, self.res) if self.flow.covers \
            else None
        if gaps is not None:
            return self.close(area, "traced", "C_A^B traced through other areas",
                              pieces={"W2": gaps} if gaps else None)
        if area.zero_G:
            return self.zero_G(area)
        G = area.G
        pose = None if G is not None or not self.flow.detection else single_posture(
            area, probe, same)
        if pose is not None:
            probe.note_phase("detection", area.index)
            G, ok = single_detection(probe, pose, area)
            if ok and G is None:
                return self.zero_G(area)
        probe.note_phase("escape" if area.escape else "initial_pass", area.index)
        reading, G, why = initial_pass(probe, area, G)
        if reading is None:
            return self.defer(area, why)
        # C read again where the probe stands (a fine noisy sensor; reread_pass)
        c, pose_c = reread_pass(probe, reading)
        end = end_radius(self.res) * self.flow.same
        if _same(c, area.a, end) or _same(c, area.b, end):
            # within eps/2 of A_i or B_i: the same contact at the paper's resolution
            return self.defer(area, "Theorem 1 pass found no new contact")
        if self.flow.map and beyond_ends(self.res, area.a, area.b, c):
            # a noisy sensor's grazing pass past an end (core2d.planner.grazing)
            return self.defer(area, "Theorem 1 pass met the lid's line beyond its ends")
        if self.flow.map and self.known.distance(c) <= self.res.near and not \
                touched_from_behind(self.known, self.res, c, pose_c.joint):
            # contour the robot has recorded already (Ext, or Int traced through
            # other areas): nothing new to start the search from -- unless the rod
            # lies behind that record (core2d.planner.thin_walls: a thin wall's far face)
            return self.defer(area, "Theorem 1 pass touched recorded contour")
        joint_i = reading.joint.copy()
        probe.note_phase("bisection", area.index)
        local = None if area.escape else bisection(probe, area, G, reading)
        if local is None:
            return self.escape(area, c, pose_c)
        self.trace(area, G, joint_i, local)

    def zero_G(self, area):
        """Single probe detection with Area(G_i) = 0 (Fig. 6(b), §4.2.1): the
        paper's W3 -- the pass the probe held is the only one through its
        tip. W3 at once when the robot's map agrees that no line from F
        crosses the lid (:func:`proof_lines`). Where lines remain (a slit
        narrower than eps that the pivot about the tip cannot resolve, or
        Fig. 6(b) met inside a slot narrower than eps, where §3.2 fails) the
        area is deferred: :mod:`core2d.planner.revisit` tries those lines.
        Without ``flow.w3_proof`` (the paper's flow): W3 at once."""
        if not self.flow.w3_proof:
            return self.close(area, "W3", "single probe detection, Area(G) = 0 (§4.2.1)")
        if (lid_like(self, area) and closes_loop(self.known, area, self.res.tip_zone,
                                                 self.res.loop_width)
                and not proof_lines(self, area)):
            return self.close(area, "W3", "single probe detection, Area(G) = 0")
        return self.defer(area, "single probe detection, Area(G) = 0; lines still cross the lid")

    def escape(self, area, c, pose_c, rule="escape"):
        """§4.4: split A_iB_i at the new contact found by the initial pass."""
        self.counters.escapes += rule == "escape"
        d = area.depth + 1
        kids = [Area(area.a, c, area.pose_a, pose_c, area.index, rule, d),
                Area(c, area.b, pose_c, area.pose_b, area.index, rule, d)]
        self.children(area, kids)

    def trace(self, area, G, joint_i, local):
        probe = self.probe
        probe.note_phase("tracing", area.index)
        sides, q = plan_sides(local)
        q = split_contact(q, area, G, joint_i)  # Fig. 12(c) only with Q on Int
        pose_d = Posture(local.reading.joint, local.reading.direction)
        kids = []
        dq = None
        traced = 0.0
        if len(sides) == 1 and q is not None:  # Fig. 12(c): (D_i, Q) is a single
            dq = register(local.point, pose_d, q.point, pose_d, sides[0], area.index,
                          "fig12c", area.depth + 1)  # probe detection: G_i now
            if self.flow.detection:
                attach_pivot_G(dq, probe, q.face)
        for k, toward_B in enumerate(sides):
            start = local
            if k:  # brought back to D_i; where it is not, C_{D_i}^{P_fin} begins elsewhere
                start, skipped = second_side(self, area, G, joint_i, local, toward_B)
                kids.extend(skipped)
                if start is None:
                    continue
            lines, new, _, ends = trace_side(probe, area, G, joint_i, start, toward_B,
                                             self.budget, self.flow, self.known)
            traced += self.traced(lines, ends)
            kids.extend(new)
        if len(sides) == 1:  # one-sided start: Fig. 12(c) / Theorem 4 (B)-(E)
            fin_is_A = sides[0]  # the side not traced
            p_fin = area.a if fin_is_A else area.b
            pose_fin = area.pose_a if fin_is_A else area.pose_b
            d = area.depth + 1
            if q is not None:
                kids.append(dq)
                kids.append(register(q.point, pose_d, p_fin, pose_fin, fin_is_A,
                                     area.index, "fig12c", d))
            else:
                kids.append(register(local.point, pose_d, p_fin, pose_fin, fin_is_A,
                                     area.index, "one-sided", d))
        self.children(area, kids, traced)


def explore(probe: Robot, eps: float, max_motions: int = 20000, max_areas: int = 4000,
            bootstrap_count: int = 12, flow: Flow = PULLING) -> SliceResult:
    """Run the pulling-motion algorithm with ``probe`` until nothing is left.

    Parameters
    ----------
    probe : Robot -- the motions, the joint pose and the stated constants
        (:mod:`core2d.planner.robot`); the planner learns about the world
        only through the readings the motions return.
    eps : float -- the paper's epsilon.
    max_motions, max_areas : int -- budgets; when hit, the areas still
        unknown are reported in ``result.unknown`` and ``stats.budget_hit``.
    flow : Flow -- :data:`~core2d.planner.flow.PULLING` (default) or
        :data:`~core2d.planner.flow.PAPER` (Fig. 16 alone).

    Returns
    -------
    SliceResult in the slice's 2D frame.
    """
    t0 = time.perf_counter()
    budget = Budget(probe, max_motions, max_areas)
    run = Exploration(probe, eps, budget, flow)
    probe.note_phase("bootstrap")
    for area in bootstrap(probe, bootstrap_count):
        run.add(area)
    while True:
        while run.queue and budget():
            run.process(run.queue.pop() if flow.lifo else run.queue.popleft())
        if run.queue or not budget():
            break
        if run.deferred and flow.revisit:
            revisit(run)  # dead ends, with everything recorded so far
        elif not (flow.audit and (audit(run) or seek(run))):  # contour no area holds
            break
    finish(run)
    for area in list(run.queue) + run.deferred:  # the budget ran out
        run.close(area, "unknown", run.result.areas[area.index].note)
    close_unresolved(run)  # a mouth whose inside stayed unknown is W2
    if flow.map:  # contour left unrecorded is reported, never dropped
        report_leftovers(run)
    run.result.stats = final_stats(probe, escapes=run.counters.escapes,
                                   areas=len(run.result.areas), budget_hit=budget.hit,
                                   seconds=time.perf_counter() - t0)
    return run.result
