"""Internal: compiled contact resolution of the probe simulator (§3.2, §4.3), numba.

The simulator resolves a contact by bisection: a fan of rays from the joint,
then finer fans inside the bracket where the probe turns from free to
blocked, until the bracket is below the angular resolution. In Python each
fan costs a call into the contact model, ~5 us however few its rays, and a
compliant trace makes one settle per joint micro-step: the per-call cost, not
the rays, was most of the sensing time. These kernels run the same searches
of the Python engine (:class:`core2d.sim.search.PythonEngine`: ``search``,
``_refine``, ``search_from``; :func:`core2d.sim.compliance._settle` and the
micro-step loop :func:`core2d.sim.compliance.python_steps`) in compiled code,
calling a contact model's *ray function* once per ray. They are driven by
:class:`core2d.sim.compiled.CompiledEngine`; the event and settle codes are
the named ones of :mod:`core2d.sim.codes`, shared with the Python engine.

Arrays the searches share: ``par = (L, ang_tol, fan_step, tip_zone, window
cap, REFINE)``; ``work`` (5, cap) float scratch; ``count`` (5,) int64 -- casts,
rays, pushes, push attempts, jams -- incremented in place.

A ray function is any C function ``ray(ctx, ox, oy, dx, dy, max_dist, out)``
writing ``out[:3] = distance, x, y`` (``inf, nan, nan`` for a miss), given
as the pair ``(address, ctx)`` by a contact model's ``ray_kernel`` (the
Embree backend has one, :mod:`slicer.contact.embree_direct`, and the exact backend,
:mod:`slicer.contact.exact`). core2d never learns
what is behind it: the same contract as ``cast``, one ray at a time.

The kernels cast the rays of the Python path, window by window, in the same
order, but stop each window at its first ray where the probe's state changes:
the Python engine casts a whole window in one call (a call costs more than
rays), and only that first ray and the ones before it are ever used. So
results, the motion log and the casts are identical, and the kernels cast
fewer rays: a prefix of each window, and of a settle's batch the ray at
theta and the one window it calls for. ``tests/test_core2d_kernels.py``
checks it scene by scene; the benchmark replays the rays the kernels cast
(:mod:`bench.sensing_worker`).
"""
from __future__ import annotations

import math

import numba
import numpy as np
from llvmlite import ir
from numba import types
from numba.extending import intrinsic

from core2d.sim.codes import WINDOWS as _WINDOWS
from core2d.sim.codes import Settle, TraceEvent
from core2d.sim.compliance import _distance_xy as distance_xy
from core2d.sim.compliance import overhangs
from core2d.sim.friction import self_locked

# the Python engine's scalar functions, compiled as they are (both engines decide alike)
_self_locked = numba.njit(cache=True, nogil=True)(self_locked)
_overhangs = numba.njit(cache=True, nogil=True)(overhangs)
_distance_xy = numba.njit(cache=True, nogil=True)(distance_xy)

__all__ = ["cast", "sense_rays", "search", "search_from", "settle", "trace_steps"]


@intrinsic
def _call(typingctx, fn, ctx, ox, oy, dx, dy, md, out):
    """Call the ray function at address ``fn`` (see the module doc)."""
    sig = types.void(types.int64, types.int64, types.float64, types.float64,
                     types.float64, types.float64, types.float64, types.int64)

    def codegen(context, builder, signature, args):
        dbl, i8p = ir.DoubleType(), ir.IntType(8).as_pointer()
        fnty = ir.FunctionType(ir.VoidType(), [i8p, dbl, dbl, dbl, dbl, dbl, dbl.as_pointer()])
        target = builder.inttoptr(args[0], fnty.as_pointer())
        builder.call(target, [builder.inttoptr(args[1], i8p), *args[2:7],
                              builder.inttoptr(args[7], dbl.as_pointer())])
        return context.get_dummy_value()

    return sig, codegen


