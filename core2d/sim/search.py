"""Internal: the Python ray engine of the probe simulator (§3.2): any contact model.

A swing, a settle or a compliant step ends where the probe on its joint
turns from free to blocked (or back). :class:`PythonEngine` finds that
angle with fans of rays from the joint: windows of growing size
(:meth:`~PythonEngine._offsets`), then bisection by fans of 16 rays inside
the bracket (:meth:`~PythonEngine._refine`) down to the angular resolution
``ang_tol``. It casts through the contact model's ``cast`` (and its fused
``fan`` when it has one) and counts casts, rays and their time. For a
contact model with a ray function :class:`core2d.sim.compiled.CompiledEngine`
runs the same searches compiled (the same rays, tested to give the same
answers); :func:`core2d.sim.engine.make_engine` chooses one of the two.
"""
from __future__ import annotations

import math
import time

import numpy as np

from core2d.planar import unit
from core2d.readings import LEFT, RIGHT, TIP, Contact
from core2d.resolution import Resolution
from core2d.result import SenseStats
from core2d.sim.codes import REFINE as _REFINE
from core2d.sim.codes import WINDOWS as _WINDOWS
from core2d.sim.compliance import python_steps

__all__ = ["PythonEngine"]

_STEPS = np.arange(_REFINE + 2, dtype=np.float64)[1:-1]  # np.linspace's steps 1 .. _REFINE


