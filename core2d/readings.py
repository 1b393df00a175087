"""Sensor readings: the only thing the planner learns from a motion (§3.2).

Faces follow the paper's figures (probe drawn pointing down): Face(left) is
the side that blocks a clockwise rotation, Face(right) the side that blocks
a counter-clockwise one, Face(tip) the tip (Definition 7).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["Contact", "Reading", "Rereads", "TIP", "LEFT", "RIGHT"]

TIP, LEFT, RIGHT = "tip", "left", "right"

_NO_TRACE = np.zeros((0, 2))
_NO_TRACE.flags.writeable = False  # one empty (0, 2) trace shared by every reading


def _no_trace() -> np.ndarray:
    return _NO_TRACE


@dataclass(frozen=True, slots=True)
class Contact:
    """One contact sensed by the distributed sensing elements.

    point : (2,) float -- contact position.
    face : str -- ``"tip"``, ``"left"`` or ``"right"`` (Definition 7).
    along : float -- distance from the joint along the probe.
    """

    point: np.ndarray
    face: str
    along: float


@dataclass(frozen=True, slots=True)
class Reading:
    """What the joint, torque and tactile sensors report after a motion.

    joint : (2,) float -- joint position P (joint position sensors).
    direction : (2,) float -- unit probe direction t.
    contacts : tuple of Contact -- every contact on the probe, primary first.
    blocked_cw, blocked_ccw : bool -- torque sensor: is a small clockwise /
        counter-clockwise rotation about the joint impossible.
    event : str -- why the motion stopped: ``"done"`` (ran its course),
        ``"contact"``, ``"jump"`` (contact point jumped, Case 2), ``"lost"``
        (no contact any more, Case 2-3), ``"pushing"`` (v.t > 0, Case 3),
        ``"blocked"`` (joint lost freedom along v, Case 4), ``"reached"``
        (a part of the probe reached the requested stop point, P_fin),
        ``"limit"`` (step budget of the motion).
    trace : (k, 2) float -- tip contacts recorded during a compliant trace.
    before_joint, before_direction : (2,) float -- posture at ``trace[-1]``,
        the last contact before a jump (for G_j of the new area).
    angle : float -- signed rotation performed by a swing (ccw positive).
    """

    joint: np.ndarray
    direction: np.ndarray
    contacts: tuple = ()
    blocked_cw: bool = False
    blocked_ccw: bool = False
    event: str = "done"
    trace: np.ndarray = field(default_factory=_no_trace)
    before_joint: np.ndarray | None = None
    before_direction: np.ndarray | None = None
    angle: float = 0.0

    def faces(self) -> set:
        return {c.face for c in self.contacts}

    def contact(self, face: str):
        """First contact on ``face`` or None."""
        for c in self.contacts:
            if c.face == face:
                return c
        return None

    @property
    def tip_contact(self):
        return self.contact(TIP)


@dataclass(frozen=True, slots=True)
class Rereads:
    """What k more reads where the probe stands report (``Robot.reread``): the
    joint position sensors, the tip's contact and the torque sensor, read by read.

    joint, direction : (k, 2) float -- P and the unit t of each read.
    tip : (k, 2) float -- the tip's contact of each read (NaN: none).
    blocked : (k, 2) bool -- the torque sensor's (ccw, cw) flags of each read.

    >>> r = Reading(np.zeros(2), np.array([0.0, -1.0]), (Contact(np.ones(2), TIP, 1.0),))
    >>> Rereads.of([r, r]).tip.tolist(), Rereads.of([r]).blocked.tolist()
    ([[1.0, 1.0], [1.0, 1.0]], [[False, False]])
    """

    joint: np.ndarray
    direction: np.ndarray
    tip: np.ndarray
    blocked: np.ndarray

    @classmethod
    def of(cls, readings) -> Rereads:
        """The record of a sequence of readings."""
        none = (np.nan, np.nan)
        tips = [none if (c := r.tip_contact) is None else c.point for r in readings]
        return cls(np.array([r.joint for r in readings], float).reshape(-1, 2),
                   np.array([r.direction for r in readings], float).reshape(-1, 2),
                   np.array(tips, float).reshape(-1, 2),
                   np.array([(r.blocked_ccw, r.blocked_cw) for r in readings],
                            bool).reshape(-1, 2))
