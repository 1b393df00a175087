"""An object met once and never again: the bootstrap aimed at it.

The bootstrap (:mod:`core2d.planner.bootstrap`) inserts the probe from the workspace circle
towards its centre; an object small enough to lie between its insertions (an island, §3.2:
several objects in a slice) is met, if at all, by a later pass. With perfect sensing a revisit
pass's contact splits the lid it was aimed at wherever it lies, and the children's flow traces
the object. With a noisy sensor a contact met in front of the lid, farther from it than half
its length, does not split it (:func:`~core2d.planner.pass_contacts.in_reach`: it is more
often a wall the probe reached through a gap in a noisy record, and a split there lays the
children's lids across material). Such a contact is kept here as an *orphan* when it lies
farther than :data:`UNTOUCHED` eps from everything recorded.

When nothing else is left (after the revisit and the audit, :func:`seek`), an orphan still
that far from the record is contour no area holds: the robot bootstraps again, every
insertion from the workspace circle aimed at the orphan instead of the centre
(:func:`~core2d.planner.bootstrap.bootstrap`'s ``aim``), and its areas go through the paper's
flow like the first ones (those whose contour is recorded already close as traced). A round (a
call of :func:`seek`) makes one aimed bootstrap per group of orphans within :data:`UNTOUCHED`
eps of each other; at most :data:`MAX_SEEKS` rounds in a run. Perfect sensing never makes an orphan, so its runs are unchanged.

``vtk_42400-IDGH`` z-plane 2 of 5 at sigma 0.1 eps, sensor seed 2: a square island 2.5 eps
wide, 14 eps from every other object, which the first bootstrap's insertions passed by, was
met once by a revisit pass 31 eps in front of a lid 24 eps long, refused, and never touched
again (0.974 of the reachable contour within eps/2 + 2 sigma; 1.000 noiselessly).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from core2d.planner.bootstrap import bootstrap

if TYPE_CHECKING:  # the planner state that drives this module; typing only
    from core2d.planner.run import Exploration

__all__ = ["Orphans", "seek", "UNTOUCHED", "MAX_SEEKS"]

#: an orphan lies at least this many eps from every recorded piece
UNTOUCHED = 4.0
#: rounds of aimed bootstraps in one run
MAX_SEEKS = 2


@dataclass
class Orphans:
    """Contacts a revisit refused that lay far from the record: ``points`` (k, 2) as a list."""

    points: list = field(default_factory=list)
    rounds: int = 0

    def note(self, run: Exploration, point) -> None:
        """Keep ``point`` (2,) if it lies farther than :data:`UNTOUCHED` eps from the map."""
        p = np.asarray(point, dtype=np.float64)
        if run.known.distance(p) > UNTOUCHED * run.eps:
            self.points.append(p)


def seek(run: Exploration, count: int = 12) -> int:
    """Bootstrap again, aimed at each orphan still farther than :data:`UNTOUCHED` eps from
    the record (one aim per group of orphans within that of each other); returns how many
    areas were registered (module doc)."""
    orphans = run.orphans
    if orphans.rounds >= MAX_SEEKS or not orphans.points:
        return 0
    reach = UNTOUCHED * run.eps
    aims = []
    for p in orphans.points:
        if run.known.distance(p) > reach and all(np.hypot(*(p - q)) > reach for q in aims):
            aims.append(p)
    orphans.points = []
    if not aims:
        return 0
    orphans.rounds += 1
    added = 0
    for aim in aims:
        if not run.budget():
            break
        run.probe.note_phase("bootstrap")
        for area in bootstrap(run.probe, count, aim=aim):
            area.rule = "orphan"
            run.add(area)
            added += 1
    return added
