"""Probe simulator (§3.2): owns the geometry, returns sensor readings only.

A rigid probe of length L and negligible thickness hangs on a joint at
``joint`` and points along the unit vector t; the tip is ``joint + L t``.
Contacts come from a :class:`core2d.sim.contact.ContactModel` through batched
ray casts: a fan of rays from the joint for a swing, one ray from the tip for
an insertion, rays along the probe for a translation. Contacts are resolved
to ``tol`` by bisection with refining fans (:mod:`core2d.sim.search`). No
dynamics, no friction: the pulling strategy is what avoids pushing, and
:attr:`stats.pushes` counts the trace steps that were executed in sliding
contact with v.t > 0.

When the contact model has a ray function (``ray_kernel``, the Embree
backend) the searches, the settles of a compliant trace and the tactile
reading's rays run compiled (:mod:`core2d.sim.kernels`): the same rays, the
same answers, the same counts, without the Python between the rays.
"""
from __future__ import annotations

import math
import time

import numpy as np

from core2d.planar import angle_of, unit
from core2d.readings import LEFT, RIGHT, TIP, Contact, Reading
from core2d.result import SenseStats
from core2d.sim import kernels
from core2d.sim.search import AngularSearch

__all__ = ["Probe", "unit", "angle_of"]

_WINDOWS = kernels._WINDOWS  # fan windows at the fan spacing


