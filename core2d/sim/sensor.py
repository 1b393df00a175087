"""The sensors a robot really has: noisy contacts, taxels, noisy joint readings.

The paper assumes perfect sensing (§3.2): the distributed sensing elements
report the exact contact point, the joint position sensors the exact
posture (P, t). :class:`SensorModel` states how a real robot departs from
that, and :class:`Sensor` applies it to every :class:`~core2d.readings.Reading`
the simulator returns -- the planner sees only the degraded readings:

* **taxels** -- the skin is a row of sensing elements ``taxel`` apart along
  the probe; a contact is reported at the centre of the taxel that holds it.
  The tip is a taxel of its own, centred on the tip (a contact within
  ``taxel / 2`` of the tip along the probe is the tip's). The point is
  placed from the reported posture: ``P' + a t'`` with ``a`` the taxel's
  distance from the joint, plus the contact's offset across the probe.
* **contact noise** -- Gaussian, standard deviation ``noise`` per axis, on
  every reported contact point (the tip contacts of a compliant trace too).
* **joint readings** -- Gaussian noise on the joint position P (standard
  deviation ``noise``) and on the direction t (``noise / L`` radians, the
  same displacement at the tip): the joint position sensors' error.
* **repeated reads** -- ``reads`` N: the robot reads its skin, joint sensors
  and torque sensor N times at each reading point (a posture it stands in:
  after a motion, at each micro-step of a compliant trace) and takes the
  means. The mean of N independent Gaussian draws is one draw with the
  standard deviation divided by sqrt(N), and that one draw is what the
  simulator makes; the taxel's rounding is the same on every read and stays.
  :func:`core2d.resolution.repeated_reads` picks N from the data sheet.
* **torque sensor** -- the blocked-rotation readings of §3.2 (is a small
  rotation about the joint, moving the tip sideways by tol, blocked?). The
  simulator measures how deep the surface intrudes into that rotation,
  ``m`` (a length: ``reach - d`` of :meth:`core2d.sim.probe.Probe.sense`,
  negative when the rotation is free); the sensor reads ``max(m, 0)``
  plus Gaussian noise ``torque_noise`` and reports the rotation blocked when
  the reading is at least ``torque_threshold``. A threshold hides slight
  obstructions (a slope the check's tol-wide rotation barely touches); noise
  above the threshold makes a free rotation read blocked now and then. Both
  0 (the default) is the paper's torque sensor: blocked exactly when
  ``m >= 0``.

The simulator's own state (the true posture the rays are cast from) is
never perturbed: noise is a property of the readings, not of the world.
Every draw comes from one seeded generator, so a run is reproducible.

**Keyed streams** (``keyed=True``; common random numbers, for comparing two planners):
by default the draws follow one another, so a planner that adds or drops one motion
re-draws every later reading of the slice, and two planners differing in one rule
differ, run by run, by the whole lottery of the noise (+-0.01 to 0.03 of a slice's
coverage at sigma 0.3 eps). Keyed, each reading's draws come from a generator seeded by
the seed, the reading's true posture (P, t) and how many times that posture was read
before (a re-read is a fresh draw): a motion both planners make reads the same. Each
reading is still one independent draw of the same distribution: over many runs the two
modes give the same figures, run by run they differ.
"""
from __future__ import annotations

import hashlib
import math
import struct
from dataclasses import dataclass, replace

import numpy as np

from core2d.readings import TIP, Contact, Reading, Rereads

__all__ = ["SensorModel", "Sensor"]


