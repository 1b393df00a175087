"""Probe simulator (§3.2): owns the geometry, returns sensor readings only.

A rigid probe of length L and negligible thickness hangs on a joint at
``joint`` and points along the unit vector t; the tip is ``joint + L t``.
Contacts come from a :class:`core2d.sim.contact.ContactModel` through batched
ray casts: a fan of rays from the joint for a swing, one ray from the tip for
an insertion, rays along the probe for a translation. Contacts are resolved
to ``tol`` by bisection with refining fans. No dynamics; friction at the
tip only when asked (``friction`` = mu, :mod:`core2d.sim.friction`: a
pushing trace step inside the friction cone jams). :attr:`stats.pushes`
counts the trace steps executed in sliding contact with v.t > 0,
:attr:`stats.jams` the pushing steps that jammed.

Every ray goes through the probe's ray engine (:mod:`core2d.sim.engine`),
chosen once here: compiled when the contact model has a ray function
(``ray_kernel``: the Embree and exact backends), Python otherwise -- the same rays, the
same answers, the same counts.
"""
from __future__ import annotations

import math

import numpy as np

from core2d.planar import angle_of, magnitude, unit
from core2d.readings import LEFT, RIGHT, TIP, Contact, Reading, Rereads
from core2d.resolution import Resolution
from core2d.result import SenseStats
from core2d.sim.compliance import compliant_trace
from core2d.sim.contact import ContactModel
from core2d.sim.engine import make_engine
from core2d.sim.sensor import Sensor, SensorModel

__all__ = ["Probe"]


