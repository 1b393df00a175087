"""The probe simulator's angular search, in Python (§3.2).

A swing, a settle or a compliant step ends where the probe on its joint
turns from free to blocked (or back). :class:`AngularSearch` finds that
angle with fans of rays from the joint: windows of growing size
(:meth:`~AngularSearch._offsets`), then bisection by fans of 16 rays inside
the bracket (:meth:`~AngularSearch._refine`) down to the angular resolution
``ang_tol``. It is the path of every contact model; for one with a ray
function :mod:`core2d.sim.kernels` runs the same searches compiled (the same
rays, tested to give the same answers).
"""
from __future__ import annotations

import math

import numpy as np

from core2d.sim import kernels

__all__ = ["AngularSearch"]

_WINDOWS = kernels._WINDOWS  # fan windows at the fan spacing
_REFINE = 16
_NO_FIRST = np.zeros((3, 0))
_STEPS = np.arange(_REFINE + 2, dtype=np.float64)[1:-1]  # np.linspace's steps 1 .. _REFINE


class AngularSearch:
    """Mixin of :class:`core2d.sim.probe.Probe`: its searches about a joint.

    Uses the probe's ``fan_step``, ``ang_tol``, ``_offset_cache``, ``_fan``
    and, when set, ``_compiled`` / ``_run_kernel``.
    """

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

    def _settle_offsets(self, along_angle, back_angle):
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

    def _search(self, joint, theta0, rot_dir, max_angle, want_blocked=True, first=None):
        """First angle from ``theta0`` (excluded) towards ``rot_dir`` where the
        probe on ``joint`` becomes blocked (or free), resolved to ang_tol.
        ``first`` is the ``(dist, point)`` answer for the rays of the first
        window when the caller cast them already (in a batch with others).

        Returns ``(free_angle, (dist, point))`` -- the free side of the
        bracket and the hit of its blocked side -- or None when nothing
        changes within ``max_angle``.
        """
        if self._compiled is not None and first is None:
            found, angle, d, x, y = self._run_kernel(
                kernels.search, float(joint[0]), float(joint[1]), float(theta0),
                float(rot_dir), float(max_angle), want_blocked, _NO_FIRST)
            return (angle, (d, np.array((x, y)))) if found else None
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
            d, p = self._fan(joint, ang)
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
            d, p = self._fan(joint, ang)
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
            d, p = self._fan(joint, [a_before])
            last_blocked = (d[0], p[0])
        return a_after, last_blocked
