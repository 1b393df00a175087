"""The simulator's ray engine: one interface, two implementations.

Every ray the probe simulator casts goes through an :class:`Engine`, chosen
once when the probe is built (:func:`make_engine`):

* :class:`~core2d.sim.compiled.CompiledEngine` when the contact model
  offers a ray function (``ray_kernel``: the Embree and exact backends): the searches,
  the settles and the micro-steps of a compliant trace run compiled
  (:mod:`core2d.sim.kernels`);
* :class:`~core2d.sim.search.PythonEngine` otherwise: the same searches in
  Python over the contact model's batched ``cast``.

Both cast the same rays and count the same casts, rays and pushes into the
probe's :class:`~core2d.result.SenseStats`; results are identical.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Protocol

import numpy as np

from core2d.readings import Contact
from core2d.resolution import Resolution
from core2d.result import SenseStats
from core2d.sim.codes import TraceEvent
from core2d.sim.compiled import CompiledEngine
from core2d.sim.contact import ContactModel
from core2d.sim.search import PythonEngine

if TYPE_CHECKING:  # the probe drives the engine; typing only
    from core2d.sim.probe import Probe

__all__ = ["Engine", "make_engine"]

Hits = tuple[np.ndarray, np.ndarray]  # (distances (n,), points (n, 2)); inf / nan: no hit


class Engine(Protocol):
    """What the probe asks of its ray engine (angles in radians, ccw positive)."""

    stats: SenseStats  # casts, rays, cast time and pushes are booked here

    def cast(self, origins: np.ndarray, dirs: np.ndarray,
             max_dist: np.ndarray | float) -> Hits:
        """One batch of rays, as the contact model's ``cast``."""

    def sense_rays(self, jx: float, jy: float, th: float, alpha: float, L: float,
                   tol: float) -> Hits:
        """The three rays of a reading: from the joint at ``th +- alpha`` up
        to L + tol, from the tip along t up to tol."""

    def contact_at(self, dist: float, point: np.ndarray, rot_dir: int) -> Contact:
        """The contact of a ray from the joint that blocks rotation ``rot_dir``."""

    def search(self, joint: np.ndarray, theta0: float, rot_dir: int, max_angle: float,
               want_blocked: bool = True, first: Hits | None = None
               ) -> tuple[float, tuple[float, np.ndarray]] | None:
        """First angle from ``theta0`` towards ``rot_dir`` where the probe on
        ``joint`` becomes blocked (or free): ``(free angle, (dist, point))``."""

    def search_from(self, origin: np.ndarray, theta0: float, rot_dir: int,
                    max_angle: float) -> float | None:
        """Offset of the first ray from ``origin`` (a pivot about the tip) that hits."""

    def trace_steps(self, probe: Probe, v: np.ndarray, rot_dir: int, delta0: float,
                    max_dist: float, max_steps: int, guard_push: bool, last: Contact | None,
                    stop: np.ndarray | None, leave: np.ndarray | None
                    ) -> tuple[TraceEvent, list | np.ndarray, tuple, Contact | None]:
        """The micro-steps of a compliant trace (moves ``probe``); see
        :func:`core2d.sim.compliance.python_steps`."""


def make_engine(contact: ContactModel, stats: SenseStats, length: float,
                resolution: Resolution) -> Engine:
    """The compiled engine when ``contact`` has a ray function, else the Python one."""
    kernel = getattr(contact, "ray_kernel", None)  # optional (the Embree and exact backends)
    if kernel is not None:
        return CompiledEngine(contact, stats, length, resolution, kernel)
    return PythonEngine(contact, stats, length, resolution)
