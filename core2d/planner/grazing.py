"""Passes that cannot tell: grazing and blocked passes under a noisy sensor.

With a perfect sensor a lid A_iB_i laid along a straight wall coincides with
the wall, and a pass through its middle (Theorem 1's pass, the §4.4 escape,
a revisit pass) meets the wall at the middle: the area splits in two and the
halves end as W2 (Dist < eps, §3.1). With a noisy sensor A_i and B_i are
readings that scatter by the noise sigma, so the lid lies up to a few sigma
off the wall, and a pass crossing it at a small angle alpha meets the wall
about sigma / tan(alpha) from where it crossed. In a deep slot a few eps
wide (the built-in ``comb``: slots 1.5 - 4 eps wide, 84 eps deep) every line
from F crosses such a lid at a few degrees: the passes land anywhere on the
wall, near an end, or -- through a gap of the noisy record that the map
takes for a free line -- on contour in front of the lid. Measured on
``comb`` z4 at sigma = 0.1 eps (budget 20,000, all used): 8,484 motions in
lids that ended unknown after their revisit passes (:mod:`~core2d.planner.revisit`,
up to 54 passes each), and 2,237 of those lids' passes stopped in front of
the lid, two eps or more from it. Three rules read what such passes say,
and :class:`~core2d.planner.reaim.Aim` aims a pass again from where it
landed; all are off with a perfect sensor (the paper's flow is unchanged):

* :func:`beyond_ends` (jitter > 0) -- a contact on the lid's line (within
  :attr:`~core2d.resolution.Resolution.jitter`) but beyond A_i or B_i is the
  wall the lid lies along, met by a grazing pass past the lid's end. It is
  not on C_{A_i}^{B_i}, which runs *behind* the lid from A_i to B_i;
  splitting A_iB_i there (§4.4, revisit) made a child longer than its
  parent along the same wall, again and again.
* :func:`steep_enough` (noise > 0 and :func:`resolves_half_eps`) -- the
  revisit's sweep (one pass every eps/2 along the lid) resolves the contour
  behind the lid at eps/2 only where a pass's landing is known to better
  than eps/2: sigma / tan(alpha) < eps/2. Shallower sweep passes are not
  made (the six spread passes of the revisit still are), and a shallower
  pass that ends at a touched end is no evidence for the revisit's W3 "each
  pass ended at a touched end".
* :class:`Blockers` (:func:`resolves_half_eps`) -- a revisit pass that stops
  in front of the lid (its segment from the joint to the contact C does not
  cross the lid, and C is at no end) met contour on a line the map called
  free; a later planned pass whose line passes within
  :attr:`~core2d.resolution.Resolution.near` of C -- the distance within
  which a point is on recorded contour -- meets the same contour, and is
  not made (it counts as a pass that found nothing and ended at no end).

And :func:`end_radius` (:func:`resolves_half_eps`): whether a pass's contact
is A_i or B_i again is decided at the paper's eps/2, not at the same-contact
radius widened by the jitter, and the pass's contact is the mean of
repeated readings (:func:`core2d.planner.tracing.reread_pass`): the landings
of grazing passes between eps/2 and eps/2 + jitter from an end split the lid.

:func:`resolves_half_eps`: the last two rules act only while two readings of
one point lie within the paper's same-point radius (jitter <= eps/2 - tol).
A blocker's disc (radius ``near`` = 2 tol + jitter) then spans at most
eps + 2 tol, so it cannot close an opening wider than eps -- one that is not
W2 and must stay open to passes; and the noise (sigma <= 0.106 eps) keeps
the sweep's cone of skipped directions within 12 degrees of the lid. Beyond it
(sigma = 0.3 eps, or taxels of a quarter eps) the revisit is the one
measured before these rules.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from core2d.planner.regions import cross
from core2d.resolution import Resolution

__all__ = ["beyond_ends", "steep_enough", "resolves_half_eps", "end_radius", "crosses_lid",
           "Blockers"]


def resolves_half_eps(res: Resolution) -> bool:
    """0 < jitter <= eps/2 - tol: a noisy sensor whose two readings of one
    point stay within the paper's same-point radius eps/2."""
    return res.resolves_half_eps


