"""Is a change between two sensor studies more than the sensor's lottery? Paired statistics.

Under a noisy sensor one run of a slice is one draw: a change to the planner that adds or
removes a motion re-draws every later reading of that slice, so each slice run moves up or
down by +-0.01 to 0.03 whatever the change did. Two studies made with the same arguments
pair their slice runs (same case, slice, sensor level and seed), and the pairs say how
large a pooled change the lottery alone makes:

* :func:`sign_test` -- of the slice runs whose coverage moved, how many went up: the
  two-sided binomial p-value against "up and down equally likely" (scipy's ``binomtest``).
* :func:`pooled_change` -- the change of a pooled figure (coverage: covered length over
  reachable length; motions: their total) with a 95 % interval from a paired bootstrap
  over the slice runs (scipy's ``bootstrap``, percentile method, a fixed seed, so the same
  CSVs print the same interval).

An interval that holds 0 says the two studies differ by no more than re-drawing the
sensor's noise would make them differ; it says nothing of a change too small to show
over that many runs.

>>> sign_test(20, 20)
1.0
>>> round(sign_test(30, 10), 4)
0.0022
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import stats

__all__ = ["Change", "sign_test", "pooled_change"]

RESAMPLES = 2000  #: bootstrap resamples (the interval's ends move by ~1e-4 of coverage)


@dataclass(frozen=True)
class Change:
    """A pooled figure before and after, its change and the change's 95 % interval
    (``low`` and ``high`` NaN when the runs are too few to resample)."""

    before: float
    after: float
    change: float
    low: float
    high: float

    def holds_zero(self) -> bool:
        """Is 0 inside the interval (no change beyond the lottery)?"""
        return not (self.low > 0 or self.high < 0)


def sign_test(up: int, down: int) -> float:
    """Two-sided p-value of ``up`` of ``up + down`` moved runs going up, if up and down
    were equally likely (1.0 when none moved)."""
    if up + down == 0:
        return 1.0
    return float(stats.binomtest(int(up), int(up + down), 0.5).pvalue)


def pooled_change(before, after, weight=None, relative: bool = False,
                  min_runs: int = 10) -> Change:
    """The change of a pooled figure over paired slice runs, with its 95 % interval.

    Parameters
    ----------
    before, after : (n,) float -- each run's amount (covered length, motions), paired.
    weight : (n,) float, optional -- each run's share of the pool (reachable length): the
        figure is ``sum(amount) / sum(weight)``; none: the figure is ``sum(amount)``.
    relative : bool -- the change as after / before - 1 (motions) instead of after - before.
    min_runs : int -- fewer paired runs: no interval.

    >>> c = pooled_change([9.0, 8.0], [9.5, 8.5], weight=[10.0, 10.0])
    >>> round(c.before, 3), round(c.after, 3), round(c.change, 3)
    (0.85, 0.9, 0.05)
    """
    a = np.asarray(before, float)
    b = np.asarray(after, float)
    w = np.ones_like(a) if weight is None else np.asarray(weight, float)
    if not (a.shape == b.shape == w.shape and a.ndim == 1):
        raise ValueError("before, after and weight must be paired (n,) arrays")

    def figure(x, y, z, axis=-1):
        pool_a = x.sum(axis) / (z.sum(axis) if weight is not None else 1.0)
        pool_b = y.sum(axis) / (z.sum(axis) if weight is not None else 1.0)
        return pool_b / pool_a - 1.0 if relative else pool_b - pool_a

    pool_a = float(a.sum() / (w.sum() if weight is not None else 1.0))
    pool_b = float(b.sum() / (w.sum() if weight is not None else 1.0))
    change = float(figure(a, b, w))
    low = high = float("nan")
    if len(a) >= min_runs and np.any(a != b):
        ci = stats.bootstrap((a, b, w), figure, paired=True, vectorized=True,
                             n_resamples=RESAMPLES, method="percentile",
                             random_state=np.random.default_rng(0)).confidence_interval
        low, high = float(ci.low), float(ci.high)
    elif len(a) >= min_runs:
        low = high = change
    return Change(pool_a, pool_b, change, low, high)