@numba.njit(cache=True, nogil=True)
def cast(fn, ctx, origins, dirs, limits, out):  # pragma: no cover - compiled
    """Rays ``origins`` (n, 2) along unit ``dirs`` (n, 2) up to ``limits`` (n,)
    into ``out`` (n, 3): distance, x, y (one cast)."""
    res = np.empty(3)
    addr = res.ctypes.data
    for i in range(origins.shape[0]):
        _call(fn, ctx, origins[i, 0], origins[i, 1], dirs[i, 0], dirs[i, 1], limits[i], addr)
        out[i, 0], out[i, 1], out[i, 2] = res[0], res[1], res[2]


@numba.njit(cache=True, nogil=True)
def sense_rays(fn, ctx, jx, jy, theta, alpha, L, tol, out):  # pragma: no cover - compiled
    """The three rays of ``Probe.sense`` into ``out`` (3, 3) (one cast): from
    the joint at ``theta +- alpha`` up to L + tol, and from the tip along t
    up to tol."""
    res = np.empty(3)
    addr = res.ctypes.data
    c, s = math.cos(theta), math.sin(theta)
    for k in range(3):
        if k < 2:
            a = theta + alpha if k == 0 else theta - alpha
            _call(fn, ctx, jx, jy, math.cos(a), math.sin(a), L + tol, addr)
        else:
            _call(fn, ctx, jx + L * c, jy + L * s, c, s, tol, addr)
        out[k, 0], out[k, 1], out[k, 2] = res[0], res[1], res[2]


@numba.njit(cache=True, nogil=True)
def search_from(fn, ctx, ox, oy, theta0, rot_dir, max_angle, n, tol, par, work, count):
    # pragma: no cover - compiled
    """``PythonEngine.search_from``: the first of ``n`` rays from ``(ox, oy)``
    (offset by ``tol`` along each ray) at ``theta0 + rot_dir k step``
    (k = 1 .. n, clipped to ``max_angle``) that hits, in the windows of the
    Python engine (``cap`` rays, one cast each), each cast up to its first
    hit; its offset ``k step`` (k from 0), or -1.
    ``work`` is not used (the common signature); ``count[:2]`` is incremented."""
    L, step, cap = par[0], par[2], int(par[4])
    res = np.empty(3)
    addr = res.ctypes.data
    for lo in range(0, n, cap):
        hi = min(n, lo + cap)
        count[0] += 1
        for k in range(lo + 1, hi + 1):
            a = theta0 + rot_dir * min(k * step, max_angle)
            c, s = np.cos(a), np.sin(a)
            _call(fn, ctx, ox + tol * c, oy + tol * s, c, s, L, addr)
            count[1] += 1
            if res[0] < np.inf:
                return (k - 1) * step
    return -1.0


@numba.njit(cache=True, nogil=True)
def _scan(fn, ctx, jx, jy, angles, n, max_dist, want_blocked, d, px, py):
    # pragma: no cover - compiled
    """Rays from ``(jx, jy)`` at ``angles[:n]`` into ``d, px, py``, in order,
    up to the first blocked (finite) or free (inf) one as ``want_blocked``:
    its index (the rays cast: index + 1), or -1 (all ``n`` cast)."""
    out = np.empty(3)
    addr = out.ctypes.data
    for i in range(n):
        _call(fn, ctx, jx, jy, np.cos(angles[i]), np.sin(angles[i]), max_dist, addr)
        d[i], px[i], py[i] = out[0], out[1], out[2]
        if (out[0] < np.inf) == want_blocked:
            return i
    return -1


