"""The second side of D_i (Theorem 4 (A), §4.3): the probe brought back to D_i.

Theorem 4 (A) traces both sides of the local concave point D_i. After the
first side the probe is brought back along the posture that stood at D_i
(:func:`~core2d.planner.detection.reestablish`) and the second side's trace
starts there. With a perfect sensor the insertion ends on D_i. With a noisy
one the posture is a reading, and a probe that lies along a face at a few
degrees meets it about offset / tan(angle) from D_i: the tip touches the
contour the second side would have traced, some way along it.

:func:`back_at` asks whether the probe is on D_i again; :func:`second_side`
decides what the second side becomes when it is not.
"""
from __future__ import annotations

from dataclasses import replace

from core2d.planar import magnitude
from core2d.planner.areas import register
from core2d.planner.detection import reestablish
from core2d.planner.grazing import end_radius, resolves_half_eps
from core2d.planner.regions import Posture
from core2d.planner.tracing import is_internal

__all__ = ["back_at", "second_side"]


def back_at(res, reading, d_i) -> bool:
    """Is the probe, brought back along the posture that stood at D_i to
    trace the other side (Theorem 4), on D_i again? ``reading``: the
    insertion's Reading; ``d_i``: (2,) float. With a perfect sensor:
    a tip contact. With a noisy one the tip contact must also lie within
    the same-contact radius of D_i: the recorded posture is a reading, off
    by the noise, and the probe reached D_i by the bisection's swings, so
    the straight insertion along it can stop on a corner the posture
    grazed (the body contact of Y1 = 2) -- the trace then started there
    and its first step made a W1 segment through material
    (``textured_pocket`` z0 and z6 at sigma 0.1 eps: 53 eps long, 7.6 eps
    deep). Only while :func:`~core2d.planner.grazing.resolves_half_eps` (measured
    there; at sigma 0.3 eps the same W1 was seen on ``twin_posts`` and
    ``mushroom`` z4, not measured with this test)."""
    tip = reading.tip_contact
    if tip is None:
        return False
    return not resolves_half_eps(res) or magnitude(tip.point - d_i) <= res.tip_zone


def second_side(run, area, G, joint_i, local, toward_B):
    """Bring the probe back to D_i and say where the second side's trace starts.

    Parameters
    ----------
    run : Exploration -- the probe, its resolution and the robot's map.
    area : Area -- A_iB_i; G : G_i; joint_i : (2,) float, P_i (T_i).
    local : LocalResult -- the bisection's final state at D_i.
    toward_B : bool -- the side to trace.

    Returns
    -------
    (start, kids) : the LocalResult the trace starts from (``local`` when the
    probe is back on D_i, None when the side is not traced) and the areas
    registered for what is not traced.

    Notes
    -----
    Not back on D_i (:func:`back_at`), the side C_{D_i}^{P_fin} was registered
    unknown (``limit``) and explored afresh. Where the insertion's tip contact C
    is new contour (not P_fin's or D_i's contact at the sensor's end radius,
    farther than ``near`` from the robot's map) on Int(A_iB_i) (Fig. 13's test,
    :func:`~core2d.planner.tracing.is_internal`), C lies on C_{D_i}^{P_fin}:
    the trace starts at C, as the paper's starts at D_i, and the stretch skipped
    (D_i, C) is registered (``reentry``, §4.3.3's orientation). The trace's first
    point is C, so no W1 joins D_i to C. Perfect sensing is unchanged: there any
    tip contact is back at D_i.

    Measured on ``numerics`` seed 0 at sigma 0.3 eps, taxels 0.25 eps: D_i at the
    base of a needle 0.56 eps wide and 39 long, the posture 3.5 degrees off the
    needle's face, C read 1.3 - 2.5 eps out along it. Registered ``limit``, the
    area (P_fin, D_i) spanned the needle's base, its trace from the other pocket
    reached P_fin across the base (Case 1) and the whole needle was lost: 0.79 of
    the reachable contour covered within eps/2 + 2 sigma (sensor seed 2000; keyed
    seeds 2000, 3000, 4000). Traced from C: 1.00 (keyed 2000: 0.999, 4000: 1.00;
    3000: 0.89, the needle's outer 19 eps, thinner than the jitter, lost on a
    later area). Split at C instead, both halves explored afresh: 0.91.
    """
    res, probe = run.res, run.probe
    pose_d = Posture(local.reading.joint, local.reading.direction)
    back = reestablish(probe, pose_d)
    if back_at(res, back, local.point):
        return local, []
    fin_is_A = not toward_B
    p_fin = area.a if fin_is_A else area.b
    pose_fin = area.pose_a if fin_is_A else area.pose_b
    depth = area.depth + 1
    c = back.tip_contact
    if (c is None or not run.flow.map
            or any(magnitude(c.point - p) <= end_radius(res) for p in (local.point, p_fin))
            or run.known.distance(c.point) <= res.near
            or not is_internal(c.point, area, G, joint_i)):
        return None, [register(local.point, pose_d, p_fin, pose_fin, fin_is_A, area.index,
                               "limit", depth)]
    skipped = register(local.point, pose_d, c.point, Posture(back.joint, back.direction),
                       fin_is_A, area.index, "reentry", depth)
    return replace(local, point=c.point, reading=back), [skipped]
