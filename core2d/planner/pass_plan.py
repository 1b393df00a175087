"""The revisit's passes through one lid, each planned when it is next.

Step 3 of :mod:`core2d.planner.revisit`.

A look at a deferred area A_iB_i makes up to ``MAX_TRIES`` spread passes through its lid
(:func:`spread`) and then, if the lid could be W3, one pass every eps/2 along it
(:func:`sweep`; with a noisy sensor that resolves eps/2, one every eps once a pass
has left through the lid), until one finds a new contact and splits the area. Each pass goes
through the free lid sample nearest a planned position
(:meth:`core2d.planner.lid_lines.FreeLines.nearest_many`), and each sample's free gap is a
lid question against the whole recorded contour. A look often ends in a split at its first
or second pass (33 - 75 % of the looks that make passes, noiseless, on four scenes), so the passes are planned as they are asked for: a spread pass when it is next, the sweep
eight positions at a time. Every sample's gap is the one the whole batch would give
(:mod:`core2d.planner.lid_lines`), so the passes are those of a plan made at once, and a
lid split early leaves the later positions unsolved (47 - 87 % fewer lid samples solved on
the z-slices of five built-in scenes than with the whole plan made first).

>>> plan = PassPlan([iter([(1, 2)]), iter([(3, 4), (5, 6)])])
>>> plan.next(), plan.push((7, 8)), plan.next(), plan.next(), plan.count
((1, 2), None, (7, 8), (3, 4), 3)
"""
from __future__ import annotations

from collections import deque
from collections.abc import Iterable, Iterator
from itertools import chain

import numpy as np

__all__ = ["spread", "sweep", "PassPlan", "MAX_TRIES", "MAX_SWEEP", "PLAN", "SWEEP_CHUNK"]

#: (position along the lid A -> B, which way to steer in the free gap), in the passes' order
PLAN = ((0.5, 0.0), (0.9, 1.0), (0.1, -1.0), (0.3, 0.0), (0.7, 0.0), (0.5, 1.0))
#: spread passes (:func:`spread`) before the sweep at resolution eps
MAX_TRIES = len(PLAN)
#: most passes of the sweep along one lid
MAX_SWEEP = 48
#: sweep positions solved together
SWEEP_CHUNK = 8


def spread(lines, a, b, distinct: bool = False) -> Iterator[tuple[np.ndarray, np.ndarray]]:
    """Spread passes ``(point, direction)`` through the lid, in the order of
    :data:`PLAN`: for each planned position the nearest free lid sample, its
    direction at the middle of the free gap (steer 0) or at 0.1 / 0.9 of it,
    whichever edge leans towards B (steer +1) or A (steer -1). Each position is
    solved when its pass is asked for. ``distinct`` (a noisy sensor): a sample
    an earlier pass took with the same steer gives way to the nearest free one
    not taken, while there is one -- when only one end of the lid is free,
    the positions all fall on its first free sample.

    lines : FreeLines with a free line; a, b : (2,) float -- A_i and B_i."""
    ab = np.asarray(b, float) - a
    taken = {-1.0: [], 0.0: [], 1.0: []}
    for pos, steer in PLAN:
        ln = lines.nearest(pos, taken[steer]) if distinct else None
        ln = ln or lines.nearest(pos)
        if ln is None:  # every line blocked by now (FreeLines.block)
            return
        taken[steer].append(ln.along)
        if steer == 0:
            yield ln.point, ln.direction
            continue
        d0, d1 = ln.turned(0.1), ln.turned(0.9)
        toward_b, toward_a = (d0, d1) if d0 @ ab > d1 @ ab else (d1, d0)
        yield ln.point, toward_b if steer > 0 else toward_a