@dataclass(frozen=True)
class SensorModel:
    """A robot's sensor data sheet (lengths in the slice's units).

    noise : float -- standard deviation of contact positions and of the
        joint position reading (0: exact).
    taxel : float -- spacing of the tactile elements along the probe
        (0: a continuous skin).
    seed : int -- seed of the noise.
    torque_threshold : float -- smallest intrusion of the surface into the
        torque check's rotation (a length) read as blocked (0: any contact).
    torque_noise : float -- standard deviation of that reading (a length).
    keyed : bool -- each reading's draws keyed by its true posture and how often that
        posture was read (common random numbers; see the module doc), instead of one
        stream of draws.
    reads : int -- how many reads the robot averages at each reading point (1: one
        read; see the module doc). The noise of the means is :attr:`read_noise`.

    >>> SensorModel.of_eps(2.0, noise=0.1, taxel=0.25).taxel
    0.5
    """

    noise: float = 0.0
    taxel: float = 0.0
    seed: int = 0
    torque_threshold: float = 0.0
    torque_noise: float = 0.0
    keyed: bool = False
    reads: int = 1

    @classmethod
    def of_eps(cls, eps: float, noise: float = 0.0, taxel: float = 0.0,
               seed: int = 0, torque_threshold: float = 0.0,
               torque_noise: float = 0.0, keyed: bool = False,
               reads: int = 1) -> SensorModel:
        """The model with ``noise``, ``taxel`` and the torque figures given as
        multiples of eps."""
        return cls(float(noise) * eps, float(taxel) * eps, int(seed),
                   float(torque_threshold) * eps, float(torque_noise) * eps, bool(keyed),
                   int(reads))

    @property
    def read_noise(self) -> float:
        """noise / sqrt(reads): the standard deviation of a reading point's means.

        >>> round(SensorModel(noise=0.3, reads=9).read_noise, 12)
        0.1
        """
        return self.noise / math.sqrt(self.reads)

    @property
    def read_torque_noise(self) -> float:
        """torque_noise / sqrt(reads): the same for the torque check's reading."""
        return self.torque_noise / math.sqrt(self.reads)

    @property
    def exact_torque(self) -> bool:
        """The paper's torque sensor: no threshold, no noise."""
        return self.torque_threshold == 0 and self.torque_noise == 0

    @property
    def ideal(self) -> bool:
        """The paper's perfect sensing (§3.2): nothing to apply."""
        return self.noise == 0 and self.taxel == 0 and self.exact_torque

    def reseeded(self, *keys: int) -> SensorModel:
        """The same model with a seed derived from ``seed`` and ``keys`` (one
        stream per slice: results do not depend on the order slices run in)."""
        seq = np.random.SeedSequence([self.seed, *[int(k) for k in keys]])
        return replace(self, seed=int(seq.generate_state(1)[0]))

    def as_dict(self) -> dict:
        return {"noise": float(self.noise), "taxel": float(self.taxel), "seed": int(self.seed),
                "torque_threshold": float(self.torque_threshold),
                "torque_noise": float(self.torque_noise), "keyed": bool(self.keyed),
                "reads": int(self.reads)}


