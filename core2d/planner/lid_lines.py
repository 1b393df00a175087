"""Free lines through a lid, answered lazily: the lid question per sample asked.

:meth:`core2d.planner.known.KnownContour.free_lines` samples the open lid
L_A^B (Def. 3) and asks, at each sample, for the widest gap of directions
from F past the recorded contour (:func:`core2d.visibility.free_gaps`,
hundreds of samples against thousands of recorded segments). The planner
then needs little of that answer: whether any free line is left (the W3
proof of the revisit, §4.2.1 extended to recorded lids) and, for each pass it
plans, the free sample nearest a position along the lid
(:mod:`core2d.planner.pass_plan`). :class:`FreeLines` answers those two
questions sample by sample, nearest first, and stops at the first free
sample: every sample's gap is computed exactly as the whole batch would
compute it (the lid question is independent per sample), so the lines and
passes are the same as from the full list, at a fraction of the samples.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core2d.visibility import free_gaps, joined_segments

__all__ = ["FreeLine", "FreeLines"]


@dataclass(frozen=True)
class FreeLine:
    """A line from F that crosses the lid past the recorded contour.

    point : (2,) float -- where it crosses the lid.
    direction : (2,) float -- unit direction from F towards the lid, through
        the middle of the free gap.
    gap : float -- angular width of that free gap (rad).
    along : float -- position of ``point`` along the lid, 0 at A, 1 at B.
    """

    point: np.ndarray
    direction: np.ndarray
    gap: float
    along: float

    def turned(self, fraction: float) -> np.ndarray:
        """Direction from F through the gap at ``fraction`` of its width
        (0.5 the middle, 0 and 1 its edges), counter-clockwise positive."""
        ang = np.arctan2(self.direction[1], self.direction[0]) + (fraction - 0.5) * self.gap
        return np.array([np.cos(ang), np.sin(ang)])


class FreeLines:
    """The free lines through one lid's samples, each sample solved on first use.

    Parameters
    ----------
    points : (k, 2) float -- lid samples, in order from A to B.
    tangent : (k, 2) float -- unit tangent per sample (V_i on its right).
    along : (k,) float -- position of each sample along the lid, 0 at A, 1 at B.
    seg_a, seg_b : (n, 2) float -- the recorded segments (kept as given).
    min_gap : float -- a sample is free when its gap is wider.

    ``bool(lines)``: is any line free; ``lines.nearest(pos)`` (and
    ``nearest_many``): the free line nearest ``pos`` along the lid (ties: the
    first sample), None if none; ``len``, ``[i]`` and iteration: every free
    line in lid order (solves every sample).
    """

    def __init__(self, points, tangent, along, seg_a, seg_b, min_gap: float):
        self.points, self.tangent, self.along = points, tangent, along
        self.seg_a, self.seg_b, self.min_gap = seg_a, seg_b, float(min_gap)
        k = len(points)
        self.width, self.angle = np.full(k, np.nan), np.full(k, np.nan)
        self._solved = np.zeros(k, dtype=bool)
        self._all = None
        self._joined = None  # of the recorded segments: computed once for every solve

    def _solve(self, idx) -> None:
        """Solve the samples ``idx`` (int array) not solved yet."""
        idx = idx[~self._solved[idx]]
        if len(idx):
            if self._joined is None:
                self._joined = joined_segments(self.seg_a, self.seg_b)
            self.width[idx], self.angle[idx] = free_gaps(self.points[idx], self.tangent[idx],
                                                         self.seg_a, self.seg_b,
                                                         joined=self._joined)
            self._solved[idx] = True

    def block(self, point, radius: float) -> None:
        """Block the directions through a disc of ``radius`` round ``point`` (2,):
        a contact where a pass stopped in front of the lid
        (:class:`~core2d.planner.grazing.Blockers`). Two crossed segments
        2 ``radius`` long stand for the disc; every sample is solved again."""
        c = np.asarray(point, dtype=np.float64)
        arm = np.array([[radius, 0.0], [0.0, radius]])
        self.seg_a = np.concatenate([self.seg_a, c - arm])
        self.seg_b = np.concatenate([self.seg_b, c + arm])
        self.width[:], self.angle[:] = np.nan, np.nan
        self._solved[:] = False
        self._all, self._joined = None, None

    def _line(self, i) -> FreeLine:
        ang = self.angle[i]
        toward = -np.array([np.cos(ang), np.sin(ang)])  # from F to the lid
        return FreeLine(self.points[i], toward, float(self.width[i]), float(self.along[i]))

    def nearest(self, pos: float, skip=()) -> FreeLine | None:
        """The free line whose ``along`` is nearest ``pos`` (as ``argmin`` of
        ``|along - pos|`` over the free lines in lid order), None if none;
        ``skip``: ``along`` values of samples left out."""
        return self.nearest_many([pos], skip)[0]

    def nearest_many(self, positions, skip=()) -> list:
        """:meth:`nearest` for every position of ``positions``, the samples
        of all positions solved together: each position's nearest sample
        first, the next nearest ones (2, 4, ... at a time) only where those
        are blocked."""
        orders = [np.argsort(np.abs(self.along - pos), kind="stable") for pos in positions]
        found = [None] * len(orders)
        todo = [q for q in range(len(orders)) if len(orders[q])]
        start, step = 0, 1
        while todo:
            self._solve(np.concatenate([orders[q][start:start + step] for q in todo]))
            left = []
            for q in todo:
                batch = orders[q][start:start + step]
                free = np.flatnonzero((self.width[batch] > self.min_gap)
                                      & ~np.isin(self.along[batch], skip))
                if len(free):
                    found[q] = self._line(batch[free[0]])
                elif start + step < len(orders[q]):
                    left.append(q)
            todo, start, step = left, start + step, 2 * step
        return found

    def __bool__(self) -> bool:
        return self.nearest(0.5) is not None

    def _lines(self) -> list[FreeLine]:
        if self._all is None:
            self._solve(np.arange(len(self.points)))
            self._all = [self._line(i) for i in np.flatnonzero(self.width > self.min_gap)]
        return self._all

    def __len__(self) -> int:
        return len(self._lines())

    def __getitem__(self, i) -> FreeLine:
        return self._lines()[i]

    def __iter__(self):
        return iter(self._lines())
