"""core2d: pure 2D pulling-motion tactile sensing (Kaneko & Tsuji, WAFR 2000).

Three rooms, each with its own subpackage and its own import rules (checked
by ``tests/test_core2d_walls.py``):

* :mod:`core2d.sim` -- the probe simulator. It owns the geometry (a
  :class:`~core2d.sim.contact.ContactModel`) and returns sensor readings.
* :mod:`core2d.planner.run` -- the paper's algorithm. It decides motions from
  sensor readings (:mod:`core2d.readings`) and its own records only; it
  imports neither the simulator nor the ground truth.
* :mod:`core2d.truth` -- ground truth: exact reachability and metrics of a
  result against the true contour. Never seen by the planner.

:func:`sense_slice` (:mod:`core2d.sense`) puts the simulator and the planner
together; :mod:`core2d.planar`, :mod:`core2d.readings`,
:mod:`core2d.resolution` (every tolerance derived from eps and tol) and
:mod:`core2d.result` are the plain data and maths they share. The planner
is typed against the probe protocol :class:`core2d.planner.robot.Robot`,
which the simulator's :class:`~core2d.sim.probe.Probe` implements.
"""
from core2d.readings import Contact, Reading
from core2d.resolution import Resolution
from core2d.result import AreaRecord, SenseStats, SliceResult
from core2d.sense import sense_slice
from core2d.sim.contact import ContactModel
from core2d.sim.probe import Probe
from core2d.sim.sensor import SensorModel

__all__ = [
    "ContactModel", "Probe", "Contact", "Reading", "sense_slice",
    "SliceResult", "SenseStats", "AreaRecord", "Resolution", "SensorModel",
]