def sweep_length(res: Resolution) -> float:
    """The length whose half spaces the revisit's sweep passes
    (:func:`~core2d.planner.pass_plan.sweep`): eps, the paper's resolution, for perfect
    sensing and a sensor that resolves eps/2; the W2 distance eps + jitter for a coarser
    one. Two of its readings of one point lie up to the jitter apart (1.52 eps at sigma
    0.3 eps with taxels 0.25 eps), so passes eps/2 apart land on what it reads as one
    contact. Measured at that level (8 slices, six keyed sensor seeds,
    docs/notes/noise.md): motions -7 to -13 % per group, coverage within the lottery but
    more slice runs down than up; with the swing passes into the touches' gaps, which it
    makes room for, coverage as before or higher and motions -5 to -10 %."""
    return res.eps if resolves_half_eps(res) else res.w2_dist


def end_radius(res: Resolution) -> float:
    """Within what distance of A_i or B_i a pass's contact is that end again,
    not a new contact on C_{A_i}^{B_i} (Theorem 1's pass, the §4.4 escape,
    a revisit pass), and how far from the touched ends a line through the
    lid must pass to count in the W3 proof.

    The paper's radius is eps/2. A noisy sensor's same-contact radius
    (:attr:`~core2d.resolution.Resolution.tip_zone`) adds the jitter so that
    two readings of one point stay one contact. While
    :func:`resolves_half_eps` (jitter <= eps/2 - tol), two readings of one
    point already lie within eps/2 - tol of each other, so eps/2 tells a
    re-reading of an end from a new contact: eps/2 is returned. The wider
    radius discarded real contacts: in a pocket one to three eps wide every
    pass meets the wall at a few degrees and lands about sigma / tan(alpha)
    from where it crossed the lid, often between eps/2 and eps/2 + jitter
    from an end; such a lid ended unknown where the paper's radius splits
    it ((A_i, C) W2, §3.1) and the wall is covered (the ``comb`` and
    ``star`` outlines at sigma 0.1 eps). And a lid shorter than twice the
    radius left no line to check, so the W3 proof held for any lid between
    eps + jitter (W2 below) and eps + 2 jitter long, whatever lay behind it.
    Beyond :func:`resolves_half_eps`, and for perfect sensing (where both
    are eps/2), :attr:`~core2d.resolution.Resolution.tip_zone`.

    >>> end_radius(Resolution.of(1.0, noise=0.1)), end_radius(Resolution.of(1.0))
    (0.5, 0.5)
    >>> round(end_radius(Resolution.of(1.0, noise=0.3)), 3)
    1.773
    """
    return res.eps / 2.0 if resolves_half_eps(res) else res.tip_zone


def beyond_ends(res: Resolution, a, b, point) -> bool:
    """Does ``point`` (2,) lie on the line of the lid ``a`` -> ``b`` (within
    ``res.jitter``) but outside the segment (its projection before A_i or
    past B_i)? Always False with a perfect sensor (jitter 0)."""
    if res.jitter == 0:
        return False
    a, b, p = (np.asarray(x, float) for x in (a, b, point))
    ab = b - a
    n2 = float(ab @ ab)
    if n2 == 0.0:
        return False
    t = float((p - a) @ ab) / n2
    off = abs(float(cross(ab, p - a))) / np.sqrt(n2)
    return (t < 0.0 or t > 1.0) and off <= res.jitter


def steep_enough(res: Resolution, a, b, direction) -> bool:
    """Is a sweep pass along ``direction`` (2,) resolved at eps/2 against
    the lid ``a`` -> ``b``: noise / tan(alpha) < eps / 2, alpha the angle
    between them? Always True without contact noise or beyond
    :func:`resolves_half_eps`."""
    if res.noise == 0 or not resolves_half_eps(res):
        return True
    u = np.asarray(b, float) - np.asarray(a, float)
    u = u / np.hypot(*u)
    d = np.asarray(direction, float)
    return abs(float(cross(u, d))) > 2.0 * res.noise / res.eps * abs(float(u @ d))


