"""W2 chords the probe has passed through: openings, not contour, for the free lines.

The robot's map (:class:`~core2d.planner.known.KnownContour`) holds every W2
chord it closed, and :meth:`~core2d.planner.known.KnownContour.free_lines`
lets no line through one: with Dist(A_i, B_i) < eps the contour behind a
chord lies within eps of it (§3.1), and a line crossing the chord crosses
that contour too. A noisy sensor closes W2 up to eps + jitter
(:attr:`~core2d.resolution.Resolution.w2_dist`), and a chord read in that
band can span a real opening a little wider than eps. The mouth of a
slot 1.45 eps wide, read 1.24 eps across from a reading of one corner that
lay 0.26 eps inside the mouth, was closed W2 (a Case 2-3 child, ``comb``
outline seed 1, sigma 0.1 eps, sensor seed 1001). The robot then went into
the slot through the mouth anyway. But every revisit pass later planned
into the slot had to pass the 0.26 eps the chord left open: only lines
slanting away from the far wall did, and 9 eps of that wall were never
touched (0.976).

The robot knows the chord is no contour when its own probe went through
it. An insertion moves the rod along its axis, so the rod sweeps the
segment from the joint where the insertion began to the tip where it ended
(the joint pose and the probe length). Take a W2 chord longer than
eps (there is none with perfect sensing). If such a sweep crosses it, it is
an opening the probe passed, under three conditions:

* the sweep crosses steeply, at more than 45°. A rod running along a wall
  crosses a wall chord at a few degrees;
* it crosses well inside the chord, farther than eps/4 from both ends;
* it goes on beyond the chord by more than the same-contact radius
  eps/2 + jitter. The chord's ends are readings, so a chord laid along a
  wall can lie a little in front of it, and an insertion whose tip stopped
  on that wall just behind the chord crosses it. On the ``islands``
  outline seed 1 at sigma 0.1, five chords were opened without this
  condition and the run took 2.002 x its noiseless motions. With it, two
  were opened and the run took 1.986 x.

:func:`soften_passed` marks such a chord, and the free lines go through it
(:meth:`~core2d.planner.known.KnownContour.soften`).
It stays W2 in the result and on the map for every other question (the
chains, the loose ends, the distances). The free lines serve the revisit's
passes and its W3 proof. A chord that blocks fewer lines can only make that
proof harder to pass.

It acts while two readings of one point resolve eps/2
(:func:`~core2d.planner.grazing.resolves_half_eps`), as the other rules of a
fine sensor do. At sigma 0.3 eps with taxels 0.25 eps it held every target
over six sensor seeds, but it gained no coverage (case runs meeting 0.98:
164 -> 166 of 210; pooled coverage within +-0.001). It cost 2.5 % more motions, and 6.6 %
on the ``comb`` scene, whose costliest slice already runs 17,211 of its
20,000 motions.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # the planner state that drives this module; typing only
    from core2d.planner.run import Exploration

__all__ = ["SweptRobot", "crossed", "soften_passed", "MIN_SIN"]

#: a sweep crosses a chord steeply when the sine of their angle is at least this (45°)
MIN_SIN = np.sqrt(0.5)


class SweptRobot:
    """The robot (:class:`~core2d.planner.robot.Robot`), logging what each insertion
    swept: the segment from the joint pose before it to the tip after it.

    Every attribute and motion is the robot's own; ``sweeps()`` gives the log as
    ((n, 2) float starts, (n, 2) float ends).
    """

    def __init__(self, robot):
        self._robot = robot
        self._starts: list = []
        self._ends: list = []

    def __getattr__(self, name):
        return getattr(self._robot, name)

    def insert(self, max_dist=None):
        """The robot's insertion (§3.2), its sweep logged."""
        start = np.array(self._robot.joint, dtype=float)
        reading = self._robot.insert(max_dist)
        self._starts.append(start)
        self._ends.append(np.array(self._robot.tip, dtype=float))
        return reading

    def sweeps(self) -> tuple[np.ndarray, np.ndarray]:
        """((n, 2) float, (n, 2) float): where each insertion's sweep began and ended."""
        if not self._starts:
            return np.zeros((0, 2)), np.zeros((0, 2))
        return np.asarray(self._starts), np.asarray(self._ends)


def crossed(a, b, starts, ends, margin: float, beyond: float) -> bool:
    """Does any segment ``starts[i]`` -> ``ends[i]`` ((n, 2) float each) cross the chord
    ``a`` -> ``b`` at more than 45°, farther than ``margin`` from both ends, and go on
    farther than ``beyond`` past it?

    >>> crossed((0, 0), (1.2, 0), [[0.6, 5.0]], [[0.6, -3.0]], 0.25, 1.0)  # straight in
    True
    >>> crossed((0, 0), (1.2, 0), [[0.1, 5.0]], [[0.1, -3.0]], 0.25, 1.0)  # by an end
    False
    >>> crossed((0, 0), (1.2, 0), [[-4.0, 0.1]], [[5.0, -0.1]], 0.25, 1.0)  # along it
    False
    >>> crossed((0, 0), (1.2, 0), [[0.6, 5.0]], [[0.6, -0.4]], 0.25, 1.0)  # a tip just behind
    False
    """
    a, b = np.asarray(a, float), np.asarray(b, float)
    p, q = np.asarray(starts, float).reshape(-1, 2), np.asarray(ends, float).reshape(-1, 2)
    ab, pq = b - a, q - p
    den = ab[0] * pq[:, 1] - ab[1] * pq[:, 0]
    lengths = np.hypot(*ab) * np.hypot(pq[:, 0], pq[:, 1])
    steep = np.abs(den) >= MIN_SIN * lengths
    ap = p - a
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (ap[:, 0] * pq[:, 1] - ap[:, 1] * pq[:, 0]) / den  # along the chord
        t = (ap[:, 0] * ab[1] - ap[:, 1] * ab[0]) / den  # along the sweep
    inner = margin / max(float(np.hypot(*ab)), 1e-300)
    past = (1.0 - t) * np.hypot(pq[:, 0], pq[:, 1])  # how far the sweep goes on beyond it
    return bool((steep & (s > inner) & (s < 1.0 - inner) & (t >= 0.0) & (past > beyond)).any())


def soften_passed(run: Exploration) -> int:
    """Mark on the map every W2 chord longer than eps that an insertion of the probe
    has crossed (see the module doc); returns how many were marked now.

    ``run.band_w2`` holds [map piece, sweeps already looked at] per chord not marked
    yet: each sweep is checked against each chord once."""
    if not isinstance(run.probe, SweptRobot) or not run.band_w2:
        return 0
    starts, ends = run.probe.sweeps()
    done, left = 0, []
    for piece, seen in run.band_w2:
        a, b = run.known.pieces[piece][0], run.known.pieces[piece][-1]
        if crossed(a, b, starts[seen:], ends[seen:], run.eps / 4.0, run.res.tip_zone):
            run.known.soften(piece)
            done += 1
        else:
            left.append([piece, len(starts)])
    run.band_w2 = left
    return done
