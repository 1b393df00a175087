"""Plain data produced by sensing one slice (DESIGN.md "Outputs per slice").

W1, W2 and W3 follow §3.1 of the paper:

* W1 -- contour traced by the probe tip (polylines of tip contacts);
* W2 -- straight-line approximation L_{A}^{B} of an area with Dist(A, B) < eps;
* W3 -- lid A_jB_j of a never-touching area verified by probing (Area(G_j) = 0).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from core2d.motionlog import MotionLog

__all__ = ["AreaRecord", "SenseStats", "SliceResult"]


@dataclass
class AreaRecord:
    """One unknown area A_iB_i (§3.3) and what became of it.

    index : int
        Running number i.
    a, b : (2,) float
        A_i and B_i. The unknown contour C_{A_i}^{B_i} runs from A_i to B_i,
        and V_i (Def. 3) -- the free side -- lies on the right when moving
        from B_i to A_i.
    parent : int
        Index of the area whose processing registered this one (-1 for the
        bootstrap).
    rule : str
        What created it: ``"bootstrap"``, ``"case2-1"``, ``"case2-2"``,
        ``"case2-3"``, ``"case3"``, ``"case4"``, ``"fig12c"``, ``"one-sided"``
        (Theorem 4 (B)/(C): the side not traced), ``"left"`` (a trace left
        the area through its other end), ``"hop"`` (the tip of a trace
        hopped over a gap -- a step longer than eps / 4 that turns concave,
        or Case 1 passing P_fin across a gap: the contour between was not
        traced), ``"escape"``, ``"revisit"`` (a pass
        through a deferred lid found a new contact), ``"limit"`` (a budget
        hit, or the second side of D_i where the probe did not come back to
        D_i), ``"reentry"`` (the stretch from D_i to where the probe came
        back instead: the second side is traced from there,
        :func:`core2d.planner.other_side.second_side`),
        ``"audit"`` (a stretch between a loose end and a loose start of the
        recorded contour that no area held), ``"loose"`` (such a stretch the
        audit left untraced: reported ``"unknown"`` at the end), ``"orphan"``
        (the bootstrap again, aimed at a contact met far from everything
        recorded: :mod:`core2d.planner.orphans`).
    outcome : str
        How it ended: ``"traced"`` (Case 1 over all of it), ``"W2"``,
        ``"W3"``, ``"split"`` (children registered), ``"deferred"`` (a dead
        end, to be looked at again), ``"open"`` (an opening to F between
        separate objects: nothing behind the lid itself; contour left
        untraced behind its ends is reported by ``"loose"`` areas),
        ``"unknown"`` (still unknown: passes found nothing new, a budget
        ran out, or a ``"loose"`` stretch).
    """

    index: int
    a: np.ndarray
    b: np.ndarray
    parent: int
    rule: str
    outcome: str = "pending"
    note: str = ""


@dataclass
class SenseStats:
    """Cost counters of one slice (the ``stats`` object of sensing.json).

    ``pushes`` counts trace steps executed in sliding contact with v.t > 0;
    ``push_attempts`` counts the steps where the planner's commanded v would
    have pushed and the guard stopped the trace (Case 3, §4.3.2): the honest
    measure of the pulling strategy, since the guard keeps ``pushes`` at 0.
    ``jams`` counts the pushing steps that stuck under tip friction (the
    rod inside the friction cone, :mod:`core2d.sim.friction`); 0 without it.
    ``sensor_reads`` counts the reads of a real sensor (reading points x the
    reads averaged at each, :mod:`core2d.sim.sensor`); the paper's perfect
    sensing takes none, and the key is then left out of :meth:`as_dict`.
    """

    motions: int = 0
    rays: int = 0
    casts: int = 0
    joint_path: float = 0.0
    pushes: int = 0
    push_attempts: int = 0
    jams: int = 0
    areas: int = 0
    escapes: int = 0
    budget_hit: bool = False
    seconds: float = 0.0
    cast_seconds: float = 0.0
    sensor_reads: int = 0

    def as_dict(self) -> dict:
        return {
            "motions": int(self.motions),
            "rays": int(self.rays),
            "joint_path": float(self.joint_path),
            "pushes": int(self.pushes),
            "push_attempts": int(self.push_attempts),
            "jams": int(self.jams),
            "areas": int(self.areas),
            "escapes": int(self.escapes),
            "budget_hit": bool(self.budget_hit),
            "seconds": float(self.seconds),
        } | ({"sensor_reads": int(self.sensor_reads)} if self.sensor_reads else {})


@dataclass
class SliceResult:
    """Everything the planner reports for one slice, in the slice's 2D frame.

    w1 : list of (k, 2) float -- traced polylines.
    w2 : list of (2, 2) float -- approximated segments (length < eps).
    w3 : list of (2, 2) float -- lids of never-touching areas.
    unknown : list of (2, 2) float -- areas still unknown at the end (a
        budget hit, passes through the lid found nothing new, or recorded
        contour that stops at a loose end no area traced on from).
    areas : list of AreaRecord -- the A_iB_i log.
    stats : SenseStats
    known_at : dict -- ``"w1"``, ``"w2"``, ``"w3"`` -> list of int parallel to
        that class: the index of the motion after which each piece was
        recorded (an animation grows the known contour with it).
    motions : MotionLog or None -- one row per motion (:mod:`core2d.motionlog`).
    """

    w1: list = field(default_factory=list)
    w2: list = field(default_factory=list)
    w3: list = field(default_factory=list)
    unknown: list = field(default_factory=list)
    areas: list = field(default_factory=list)
    stats: SenseStats = field(default_factory=SenseStats)
    known_at: dict = field(default_factory=lambda: {"w1": [], "w2": [], "w3": []})
    motions: MotionLog | None = None
