"""Traced contour from noisy readings: block means over the sensor's jitter.

W1 is the contour the tip slid along (§3.1), recorded as the tip contacts of
a compliant trace, one every eps / 4 or less. With a noisy sensor
(:class:`core2d.sim.sensor.SensorModel`) each reported contact scatters by
the noise, which is then larger than the spacing of the contacts: the
recorded polyline zigzags, its segments turn back on each other, and the
robot's map (:class:`~core2d.planner.known.KnownContour`), which chains pieces
that turn less than 120 degrees, no longer follows it -- dead ends and cycles
that noise alone made.

:func:`smooth` replaces each run of contacts spanning
:attr:`~core2d.resolution.Resolution.hop` (eps / 4 + the sensor's jitter) by
its mean: the noise of a point falls by the square root of the run's count,
consecutive points lie farther apart than their scatter, and the ends (the
contacts the areas were registered at, P_1st, P_fin, ...) are kept as read.
A corner is cut by at most half a run, within the sensor's tolerance
eps / 2 + 2 noise. Perfect sensing (jitter 0) keeps the polyline as traced.
"""
from __future__ import annotations

import numpy as np

from core2d.resolution import Resolution

__all__ = ["smooth"]


def smooth(polyline: np.ndarray, res: Resolution) -> np.ndarray:
    """(k, 2) traced polyline -> (m, 2), m <= k: block means over ``res.hop``
    of arc length between the kept first and last points (unchanged when
    ``res.jitter`` is 0 or the polyline is shorter than two blocks)."""
    pl = np.asarray(polyline, dtype=np.float64).reshape(-1, 2)
    if res.jitter == 0 or len(pl) < 4:
        return pl
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pl, axis=0).T))])
    block = np.floor(s[1:-1] / res.hop).astype(np.int64)
    if block[-1] < 1:
        return pl
    inner = pl[1:-1]
    counts = np.bincount(block)
    keep = counts > 0
    means = np.stack([np.bincount(block, inner[:, k]) for k in (0, 1)], axis=1)[keep]
    return np.concatenate([pl[:1], means / counts[keep][:, None], pl[-1:]])
