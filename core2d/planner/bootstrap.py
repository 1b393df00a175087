"""Bootstrap of a closed slice: probing from the free area F (DESIGN.md).

§4.1 starts by inserting the probe from F toward the unknown area. On a
closed cross-section the robot knows only a bounding circle of its
workspace: it inserts the probe from points around that circle aimed at its
centre (finger probing), clockwise, and refines adaptively between
neighbouring insertions whose contacts are far apart. Each pair of
neighbouring contacts A, B with the two postures that found them becomes an
unknown area A_iB_i whose G_i is the region of those postures (Def. 1).
Clockwise order makes C_A^B run with the material on the right, so V_i
(Def. 3) is the outside, as in the paper's Fig. 3.
"""
from __future__ import annotations

import numpy as np

from core2d.planner.areas import Area
from core2d.planar import magnitude, unit
from core2d.planner.regions import Posture, cross, in_V
from core2d.planner.robot import Robot

__all__ = ["bootstrap", "undecided"]

#: standard deviations of its error beyond which Def. 3's test is read from
#: one reading (a flip then has probability below 0.0014)
DECIDED = 3.0


def _probe_from(probe: Robot, angle, reads: int = 1, aim=None):
    """Insert from the circle point at ``angle`` towards the centre (or ``aim``, (2,));
    (contact, posture), each the mean of ``reads`` readings where the probe stopped (the
    first the insertion's own, the others :meth:`Robot.reread`: no motion)."""
    start = probe.center + probe.radius * unit(angle)
    toward = -unit(angle) if aim is None else np.asarray(aim, dtype=np.float64) - start
    probe.approach(start, toward / magnitude(toward))
    r = probe.insert(2 * probe.radius)
    c = r.tip_contact
    if c is None:
        return None
    if reads <= 1:
        return c.point, Posture(r.joint, r.direction)
    got = probe.reread(reads - 1)
    touched = ~np.isnan(got.tip[:, 0])
    t = np.sum(np.vstack((r.direction, got.direction[touched])), axis=0)
    return (np.mean(np.vstack((c.point, got.tip[touched])), axis=0),
            Posture(np.mean(np.vstack((r.joint, got.joint[touched])), axis=0), t / magnitude(t)))


def bootstrap(probe: Robot, count=12, far=None, max_depth=3, aim=None):
    """Find the initial unknown areas of a closed slice.

    Parameters
    ----------
    probe : Probe
    count : int -- initial insertions, evenly spaced around the circle.
    far : float -- refine between neighbours farther apart than this
        (default: workspace radius / 2).
    max_depth : int -- refinement levels.
    aim : (2,) float, optional -- every insertion aimed at this point instead of the
        circle's centre (:mod:`core2d.planner.orphans`: an object met once, far from
        everything recorded).

    Returns
    -------
    list of Area (rule ``"bootstrap"``), in clockwise order. With two
    contacts (two small objects far apart, say) the two areas are the two
    sides of the contour, C_A^B and C_B^A: the pairs (A, B) and (B, A)
    share one midpoint of their postures' joints, so the orientation test
    of Def. 3 (:func:`_oriented`) would label both alike and register one
    area twice; the second is the first reversed.
    """
    far = probe.radius / 2 if far is None else far
    angles = list(np.pi / 2 - 2 * np.pi * np.arange(count) / count)
    step = 2 * np.pi / count
    found = {a: _probe_from(probe, a, aim=aim) for a in angles}
    for _ in range(max_depth):
        step /= 2
        extra = []
        for k, a in enumerate(angles):
            b = angles[(k + 1) % len(angles)]
            fa, fb = found[a], found[b]
            if fa is None or fb is None or np.linalg.norm(fa[0] - fb[0]) > far:
                extra.append(a - step)
        if not extra:
            break
        for a in extra:
            found[a] = _probe_from(probe, a, aim=aim)
        angles = sorted(angles + extra, reverse=True)
    kept = [a for a in angles if found[a] is not None]
    keep = set()  # pairs whose Def. 3 test the sensor cannot decide: clockwise
    if probe.resolution.jitter > 0:
        keep = _reread_undecided(probe, kept, found, aim)
    hits = [found[a] for a in kept]
    if len(hits) < 2:
        return []
    if len(hits) == 2:  # the two sides of the contour: C_A^B and C_B^A
        first = _oriented(hits[0][0], hits[1][0], hits[0][1], hits[1][1], 0 in keep)
        return [first, Area(first.b, first.a, first.pose_b, first.pose_a)]
    return [_oriented(pa, pb, posa, posb, k in keep)
            for k, ((pa, posa), (pb, posb)) in enumerate(zip(hits, hits[1:] + hits[:1]))]


