"""Internal: the codes and constants shared by the Python and the compiled ray engines.

Both engines (:mod:`core2d.sim.search` in Python, :mod:`core2d.sim.kernels`
compiled) end a settle and a compliant trace with the same named codes, and
cast their fans in the same windows.

The kernels freeze these values when numba compiles them, and numba's cache
is keyed on ``kernels.py`` alone: after changing a value here, touch
``core2d/sim/kernels.py`` (or delete its ``__pycache__``) so they recompile.
"""
from __future__ import annotations

from enum import IntEnum

__all__ = ["TraceEvent", "Settle", "EVENTS", "WINDOWS", "REFINE"]


class TraceEvent(IntEnum):
    """Why the micro-steps of a compliant trace stopped (``Reading.event``)."""

    LIMIT = 0  #: the step budget of the motion ran out
    REACHED_BODY = 1  #: a part of the probe other than the tip reached P_fin
    PUSHING = 2  #: v.t > 0, intercepted by the guard (Case 3)
    DONE = 3  #: the joint travelled ``max_dist``
    BLOCKED = 4  #: the joint cannot move along v (Case 4)
    LOST = 5  #: no contact any more (Case 2-3)
    JUMP = 6  #: the contact point jumped (Case 2)
    REACHED = 7  #: the tip passed P_fin during a step
    LEFT = 8  #: the tip passed the other end of the designated area

    @property
    def label(self) -> str:
        """The event's name in a :class:`~core2d.readings.Reading`, e.g. ``"reached-body"``."""
        return self.name.lower().replace("_", "-")


class Settle(IntEnum):
    """How the probe settled on its joint after a micro-step."""

    OK = 0  #: swung or yielded to a contact
    LOST = 1  #: swung MAX_SETTLE without touching
    JAMMED = 2  #: no free angle within _MAX_YIELD against the torque


#: event labels by code
EVENTS = tuple(e.label for e in TraceEvent)
#: fan windows at the fan spacing (rays per cast), the last one the cap
WINDOWS = (8, 32, 128, 512, 2048, 8192)
#: rays per fan of the bisection inside a bracket
REFINE = 16
