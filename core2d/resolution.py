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

import math
from dataclasses import dataclass

__all__ = ["Resolution", "repeated_reads", "MAX_READS", "AIM_READS"]

MAX_READS = 64
"""The most reads :func:`repeated_reads` averages at one reading point."""

AIM_READS = 16
"""The most reads :func:`repeated_reads` takes to bring the means' noise towards tol / 2
(16 ms of a 1 kHz skin at each reading point); more only where the fine path needs them."""


@dataclass(frozen=True)
class Resolution:
    """The robot's stated resolution: ``eps`` and ``tol`` and what follows.

    Build it with :meth:`of`, which fills in the default ``tol = eps / 20``.
    ``noise`` and ``taxel`` are the sensor's stated figures (0: the paper's
    perfect sensing); ``torque_threshold`` and ``torque_noise`` the torque
    sensor's (lengths, :class:`core2d.sim.sensor.SensorModel`).

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
    torque_threshold: float = 0.0
    torque_noise: float = 0.0

    @classmethod
    def of(cls, eps: float, tol: float | None = None, noise: float = 0.0,
           taxel: float = 0.0, torque_threshold: float = 0.0,
           torque_noise: float = 0.0) -> Resolution:
        """``Resolution(eps, tol, noise, taxel, ...)`` with the default contact
        resolution eps / 20."""
        return cls(float(eps), float(tol if tol is not None else eps / 20.0), float(noise),
                   float(taxel), float(torque_threshold), float(torque_noise))

    @property
    def torque_reads(self) -> int:
        """How many times the planner reads the torque sensor at a final
        state D_i of the local search (§4.2.2) to take each blocked-rotation
        flag by majority: 1 for a noiseless torque sensor, else 5. A reading
        costs no motion (the probe stays put), and with a flip probability p
        per reading the majority of 5 errs with probability
        10 p^3 (1 - p)^2 + ... (< 0.01 for p = 0.1)."""
        return 1 if self.torque_noise == 0 else 5

    @property
    def contact_reads(self) -> int:
        """How many readings the planner averages where a contact's position
        decides a test and re-reading is free (the probe stays put, no
        motion): 1 with the paper's perfect contact sensing, else 25 -- the
        mean of 25 readings scatters a fifth as much
        (:func:`core2d.planner.bootstrap.undecided`)."""
        return 1 if self.noise == 0 and self.taxel == 0 else 25

    @property
    def sensor_tol(self) -> float:
        """eps / 2 + 2 noise: the distance within which a reported point
        stands for the contour (the metric tolerance of a noisy sensor)."""
        return self.eps / 2.0 + 2.0 * self.noise

    @property
    def jitter(self) -> float:
        """How far apart two readings of one point may lie: three standard
        deviations of their difference while that resolves eps/2, else the
        worst case.

        The difference of two readings is the difference of two noise draws
        (Gaussian, sqrt(2) noise per axis) plus, along the probe, the
        difference of two taxel errors: a contact is reported at the centre
        of its taxel, up to taxel / 2 away, and over the postures that read
        one point that error is uniform on +-taxel / 2, so the difference of
        two is triangular on +-taxel with standard deviation taxel / sqrt(6).
        The two are independent, so their standard deviations add in
        quadrature: 3 sqrt(2 noise^2 + taxel^2 / 6). With only one of the
        two it is that one's bound (taxels alone: taxel; noise alone:
        3 sqrt(2) noise), 0 for the paper's perfect sensing, so every
        tolerance below is then the paper's own.

        Where the quadrature does not resolve eps/2 (above eps/2 - tol: the
        coarse sensor's path, :func:`~core2d.planner.grazing.resolves_half_eps`)
        the two bounds stay added, 3 sqrt(2) noise + taxel. The coarse path's
        radii join chains of readings (the map's joins, lids along walls, the
        W3 proof's blocking lines), not two, and were measured sound with the
        sum: at sigma 0.3 eps, taxels 0.25 eps the quadrature (1.31 eps
        against 1.52) proved a W3 lid over reachable contour on ``bowl`` z3
        of 8 (the sensor study's one unsound lid) and lost coverage on the
        outlines (0.952 -> 0.947).

        Adding the two bounds everywhere (as before) overstated the
        scatter of a fine sensor with taxels: sigma 0.06 eps with taxels
        0.25 eps read 0.50 eps, beyond eps/2 - tol, so the planner took the
        coarse sensor's wide radii
        (:func:`~core2d.planner.grazing.resolves_half_eps`), and reachable
        coverage within eps/2 + 2 sigma fell to 0.975 (outlines, worst
        0.883) and 0.973 (scenes' middle slices) against 0.992 and 0.985
        with taxels alone; in quadrature it reads 0.40 eps, and the same
        runs cover 0.997 (worst 0.983) and 0.984
        (``python -m bench.sensor_study --groups outlines,scenes
        --levels 0.06:0.25``).

        >>> round(Resolution.of(1.0, noise=0.06, taxel=0.25).jitter, 3)
        0.398
        >>> round(Resolution.of(1.0, noise=0.3, taxel=0.25).jitter, 3)  # coarse: the sum
        1.523
        >>> Resolution.of(1.0, taxel=0.25).jitter, round(Resolution.of(1.0, noise=0.1).jitter, 3)
        (0.25, 0.424)
        """
        both = 3.0 * 2.0 ** 0.5 * self.noise + self.taxel
        if self.noise == 0 or self.taxel == 0:  # one of them: its own bound, bit for bit
            return both
        quad = 3.0 * (2.0 * self.noise ** 2 + self.taxel ** 2 / 6.0) ** 0.5
        return quad if quad <= self.eps / 2.0 - self.tol else both

    @property
    def tip_zone(self) -> float:
        """eps / 2 (+ :attr:`jitter`): contacts closer than this are one
        contact at the paper's resolution (the same-point radius); near the
        tip they are the tip's contact, and a contact point moving farther in
        one step jumped. Readings of one point scatter by the jitter, so
        the radius grows by it: two readings of one contact stay one."""
        return self.eps / 2.0 + self.jitter

    @property
    def hop(self) -> float:
        """eps / 4 (+ :attr:`jitter`): a traced step longer than this is not
        a micro-step of the trace (a hop, ``core2d.planner.tracing``); the
        scatter of two noisy readings is no hop."""
        return self.fan_spacing + self.jitter

    @property
    def face_span(self) -> float:
        """How much of the trace a face's line is read over where the side of
        a point matters (:func:`core2d.planner.hops.across_wall`): :attr:`hop`
        by its two ends with perfect sensing (two exact contacts give the
        line), else twice :attr:`tip_zone` (the slide's length) by least
        squares. Two readings :attr:`hop` apart tilt the line by up to
        atan(jitter / hop) (33 degrees at sigma 0.3 eps, taxels 0.25 eps, 16 reads);
        a fit through every reading of the longer stretch averages them."""
        return self.hop if self.jitter == 0 else 2.0 * self.tip_zone

    @property
    def w2_dist(self) -> float:
        """eps (+ :attr:`jitter`): Dist(A_i, B_i) below which an area is W2
        (§3.1). Its ends are readings: a gap narrower than eps may read up
        to the jitter wider. The chord then stays within (eps + jitter) / 2
        of the contour, about the sensor's tolerance eps / 2 + 2 noise."""
        return self.eps + self.jitter

    @property
    def loop_width(self) -> float:
        """:attr:`tip_zone` / 2 (eps / 4 with perfect sensing): how thick
        (area / perimeter) the loop a W3 lid closes with recorded contour
        must be (``core2d.planner.w3_checks.closes_loop``). A lid laid a
        reading's scatter beside the wall it would hide -- ``gear`` z7 at
        sigma 0.3 eps, taxels 0.25 eps, sensor seed 2007: 0.5 - 1.75 eps off
        a traced tooth flank, 8 eps long -- closes a loop 0.44 eps thick
        with it; the wall and the lid are one contour at the sensor's
        resolution, and nothing hides between."""
        return self.tip_zone / 2.0

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
    def resolves_half_eps(self) -> bool:
        """0 < jitter <= eps/2 - tol: a noisy sensor whose two readings of one
        point stay within the paper's same-point radius eps/2 (the fine
        sensor's path of the planner; the coarse one's beyond it)."""
        return 0.0 < self.jitter <= self.eps / 2.0 - self.tol

    @property
    def near(self) -> float:
        """2 tol (+ :attr:`jitter`): a point this close to the probe or to
        recorded contour is on it (contact noise)."""
        return 2 * self.tol + self.jitter

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


def repeated_reads(eps: float, noise: float, taxel: float = 0.0, tol: float | None = None,
                   cap: int = MAX_READS) -> int:
    """How many times the robot reads its sensors at each reading point and
    averages them: enough for the means' noise to reach half the contact
    resolution (N >= (2 noise / tol)^2) but at most :data:`AIM_READS`, and at
    least the fewest N for which the means resolve eps/2
    (:attr:`Resolution.resolves_half_eps` with noise / sqrt(N)), up to ``cap``;
    1 where no N up to the cap resolves eps/2.

    A reading point is a posture the probe stands in (after a motion, at each
    micro-step of a compliant trace); reading the skin, the joint sensors and
    the torque sensor again there moves nothing. The mean of N independent
    Gaussian draws of standard deviation ``noise`` is one draw of
    noise / sqrt(N); the taxel's rounding is the same on every read and stays.

    Why towards tol / 2: that is the planner's finest step (a guarded move
    stops tol / 2 short of a contact, :attr:`Resolution.stop_short`; the
    bisections' angular resolution is tol / 2 at the tip), so means scattered
    less than it no longer move a decision the paper's searches make. The
    fewest N that only just resolve eps/2 leave a jitter of up to eps/2 - tol:
    at sigma 0.1 eps (one read, jitter 0.42 eps) the ``comb`` scene's
    bisections slipped past a tooth's corner and the slots behind went
    untraced (0.977 - 0.986 of the part eps resolves per sensor seed, against
    0.9987 noiselessly); with 16 reads (the means' sigma 0.025 eps) 0.988 -
    0.999, and the 8-slice study's slice runs went 196 up, 32 down
    (docs/notes/noise.md).

    Why at most 16 for that aim: a read costs no motion but costs time (1 ms of
    a 1 kHz skin; 16 reads were 6.6 % of ``comb``'s robot time at sigma
    0.1 eps), and going on to 64 reads at sigma 0.3 eps, taxels 0.25 eps moved
    more slice runs up than down (111 against 43) but won no case run: 197 of
    210 met the targets against 200 with 15 reads, the runs lost being
    ``numerics-0``'s needle (missed noiselessly too) and ``comb-0`` in its
    slots narrower than eps.

    Why the fine path or nothing: the planner's rules for a sensor whose
    readings do not resolve eps/2 were measured at a jitter of 1.5 eps (sigma
    0.3 eps, taxels 0.25 eps), and there they hold the motion targets. Between
    the two paths they do not: at sigma 0.1 eps with taxels 0.25 eps (jitter
    0.67 eps) the ``comb`` scene took 2.2 - 2.4 x its noiseless motions on six
    of six sensor seeds and hit the budget on 10 of 48 slices (keyed, 8
    slices). So reads that would bring the sensor only part of the way are not
    taken (docs/notes/noise.md).

    Parameters
    ----------
    eps, noise, taxel : float -- the paper's eps and the sensor's data sheet
        (lengths, as in :class:`Resolution`).
    tol : float, optional -- contact resolution, default eps / 20.
    cap : int -- at most this many reads (:data:`MAX_READS`).

    Returns
    -------
    int >= 1.

    Examples
    --------
    >>> repeated_reads(1.0, 0.3, 0.25), repeated_reads(1.0, 0.1), repeated_reads(1.0, 0.0, 0.25)
    (16, 16, 1)
    >>> repeated_reads(1.0, 0.03), repeated_reads(1.0, 0.5), repeated_reads(1.0, 1.0)
    (2, 23, 1)
    """
    if noise <= 0:
        return 1
    aim = Resolution.of(eps, tol).stop_short
    least = min(AIM_READS, max(1, math.ceil((noise / aim) ** 2 * (1.0 - 1e-9))))
    for n in range(1, int(cap) + 1):
        if Resolution.of(eps, tol, noise / n ** 0.5, taxel).resolves_half_eps:
            return max(n, min(least, int(cap)))
    return 1