@numba.njit(cache=True, nogil=True)
def _refine(fn, ctx, jx, jy, a_before, a_after, hd, hx, hy, want_blocked, par, work, count):
    # pragma: no cover - compiled
    """``PythonEngine._refine``: shrink [a_before, a_after] to ang_tol, fans of
    ``REFINE`` rays each cast up to its first ray past the bracket's change;
    ``(hd, hx, hy)`` is the hit at ``a_after``. Returns the resolved angle
    and the blocked side's ``(d, x, y)``."""
    L, ang_tol, nref = par[0], par[1], int(par[5])
    ang, d, px, py = work[0], work[1], work[2], work[3]
    have = want_blocked
    bd, bx, by = (hd, hx, hy) if want_blocked else (np.inf, np.nan, np.nan)
    while abs(a_after - a_before) > ang_tol:
        w = (a_after - a_before) / (nref + 1)
        for j in range(nref):
            ang[j] = (j + 1.0) * w + a_before
        i = _scan(fn, ctx, jx, jy, ang, nref, L, want_blocked, d, px, py)
        count[0] += 1
        count[1] += nref if i < 0 else i + 1
        if i >= 0:
            a_after = ang[i]
            if i > 0:
                a_before = ang[i - 1]
            if want_blocked:
                bd, bx, by, have = d[i], px[i], py[i], True
            elif i > 0:
                bd, bx, by, have = d[i - 1], px[i - 1], py[i - 1], True
        else:
            a_before = ang[nref - 1]
            if not want_blocked:
                bd, bx, by, have = d[nref - 1], px[nref - 1], py[nref - 1], True
    if want_blocked:
        return a_before, bd, bx, by
    if not have:  # the blocked side is the start angle itself
        res = np.empty(3)
        _call(fn, ctx, jx, jy, np.cos(a_before), np.sin(a_before), L, res.ctypes.data)
        count[0] += 1
        count[1] += 1
        bd, bx, by = res[0], res[1], res[2]
    return a_after, bd, bx, by


@numba.njit(cache=True, nogil=True)
def _window(offs, st, max_angle, fan_step, cap):  # pragma: no cover - compiled
    """Next window of ``PythonEngine._offsets(max_angle)`` into ``offs``; its size, 0
    at the end. ``st`` = [phase, pos, step, window index] carries the state:
    fine windows of 8 (step x4 each) up to the fan spacing, windows of
    8 ... 8192 rays at the fan spacing, then windows of ``cap``; every
    offset clipped to ``max_angle``."""
    if st[0] == 0:
        if st[2] < fan_step and st[1] < max_angle:
            for j in range(8):
                offs[j] = st[1] + st[2] * (j + 1)
            st[1], st[2] = offs[7], min(fan_step, 4 * st[2])
            for j in range(8):
                offs[j] = min(offs[j], max_angle)
            return 8
        st[0] = 1
    if st[0] == 1:
        w = int(st[3])
        if w < len(_WINDOWS) and st[1] < max_angle:
            n = _WINDOWS[w]
            for j in range(n):
                offs[j] = st[1] + fan_step * (j + 1)
            st[1], st[3] = offs[n - 1], w + 1
            for j in range(n):
                offs[j] = min(offs[j], max_angle)
            return n
        st[0], st[1] = 2, min(st[1], max_angle)  # the tail starts at the last offset
    if st[1] < max_angle:
        for j in range(cap):
            offs[j] = min(st[1] + fan_step * (j + 1), max_angle)
        st[1] = offs[cap - 1]
        return cap
    return 0


@numba.njit(cache=True, nogil=True)
def search(fn, ctx, jx, jy, theta0, rot_dir, max_angle, want_blocked, par, work, count):
    # pragma: no cover - compiled
    """``PythonEngine.search``: first angle from ``theta0`` towards ``rot_dir``
    (+-1.0) where the probe becomes blocked (or free), in the windows of the
    Python engine, each cast up to its first ray where the state changes (the
    rays past it are never used).

    par, work : see the module doc. count : (4,) int -- casts and rays
        (``count[:2]``) incremented.

    Returns ``(found, angle, d, x, y)``.
    """
    L, fan_step, cap = par[0], par[2], int(par[4])
    ang, d, px, py, offs = work[0], work[1], work[2], work[3], work[4]
    st = np.array((0.0, 0.0, min(fan_step, 2 * par[1]), 0.0))
    prev = 0.0
    while True:
        n = _window(offs, st, max_angle, fan_step, cap)
        if n == 0:
            return False, 0.0, np.inf, np.nan, np.nan
        for j in range(n):
            ang[j] = theta0 + rot_dir * offs[j]
        i = _scan(fn, ctx, jx, jy, ang, n, L, want_blocked, d, px, py)
        count[0] += 1
        count[1] += n if i < 0 else i + 1
        if i >= 0:
            lo = theta0 + rot_dir * (prev if i == 0 else offs[i - 1])
            a, bd, bx, by = _refine(fn, ctx, jx, jy, lo, ang[i], d[i], px[i], py[i],
                                    want_blocked, par, work, count)
            return True, a, bd, bx, by
        prev = offs[n - 1]


