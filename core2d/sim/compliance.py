"""Internal: the compliant tracing motion (§4.3), a guarded move of the simulator.

The joint moves along a fixed direction v while a constant torque
tau = tau0 sgn(v, t*) (clockwise positive, eq. 2) keeps the probe pressed
against the environment. The simulator resolves the continuous motion in
micro-steps: after each joint step the probe settles -- it swings with the
torque until it touches, or yields against the torque when the step pressed
it into the surface. A step whose contact point moves discontinuously is
halved until either the motion is continuous again or the step is below
``tol``: then it is a real contact point jump (Case 2) and the motion stops.
A contact that moved less than the same-point radius (eps / 2) is still a
jump when it left the probe's end for its body with the end hanging into
the contour it passed (:func:`overhangs`: a slot narrower than eps / 2
stepped over, the body on its far corner), unless the end still touches
contour (its tip ray) within ``near`` (2 tol) of the body's contact: the
two are then one contact at the sensor's resolution, the end in the apex
of a concave corner that the step cut.
The controller also stops when the probe loses every contact (Case 2-3),
when v.t > 0 is detected (Case 3, if guarded), when the joint cannot move
along v (Case 4; with tip friction, also a pushing step inside the friction
cone, which jams: :mod:`core2d.sim.friction`), or when a part of the probe reaches ``stop_at`` (P_fin): event
``"reached"`` when the tip's path passed it, ``"reached-body"`` otherwise;
and when the tip passes ``leave_at``, the other end of the designated area
(``"left"``: Definition 8's P_fin lay the other way).
"""
from __future__ import annotations

import math

import numpy as np

from core2d.readings import TIP
from core2d.sim.codes import Settle, TraceEvent
from core2d.sim.friction import self_locked

__all__ = ["compliant_trace", "python_steps", "overhangs", "settle_plan", "MAX_SETTLE"]

MAX_SETTLE = np.pi / 3  # largest swing the torque may cause in one step
_MAX_YIELD = np.pi / 6


def _settle(engine, joint, theta, rot_dir):
    """Pose reached on ``joint`` from ``theta`` under torque ``rot_dir``.

    Returns ``(status, theta, contact)``, status a :class:`Settle`: ``OK``,
    ``LOST`` (swung MAX_SETTLE without touching) or ``JAMMED`` (no free
    angle within _MAX_YIELD against the torque).

    One batch holds the ray at ``theta`` and the first search window on
    both sides (with the torque, and against it): which of the two is
    needed depends on that first ray, and a window of 8 rays costs Embree
    less than a call.
    """
    offsets, n_along, _ = engine.settle_offsets(MAX_SETTLE, _MAX_YIELD)
    d, p = engine.fan(joint, theta + rot_dir * offsets)  # theta, along, then back
    if d[0] == np.inf:
        first = (d[1:1 + n_along], p[1:1 + n_along])
        found = engine.search(joint, theta, rot_dir, MAX_SETTLE, want_blocked=True, first=first)
        if found is None:
            return Settle.LOST, theta + rot_dir * MAX_SETTLE, None
    else:
        first = (d[1 + n_along:], p[1 + n_along:])
        found = engine.search(joint, theta, -rot_dir, _MAX_YIELD, want_blocked=False, first=first)
        if found is None:
            return Settle.JAMMED, theta, None
    free, (d, p) = found
    return Settle.OK, free, engine.contact_at(d, p, rot_dir)


def _segment_distance(point, a, b) -> float:
    """Distance from ``point`` to segment ab (scalar math: hot path)."""
    px, py, ax, ay = float(point[0]), float(point[1]), float(a[0]), float(a[1])
    return _distance_xy(px, py, ax, ay, float(b[0]) - ax, float(b[1]) - ay)


def _distance_xy(px, py, ax, ay, abx, aby) -> float:
    """Distance from (px, py) to the segment from (ax, ay) along (abx, aby)."""
    den = abx * abx + aby * aby
    s = 0.0 if den == 0 else min(1.0, max(0.0, ((px - ax) * abx + (py - ay) * aby) / den))
    return math.hypot(ax + s * abx - px, ay + s * aby - py)


def _passes(tip_zone, point, p, q) -> bool:
    """Did the tip, stepping from contact p to contact q, pass ``point``?

    Within eps/2 of the step (the tip zone): the paper's resolution -- a
    step's chord cuts a convex corner.
    """
    return _segment_distance(point, p, q) <= tip_zone


