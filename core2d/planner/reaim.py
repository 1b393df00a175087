"""Grazing passes aimed again from where they landed (a secant on the line's offset).

With a noisy sensor a lid A_iB_i laid along a straight wall lies a few sigma
off the wall, and a pass crossing it at a small angle meets the wall about
offset / tan(angle) from where it crossed (:mod:`core2d.planner.grazing`).
In a slot one or two eps wide and tens of eps deep every line from F runs
within a degree or two of the walls: the revisit's passes land near an end
of the lid or past it, and the lid ends unknown (``trimesh_octagonal_pocket``
z1 at sigma 0.1 eps, sensor seed 2001: passes at 0.03 - 3.8 degrees to lids
1.4 - 2.5 eps long landed 0.05 - 0.5 eps from an end, or beyond it).

Moving the crossing point along the lid hardly moves such a landing (the
line moves sideways by the shift times sin(angle)). Moving the line
sideways does, and linearly while the wall is straight: a line shifted by
``s`` across its direction d meets a wall of direction w

    cross(d, n) / cross(d, w) * s

farther along it (n the shift's unit normal). :class:`Aim` keeps, for the
passes of one lid, the line of the first pass that landed on the lid's line
(within the jitter: the wall the lid lies along) and each landing; the next
pass is that line shifted to land at the lid's middle, by the lid's
direction for the first guess and by the secant through the last two
landings after it. Where a pass lands is geometry, not noise (the readings
only place it within sigma), so the secant converges on a straight wall in
two or three passes. The contacts are judged as any other
(``revisit._new_contact``): the landings only steer where the robot looks,
from its own readings.

Only under a noisy sensor whose jitter (two readings of one point) is at
most :data:`MAX_JITTER` eps: sigma <= 0.47 eps without taxels, so sigma 0.1
and sigma 0.3 with taxels 0.25 eps (jitter 1.52 eps) are in. Measured on
the sensor study's middle slices at sigma 1 eps (jitter 4.24 eps), where a
contact "on the lid's line" may lie four eps off it and a landing is read
to an eps: the scenes' coverage within eps/2 + 2 sigma fell 0.9406 ->
0.9230 with the rule. With perfect sensing a lid along a wall lies on it
and a pass lands where it crosses: nothing to correct.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from core2d.planner.regions import cross
from core2d.resolution import Resolution

__all__ = ["Aim", "MAX_REAIM", "MAX_JITTER"]

#: passes aimed again per lid
MAX_REAIM = 4
#: the rule acts while the sensor's jitter is at most this many eps
MAX_JITTER = 2.0


@dataclass
class Aim:
    """The secant of one lid's re-aimed passes.

    res : Resolution -- the sensor's stated resolution.
    a, b : (2,) float -- A_i and B_i.
    base : ((2,) float, (2,) float) or None -- the line (a point, a unit
        direction) of the first pass that landed on the lid's line.
    landings : list of (float, float) -- (sideways shift of the line from
        ``base``, landing's parameter along A_i -> B_i) per pass of the series.
    spent : int -- passes aimed again so far (at most :data:`MAX_REAIM`).
    """

    res: Resolution
    a: np.ndarray
    b: np.ndarray
    base: tuple | None = None
    landings: list = field(default_factory=list)
    spent: int = 0

    def landed(self, point, direction, contact, shift=None):
        """Record the pass along ``direction`` through ``point`` (``shift``:
        its sideways shift from :attr:`base`, None for a planned pass) that
        touched ``contact``; return the next pass ``(point, direction,
        shift)`` aimed at the lid's middle, or None.

        None when the sensor is perfect or coarser than :data:`MAX_JITTER`,
        the contact is off the lid's line (more than the jitter), it landed
        within eps/4 of the middle, the passes are spent, or the secant is
        flat.

        Examples
        --------
        A wall along y = 0.05 behind a lid on y = 0 (material above): a
        line at 0.5 degrees through the lid's middle lands 5.7 eps on; the
        next pass, shifted sideways, lands at the middle.

        >>> from core2d.resolution import Resolution
        >>> aim = Aim(Resolution.of(1.0, noise=0.1), np.zeros(2), np.array([2.0, 0.0]))
        >>> d = np.array([np.cos(0.0087), np.sin(0.0087)])
        >>> def hit(p, d):  # where the line through p along d meets the wall
        ...     return np.asarray(p, float) + (0.05 - p[1]) / d[1] * d
        >>> hit((1.0, 0.0), d).round(2).tolist()
        [6.75, 0.05]
        >>> p, d2, s = aim.landed((1.0, 0.0), d, hit((1.0, 0.0), d))
        >>> hit(p, d2).round(6).tolist(), round(float(s), 4)
        ([1.0, 0.05], 0.05)
        """
        if not 0.0 < self.res.jitter <= MAX_JITTER * self.res.eps or self.spent >= MAX_REAIM:
            return None
        u = self.on_line(contact)
        if u is None:
            return None
        length = np.sqrt(float((self.b - self.a) @ (self.b - self.a)))
        if abs(u - 0.5) * length <= self.res.eps / 4.0:
            return None
        d = np.asarray(direction, float)
        if shift is None:  # a planned pass: a new series on its line
            self.base, self.landings, shift = (np.asarray(point, float), d), [], 0.0
        self.landings.append((float(shift), u))
        again = self.toward(0.5)
        if again is not None:
            self.spent += 1
        return again

    def on_line(self, contact) -> float | None:
        """Where ``contact`` lies along A_i -> B_i (0 at A_i, 1 at B_i) if it lies on the
        lid's line within the jitter (the wall the lid lies along), else None."""
        ab = self.b - self.a
        n2 = float(ab @ ab)
        c = np.asarray(contact, float)
        if n2 == 0.0 or abs(float(cross(ab, c - self.a))) / np.sqrt(n2) > self.res.jitter:
            return None
        return float((c - self.a) @ ab) / n2

    def record(self, shift: float, contact) -> None:
        """Keep the landing of a pass of the current series shifted by ``shift``
        (:meth:`toward`), when it landed on the lid's line."""
        u = self.on_line(contact)
        if self.base is not None and u is not None:
            self.landings.append((float(shift), u))

    def toward(self, target: float):
        """The current series' line shifted to land at ``target`` along A_i -> B_i:
        ``(point, direction, shift)``, or None (no series yet, a flat secant, or a
        shift farther than a reading's reach). The slope of landing against shift is
        the lid's direction for the wall's while the series has one landing, then the
        secant through its last two."""
        if self.base is None or not self.landings:
            return None
        ab = self.b - self.a
        length = np.sqrt(float(ab @ ab))  # as landed() measured it
        normal = np.array([-self.base[1][1], self.base[1][0]])
        if len(self.landings) == 1:  # the lid's direction for the wall's
            sine = float(cross(self.base[1], ab / length))
            slope = float(cross(self.base[1], normal)) / sine / length if sine != 0.0 else 0.0
        else:
            (s0, u0), (s1, u1) = self.landings[-2:]
            slope = (u1 - u0) / (s1 - s0) if s1 != s0 else 0.0
        if slope == 0.0 or not np.isfinite(slope):
            return None
        s_new = self.landings[-1][0] + (target - self.landings[-1][1]) / slope
        if abs(s_new) > self.res.tip_zone:  # farther than a reading's reach: not this wall
            return None
        return self.base[0] + s_new * normal, self.base[1], float(s_new)
