"""The probe as the planner sees it: motions, a joint pose, stated constants.

The planner is typed against :class:`Robot` only. Everything it learns about
the world comes back from a motion as a :class:`~core2d.readings.Reading`;
besides the readings it may use the joint pose (joint position sensors) and
the constants a robot is told: the workspace circle, the probe length and
the resolution (:class:`~core2d.resolution.Resolution`: eps, tol and the
tolerances that follow). It never sees the contact model nor the
simulator's internals (its ray engine, its fan windows, its counters): the
planner keeps its own counters (:class:`PlannerCounters`) and asks the robot
only for its motion count and, at the end, its costs. It tells the robot
which step of Fig. 16 it is in (:meth:`Robot.note_phase`, one way: for the
motion log of :class:`core2d.sim.recorder.Recorder`).
:class:`core2d.sim.probe.Probe` implements the protocol.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

from core2d.readings import Reading, Rereads
from core2d.resolution import Resolution
from core2d.result import SenseStats

__all__ = ["Robot", "PlannerCounters", "final_stats"]


@runtime_checkable
class Robot(Protocol):
    """The probe protocol of the planner (§3.2): a probe of length L on a joint."""

    center: np.ndarray  #: (2,) centre of the workspace circle containing the slice
    radius: float  #: radius of the workspace circle
    length: float  #: probe length L
    resolution: Resolution  #: eps, tol and the tolerances that follow
    joint: np.ndarray  #: (2,) joint position P
    theta: float  #: probe angle (radians, ccw from +x)

    @property
    def direction(self) -> np.ndarray:
        """(2,) unit probe direction t."""

    @property
    def tip(self) -> np.ndarray:
        """(2,) tip position, joint + L t."""

    @property
    def motions(self) -> int:
        """Motions executed so far."""

    def costs(self) -> SenseStats:
        """The robot's cost counters so far (motions, joint path, rays, pushes)."""

    def note_phase(self, phase: str, area: int = -1) -> None:
        """Told which step of Fig. 16 the next motions serve, for area ``area``
        (one of :data:`core2d.motionlog.PHASES`). One way: returns nothing,
        changes no motion (a motion recorder logs it; the probe ignores it)."""

    def sense(self) -> Reading:
        """Read the sensors again where the probe stands (no motion: the
        readings of a noisy sensor differ from one read to the next)."""

    def reread(self, count: int) -> Rereads:
        """``count`` more reads where the probe stands (no motion): what ``count``
        calls of :meth:`sense` would report of the joint, the tip's contact and the
        torque (:class:`~core2d.readings.Rereads`)."""

    def approach(self, point: np.ndarray, direction: np.ndarray) -> Reading:
        """Free transfer to the line through ``point`` along ``direction``."""

    def insert(self, max_dist: float | None = None) -> Reading:
        """Insert along t until the tip touches."""

    def swing(self, rot_dir: int, max_angle: float) -> Reading:
        """Rotate about the joint until contact or ``max_angle``."""

    def turn_to(self, theta: float) -> Reading:
        """Swing to the absolute angle ``theta``."""

    def pivot(self, rot_dir: int, max_angle: float) -> Reading:
        """Rotate about the tip (Definition 1)."""

    def trace(self, v: np.ndarray, tau: int, max_dist: float, **kw) -> Reading:
        """Compliant tracing motion (§4.3)."""


@dataclass
class PlannerCounters:
    """What the planner counts itself (merged into the result's SenseStats)."""

    escapes: int = 0  #: §4.4 infinite-loop escapes


def final_stats(robot: Robot, **planner) -> SenseStats:
    """The robot's costs with the planner's own counters filled in."""
    stats = robot.costs()
    for key, value in planner.items():
        setattr(stats, key, value)
    return stats