def compliant_trace(probe, v, tau, max_dist, delta=None, stop_at=None,
                    guard_push=True, max_steps=20000, leave_at=None):
    """Trace with the tip from the current contact; see the module doc.

    Parameters
    ----------
    probe : Probe
    v : (2,) float -- joint moving direction v_i (unit).
    tau : int -- torque sign, +1 clockwise, -1 counter-clockwise (eq. 2).
    max_dist : float -- longest joint travel.
    delta : float -- nominal joint step, default eps / 4.
    stop_at : (2,) float, optional -- P_fin; stop when the probe reaches it.
    guard_push : bool -- stop as soon as v.t > 0 (Case 3).
    leave_at : (2,) float, optional -- the other end of the designated area;
        the tip passing it means the trace left the area (event ``"left"``).

    Returns
    -------
    Reading with ``event`` and the recorded tip ``trace``.
    """
    probe._motion()
    res = probe.exact
    v = np.asarray(v, float) / np.linalg.norm(v)
    rot_dir = -int(np.sign(tau))  # clockwise torque = negative math rotation
    delta0 = res.fan_spacing if delta is None else float(delta)
    stop = None if stop_at is None else np.asarray(stop_at, float)
    leave = None if leave_at is None else np.asarray(leave_at, float)
    first = probe.sense(exact=True)  # the simulator's true start contact
    last = first.tip_contact
    leave_far = leave is not None and last is not None and float(
        np.linalg.norm(last.point - leave)) > res.tip_zone
    event, trace, before, primary = probe.engine.trace_steps(
        probe, v, rot_dir, delta0, max_dist, max_steps, guard_push, last, stop,
        leave if leave_far else None)
    kw = dict(trace=np.array(trace).reshape(-1, 2), before_joint=before[0].copy(),
              before_direction=np.array(before[1], dtype=float))
    if primary is not None:
        kw["primary"] = primary
    return probe.sense(event.label, **kw)


def python_steps(probe, v, rot_dir, delta0, max_dist, max_steps, guard_push, last, stop,
                 leave):
    """The micro-steps of a compliant trace (the Python engine's; any contact model).

    Returns ``(event, trace points, (joint, direction) before the last
    step, primary contact or None)``, event a :class:`TraceEvent`. ``leave``
    is given only when the trace starts farther than the tip zone from it.
    """
    engine, stats, res = probe.engine, probe.stats, probe.exact
    vx, vy = float(v[0]), float(v[1])
    dmin = res.stop_short
    jump = res.tip_zone
    near = res.near
    L = probe.length
    mu = probe.friction
    step = delta0
    travelled = 0.0
    sx, sy = (0.0, 0.0) if stop is None else (float(stop[0]), float(stop[1]))
    trace = [last.point] if last is not None else []
    before = (probe.joint.copy(), probe.direction)
    event, primary = TraceEvent.LIMIT, None
    prev_disp = None
    for _ in range(max_steps):
        c, s = math.cos(probe.theta), math.sin(probe.theta)
        jx, jy = float(probe.joint[0]), float(probe.joint[1])
        if stop is not None:
            # the probe's segment: (jx + L c) - jx as _segment_distance computes it
            if _distance_xy(sx, sy, jx, jy, (jx + L * c) - jx, (jy + L * s) - jy) <= near:
                event = TraceEvent.REACHED_BODY  # a part of the probe other than the tip
                break
        pushing = vx * c + vy * s > 0
        if pushing and guard_push:  # Case 3: the guard intercepts a pushing step
            stats.push_attempts += 1
            event = TraceEvent.PUSHING
            break
        if travelled >= max_dist:
            event = TraceEvent.DONE
            break
        h = min(step, max_dist - travelled)
        joint = np.array((jx + h * vx, jy + h * vy))  # probe.joint + h v
        status, theta, contact = _settle(engine, joint, probe.theta, rot_dir)
        sliding = status == Settle.OK and contact.face == TIP and last is not None
        if sliding:
            q, o = contact.point, last.point
            disp = math.hypot(float(q[0]) - float(o[0]), float(q[1]) - float(o[1]))
        else:
            disp = math.inf
        continuous = disp <= jump
        if continuous:
            c2, s2 = math.cos(theta), math.sin(theta)
            tx, ty = float(joint[0]) + L * c2, float(joint[1]) + L * s2  # the probe's end
            if overhangs(float(o[0]), float(o[1]), float(q[0]), float(q[1]), tx, ty,
                         float(joint[0]), float(joint[1]), dmin) and (
                    math.hypot(tx - float(q[0]), ty - float(q[1])) > near
                    or _end_free(engine, tx, ty, c2, s2, res.tol)):
                continuous = False  # the contact jumped from the end onto the body: Case 2
        if not continuous:
            # A jump keeps a finite gap as the step shrinks; a fast continuous
            # slide (probe near-normal to the surface) shrinks with the step.
            shrinking = sliding and (prev_disp is None or disp < 0.75 * prev_disp)
            if (h > dmin or shrinking) and h > dmin / 1024:
                prev_disp = disp if sliding else None
                step = h / 2
                continue
        prev_disp = None
        if status == Settle.JAMMED:
            event = TraceEvent.BLOCKED
            break
        if pushing and continuous and mu > 0 and self_locked(
                mu, c, s, float(q[0]) - float(o[0]), float(q[1]) - float(o[1])):
            stats.jams += 1  # the tip sticks: sensed as Case 4 (core2d.sim.friction)
            event = TraceEvent.BLOCKED
            break
        before = (probe.joint, (c, s))
        stats.joint_path += h
        travelled += h
        probe.joint, probe.theta = joint, theta
        stats.pushes += pushing  # an executed pushing step
        if status == Settle.LOST:
            event = TraceEvent.LOST
            break
        if not continuous:
            event, primary = TraceEvent.JUMP, contact
            break
        if stop is not None and last is not None and _passes(
                jump, stop, last.point, contact.point):
            trace.append(stop)
            event = TraceEvent.REACHED  # the tip passed P_fin during this step
            break
        if leave is not None and _passes(jump, leave, last.point, contact.point):
            trace.append(leave)
            event = TraceEvent.LEFT  # the tip passed the other end of the area
            break
        last = contact
        trace.append(contact.point)
        step = min(delta0, 2 * step)
    return event, trace, before, primary


