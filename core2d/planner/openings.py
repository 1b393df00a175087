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

    Every attribute and motion is the robot's own (its motions bound once, its pose
    read through); ``sweeps()`` gives the log as ((n, 2) float starts, (n, 2) float ends).
    """

    def __init__(self, robot):
        self._robot = robot
        self._starts: list = []
        self._ends: list = []
        for name in ("approach", "swing", "turn_to", "pivot", "trace", "sense", "costs",
                     "note_phase"):
            if hasattr(robot, name):
                setattr(self, name, getattr(robot, name))

    def __getattr__(self, name):  # anything else the robot has
        return getattr(self._robot, name)

    joint = property(lambda self: self._robot.joint)
    theta = property(lambda self: self._robot.theta)
    tip = property(lambda self: self._robot.tip)
    direction = property(lambda self: self._robot.direction)
    motions = property(lambda self: self._robot.motions)

    def insert(self, max_dist=None):
        """The robot's insertion (§3.2), its sweep logged."""
        start = np.array(self._robot.joint, dtype=float)
        reading = self._robot.insert(max_dist)
        self._starts.append(start)
        self._ends.append(np.array(self._robot.tip, dtype=float))
        return reading

    def sweeps(self, first: int = 0) -> tuple[np.ndarray, np.ndarray]:
        """((n, 2) float, (n, 2) float): where each insertion's sweep began and ended,
        from the ``first`` on."""
        if len(self._starts) <= first:
            return np.zeros((0, 2)), np.zeros((0, 2))
        return np.asarray(self._starts[first:]), np.asarray(self._ends[first:])

    def __len__(self) -> int:
        return len(self._starts)


def crossed(a, b, starts, ends, margin: float, beyond: float) -> np.ndarray:
    """(m,) bool: does any segment ``starts[j]`` -> ``ends[j]`` ((n, 2) float each)
    cross the chord ``a[i]`` -> ``b[i]`` ((m, 2) or (2,) float) at more than 45°,
    farther than ``margin`` from both its ends, and go on farther than ``beyond`` past it?

    >>> crossed((0, 0), (1.2, 0), [[0.6, 5.0]], [[0.6, -3.0]], 0.25, 1.0)  # straight in
    array([ True])
    >>> crossed((0, 0), (1.2, 0), [[0.1, 5.0]], [[0.1, -3.0]], 0.25, 1.0)  # by an end
    array([False])
    >>> crossed((0, 0), (1.2, 0), [[-4.0, 0.1]], [[5.0, -0.1]], 0.25, 1.0)  # along it
    array([False])
    >>> crossed((0, 0), (1.2, 0), [[0.6, 5.0]], [[0.6, -0.4]], 0.25, 1.0)  # a tip just behind
    array([False])
    """
    a, b = np.asarray(a, float).reshape(-1, 1, 2), np.asarray(b, float).reshape(-1, 1, 2)
    p = np.asarray(starts, float).reshape(1, -1, 2)
    q = np.asarray(ends, float).reshape(1, -1, 2)
    ab, pq, ap = b - a, q - p, p - a  # (m, 1, 2), (1, n, 2), (m, n, 2)
    den = ab[..., 0] * pq[..., 1] - ab[..., 1] * pq[..., 0]  # (m, n)
    chord = np.hypot(ab[..., 0], ab[..., 1])  # (m, 1)
    sweep = np.hypot(pq[..., 0], pq[..., 1])  # (1, n)
    steep = np.abs(den) >= MIN_SIN * chord * sweep
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (ap[..., 0] * pq[..., 1] - ap[..., 1] * pq[..., 0]) / den  # along the chord
        t = (ap[..., 0] * ab[..., 1] - ap[..., 1] * ab[..., 0]) / den  # along the sweep
    inner = margin / np.maximum(chord, 1e-300)
    past = (1.0 - t) * sweep  # how far the sweep goes on beyond the chord
    return (steep & (s > inner) & (s < 1.0 - inner) & (t >= 0.0) & (past > beyond)).any(axis=1)


def soften_passed(run: Exploration) -> int:
    """Mark on the map every W2 chord longer than eps that an insertion of the probe
    has crossed (see the module doc); returns how many were marked now.

    ``run.band_w2`` holds [map piece, sweeps already looked at] per chord not marked
    yet: each sweep is checked against each chord once."""
    if not isinstance(run.probe, SweptRobot) or not run.band_w2:
        return 0
    total, done, left = len(run.probe), 0, []
    for seen in sorted({seen for _, seen in run.band_w2}):
        pieces = [piece for piece, k in run.band_w2 if k == seen]
        if seen == total:
            left += [[piece, total] for piece in pieces]
            continue
        a = np.array([run.known.pieces[i][0] for i in pieces])
        b = np.array([run.known.pieces[i][-1] for i in pieces])
        hit = crossed(a, b, *run.probe.sweeps(seen), run.eps / 4.0, run.res.tip_zone)
        for piece, h in zip(pieces, hit):
            if h:
                run.known.soften(piece)
                done += 1
            else:
                left.append([piece, total])
    run.band_w2 = sorted(left)
    return done
