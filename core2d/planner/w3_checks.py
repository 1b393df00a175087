"""Step 4 of the revisit's W3 (:mod:`core2d.planner.revisit`): a lid that passed its
proof or its probing is W3 only if the probe can hold it as a posture (:func:`holds_lid`)
and it closes a loop of recorded contour around material (:func:`closes_loop`).
"""
from __future__ import annotations

import numpy as np

from core2d.planner.grazing import resolves_half_eps
from core2d.planner.regions import near_probe

__all__ = ["holds_lid", "closes_loop"]


def holds_lid(run, area) -> bool:
    """Can the probe hold the lid as a posture (``run`` an
    :class:`~core2d.planner.run.Exploration`)? "A W3 lid is a posture the
    probe actually held": the single probe detection of Fig. 6, made on
    purpose. The probe is inserted from F along the lid's line (shifted tol
    into V_i), once from beyond each end; the lid is held when the tip
    touches the far end and the probe passes the near one, both within
    eps/2. A lid laid through material -- across a wall the robot has not
    recorded -- stops the tip short of its far end.

    Under a noisy sensor whose readings resolve eps/2
    (:func:`~core2d.planner.grazing.resolves_half_eps`) the line is shifted
    tol + the jitter into V_i: the ends are readings, and a lid read a
    hair off an unrecorded wall, its V_i on the wall's side (a Case 2-2
    child in a slit whose far wall the robot touched), was held along the
    slit though its V_i is material; the W3 proof then found every line
    from F to it blocked by the wall's outer face (the thin wall of
    ``tests/test_core2d_noisy_mouths.py``, sensor seed 2). Two readings
    of a point lie within eps/2 - tol there, so the shifted line still
    meets the far end within the same-point radius. Taxels alone keep the
    shift tol: with the jitter (0.25 eps) the two sound W3 lids of the
    ``mushroom`` scene's z4 (taxels 0.25 eps) were not held any more."""
    probe, same = run.probe, run.res.tip_zone
    a, b = np.asarray(area.a, float), np.asarray(area.b, float)
    u = (b - a) / area.dist
    noisy = run.res.noise > 0 and resolves_half_eps(run.res)
    off = run.res.tol + (run.res.jitter if noisy else 0.0)
    shift = off * np.array([-u[1], u[0]])  # towards V_i (Definition 3)
    for near, far, d in ((a, b, u), (b, a, -u)):
        if not run.budget():
            return False
        probe.approach(far + shift, d)
        r = probe.insert(2.5 * probe.radius)
        tip = r.tip_contact
        if tip is not None and np.hypot(*(tip.point - far)) <= same and near_probe(
                near, r.joint, r.direction, probe.length, same):
            return True
    return False


def closes_loop(known, area, tol, width, exclude=()) -> bool:
    """Step 4: a chain of recorded pieces leads from B_i round to A_i, and the
    loop it makes with the lid runs clockwise around material at least
    ``width`` thick: every recorded piece and the lid have the material on
    their right, so a W3 lid's loop encloses material and the pocket behind
    the lid. A loop running counter-clockwise encloses free space (a lid
    laid inside a slot narrower than eps, whose chain runs down the slot's
    wall); one enclosing less than ``width`` x its perimeter hugs the lid
    (a chain back along another lid over the same gap)."""
    path = known.chain(area.b, area.a, tol, exclude)
    if path is None:
        return False
    x, y = path[:, 0], path[:, 1]  # closed by the lid A -> B
    twice = float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
    perimeter = float(np.hypot(*np.diff(path, axis=0).T).sum()) + area.dist
    return twice < 0 and -twice / 2 >= width * perimeter
