"""Plain data: the motion log of one slice, one row per motion of the probe.

Filled by :class:`core2d.sim.recorder.Recorder` (the robot layer), tagged
with the planner's phase (Fig. 16: bootstrap, single probe detection of
Fig. 6, Theorem 1's initial pass, the bisection of §4.2.2, the tracing of
§4.3, the escape of §4.4, the revisit of dead ends). Everything is in the
slice's 2D frame; ``recon3d.io.motions`` maps it to the world and writes
``motions.csv`` (its columns: the README, "The motion log").
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["MotionLog", "KINDS", "PHASES", "TRACE_CASES"]

KINDS = ("approach", "insert", "swing", "turn", "pivot", "translate", "trace")
"""The motions of the probe protocol (``kind`` codes index this tuple)."""

PHASES = ("none", "bootstrap", "detection", "initial_pass", "bisection", "tracing", "escape",
          "revisit")
"""The planner phases a motion can serve (``phase`` codes index this tuple)."""

TRACE_CASES = {"reached": "case1", "jump": "case2", "lost": "case2-3", "pushing": "case3",
               "blocked": "case4"}
"""A trace's Reading event -> the paper's case of §4.3.2 (Case 2-1 / 2-2 is the
planner's decision, recorded as the rule of the area it registers)."""


def _empty(*shape, dtype=np.float64):
    return np.zeros((0, *shape), dtype=dtype)


@dataclass
class MotionLog:
    """The motions of one slice, n rows.

    kind, phase : (n,) int8 -- codes into :data:`KINDS` / :data:`PHASES`.
    area : (n,) int32 -- index i of the area A_iB_i served (-1: none).
    event : (n,) str -- the Reading's event; for traces the case of §4.3.2.
    before, after : (n, 3) float -- joint x, y and probe angle theta.
    tip : (n, 2) float -- tip position after the motion.
    seen : (n, 3) float -- joint x, y and probe angle theta after the motion as the joint
        position sensors report them (:mod:`core2d.sim.sensor`; ``after`` with a perfect
        sensor). ``before`` / ``after`` are the simulator's true postures; what a robot
        knows of where it has been is ``seen``. theta is unwrapped as ``after``'s (an
        encoder counts turns).
    tip_contact : (n, 2) float -- the tip's contact point after (NaN: none).
    contacts : (n,) int16 -- contacts on the probe after (tip included).
    other_start : (n + 1,) int64 -- row k's non-tip contacts are
        ``other[other_start[k]:other_start[k + 1]]``.
    other : (m, 2) float -- the non-tip contact points.
    blocked : (n, 2) bool -- torque sensor after: (ccw, cw) blocked.
    torque : (n,) int8 -- trace rows: commanded torque sign tau (eq. 2); else 0.
    """

    kind: np.ndarray = field(default_factory=lambda: _empty(dtype=np.int8))
    phase: np.ndarray = field(default_factory=lambda: _empty(dtype=np.int8))
    area: np.ndarray = field(default_factory=lambda: _empty(dtype=np.int32))
    event: np.ndarray = field(default_factory=lambda: _empty(dtype="<U12"))
    before: np.ndarray = field(default_factory=lambda: _empty(3))
    after: np.ndarray = field(default_factory=lambda: _empty(3))
    tip: np.ndarray = field(default_factory=lambda: _empty(2))
    seen: np.ndarray = field(default_factory=lambda: _empty(3))
    tip_contact: np.ndarray = field(default_factory=lambda: _empty(2))
    contacts: np.ndarray = field(default_factory=lambda: _empty(dtype=np.int16))
    other_start: np.ndarray = field(default_factory=lambda: np.zeros(1, dtype=np.int64))
    other: np.ndarray = field(default_factory=lambda: _empty(2))
    blocked: np.ndarray = field(default_factory=lambda: _empty(2, dtype=bool))
    torque: np.ndarray = field(default_factory=lambda: _empty(dtype=np.int8))

    def __len__(self) -> int:
        return len(self.kind)

    def others(self, k: int) -> np.ndarray:
        """(j, 2) float: the non-tip contacts of row ``k``."""
        return self.other[self.other_start[k]:self.other_start[k + 1]]