class Probe(AngularSearch):
    """Simulated tactile probe on a robot joint.

    Parameters
    ----------
    contact : ContactModel
        Ray-cast backend (Embree or exact).
    workspace : ((2,) float, float)
        Centre and radius of a circle containing the whole slice: the only
        prior knowledge of the robot.
    eps : float
        The paper's epsilon; fans are spaced eps/4 at the tip.
    length : float, optional
        Probe length L, default 2 x the workspace diameter so the joint
        always stays in the free area F.
    tol : float, optional
        Contact resolution, default eps / 20.
    """

    def __init__(self, contact, workspace, eps, length=None, tol=None):
        self.contact = contact
        self.center = np.asarray(workspace[0], dtype=np.float64)
        self.radius = float(workspace[1])
        self.eps = float(eps)
        self.length = float(length if length is not None else 4.0 * self.radius)
        self.tol = float(tol if tol is not None else eps / 20.0)
        self.fan_step = (self.eps / 4.0) / self.length  # angular fan spacing
        self.ang_tol = (self.tol / 2.0) / self.length  # angular resolution
        # contacts closer than eps/2 are one contact at the paper's resolution
        # (§3.2: the contour is smooth at the eps level); near the tip they
        # are the tip's contact (a probe lying at a grazing angle).
        self.tip_zone = self.eps / 2.0
        self.stats = SenseStats()
        self._offset_cache = {}
        self._fused_fan = getattr(contact, "fan", None)  # optional (Embree backend)
        self._compiled = None  # (ray function, context address): core2d.sim.kernels
        kernel = getattr(contact, "ray_kernel", None)  # optional (Embree backend)
        if kernel is not None:
            self._context = kernel[1]  # keeps the context alive
            self._compiled = (int(kernel[0]), int(kernel[1].ctypes.data))
            self._par = np.array((self.length, self.ang_tol, self.fan_step, self.tip_zone,
                                  _WINDOWS[-1]))
            self._work = np.empty((5, _WINDOWS[-1]))
            self._count = np.zeros(4, dtype=np.int64)
        self.joint = self.center + np.array([0.0, self.length + 2 * self.radius])
        self.theta = -np.pi / 2

    # ------------------------------------------------------------------ state
    @property
    def direction(self) -> np.ndarray:
        """(2,) float: unit probe direction t."""
        return np.array((math.cos(self.theta), math.sin(self.theta)))

    @property
    def tip(self) -> np.ndarray:
        """(2,) float: tip position, joint + L t."""
        th, L = self.theta, self.length
        return np.array((self.joint[0] + L * math.cos(th), self.joint[1] + L * math.sin(th)))

    def _cast(self, origins, dirs, max_dist):
        t0 = time.perf_counter()
        if self._compiled is not None:  # the same rays, one at a time
            n = len(origins)
            limits = max_dist if type(max_dist) is np.ndarray else np.full(n, float(max_dist))
            out = np.empty((n, 3))
            kernels.cast(*self._compiled, origins, dirs, limits, out)
            d, p = out[:, 0], out[:, 1:]
        else:
            d, p, _ = self.contact.cast(origins, dirs, max_dist)
        self._book(t0, len(origins))
        return d, p

    def _book(self, t0, rays):
        """Count one cast of ``rays`` rays that started at ``t0``."""
        stats = self.stats
        stats.cast_seconds += time.perf_counter() - t0
        stats.casts += 1
        stats.rays += rays

    def _fan(self, joint, angles):
        """Rays from ``joint`` at ``angles`` over the probe length (through the
        contact model's fused ``fan`` when it has one: the same rays)."""
        fan = self._fused_fan
        if fan is not None:
            angles = np.asarray(angles, dtype=np.float64).reshape(-1)
            t0 = time.perf_counter()
            d, p = fan(joint, angles, self.length)
            stats = self.stats
            stats.cast_seconds += time.perf_counter() - t0
            stats.casts += 1
            stats.rays += len(angles)
            return d, p
        dirs = unit(angles).reshape(-1, 2)
        origins = np.empty_like(dirs)
        origins[:] = joint
        return self._cast(origins, dirs, self.length)

    # --------------------------------------------------------------- sensing
    def sense(self, event="done", **extra) -> Reading:
        """Read the tactile skin and the torque sensor at the current pose.

        Tactile skin: a ray from the tip along t (reach ``tol``) and the two
        rays of the torque check below; contacts on the probe (distance from
        the joint <= L) are reported with their face.

        Torque sensor (§3.2): is a small rotation about the joint, moving the
        tip sideways by ``tol``, blocked? The probe is held in contact, so
        the check is made with the tip pressed onto the surface it touches:
        the rotated ray from the joint reaches as far as the tip's contact
        (L + gap, the gap being the tip's stand-off along t). A rotation is
        blocked when the rotated ray meets the surface before that depth: the
        surface rises towards the joint on that side (a slope, Fig. 10(b), or
        the other face of a concave corner within ``tol`` of the tip,
        Fig. 10(a)). On a surface normal to the probe the tip's arc lifts off
        it and both rotations are free. Without a tip contact only contacts
        on the probe itself (distance <= L) block.
        """
        alpha = self.tol / self.length
        th, L, tol = self.theta, self.length, self.tol
        c, sn = math.cos(th), math.sin(th)
        jx, jy = float(self.joint[0]), float(self.joint[1])
        if self._compiled is not None:  # the same rays in compiled code
            out = np.empty((3, 3))
            t0 = time.perf_counter()
            kernels.sense_rays(*self._compiled, jx, jy, th, alpha, L, tol, out)
            self._book(t0, 3)
            d, p = out[:, 0], out[:, 1:]
        else:
            origins = np.array(((jx, jy), (jx, jy), (jx + L * c, jy + L * sn)))
            dirs = np.array(((math.cos(th + alpha), math.sin(th + alpha)),
                             (math.cos(th - alpha), math.sin(th - alpha)), (c, sn)))
            d, p = self._cast(origins, dirs, np.array((L + tol, L + tol, tol)))
        t = np.array((c, sn))
        d = d.tolist()
        tip_touch = d[2] < math.inf
        reach = L + (d[2] - 1e-3 * self.tol if tip_touch else 0.0)
        contacts = []
        if tip_touch:
            contacts.append(Contact(p[2], TIP, L))
        for k, face in ((0, RIGHT), (1, LEFT)):
            if d[k] <= L:
                f = TIP if L - d[k] <= self.tip_zone else face
                if not any(np.linalg.norm(q.point - p[k]) <= self.tip_zone for q in contacts):
                    contacts.append(Contact(p[k], f, d[k]))
        primary = extra.pop("primary", None)
        if primary is not None:
            contacts = [primary] + [
                c for c in contacts if np.linalg.norm(c.point - primary.point) > self.tip_zone
            ]
        return Reading(
            joint=self.joint.copy(),
            direction=t,
            contacts=tuple(contacts),
            blocked_ccw=d[0] <= reach,
            blocked_cw=d[1] <= reach,
            event=event,
            **extra,
        )

    def _contact_at(self, dist, point, rot_dir) -> Contact:
        """Contact found by a ray from the joint blocking rotation ``rot_dir``."""
        if self.length - dist <= self.tip_zone:
            return Contact(point, TIP, float(dist))
        return Contact(point, RIGHT if rot_dir > 0 else LEFT, float(dist))

    def _run_kernel(self, kernel, *args):
        """Call a compiled search (:mod:`core2d.sim.kernels`) and book its
        casts, rays and time as the Python path would."""
        count = self._count
        count[:] = 0
        t0 = time.perf_counter()
        out = kernel(*self._compiled, *args, self._par, self._work, count)
        stats = self.stats
        stats.cast_seconds += time.perf_counter() - t0
        stats.casts += int(count[0])
        stats.rays += int(count[1])
        stats.pushes += int(count[2])
        stats.push_attempts += int(count[3])
        return out

    # --------------------------------------------------------------- motions
    def _motion(self):
        self.stats.motions += 1

    def approach(self, point, direction) -> Reading:
        """Move through F to the line through ``point`` along ``direction``,
        tip retracted to the workspace circle (a free transfer motion)."""
        self._motion()
        t = np.asarray(direction, float) / np.linalg.norm(direction)
        w = np.asarray(point, float) - self.center
        b = w @ t
        disc = b * b - (w @ w - self.radius**2)
        s = -b - np.sqrt(disc) if disc > 0 else -b  # circle entry along the line
        tip = np.asarray(point, float) + (s - self.tol) * t
        joint = tip - self.length * t
        self.stats.joint_path += float(np.linalg.norm(joint - self.joint))
        self.joint, self.theta = joint, angle_of(t)
        return self.sense()

    def insert(self, max_dist=None) -> Reading:
        """Insert along t until the tip touches (or ``max_dist``)."""
        self._motion()
        max_dist = 2.5 * self.radius if max_dist is None else float(max_dist)
        d, p = self._cast(self.tip[None], self.direction[None], max_dist)
        move = max_dist if not np.isfinite(d[0]) else max(0.0, d[0] - self.tol / 2)
        self.joint = self.joint + move * self.direction
        self.stats.joint_path += move
        if np.isfinite(d[0]):
            return self.sense("contact", primary=Contact(p[0], TIP, self.length))
        return self.sense("done")

    def swing(self, rot_dir, max_angle) -> Reading:
        """Rotate about the joint (``rot_dir`` +1 ccw, -1 cw) until contact
        or ``max_angle``."""
        self._motion()
        found = self._search(self.joint, self.theta, rot_dir, max_angle)
        if found is None:
            self.theta += rot_dir * max_angle
            return self.sense("done", angle=rot_dir * max_angle)
        free, (d, p) = found
        angle = free - self.theta
        self.theta = free
        return self.sense("contact", primary=self._contact_at(d, p, rot_dir), angle=angle)

    def turn_to(self, theta) -> Reading:
        """Swing to absolute angle ``theta`` (stops early at a contact)."""
        delta = (theta - self.theta + np.pi) % (2 * np.pi) - np.pi
        return self.swing(1 if delta >= 0 else -1, abs(delta))

    def pivot(self, rot_dir, max_angle) -> Reading:
        """Rotate about the tip (Definition 1, single probe detection): the
        probe line sweeps around the fixed tip until it touches."""
        self._motion()
        tip = self.tip
        back = self.theta + np.pi
        found = self._search_from(tip, back, rot_dir, max_angle)
        new_back = back + rot_dir * (max_angle if found is None else found[0])
        joint = tip + self.length * unit(new_back)
        self.stats.joint_path += self.length * abs(new_back - back)
        self.joint, self.theta = joint, new_back - np.pi
        return self.sense("done" if found is None else "contact", angle=new_back - back)

    def _search_from(self, origin, theta0, rot_dir, max_angle):
        """Like :meth:`_search` for rays from ``origin`` (offset by tol), at
        the fan spacing, in windows of at most 8192 rays."""
        step = self.fan_step
        n = max(1, int(np.ceil(max_angle / step)))
        if self._compiled is not None:  # the same rays and windows, compiled
            off = self._run_kernel(kernels.search_from, float(origin[0]), float(origin[1]),
                                   float(theta0), float(rot_dir), float(max_angle), n,
                                   self.tol)
            return None if off < 0 else (off,)
        for lo in range(0, n, _WINDOWS[-1]):
            k = np.arange(lo + 1, min(n, lo + _WINDOWS[-1]) + 1)
            dirs = unit(theta0 + rot_dir * np.minimum(k * step, max_angle))
            d, _ = self._cast(origin + self.tol * dirs, dirs, self.length)
            hit = np.isfinite(d)
            if hit.any():
                return ((lo + int(np.argmax(hit))) * step,)
        return None

    def translate(self, v, dist) -> Reading:
        """Translate the joint along unit ``v`` by up to ``dist`` keeping t.

        Parallel rays from samples along the probe (spacing eps/4 inside the
        workspace) find the first obstacle; the probe stops tol/2 short."""
        self._motion()
        v = np.asarray(v, float) / np.linalg.norm(v)
        along = self._samples_along()
        pts = self.joint + along[:, None] * self.direction
        d, p = self._cast(pts, np.broadcast_to(v, pts.shape), dist)
        if not np.isfinite(d).any():
            self.joint = self.joint + dist * v
            self.stats.joint_path += dist
            return self.sense("done")
        i = int(np.argmin(d))
        move = max(0.0, d[i] - self.tol / 2)
        self.joint = self.joint + move * v
        self.stats.joint_path += move
        face = TIP if i == len(along) - 1 else (
            LEFT if self.direction[0] * v[1] - self.direction[1] * v[0] < 0 else RIGHT)
        return self.sense("blocked", primary=Contact(p[i], face, float(along[i])))

    def _samples_along(self) -> np.ndarray:
        """Distances along the probe that lie inside the workspace circle."""
        t = self.direction
        w = self.joint - self.center
        b = w @ t
        disc = b * b - (w @ w - self.radius**2)
        if disc <= 0:
            return np.array([self.length])
        lo = max(0.0, -b - np.sqrt(disc))
        hi = min(self.length, -b + np.sqrt(disc))
        n = max(2, int(np.ceil((hi - lo) / (self.eps / 4))) + 1)
        return np.concatenate([np.linspace(lo, hi, n), [self.length]])

    def trace(self, v, tau, max_dist, **kw) -> Reading:
        """Compliant tracing step sequence; see :func:`core2d.sim.compliance.compliant_trace`."""
        from core2d.sim.compliance import compliant_trace

        return compliant_trace(self, v, tau, max_dist, **kw)
