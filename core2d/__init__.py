"""core2d: pure 2D pulling-motion tactile sensing (Kaneko & Tsuji, WAFR 2000).

The simulator (:class:`Probe`) owns the geometry and returns sensor readings;
the planner (:func:`sense_slice`) decides motions from those readings only.
Evaluation against ground truth lives in :mod:`core2d.reachability` and
:mod:`core2d.metrics` and is never used by the planner.
"""
from core2d.contact import ContactModel
from core2d.planner import sense_slice
from core2d.probe import Probe
from core2d.readings import Contact, Reading
from core2d.result import AreaRecord, SenseStats, SliceResult

__all__ = [
    "ContactModel", "Probe", "Contact", "Reading", "sense_slice",
    "SliceResult", "SenseStats", "AreaRecord",
]