class Probe:
    """Simulated tactile probe on a robot joint.

    It offers what the planner is typed against
    (:class:`core2d.planner.robot.Robot`): the motions, the joint pose, the
    robot's stated constants (``center``, ``radius``, ``length``,
    ``resolution``) and its cost counters (``motions``, :meth:`costs`).

    Parameters
    ----------
    contact : ContactModel
        Ray-cast backend (Embree, direct Embree, trimesh or exact).
    workspace : ((2,) float, float)
        Centre and radius of a circle containing the whole slice: the only
        prior knowledge of the robot.
    eps : float
        The paper's epsilon; fans are spaced eps/4 at the tip.
    length : float, optional
        Probe length L, default 2 x the workspace diameter so the joint
        always stays in the free area F.
    tol : float, optional
        Contact resolution, default eps / 20 (:meth:`Resolution.of`).
    sensor : SensorModel, optional
        How the readings depart from the truth (:mod:`core2d.sim.sensor`;
        default exact). Its stated noise and taxel spacing are part of the
        robot's ``resolution``.
    friction : float, optional
        Coulomb coefficient mu at the tip (default 0: frictionless, the
        paper's simulator); the planner is not told it.
    """

    def __init__(self, contact: ContactModel, workspace, eps: float,
                 length: float | None = None, tol: float | None = None,
                 sensor: SensorModel | None = None, friction: float = 0.0):
        self.contact = contact
        self.center = np.asarray(workspace[0], dtype=np.float64)
        self.radius = float(workspace[1])
        model = sensor if sensor is not None else SensorModel()
        # the robot's stated resolution (the planner's: the sensor's data
        # sheet included) and the simulator's own, exact one (its searches,
        # settles and jump tests resolve the true geometry)
        # (the noise of the means of ``model.reads`` reads per reading point)
        self.resolution = Resolution.of(eps, tol, model.read_noise, model.taxel,
                                        model.torque_threshold, model.read_torque_noise)
        self.exact = res = Resolution.of(eps, tol)
        self.eps, self.tol = res.eps, res.tol
        self.length = float(length if length is not None else 4.0 * self.radius)
        self.sensor = Sensor(model, self.length)
        self._ideal = model.ideal  # the paper's sensors: readings as simulated
        self.friction = float(friction)
        if not self.friction >= 0:
            raise ValueError(f"friction must be >= 0, got {friction!r}")
        self.stats = SenseStats()
        self.engine = make_engine(contact, self.stats, self.length, res)
        # the angular fan spacing and resolution of the searches, and the tip
        # zone: contacts closer than eps/2 are one contact at the paper's
        # resolution (§3.2: the contour is smooth at the eps level); near the
        # tip they are the tip's contact (a probe lying at a grazing angle).
        self.fan_step = res.fan_angle(self.length)
        self.ang_tol = res.angle_tol(self.length)
        self.tip_zone = res.tip_zone
        self.joint = self.center + np.array([0.0, self.length + 2 * self.radius])
        self.theta = -np.pi / 2

    @property
    def motions(self) -> int:
        """Motions executed so far (the controller's count)."""
        return self.stats.motions

    def costs(self) -> SenseStats:
        """A copy of the cost counters so far (motions, joint path, rays, pushes,
        sensor reads)."""
        return SenseStats(**{**vars(self.stats), "sensor_reads": self.sensor.count})

    def note_phase(self, phase: str, area: int = -1) -> None:
        """The planner's phase hook: the bare probe ignores it
        (:class:`core2d.sim.recorder.Recorder` logs it)."""

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

    # --------------------------------------------------------------- sensing
    def sense(self, event="done", exact=False, **extra) -> Reading:
        """Read the tactile skin and the torque sensor at the current pose,
        as the sensors report it (:mod:`core2d.sim.sensor`; ``exact``: the
        simulator's own, true reading).

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
        reading, intrusion = self._true(event, **extra)
        if exact or self._ideal:
            return reading
        return self.sensor.reading(reading, intrusion)

    def _true(self, event="done", **extra) -> tuple[Reading, tuple[float, float]]:
        """The true reading at the current pose (:meth:`sense` before the sensors) and
        the torque check's intrusions (ccw, cw): how far the surface reaches into each
        rotation (negative or -inf: free)."""
        th, L, tol, zone = self.theta, self.length, self.tol, self.tip_zone
        joint = self.joint
        d, p = self.engine.sense_rays(float(joint[0]), float(joint[1]), th, tol / L, L, tol)
        d0, d1, d2 = d.tolist()
        tip_touch = d2 < math.inf
        reach = L + (d2 - 1e-3 * tol if tip_touch else 0.0)
        contacts = [Contact(p[2], TIP, L)] if tip_touch else []
        for dk, k, face in ((d0, 0, RIGHT), (d1, 1, LEFT)):
            if dk <= L:
                pk = p[k]
                if not any(magnitude(q.point - pk) <= zone for q in contacts):
                    contacts.append(Contact(pk, TIP if L - dk <= zone else face, dk))
        primary = extra.pop("primary", None)
        if primary is not None:
            contacts = [primary] + [
                c for c in contacts if magnitude(c.point - primary.point) > zone
            ]
        reading = Reading(joint.copy(), np.array((math.cos(th), math.sin(th))), tuple(contacts),
                          blocked_cw=d1 <= reach, blocked_ccw=d0 <= reach, event=event, **extra)
        return reading, (reach - d0, reach - d1)

    def reread(self, count: int) -> Rereads:
        """``count`` more reads where the probe stands (no motion): what ``count`` calls
        of :meth:`sense` report of the joint, the tip's contact and the torque
        (:class:`~core2d.readings.Rereads`), the same draws in the same order, the same
        to the bit. Standing still, the true contacts and the torque check's
        intrusions do not change from one read to the next, only the sensors' draws:
        the rays are cast once (``stats.rays`` counts them once) and the draws are
        applied together, as arrays (:meth:`core2d.sim.sensor.Sensor.readings`). The
        planner's re-reads at a jump's P_2nd and at a pass's new contact (25 of them
        at sigma 0.1 eps) made 58 % of the CPU time of a noisy run one by one (``comb``
        z1 of 8, sigma 0.1 eps, keyed seed 1001; docs/notes/speed.md).
        """
        reading, intrusion = self._true()
        if self._ideal:
            return Rereads.of([reading] * count)
        return self.sensor.readings(reading, intrusion, count)

    # --------------------------------------------------------------- motions
    def _motion(self):
        self.stats.motions += 1

    def approach(self, point, direction) -> Reading:
        """Move through F to the line through ``point`` along ``direction``,
        tip retracted to the workspace circle (a free transfer motion)."""
        self._motion()
        t = np.asarray(direction, float)
        t = t / magnitude(t)
        w = np.asarray(point, float) - self.center
        b = w @ t
        disc = b * b - (w @ w - self.radius**2)
        s = -b - np.sqrt(disc) if disc > 0 else -b  # circle entry along the line
        tip = np.asarray(point, float) + (s - self.tol) * t
        joint = tip - self.length * t
        self.stats.joint_path += magnitude(joint - self.joint)
        self.joint, self.theta = joint, angle_of(t)
        return self.sense()

    def insert(self, max_dist=None) -> Reading:
        """Insert along t until the tip touches (or ``max_dist``)."""
        self._motion()
        max_dist = 2.5 * self.radius if max_dist is None else float(max_dist)
        d, p = self.engine.cast(self.tip[None], self.direction[None], max_dist)
        move = max_dist if not np.isfinite(d[0]) else max(0.0, d[0] - self.resolution.stop_short)
        self.joint = self.joint + move * self.direction
        self.stats.joint_path += move
        if np.isfinite(d[0]):
            return self.sense("contact", primary=Contact(p[0], TIP, self.length))
        return self.sense("done")

    def swing(self, rot_dir, max_angle) -> Reading:
        """Rotate about the joint (``rot_dir`` +1 ccw, -1 cw) until contact
        or ``max_angle``."""
        self._motion()
        found = self.engine.search(self.joint, self.theta, rot_dir, max_angle)
        if found is None:
            self.theta += rot_dir * max_angle
            return self.sense("done", angle=rot_dir * max_angle)
        free, (d, p) = found
        angle = free - self.theta
        self.theta = free
        return self.sense("contact", primary=self.engine.contact_at(d, p, rot_dir), angle=angle)

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
        found = self.engine.search_from(tip, back, rot_dir, max_angle)
        new_back = back + rot_dir * (max_angle if found is None else found)
        joint = tip + self.length * unit(new_back)
        self.stats.joint_path += self.length * abs(new_back - back)
        self.joint, self.theta = joint, new_back - np.pi
        return self.sense("done" if found is None else "contact", angle=new_back - back)

    def translate(self, v, dist) -> Reading:
        """Translate the joint along unit ``v`` by up to ``dist`` keeping t.

        Parallel rays from samples along the probe (spacing eps/4 inside the
        workspace) find the first obstacle; the probe stops tol/2 short."""
        self._motion()
        v = np.asarray(v, float) / np.linalg.norm(v)
        along = self._samples_along()
        pts = self.joint + along[:, None] * self.direction
        d, p = self.engine.cast(pts, np.broadcast_to(v, pts.shape), dist)
        if not np.isfinite(d).any():
            self.joint = self.joint + dist * v
            self.stats.joint_path += dist
            return self.sense("done")
        i = int(np.argmin(d))
        move = max(0.0, d[i] - self.resolution.stop_short)
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
        n = max(2, int(np.ceil((hi - lo) / self.resolution.fan_spacing)) + 1)
        return np.concatenate([np.linspace(lo, hi, n), [self.length]])

    def trace(self, v, tau, max_dist, **kw) -> Reading:
        """Compliant tracing step sequence; see :func:`core2d.sim.compliance.compliant_trace`."""
        return compliant_trace(self, v, tau, max_dist, **kw)
