"""Internal: the compiled ray engine, for a contact model with a ray function.

:class:`CompiledEngine` runs the searches, the settles of a compliant trace
and a reading's rays in compiled code (:mod:`core2d.sim.kernels`), calling
the contact model's ray function (``ray_kernel``: the Embree and exact backends) ray
by ray: the rays of :class:`~core2d.sim.search.PythonEngine` up to the
first hit of each window, the same answers and the same casts, without the
Python between the rays. It shares the Python engine's ray plan (the offset windows, the settle
batch) and overrides every operation that casts.
"""
from __future__ import annotations

import time

import numpy as np

from core2d.resolution import Resolution
from core2d.result import SenseStats
from core2d.sim import kernels
from core2d.sim.codes import REFINE as _REFINE
from core2d.sim.codes import WINDOWS as _WINDOWS
from core2d.sim.compliance import settle_plan
from core2d.sim.search import PythonEngine

__all__ = ["CompiledEngine"]

class CompiledEngine(PythonEngine):
    """The simulator's ray engine in compiled code (see :class:`core2d.sim.engine.Engine`).

    ray_kernel : (address, context) -- the contact model's ray function and
        the array whose data pointer is its context (kept alive here).
    The other parameters are those of :class:`~core2d.sim.search.PythonEngine`.
    """

    def __init__(self, contact, stats: SenseStats, length: float, resolution: Resolution,
                 ray_kernel):
        super().__init__(contact, stats, length, resolution)
        self._context = ray_kernel[1]  # keeps the context alive
        self._ray = (int(ray_kernel[0]), int(ray_kernel[1].ctypes.data))
        self._par = np.array((self.length, self.ang_tol, self.fan_step, self.tip_zone,
                              _WINDOWS[-1], _REFINE))
        self._work = np.empty((5, _WINDOWS[-1]))
        self._count = np.zeros(5, dtype=np.int64)

    def _run(self, kernel, *args):
        """Call a compiled search (:mod:`core2d.sim.kernels`) and book its
        casts, rays, pushes, jams and time as the Python engine would."""
        count = self._count
        count[:] = 0
        t0 = time.perf_counter()
        out = kernel(*self._ray, *args, self._par, self._work, count)
        stats = self.stats
        stats.cast_seconds += time.perf_counter() - t0
        stats.casts += int(count[0])
        stats.rays += int(count[1])
        stats.pushes += int(count[2])
        stats.push_attempts += int(count[3])
        stats.jams += int(count[4])
        return out

    def cast(self, origins, dirs, max_dist):
        t0 = time.perf_counter()
        n = len(origins)
        limits = max_dist if type(max_dist) is np.ndarray else np.full(n, float(max_dist))
        out = np.empty((n, 3))
        kernels.cast(*self._ray, origins, dirs, limits, out)
        self._book(t0, n)
        return out[:, 0], out[:, 1:]

    def sense_rays(self, jx, jy, th, alpha, L, tol):
        out = np.empty((3, 3))
        t0 = time.perf_counter()
        kernels.sense_rays(*self._ray, jx, jy, th, alpha, L, tol, out)
        self._book(t0, 3)
        return out[:, 0], out[:, 1:]

    def search(self, joint, theta0, rot_dir, max_angle, want_blocked=True, first=None):
        if first is not None:  # a window cast by the caller (the Python settle's batch)
            return super().search(joint, theta0, rot_dir, max_angle, want_blocked, first)
        found, angle, d, x, y = self._run(
            kernels.search, float(joint[0]), float(joint[1]), float(theta0), float(rot_dir),
            float(max_angle), bool(want_blocked))
        return (angle, (d, np.array((x, y)))) if found else None

    def search_from(self, origin, theta0, rot_dir, max_angle):
        n = max(1, int(np.ceil(max_angle / self.fan_step)))
        off = self._run(kernels.search_from, float(origin[0]), float(origin[1]), float(theta0),
                        float(rot_dir), float(max_angle), n, self.tol)
        return None if off < 0 else off

    def trace_steps(self, probe, v, rot_dir, delta0, max_dist, max_steps, guard_push, last,
                    stop, leave):
        """The micro-steps of a compliant trace (:func:`core2d.sim.kernels.trace_steps`):
        the same steps and rays as :func:`core2d.sim.compliance.python_steps`."""
        stats = self.stats
        pose = np.array((probe.joint[0], probe.joint[1], probe.theta, stats.joint_path))
        res = probe.exact
        motion = (float(v[0]), float(v[1]), float(rot_dir), float(delta0), res.stop_short,
                  res.tip_zone, res.near, float(max_dist), float(max_steps),
                  1.0 if guard_push else 0.0, probe.friction)
        marks = np.zeros(9)
        for k, point in ((0, None if last is None else last.point), (3, stop), (6, leave)):
            if point is not None:
                marks[k:k + 3] = (1.0, point[0], point[1])
        event, trace, before, primary = self._run(
            kernels.trace_steps, pose, motion, marks, settle_plan(self))
        probe.joint, probe.theta = pose[:2].copy(), float(pose[2])
        stats.joint_path = float(pose[3])
        if not np.isnan(primary[0]):
            primary = self.contact_at(primary[0], primary[1:].copy(), rot_dir)
        else:
            primary = None
        return event, trace, (before[:2], before[2:]), primary
