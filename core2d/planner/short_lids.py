"""Short lids under a coarse noisy sensor: the middle band a lid keeps.

The revisit (:mod:`core2d.planner.revisit`) tells a pass's contact C from
the lid's touched ends A_i, B_i and from recorded contour by radii that a
noisy sensor widens by its jitter (the distance within which two readings
of one point lie, :attr:`~core2d.resolution.Resolution.jitter`): the same-contact
radius eps/2 + jitter (:func:`~core2d.planner.grazing.end_radius`) and
``near`` = 2 tol + jitter. Where the sensor does not resolve eps/2
(sigma 0.3 eps, taxels 0.25 eps: jitter 1.52 eps) a lid between the W2
distance eps + jitter and twice the same-contact radius long (2.52 - 4.04 eps)
had no point farther than that radius from both ends. No pass could find a
new contact, the W3 proof of the revisit's step 2 had no line to check, and
the lid's whole middle lay within ``near`` of the recorded pieces that end
at A_i and B_i: such lids were closed without a single pass (``unknown`` when
the probe could not hold them, "traced" on the map), and the contour behind
them was never touched -- the arcs of the small rings of ``cup_handle``
z6 / z7 (13 eps across, 0.66 and 0.82 coverage within eps/2 + 2 sigma).
A short lid keeps a middle band eps/2 wide (§3.1's resolution), see
:func:`lid_end_radius`. Perfect and fine sensors are unchanged.
"""
from __future__ import annotations

from core2d.planner.grazing import end_radius
from core2d.resolution import Resolution

__all__ = ["lid_end_radius", "on_map"]


def lid_end_radius(res: Resolution, dist: float) -> float:
    """The end radius of a lid ``dist`` long: within it a pass's contact is
    A_i or B_i again, and the W3 proof's lines leave it at each end.

    :func:`~core2d.planner.grazing.end_radius`, except for a *short lid*
    under a noisy sensor that does not resolve eps/2 (sigma 0.3 eps, or
    taxels with noise): one shorter than twice that radius (eps/2 + jitter,
    4.04 eps at sigma 0.3, taxel 0.25) has no point farther than the radius
    from both ends. Every pass's contact is then an end again, and no line
    is left for the proof of step 2, so each lid between
    :attr:`~core2d.resolution.Resolution.w2_dist` and twice the radius long
    was closed without a pass (W3 if the probe held it, else ``unknown``):
    the lids over the arcs of ``cup_handle`` z6 / z7 (circles 13 eps across)
    and over the mouths of short pockets. Such a lid keeps a middle band
    eps/2 wide (the paper's resolution, §3.1): the radius is
    Dist(A_i, B_i)/2 - eps/4, at least eps/2. A contact in the band splits
    the lid as Theorem 1's pass does; if it was a re-reading of an end, the
    child (A_i, C) is shorter than the jitter (W2, Dist < eps + jitter) and
    (C, B_i) shorter than Dist(A_i, B_i)/2 + eps/4 + the contact's offset
    from the lid. Perfect sensing (jitter 0) and fine sensors
    (:func:`~core2d.planner.grazing.resolves_half_eps`: the radius is eps/2
    and every lid not W2 is at least eps long) are unchanged.

    >>> res = Resolution.of(1.0, noise=0.3, taxel=0.25)
    >>> round(lid_end_radius(res, 3.5), 3), round(lid_end_radius(res, 10.0), 3)
    (1.5, 2.023)
    """
    r = end_radius(res)
    if res.jitter == 0 or dist >= 2.0 * r:
        return r
    return max(res.eps / 2.0, dist / 2.0 - res.eps / 4.0)


def on_map(res: Resolution, dist: float) -> float:
    """Within what distance of recorded contour a point is on it, near a lid
    ``dist`` long: :attr:`~core2d.resolution.Resolution.near` (2 tol + the
    jitter), at most :func:`lid_end_radius` for a short lid, whose ends'
    recorded pieces would otherwise put its whole middle on the map."""
    r = lid_end_radius(res, dist)
    return min(res.near, r) if r < end_radius(res) else res.near
