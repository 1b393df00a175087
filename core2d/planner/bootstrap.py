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
from core2d.planar import unit
from core2d.planner.regions import Posture, cross, in_V
from core2d.planner.robot import Robot

__all__ = ["bootstrap", "undecided"]


def _probe_from(probe: Robot, angle):
    """Insert radially from the circle point at ``angle``; (contact, posture)."""
    start = probe.center + probe.radius * unit(angle)
    probe.approach(start, -unit(angle))
    r = probe.insert(2 * probe.radius)
    c = r.tip_contact
    if c is None:
        return None
    return c.point, Posture(r.joint, r.direction)


def bootstrap(probe: Robot, count=12, far=None, max_depth=3):
    """Find the initial unknown areas of a closed slice.

    Parameters
    ----------
    probe : Probe
    count : int -- initial insertions, evenly spaced around the circle.
    far : float -- refine between neighbours farther apart than this
        (default: workspace radius / 2).
    max_depth : int -- refinement levels.

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
    found = {a: _probe_from(probe, a) for a in angles}
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
            found[a] = _probe_from(probe, a)
        angles = sorted(angles + extra, reverse=True)
    hits = [found[a] for a in angles if found[a] is not None]
    if len(hits) < 2:
        return []
    jitter = probe.resolution.jitter
    if len(hits) == 2:  # the two sides of the contour: C_A^B and C_B^A
        first = _oriented(hits[0][0], hits[1][0], hits[0][1], hits[1][1], jitter)
        return [first, Area(first.b, first.a, first.pose_b, first.pose_a)]
    return [_oriented(pa, pb, posa, posb, jitter)
            for (pa, posa), (pb, posb) in zip(hits, hits[1:] + hits[:1])]


def _oriented(pa, pb, posa, posb, jitter=0.0):
    """Label the pair so the postures' joints lie in V_i (Def. 3): the probe
    came from the free side, as in Fig. 5(a), (c), (d) where G_i cap V_i = G_i.
    Neighbouring radial insertions can cross inside a pocket, so the angular
    order alone does not give the order along the contour.

    With a noisy sensor (``jitter`` > 0, :attr:`~core2d.resolution.Resolution.jitter`)
    the test is read only when it is decided: the joints' midpoint q lies
    farther from the line A_iB_i than the readings' error can move it
    (:func:`undecided`). Otherwise -- q on the line, which happens when one
    insertion grazed the other's contact on its way into a pocket (its joint,
    that contact and its own lie on one line) -- the clockwise order of the
    insertions stands (``pa`` first), as it does for every pair that does
    not cross. With a perfect sensor the test is the paper's, unchanged."""
    joints = (posa.joint + posb.joint) / 2
    if jitter > 0 and undecided(joints, pa, pb, jitter):
        return Area(pa, pb, posa, posb)
    if in_V(joints, pa, pb) or np.allclose(pa, pb):
        return Area(pa, pb, posa, posb)
    return Area(pb, pa, posb, posa)


def undecided(q, a, b, jitter: float) -> bool:
    """Can readings each off by up to ``jitter`` put ``q`` (2,) on either
    side of the line through ``a`` and ``b`` (each (2,))? The signed
    distance of q from the line moves by up to ``jitter`` with q itself and,
    as the line turns about one end when the other moves by ``jitter``, by
    ``jitter |q - a| / |ab|`` and ``jitter |q - b| / |ab|`` with the ends.
    The joints of Def. 3's test lie a probe length away, many times
    Dist(A_i, B_i), so the margin is many jitters wide."""
    q, a, b = (np.asarray(x, float) for x in (q, a, b))
    ab = float(np.hypot(*(b - a)))
    if ab == 0:
        return True
    off = abs(float(cross(b - a, q - a))) / ab
    margin = jitter * (1.0 + (float(np.hypot(*(q - a))) + float(np.hypot(*(q - b)))) / ab)
    return off <= margin