def crosses_lid(a, b, joint, point) -> bool:
    """Does the segment from ``joint`` to ``point`` cross the lid ``a`` -> ``b``?"""
    a, b, p, q = (np.asarray(x, float) for x in (a, b, joint, point))
    ab, pq = b - a, q - p
    den = float(cross(ab, pq))
    if den == 0.0:
        return False
    s, t = float(cross(p - a, pq)) / den, float(cross(p - a, ab)) / den
    return 0.0 <= s <= 1.0 and 0.0 <= t <= 1.0


def _segment_distance(p, a, b) -> float:
    ab = b - a
    t = float(np.clip((p - a) @ ab / max(float(ab @ ab), 1e-300), 0.0, 1.0))
    return float(np.hypot(*(p - a - t * ab)))


@dataclass
class Blockers:
    """Contacts at which revisit passes through one lid stopped in front of it.

    radius : float -- a planned line passing this close to a blocker meets
        the same contour (``Resolution.near``).
    reach : float -- length of a pass's line from F up to the lid.
    active : bool -- False: nothing is kept (perfect sensing, or beyond
        :func:`resolves_half_eps`).
    points : list of (2,) float -- the blocking contacts so far.
    """

    radius: float
    reach: float
    active: bool = True
    points: list = field(default_factory=list)

    @classmethod
    def of(cls, res: Resolution, reach: float) -> Blockers:
        """Blockers with ``res.near``, active where :func:`resolves_half_eps`."""
        return cls(res.near, float(reach), resolves_half_eps(res))

    def add(self, a, b, joint, point) -> bool:
        """Keep contact ``point`` when the pass from ``joint`` stopped there in
        front of the lid ``a`` -> ``b`` (the caller leaves out contacts at an end);
        True when kept."""
        if self.active and not crosses_lid(a, b, joint, point):
            self.points.append(np.asarray(point, float))
            return True
        return False

    def off_lid(self, a, b, point) -> bool:
        """Does blocker ``point`` lie farther than ``radius`` from the lid ``a`` -> ``b``?
        Then it is on the way of every pass through its disc, and the lid's lines
        may leave the disc out (:meth:`~core2d.planner.lid_lines.FreeLines.block`);
        one nearer is contour at the lid for the samples beside it (:meth:`stops`).
        ``star-1`` at sigma 0.1 eps, keyed sensor seed 1001: the widest gaps of a lid
        along a slot's wall ran back through the part's body and a gap of its record,
        and the passes stopped 49 eps in front; with the disc closed, the next line
        came down the slot (0.9878 -> 0.9931). Closing the disc of the blocker 0.09 eps
        in front of the lid of :meth:`stops`' case closed that slot's mouth again."""
        return _segment_distance(np.asarray(point, float), np.asarray(a, float),
                                 np.asarray(b, float)) > self.radius

    def stops(self, point, direction) -> bool:
        """Does the pass to lid sample ``point`` along ``direction`` (from F)
        pass within ``radius`` of a blocker on its way to the lid? A blocker
        within ``radius`` of the sample itself is not on the way: at the
        sensor's resolution it is contour at the lid (the corner a lid's end
        stands on), and the pass may go on past it into V_i. ``comb`` outline
        seed 0 at sigma 0.3 eps, taxels 0.25 eps, 15 reads, keyed sensor seed
        1000: a lid along the top face over a slot 1.85 eps wide; the first
        pass stopped on the slot's corner, 0.51 eps from the sample of the one
        pass straight down the mouth, which it then stopped, and the slot was
        never entered (0.969; 1.000 with the sample's own radius left out)."""
        if not self.points:
            return False
        end = np.asarray(point, float)
        start = end - self.reach * np.asarray(direction, float)
        return any(_segment_distance(c, start, end) <= self.radius
                   and float(np.hypot(*(c - end))) > self.radius for c in self.points)
