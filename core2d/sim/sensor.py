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

from core2d.readings import TIP, Contact, Reading

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

        >>> SensorModel(noise=0.3, reads=9).read_noise
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
        self.noise = model.read_noise  # the means of ``model.reads`` reads
        self.torque_noise = model.read_torque_noise
        self.count = 0  # reads taken: reading points x model.reads (not for perfect sensing)

    def _key(self, joint, direction) -> None:
        """Keyed streams: the generator restarted at the state that the seed, the true
        posture (``joint``, ``direction``) and the number of earlier reads of it give
        (BLAKE2b of the three; PCG64's state is 128 bits)."""
        pose = struct.pack("<Q4d", self.model.seed % 2**64, *joint, *direction)
        n = self._reads.get(pose, 0)
        self._reads[pose] = n + 1
        digest = hashlib.blake2b(pose + struct.pack("<Q", n), digest_size=16).digest()
        state = self.rng.bit_generator.state
        state["state"]["state"] = int.from_bytes(digest, "little")
        state["has_uint32"] = state["uinteger"] = 0
        self.rng.bit_generator.state = state

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
