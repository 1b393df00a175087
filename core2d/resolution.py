"""The paper's resolution: every tolerance derived from eps and tol, in one place.

The robot is told two lengths (§3.2): the paper's epsilon -- the contour is
smooth at that scale and areas with Dist(A, B) < eps are W2 -- and the
contact resolution ``tol``; a robot with real sensors is also told their
data sheet (:class:`core2d.sim.sensor.SensorModel`): the standard deviation
``noise`` of its contact and joint readings and its ``taxel`` spacing. Every other tolerance of the simulator, the
planner and the ground truth follows from them here, so that all three rooms
of core2d agree on what "the same point" means.
"""
from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Resolution"]


@dataclass(frozen=True)
class Resolution:
    """The robot's stated resolution: ``eps`` and ``tol`` and what follows.

    Build it with :meth:`of`, which fills in the default ``tol = eps / 20``.
    ``noise`` and ``taxel`` are the sensor's stated figures (0: the paper's
    perfect sensing).

    Examples
    --------
    >>> r = Resolution.of(1.0)
    >>> r.tol, r.tip_zone, r.fan_spacing, r.near, r.metric_tol
    (0.05, 0.5, 0.25, 0.1, 0.5)
    """

    eps: float
    tol: float
    noise: float = 0.0
    taxel: float = 0.0

    @classmethod
    def of(cls, eps: float, tol: float | None = None, noise: float = 0.0,
           taxel: float = 0.0) -> Resolution:
        """``Resolution(eps, tol, noise, taxel)`` with the default contact
        resolution eps / 20."""
        return cls(float(eps), float(tol if tol is not None else eps / 20.0), float(noise),
                   float(taxel))

    @property
    def sensor_tol(self) -> float:
        """eps / 2 + 2 noise: the distance within which a reported point
        stands for the contour (the metric tolerance of a noisy sensor)."""
        return self.eps / 2.0 + 2.0 * self.noise

    @property
    def tip_zone(self) -> float:
        """eps / 2: contacts closer than this are one contact at the paper's
        resolution (the same-point radius); near the tip they are the tip's
        contact, and a contact point moving farther in one step jumped."""
        return self.eps / 2.0

    @property
    def fan_spacing(self) -> float:
        """eps / 4: spacing of the fans at the tip, of the samples along the
        probe and the nominal joint step of a compliant trace."""
        return self.eps / 4.0

    @property
    def stop_short(self) -> float:
        """tol / 2: how far short of a contact a guarded move stops (and the
        smallest joint step of a compliant trace)."""
        return self.tol / 2.0

    @property
    def near(self) -> float:
        """2 tol: a point this close to the probe or to recorded contour is
        on it (contact noise)."""
        return 2 * self.tol

    @property
    def metric_tol(self) -> float:
        """eps / 2: the ground truth's distance tolerance (every point of a
        W2 chord with Dist(A, B) < eps lies within eps / 2 of the contour)."""
        return self.eps / 2.0

    def fan_angle(self, length: float) -> float:
        """Angular fan spacing of a probe of ``length``: eps / 4 at the tip."""
        return self.fan_spacing / length

    def angle_tol(self, length: float) -> float:
        """Angular resolution of a probe of ``length``: tol / 2 at the tip."""
        return self.stop_short / length