def _end_free(engine, tx, ty, c, s, tol) -> bool:
    """Does the probe's end (tx, ty) touch nothing? Its tip ray, as a reading
    casts it (from the end along the probe (c, s), up to tol), hits nothing."""
    d, _ = engine.cast(np.array([[tx, ty]]), np.array([[c, s]]), tol)
    return bool(d[0] == np.inf)


def overhangs(ox, oy, qx, qy, tx, ty, jx, jy, depth) -> bool:
    """Does the probe's end (tx, ty), after a step of its contact from o to
    q, hang in a gap between them? (scalars; the kernels compile it as is)

    A contact within the tip zone (eps / 2 of the end) is the tip's, and a
    contact that moves less than that in one micro-step is continuous: so a
    probe leaning over a slot narrower than eps / 2 steps from the slot's
    near corner onto its far corner, its body resting there and its end
    inside the slot (the ``comb`` scene: a slot 0.32 eps wide between two
    teeth whose tops are one line, stepped over in one move of 0.43 eps; the
    end 0.04 - 0.06 eps deep). The end slid on nothing; the contact point
    left the end for the body, a jump (Case 2 of §4.3.2), and the stretch
    (P_1st, P_2nd) is the slot's mouth, registered by the rule of §4.3.3 (W2
    at once, Dist < eps). Recorded as a slide, the slot's mouth would be
    traced contour that the tip never met.

    The end hangs in a gap when it lies behind the chord o q (away from the
    joint (jx, jy)) by more than ``depth`` -- the trace's stop_short, tol / 2:
    the settle's resolution at the end -- and between o and q along it. Over a
    convex corner the end lies beyond q, over a face on the chord (within the
    resolution), and a contact at the very end is q itself. The controller
    asks one thing more (:func:`python_steps`, the kernels alike): that the
    end lies farther than ``near`` (2 tol) from q or touches nothing (its tip
    ray). In the apex of a concave corner the step cut, the end touches the
    corner and the body the other face a hair away (``numerics`` seed 0,
    sensor seed 3000 at sigma 0.3 eps, taxels 0.25 eps: 0.066 eps): one
    contact at the sensor's resolution, no jump. Where the end touches the
    slot's near wall (a probe leaning 20 degrees over a slot 0.3 eps wide, the
    end 0.29 eps from the body's contact on the far corner) the contact still
    jumped across the slot.

    Examples
    --------
    >>> overhangs(0, 0, 1, 0, 0.5, -0.1, 3, 5, 0.02)  # the end in the gap
    True
    >>> overhangs(0, 0, 1, 0, 1.2, -0.5, 3, 5, 0.02)  # past a convex corner
    False
    """
    ex, ey = qx - ox, qy - oy
    den = ex * ex + ey * ey
    toward = ex * (jy - oy) - ey * (jx - ox)
    if den == 0 or toward == 0:
        return False
    s = ((tx - ox) * ex + (ty - oy) * ey) / den
    side = (ex * (ty - oy) - ey * (tx - ox)) / math.sqrt(den)
    side = side if toward > 0 else -side  # > 0: on the joint's (free) side
    return 0.0 < s < 1.0 and side < -depth


def settle_plan(engine):
    """The settle's first batch and both searches' reach (for the kernels)."""
    offsets, n_along, _ = engine.settle_offsets(MAX_SETTLE, _MAX_YIELD)
    return offsets, n_along, MAX_SETTLE, _MAX_YIELD