@numba.njit(cache=True, nogil=True)
def settle(fn, ctx, jx, jy, theta, rot_dir, plan, par, work, count):
    # pragma: no cover - compiled
    """``compliance._settle``: the pose reached on the joint ``(jx, jy)`` from
    ``theta`` under the torque ``rot_dir`` (+-1.0).

    plan : ``(offsets, n_along, max_along, max_back)`` of
    :func:`core2d.sim.compliance.settle_plan`; the reaches are used. One cast
    as in the Python engine: the ray at ``theta``, then the first window of
    the one search it calls for (along the torque when that ray is free,
    against it when blocked) up to its first hit; the other window, which
    the Python engine casts in the same batch, is not needed.

    Returns ``(status, theta, d, x, y)``, status a :class:`~core2d.sim.codes.Settle`.
    """
    max_a, max_b = plan[2], plan[3]
    res = np.empty(3)
    _call(fn, ctx, jx, jy, math.cos(theta), math.sin(theta), par[0], res.ctypes.data)
    count[1] += 1  # (cast with the search's first window, which counts the cast)
    free = res[0] == np.inf  # swing with the torque to a contact, else yield against it
    found, a, d, x, y = search(fn, ctx, jx, jy, theta, rot_dir if free else -rot_dir,
                               max_a if free else max_b, free, par, work, count)
    if not found:
        if free:
            return Settle.LOST, theta + rot_dir * max_a, np.inf, np.nan, np.nan
        return Settle.JAMMED, theta, np.inf, np.nan, np.nan
    return Settle.OK, a, d, x, y