class Sensor:
    """Applies a :class:`SensorModel` to readings (one seeded generator, or one per
    reading when the model is ``keyed``).

    Parameters
    ----------
    model : SensorModel
    length : float -- probe length L (direction noise is ``noise / L``).
    """

    def __init__(self, model: SensorModel, length: float):
        self.model = model
        self.length = float(length)
        self.rng = np.random.default_rng(model.seed)
        self._reads: dict[bytes, int] = {}  # keyed: times each true posture was read
        self._inc = self.rng.bit_generator.state["state"]["inc"]  # PCG64's, for _restart
        self.noise = model.read_noise  # the means of ``model.reads`` reads
        self.torque_noise = model.read_torque_noise
        self.count = 0  # reads taken: reading points x model.reads (not for perfect sensing)

    def _key(self, joint, direction, count: int = 1) -> tuple[bytes, int]:
        """Keyed streams: the generator restarted at the state that the seed, the true
        posture (``joint``, ``direction``) and the number of earlier reads of it give
        (BLAKE2b of the three; PCG64's state is 128 bits). ``count`` > 1: as many reads
        booked at once, the generator restarted for the first; each later one by
        :meth:`_restart` with the number it is given."""
        pose = struct.pack("<Q4d", self.model.seed % 2**64, *joint, *direction)
        n = self._reads.get(pose, 0)
        self._reads[pose] = n + count
        self._restart(pose, n)
        return pose, n

    def _restart(self, pose: bytes, n: int) -> None:
        """Restart the generator at the state of the ``n``-th read of ``pose`` (its
        increment, which the seed fixed, kept)."""
        digest = hashlib.blake2b(pose + struct.pack("<Q", n), digest_size=16).digest()
        self.rng.bit_generator.state = {
            "bit_generator": "PCG64", "has_uint32": 0, "uinteger": 0,
            "state": {"state": int.from_bytes(digest, "little"), "inc": self._inc}}

    def _jitter(self, shape) -> np.ndarray:
        return self.rng.normal(0.0, self.noise, shape) if self.noise else np.zeros(shape)

    def pose(self, joint, direction) -> tuple[np.ndarray, np.ndarray]:
        """Reported (P, t): (2,) joint and (2,) unit direction."""
        if not self.noise:
            return np.array(joint, float), np.array(direction, float)
        ang = math.atan2(direction[1], direction[0]) + self.rng.normal(
            0.0, self.noise / self.length)
        return np.asarray(joint, float) + self._jitter(2), np.array((math.cos(ang),
                                                                     math.sin(ang)))

    def along(self, along: float) -> float:
        """Distance from the joint of the taxel centre holding a contact at ``along``."""
        T = self.model.taxel
        if not T:
            return float(along)
        return self.length - round((self.length - along) / T) * T

    def contact(self, c: Contact, joint, direction, seen) -> Contact:
        """The reported contact ``c`` of the true posture (``joint``,
        ``direction``), placed from the reported posture ``seen``."""
        t = np.asarray(direction, float)
        n = np.array((-t[1], t[0]))
        rel = np.asarray(c.point, float) - joint
        a, b = float(rel @ t), float(rel @ n)
        if self.model.taxel:
            a = self.along(min(a, self.length))
        P, u = seen
        point = P + a * u + b * np.array((-u[1], u[0])) + self._jitter(2)
        face = TIP if self.model.taxel and a >= self.length else c.face
        return Contact(point, face, float(min(a, self.length)))

    def blocked(self, intrusion) -> tuple[bool, bool]:
        """(blocked_ccw, blocked_cw) the torque sensor reports for the
        surface's intrusion ``m`` (2,) into the ccw / cw check rotation
        (lengths, negative or -inf: free; see the module doc)."""
        m = np.asarray(intrusion, dtype=np.float64)
        if self.model.exact_torque:
            return bool(m[0] >= 0), bool(m[1] >= 0)
        read = np.maximum(m, 0.0)
        if self.torque_noise:
            read = read + self.rng.normal(0.0, self.torque_noise, 2)
        got = read >= self.model.torque_threshold
        return bool(got[0]), bool(got[1])

    def reading(self, r: Reading, intrusion=None) -> Reading:
        """``r`` as the sensors report it; ``intrusion`` (2,): the true
        torque-check intrusions (ccw, cw), re-read by :meth:`blocked` when
        the torque sensor is not the paper's."""
        if self.model.ideal:
            return r
        self.count += self.model.reads * (1 + len(r.trace))
        if self.model.keyed:
            self._key(r.joint, r.direction)
        if intrusion is not None and not self.model.exact_torque:
            ccw, cw = self.blocked(intrusion)
            r = replace(r, blocked_ccw=ccw, blocked_cw=cw)
        if not (self.model.noise or self.model.taxel):
            return r
        seen = self.pose(r.joint, r.direction)
        contacts = tuple(self.contact(c, r.joint, r.direction, seen) for c in r.contacts)
        kw = {}
        if len(r.trace):  # tip contacts of a compliant trace: the tip taxel, noisy
            kw["trace"] = np.asarray(r.trace, float) + self._jitter(np.shape(r.trace))
        if r.before_joint is not None:
            kw["before_joint"], kw["before_direction"] = self.pose(r.before_joint,
                                                                   r.before_direction)
        return replace(r, joint=seen[0], direction=seen[1], contacts=contacts, **kw)

    def readings(self, r: Reading, intrusion=None, count: int = 1) -> Rereads:
        """``count`` reads of the one true reading ``r`` (a probe standing still) as
        :class:`~core2d.readings.Rereads`: what ``count`` calls of :meth:`reading`
        report of the joint, the tip's contact and the torque, the same draws in the
        same order, made in one call of the generator per reading point (keyed) or per
        ``count`` (one stream) instead of one per contact and axis.

        Every value is computed as :meth:`reading` computes it (``s z`` for a draw ``z``
        of scale ``s``, as numpy's ``normal(0, s)`` makes it, the same sums in the same
        order, ``math`` for the angle), so each read is the same to the bit
        (``tests/test_core2d_sensor_rereads.py``); the body's contacts are drawn (the
        stream goes on as after ``count`` readings) and not placed. A reading with a
        trace or a posture before it takes :meth:`reading` one by one.

        Examples
        --------
        >>> from core2d.readings import Contact
        >>> r = Reading(np.zeros(2), np.array([0.0, 1.0]), (Contact(np.array([0.0, 5.0]), TIP, 5.0),))
        >>> one, two = Sensor(SensorModel(noise=0.1, seed=3), 5.0), Sensor(SensorModel(noise=0.1, seed=3), 5.0)
        >>> a = [one.reading(r).tip_contact.point for _ in range(3)]
        >>> bool(np.array_equal(a, two.readings(r, None, 3).tip))
        True
        """
        model = self.model
        if model.ideal or count < 1 or len(r.trace) or r.before_joint is not None:
            return Rereads.of([self.reading(r, intrusion) for _ in range(max(count, 0))])
        self.count += model.reads * count
        torque = intrusion is not None and not model.exact_torque
        shaken = torque and bool(self.torque_noise)
        placed = bool(model.noise or model.taxel)
        moved = placed and bool(self.noise)
        width = 2 * shaken + (3 + 2 * len(r.contacts)) * moved
        if model.keyed:
            z = np.empty((count, width))
            pose, first = self._key(r.joint, r.direction, count)
            for i in range(count):
                if i:
                    self._restart(pose, first + i)
                z[i] = self.rng.standard_normal(width)
        else:
            z = self.rng.standard_normal((count, width))
        blocked = np.tile((r.blocked_ccw, r.blocked_cw), (count, 1))
        if torque:
            read = np.maximum(np.asarray(intrusion, dtype=np.float64), 0.0)
            if shaken:
                read = read + self.torque_noise * z[:, :2]
            blocked = np.broadcast_to(read >= model.torque_threshold, (count, 2)).copy()
        tip = r.tip_contact
        if not placed:
            joints = np.tile(np.asarray(r.joint, float), (count, 1))
            dirs = np.tile(np.asarray(r.direction, float), (count, 1))
            tips = np.tile((np.nan, np.nan) if tip is None else tip.point, (count, 1)).astype(float)
            return Rereads(joints, dirs, tips, blocked)
        joints, dirs = self._poses(r.joint, r.direction, z[:, 2 * shaken:], count)
        tips = np.full((count, 2), np.nan)
        t = np.asarray(r.direction, float)
        n = np.array((-t[1], t[0]))
        for j, c in enumerate(r.contacts):  # the first whose taxel is the tip's
            rel = np.asarray(c.point, float) - r.joint
            a, b = float(rel @ t), float(rel @ n)
            if model.taxel:
                a = self.along(min(a, self.length))
            if (TIP if model.taxel and a >= self.length else c.face) != TIP:
                continue
            perps = np.column_stack((-dirs[:, 1], dirs[:, 0]))
            tips = joints + a * dirs + b * perps
            if moved:
                k = 2 * shaken + 3 + 2 * j
                tips = tips + self.noise * z[:, k:k + 2]
            else:  # reading() adds its zero jitter too (-0.0 + 0.0 is 0.0)
                tips = tips + np.zeros(2)
            break
        return Rereads(joints, dirs, tips, blocked)

    def _poses(self, joint, direction, z, count) -> tuple[np.ndarray, np.ndarray]:
        """(count, 2) reported joints and directions, as :meth:`pose` gives them one by
        one from the draws ``z`` (count, >= 3): the angle's, then the joint's two."""
        if not self.noise:
            return (np.tile(np.asarray(joint, float), (count, 1)),
                    np.tile(np.asarray(direction, float), (count, 1)))
        base = math.atan2(direction[1], direction[0])
        angles = base + (self.noise / self.length) * z[:, 0]
        dirs = np.array([(math.cos(ang), math.sin(ang)) for ang in angles.tolist()])
        return np.asarray(joint, float) + self.noise * z[:, 1:3], dirs