def sweep(lines, length: float, eps: float,
          sparse=lambda: False) -> Iterator[tuple[np.ndarray, np.ndarray]]:
    """One pass every eps/2 along the lid (the nearest free sample), at most
    :data:`MAX_SWEEP`, alternately at 1/4 and 3/4 of its free gap; the positions
    solved :data:`SWEEP_CHUNK` at a time, as the passes are asked for.
    ``sparse`` (asked before each pass): True when one pass every eps is enough
    -- every other position is left out, the steer alternating over those kept;
    the positions are solved a chunk at a time, so from the next chunk on the
    ones left out are not solved either. The revisit asks it with a noisy sensor that
    resolves eps/2 once a pass has left through the lid, or ended anywhere but at a
    touched end: the lid then cannot be W3 (the eps/2 spacing is the W3 proof's),
    and the passes left only look for a new contact (the second: motions -1.0 to
    -3.2 % over six keyed seeds and 8 slices of every case, coverage within the
    sensor's lottery, docs/notes/noise.md). A coarser sensor sweeps (eps + jitter) / 2
    apart already (:func:`~core2d.planner.grazing.sweep_length`), and doubling that
    lost a ring's far side (two 16-gons 13 eps across, sigma 0.3 eps, taxels
    0.25 eps, read once, seed 0: 0.994 -> 0.909). Keyed sensor study, six seeds,
    8 slices of every case: at sigma 0.1 motions -4.3 % (meshes), -2.5 %
    (outlines), -0.7 % (scenes), coverage 5 slice runs up and 10 down
    (``twin_posts``, at most -0.005: a split the finer sweep found on the wall
    facing the gap), no case run crossing a target; at sigma 0.3 + taxels 0.25
    averaged over 15 reads (the fine path), 4 up and 3 down,
    ``vtk_42400-IDGH`` z2 + 5002 2.25 -> 1.75 x its noiseless motions. Sweeping
    no more after an escape cost coverage without noise (``twin_posts`` 1.0 ->
    0.971, docs/notes/speed.md).

    length : float -- Dist(A_i, B_i).

    >>> from types import SimpleNamespace as NS
    >>> class Lines:
    ...     def nearest_many(self, pos):
    ...         return [NS(point=p, turned=lambda f: f) for p in pos]
    >>> [float(p) for p, _ in sweep(Lines(), 4.0, 1.0)]
    [0.0625, 0.1875, 0.3125, 0.4375, 0.5625, 0.6875, 0.8125, 0.9375]
    >>> [(float(p), t) for p, t in sweep(Lines(), 4.0, 1.0, sparse=lambda: True)][:3]
    [(0.0625, 0.25), (0.3125, 0.75), (0.5625, 0.25)]
    """
    k = int(min(MAX_SWEEP, max(2, np.ceil(2 * length / eps))))
    positions = (np.arange(k) + 0.5) / k
    for s in range(0, k, SWEEP_CHUNK):
        idx = np.arange(s, min(k, s + SWEEP_CHUNK))
        if sparse():
            idx = idx[idx % 2 == 0]
        for n, ln in zip(idx.tolist(), lines.nearest_many(positions[idx])):
            if ln is None:  # every line blocked by now (FreeLines.block)
                return
            if not sparse():
                yield ln.point, ln.turned(0.25 + 0.5 * (n % 2))
            elif n % 2 == 0:
                yield ln.point, ln.turned(0.25 + 0.5 * (n // 2 % 2))


class PassPlan:
    """The passes of one look at a lid, in order, taken one by one.

    sources : iterables of passes, used up one after the other (each item is
        planned only when it is next).

    :meth:`push` puts a pass first (a grazing pass aimed again,
    :class:`~core2d.planner.reaim.Aim`); :attr:`count` is how many were taken;
    :attr:`exhausted` whether the last :meth:`next` found none left.
    """

    def __init__(self, sources: Iterable[Iterable]):
        self._rest = chain.from_iterable(sources)
        self._first: deque = deque()
        self.count = 0
        self.exhausted = False

    def next(self):
        """The next pass, or None when there is none left (:attr:`exhausted` from then on)."""
        item = self._first.popleft() if self._first else next(self._rest, None)
        self.count += item is not None
        self.exhausted = item is None
        return item

    def push(self, item) -> None:
        """Make ``item`` the next pass."""
        self._first.appendleft(item)