class PythonEngine:
    """The simulator's ray engine in Python (see :class:`core2d.sim.engine.Engine`).

    contact : ContactModel -- the geometry.
    stats : SenseStats -- the probe's counters: casts, rays and cast time
        are booked here (and pushes by the trace steps).
    length : float -- probe length L.
    resolution : Resolution -- eps and tol; the angular fan spacing and
        resolution follow at ``length``.
    """

    def __init__(self, contact, stats: SenseStats, length: float, resolution: Resolution):
        self.contact, self.stats, self.length = contact, stats, float(length)
        self.tol = resolution.tol
        self.fan_step = resolution.fan_angle(self.length)  # angular fan spacing
        self.ang_tol = resolution.angle_tol(self.length)  # angular resolution
        self.tip_zone = resolution.tip_zone
        self._offset_cache = {}
        self._fused_fan = getattr(contact, "fan", None)  # optional (Embree backend)

    # ------------------------------------------------------------------ rays
    def cast(self, origins, dirs, max_dist):
        """``(distances, points)`` of the contact model's ``cast``, booked."""
        t0 = time.perf_counter()
        d, p, _ = self.contact.cast(origins, dirs, max_dist)
        self._book(t0, len(origins))
        return d, p

    def _book(self, t0, rays):
        """Count one cast of ``rays`` rays that started at ``t0``."""
        stats = self.stats
        stats.cast_seconds += time.perf_counter() - t0
        stats.casts += 1
        stats.rays += rays

    def fan(self, joint, angles):
        """Rays from ``joint`` at ``angles`` over the probe length (through the
        contact model's fused ``fan`` when it has one: the same rays)."""
        fan = self._fused_fan
        if fan is not None:
            angles = np.asarray(angles, dtype=np.float64).reshape(-1)
            t0 = time.perf_counter()
            d, p = fan(joint, angles, self.length)
            self._book(t0, len(angles))
            return d, p
        dirs = unit(angles).reshape(-1, 2)
        origins = np.empty_like(dirs)
        origins[:] = joint
        return self.cast(origins, dirs, self.length)

    def sense_rays(self, jx, jy, th, alpha, L, tol):
        """The three rays of a reading (one cast): from the joint at
        ``th +- alpha`` up to L + tol, and from the tip along t up to tol."""
        c, sn = math.cos(th), math.sin(th)
        origins = np.array(((jx, jy), (jx, jy), (jx + L * c, jy + L * sn)))
        dirs = np.array(((math.cos(th + alpha), math.sin(th + alpha)),
                         (math.cos(th - alpha), math.sin(th - alpha)), (c, sn)))
        return self.cast(origins, dirs, np.array((L + tol, L + tol, tol)))

    def contact_at(self, dist, point, rot_dir) -> Contact:
        """Contact found by a ray from the joint blocking rotation ``rot_dir``."""
        if self.length - dist <= self.tip_zone:
            return Contact(point, TIP, float(dist))
        return Contact(point, RIGHT if rot_dir > 0 else LEFT, float(dist))

    # -------------------------------------------------------------- searches
    def _offsets(self, max_angle):
        """Angular offsets of a search, window by window: fine first
        (2 ang_tol), growing 4x per window of 8 rays up to the eps/4 fan
        spacing, then windows of 8 ... 8192 rays at that spacing, then windows
        of 8192 until ``max_angle``. The head is cached per ``max_angle``;
        the tail is generated lazily, so no window holds more than 8192 rays
        however small eps is."""
        key = float(max_angle)
        head = self._offset_cache.get(key)
        if head is None:
            head = self._offset_cache[key] = self._make_offsets(key)
        yield from head
        pos, cap = float(head[-1][-1]) if head else 0.0, _WINDOWS[-1]
        while pos < max_angle:
            ks = np.minimum(pos + self.fan_step * np.arange(1, cap + 1), max_angle)
            yield ks
            pos = float(ks[-1])

    def settle_offsets(self, along_angle, back_angle):
        """``[0, head(along_angle), -head(back_angle)]`` (cached) and the two
        head lengths: the offsets of a settle's first batch."""
        key = (float(along_angle), float(back_angle))
        got = self._offset_cache.get(key)
        if got is None:
            along, back = self._offsets_head(along_angle), self._offsets_head(back_angle)
            got = self._offset_cache[key] = (np.concatenate(([0.0], along, -back)),
                                             len(along), len(back))
        return got

    def _offsets_head(self, max_angle):
        """The first window of :meth:`_offsets` (its rays go in a caller's batch)."""
        key = float(max_angle)
        head = self._offset_cache.get(key)
        if head is None:
            head = self._offset_cache[key] = self._make_offsets(key)
        return head[0] if head else np.zeros(0)

    def _make_offsets(self, max_angle):
        out, pos, step = [], 0.0, min(self.fan_step, 2 * self.ang_tol)
        while step < self.fan_step and pos < max_angle:
            ks = pos + step * np.arange(1, 9)
            out.append(ks)
            pos, step = ks[-1], min(self.fan_step, 4 * step)
        for size in _WINDOWS:
            if pos >= max_angle:
                break
            ks = pos + self.fan_step * np.arange(1, size + 1)
            out.append(ks)
            pos = ks[-1]
        return [np.minimum(w, max_angle) for w in out]

    def search(self, joint, theta0, rot_dir, max_angle, want_blocked=True, first=None):
        """First angle from ``theta0`` (excluded) towards ``rot_dir`` where the
        probe on ``joint`` becomes blocked (or free), resolved to ang_tol.
        ``first`` is the ``(dist, point)`` answer for the rays of the first
        window when the caller cast them already (in a batch with others).

        Returns ``(free_angle, (dist, point))`` -- the free side of the
        bracket and the hit of its blocked side -- or None when nothing
        changes within ``max_angle``.
        """
        prev = 0.0
        if first is not None:  # the first window, cast already: no array of angles
            offs = self._offsets_head(max_angle)
            d, p = first
            hit = d < math.inf if want_blocked else d == math.inf
            i = int(hit.argmax())
            if hit[i]:
                lo = theta0 + rot_dir * (prev if i == 0 else offs[i - 1])
                return self._refine(joint, lo, theta0 + rot_dir * offs[i], (d[i], p[i]),
                                    want_blocked)
            prev = offs[-1]
        for k, offs in enumerate(self._offsets(max_angle)):
            if k == 0 and first is not None:
                continue
            ang = theta0 + rot_dir * offs
            d, p = self.fan(joint, ang)
            hit = d < math.inf if want_blocked else d == math.inf
            i = int(hit.argmax())
            if hit[i]:
                lo = theta0 + rot_dir * (prev if i == 0 else offs[i - 1])
                return self._refine(joint, lo, ang[i], (d[i], p[i]), want_blocked)
            prev = offs[-1]
        return None

    def _refine(self, joint, a_before, a_after, hit_after, want_blocked):
        """Shrink the bracket [a_before, a_after] where the state changes."""
        blocked_hit = hit_after if want_blocked else None
        last_blocked = hit_after if want_blocked else None
        while abs(a_after - a_before) > self.ang_tol:
            # np.linspace(a_before, a_after, _REFINE + 2)[1:-1], without its overhead
            ang = _STEPS * ((a_after - a_before) / (_REFINE + 1)) + a_before
            d, p = self.fan(joint, ang)
            hit = d < math.inf if want_blocked else d == math.inf
            i = int(hit.argmax())
            if hit[i]:
                a_after = ang[i]
                a_before = ang[i - 1] if i > 0 else a_before
                if want_blocked:
                    last_blocked = (d[i], p[i])
                elif i > 0:
                    last_blocked = (d[i - 1], p[i - 1])
            else:
                a_before = ang[-1]
                if not want_blocked:
                    last_blocked = (d[-1], p[-1])
        if want_blocked:
            return a_before, last_blocked or blocked_hit
        if last_blocked is None:  # blocked side is the start angle itself
            d, p = self.fan(joint, [a_before])
            last_blocked = (d[0], p[0])
        return a_after, last_blocked

    def search_from(self, origin, theta0, rot_dir, max_angle):
        """Like :meth:`search` for rays from ``origin`` (offset by tol), at
        the fan spacing, in windows of at most 8192 rays: the offset of the
        first ray that hits, or None."""
        step = self.fan_step
        n = max(1, int(np.ceil(max_angle / step)))
        for lo in range(0, n, _WINDOWS[-1]):
            k = np.arange(lo + 1, min(n, lo + _WINDOWS[-1]) + 1)
            dirs = unit(theta0 + rot_dir * np.minimum(k * step, max_angle))
            d, _ = self.cast(origin + self.tol * dirs, dirs, self.length)
            hit = np.isfinite(d)
            if hit.any():
                return (lo + int(np.argmax(hit))) * step
        return None

    def trace_steps(self, probe, v, rot_dir, delta0, max_dist, max_steps, guard_push, last,
                    stop, leave):
        """The micro-steps of a compliant trace: :func:`core2d.sim.compliance.python_steps`."""
        return python_steps(probe, v, rot_dir, delta0, max_dist, max_steps, guard_push, last,
                            stop, leave)