@numba.njit(cache=True, nogil=True)
def trace_steps(fn, ctx, pose, motion, marks, plan, par, work, count):
    # pragma: no cover - compiled
    """The micro-step loop of ``compliance.compliant_trace``
    (:func:`core2d.sim.compliance.python_steps`), compiled.

    pose : ``[jx, jy, theta, joint_path]``, updated in place.
    motion : ``(vx, vy, rot_dir, delta0, dmin, jump, near, max_dist, max_steps,
        guard_push, mu)`` (mu: tip friction, :mod:`core2d.sim.friction`).
    marks : ``[has_last, last x, last y, has_stop, stop x, stop y, leave_far,
        leave x, leave y]``.
    plan : the settle plan of :func:`settle`. par, work, count : see the
    module doc (all five counters incremented).

    Returns ``(event, trace (k, 2), before (4,) joint and direction,
    primary (d, x, y) or d = nan)``, event a :class:`~core2d.sim.codes.TraceEvent`.
    """
    vx, vy, rot_dir, delta0, dmin, jump, near, max_dist, max_steps, guard, mu = motion
    L, tip_zone = par[0], par[3]
    has_last, lx, ly = marks[0] > 0, marks[1], marks[2]
    has_stop, sx, sy = marks[3] > 0, marks[4], marks[5]
    leave_far, ex, ey = marks[6] > 0, marks[7], marks[8]
    trace = np.empty((64, 2))
    tip_ray = np.empty(3)
    nt = 0
    if has_last:
        trace[0, 0], trace[0, 1] = lx, ly
        nt = 1
    jx, jy, theta = pose[0], pose[1], pose[2]
    before = np.array((jx, jy, math.cos(theta), math.sin(theta)))
    primary = np.array((np.nan, np.nan, np.nan))
    event = TraceEvent.LIMIT
    step, travelled = delta0, 0.0
    prev_disp, has_prev = 0.0, False
    for _ in range(int(max_steps)):
        c, s = math.cos(theta), math.sin(theta)
        if has_stop and _distance_xy(sx, sy, jx, jy, (jx + L * c) - jx,
                                     (jy + L * s) - jy) <= near:
            event = TraceEvent.REACHED_BODY
            break
        pushing = vx * c + vy * s > 0
        if pushing and guard > 0:  # Case 3: the guard intercepts a pushing step
            count[3] += 1
            event = TraceEvent.PUSHING
            break
        if travelled >= max_dist:
            event = TraceEvent.DONE
            break
        h = min(step, max_dist - travelled)
        njx, njy = jx + h * vx, jy + h * vy
        status, nth, d, qx, qy = settle(fn, ctx, njx, njy, theta, rot_dir, plan, par, work,
                                        count)
        sliding = status == Settle.OK and L - d <= tip_zone and has_last
        disp = math.hypot(qx - lx, qy - ly) if sliding else np.inf
        continuous = disp <= jump
        if continuous:
            c2, s2 = math.cos(nth), math.sin(nth)
            tx, ty = njx + L * c2, njy + L * s2  # the probe's end
            if _overhangs(lx, ly, qx, qy, tx, ty, njx, njy, dmin):
                free = math.hypot(tx - qx, ty - qy) > near
                if not free:  # the end's tip ray, as a reading casts it (one cast)
                    _call(fn, ctx, tx, ty, c2, s2, 2 * dmin, tip_ray.ctypes.data)
                    count[0] += 1
                    count[1] += 1
                    free = tip_ray[0] == np.inf
                continuous = not free  # free: the contact jumped from the end onto the body
        if not continuous:
            shrinking = sliding and (not has_prev or disp < 0.75 * prev_disp)
            if (h > dmin or shrinking) and h > dmin / 1024:
                prev_disp, has_prev = disp, sliding
                step = h / 2
                continue
        has_prev = False
        if status == Settle.JAMMED:
            event = TraceEvent.BLOCKED
            break
        if pushing and continuous and mu > 0 and _self_locked(mu, c, s, qx - lx, qy - ly):
            count[4] += 1  # the tip sticks: sensed as Case 4
            event = TraceEvent.BLOCKED
            break
        before[0], before[1], before[2], before[3] = jx, jy, c, s
        pose[3] += h
        travelled += h
        jx, jy, theta = njx, njy, nth
        if pushing:
            count[2] += 1  # an executed pushing step
        if status == Settle.LOST:
            event = TraceEvent.LOST
            break
        if not continuous:
            event = TraceEvent.JUMP
            primary[0], primary[1], primary[2] = d, qx, qy
            break
        if nt + 1 >= len(trace):
            grown = np.empty((2 * len(trace), 2))
            for k in range(nt):  # (no slice assignment: its shape checks cost compile time)
                grown[k, 0], grown[k, 1] = trace[k, 0], trace[k, 1]
            trace = grown
        if has_stop and has_last and _distance_xy(sx, sy, lx, ly, qx - lx, qy - ly) <= tip_zone:
            trace[nt, 0], trace[nt, 1] = sx, sy
            nt += 1
            event = TraceEvent.REACHED  # the tip passed P_fin during this step
            break
        if leave_far and _distance_xy(ex, ey, lx, ly, qx - lx, qy - ly) <= tip_zone:
            trace[nt, 0], trace[nt, 1] = ex, ey
            nt += 1
            event = TraceEvent.LEFT  # the tip passed the other end of the area
            break
        has_last, lx, ly = True, qx, qy
        trace[nt, 0], trace[nt, 1] = qx, qy
        nt += 1
        step = min(delta0, 2 * step)
    pose[0], pose[1], pose[2] = jx, jy, theta
    return event, trace[:nt].copy(), before, primary