def _oriented(pa, pb, posa, posb, clockwise=False):
    """Label the pair so the postures' joints lie in V_i (Def. 3): the probe
    came from the free side, as in Fig. 5(a), (c), (d) where G_i cap V_i = G_i.
    Neighbouring radial insertions can cross inside a pocket, so the angular
    order alone does not give the order along the contour. ``clockwise``:
    the test is not read (a noisy sensor cannot decide it even from averaged
    readings, :func:`_reread_undecided`) and the pair keeps the clockwise
    order of its insertions, ``pa`` first."""
    joints = (posa.joint + posb.joint) / 2
    if clockwise or in_V(joints, pa, pb) or np.allclose(pa, pb):
        return Area(pa, pb, posa, posb)
    return Area(pb, pa, posb, posa)


def undecided(q, a, b, res, reads: int = 1) -> bool:
    """Can one noisy reading of each of A_i, B_i (``a``, ``b``, (2,)) and of
    the joints put their midpoint ``q`` (2,) on either side of the line
    A_iB_i? True when q lies within :data:`DECIDED` standard deviations of
    its offset's error from the line, the error stated by the sensor's data
    sheet (``res``: :class:`~core2d.resolution.Resolution`): a contact reading
    scatters by s_c = sqrt(3 sigma^2 + T^2 / 12) per axis (its own noise, the
    joint's, the direction's at the tip; the taxel along the probe), the
    joints' midpoint by sigma / sqrt(2); and the line turns about one end
    when the other moves, so the ends' scatter reaches q multiplied by
    |q - a| / |ab| and |q - b| / |ab|. ``reads``: each reading the mean of
    that many (the noise falls by its square root; the taxel's rounding,
    the same at every reading of one posture, does not)."""
    q, a, b = (np.asarray(x, float) for x in (q, a, b))
    ab = magnitude(b - a)
    s_c2 = 3.0 * res.noise ** 2 / reads + res.taxel ** 2 / 12.0
    sd = np.sqrt(res.noise ** 2 / (2.0 * reads)
                 + s_c2 * (magnitude(q - a) ** 2 + magnitude(q - b) ** 2) / ab ** 2)
    return abs(float(cross(b - a, q - a))) / ab <= DECIDED * sd


def _reread_undecided(probe: Robot, angles, found, aim=None) -> set:
    """Insert again, reading :attr:`~core2d.resolution.Resolution.contact_reads`
    times, from the two ``angles`` of every neighbouring pair whose Def. 3
    test (:func:`_oriented`) one noisy reading cannot decide
    (:func:`undecided`), and replace their ``found`` (contact, posture) by
    the means. Pairs closer than ``w2_dist`` are W2 whichever way they run.

    Why: where one insertion reached into a pocket past the other's contact
    (its line grazes that contact), both joints lie nearly on the line A_iB_i:
    on ``cup_handle`` z3 their midpoint lies 0.9 eps from a 129 eps lid,
    330 eps away, and one reading of A_i or B_i (sigma 0.3 eps, taxels
    0.25 eps) turns the line enough to flip the side in 25 of 40 seeds. The
    flipped area is C_B^A, the outside of the cup; the inner wall belongs
    to no area and is never traced (reachable coverage 0.82). The mean of
    25 readings scatters a fifth as much. Only such pairs are read again
    (two motions per insertion), so a slice whose bootstrap pairs are all
    decided is sensed as before. Called only with a noisy sensor.

    Returns the indices k of the pairs (angles[k], angles[k + 1]) that even
    the means cannot decide: both joints on the line A_iB_i within the
    error, where one insertion ran through the other's contact and through
    the workspace centre it aims at (``OVERHANG_LEFT`` of the figure blocks:
    0.5 eps off a 54 eps lid, 0.1 standard deviations of one reading's
    error). Those keep the clockwise order of their insertions -- the order
    along the contour of every pair that does not cross, and the right one
    on those measured (``cup_handle`` z3, ``OVERHANG_LEFT`` and
    ``OVERHANG_RIGHT``), where the test itself is a coin toss."""
    res = probe.resolution
    n = len(angles)
    again = set()
    for k in range(n if n > 2 else n - 1):
        a, b = angles[k], angles[(k + 1) % n]
        (pa, posa), (pb, posb) = found[a], found[b]
        if magnitude(pb - pa) >= res.w2_dist and undecided(
                (posa.joint + posb.joint) / 2, pa, pb, res):
            again.update((a, b))
    for a in sorted(again, reverse=True):
        got = _probe_from(probe, a, res.contact_reads, aim)
        if got is not None:
            found[a] = got
    keep = set()
    for k in range(n if n > 2 else n - 1):
        a, b = angles[k], angles[(k + 1) % n]
        if a in again and b in again:
            (pa, posa), (pb, posb) = found[a], found[b]
            if magnitude(pb - pa) >= res.w2_dist and undecided(
                    (posa.joint + posb.joint) / 2, pa, pb, res, res.contact_reads):
                keep.add(k)
    return keep
