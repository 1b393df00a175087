"""The motion recorder: a robot that logs every motion of the robot it wraps.

:class:`Recorder` implements the probe protocol the planner is typed
against (:class:`core2d.planner.robot.Robot`) by handing every call to the
wrapped robot (the simulated :class:`~core2d.sim.probe.Probe`, compiled
Embree engine or Python path alike) and writing one row per motion: the
joint pose before and after, the Reading after, and the phase of Fig. 16
the planner says it is in. The planner tells the phase through one narrow,
one-way hook, :meth:`Recorder.note_phase`; nothing recorded is ever given
back to it, so the planner decides exactly as it does without a recorder.

Cost: a tuple per motion while sensing; the arrays of
:class:`core2d.motionlog.MotionLog` are built once, by :meth:`Recorder.log`.
"""
from __future__ import annotations

import math

import numpy as np

from core2d.motionlog import KINDS, PHASES, TRACE_CASES, MotionLog

__all__ = ["Recorder"]

_KIND = {k: i for i, k in enumerate(KINDS)}
_PHASE = {p: i for i, p in enumerate(PHASES)}


class Recorder:
    """Wrap ``robot`` and log its motions (see the module doc).

    Parameters
    ----------
    robot : the probe commanded (anything with the protocol's motions).
    """

    def __init__(self, robot):
        self.robot = robot
        self.center, self.radius = robot.center, robot.radius
        self.length, self.resolution = robot.length, robot.resolution
        self._phase, self._area = 0, -1
        self._rows: list[tuple] = []

    # ------------------------------------------------- the protocol's state
    @property
    def joint(self) -> np.ndarray:
        """(2,) joint position P."""
        return self.robot.joint

    @property
    def theta(self) -> float:
        """Probe angle (radians, ccw from +x)."""
        return self.robot.theta

    @property
    def direction(self) -> np.ndarray:
        """(2,) unit probe direction t."""
        return self.robot.direction

    @property
    def tip(self) -> np.ndarray:
        """(2,) tip position."""
        return self.robot.tip

    @property
    def motions(self) -> int:
        """Motions executed so far."""
        return self.robot.motions

    def costs(self):
        """The wrapped robot's cost counters."""
        return self.robot.costs()

    def note_phase(self, phase: str, area: int = -1) -> None:
        """The planner's one-way hook: the motions that follow serve ``phase``
        (one of :data:`core2d.motionlog.PHASES`) for the area A_iB_i ``area``."""
        self._phase, self._area = _PHASE[phase], int(area)

    def sense(self):
        """Read the sensors again (no motion: not logged)."""
        return self.robot.sense()

    def reread(self, count):
        """Read the sensors ``count`` more times (no motion: not logged;
        :class:`~core2d.readings.Rereads`)."""
        return self.robot.reread(count)

    # ------------------------------------------------------------- motions
    def _do(self, kind, call, *args, torque=0, **kw):
        # the probe replaces its joint array at each move (never writes into it):
        # keeping references is keeping the poses
        r = self.robot
        j0, th0 = r.joint, r.theta
        reading = call(*args, **kw)
        self._rows.append((kind, self._phase, self._area, j0, th0, r.joint, r.theta, reading,
                           torque))
        return reading

    def approach(self, point, direction):
        return self._do(0, self.robot.approach, point, direction)

    def insert(self, max_dist=None):
        return self._do(1, self.robot.insert, max_dist)

    def swing(self, rot_dir, max_angle):
        return self._do(2, self.robot.swing, rot_dir, max_angle)

    def turn_to(self, theta):
        return self._do(3, self.robot.turn_to, theta)

    def pivot(self, rot_dir, max_angle):
        return self._do(4, self.robot.pivot, rot_dir, max_angle)

    def translate(self, v, dist):
        return self._do(5, self.robot.translate, v, dist)

    def trace(self, v, tau, max_dist, **kw):
        sign = 1 if tau > 0 else (-1 if tau < 0 else 0)
        return self._do(6, self.robot.trace, v, tau, max_dist, torque=sign, **kw)

    # ----------------------------------------------------------------- log
    def log(self) -> MotionLog:
        """The motions so far as a :class:`~core2d.motionlog.MotionLog`."""
        rows, n, L = self._rows, len(self._rows), self.length
        if not n:
            return MotionLog()
        cols = tuple(zip(*rows))  # one tuple per field of the rows
        kind, phase, area = (np.array(cols[k]) for k in range(3))
        before, after = (np.column_stack([np.array(cols[k], dtype=np.float64),
                                          np.array(cols[k + 1], dtype=np.float64)])
                         for k in (3, 5))
        tip = after[:, :2] + L * np.stack([np.cos(after[:, 2]), np.sin(after[:, 2])], axis=1)
        seen = _seen(cols[7], after)
        none, trace = (math.nan, math.nan), _KIND["trace"]
        tip_c, counts, blocked = [], [], []
        events, others, start = [], [], [0]
        for k, reading in zip(cols[0], cols[7]):  # plain lists, one array each at the end
            contacts, c = reading.contacts, reading.tip_contact
            tip_c.append(none if c is None else c.point)
            counts.append(len(contacts))
            blocked.append((reading.blocked_ccw, reading.blocked_cw))
            rest = [q.point for q in contacts if q is not c]
            others.extend(rest)
            start.append(start[-1] + len(rest))
            ev = reading.event
            events.append(TRACE_CASES.get(ev, ev) if k == trace else ev)
        return MotionLog(
            kind=kind.astype(np.int8), phase=phase.astype(np.int8), area=area.astype(np.int32),
            event=np.array(events, dtype="<U12"), before=before, after=after, tip=tip, seen=seen,
            tip_contact=np.array(tip_c, dtype=np.float64).reshape(n, 2),
            contacts=np.array(counts, dtype=np.int16), other_start=np.array(start, dtype=np.int64),
            other=np.array(others, dtype=np.float64).reshape(-1, 2),
            blocked=np.array(blocked, dtype=bool).reshape(n, 2),
            torque=np.array(cols[8], dtype=np.int8))


def _seen(readings, after: np.ndarray) -> np.ndarray:
    """(n, 3) float: the reported joint x, y and angle after each motion; the angle is
    ``after``'s plus the reading's error, wrapped to (-pi, pi] (an encoder counts turns)."""
    joint = np.array([r.joint for r in readings], dtype=np.float64).reshape(-1, 2)
    direction = np.array([r.direction for r in readings], dtype=np.float64).reshape(-1, 2)
    err = np.arctan2(direction[:, 1], direction[:, 0]) - after[:, 2]
    # wrapped before it is added: a perfect reading's error is then 0 to the bit (24,444
    # motions of four scenes, Embree engine; tested), so ``seen`` is ``after``
    err = (err + np.pi) % (2 * np.pi) - np.pi
    return np.column_stack([joint, after[:, 2] + err])
