"""Dense finger probing: the baseline a user would pick instead of pulling.

A touch-trigger probe (Cole & Yap, "Shape from probing", 1987): straight
insertions from the free area F on a grid of directions and offsets. For
each of ``directions`` evenly spaced directions t, parallel lines across the
workspace circle ``spacing`` apart (offsets along the normal n of t) are
probed in order: approach the line from outside the circle (a free
transfer), insert along t until the tip touches, read the contact. Two
motions per probe, the same motions and cost model as the pulling planner's
bootstrap; no swing, no trace, no torque.

What it reports, in the classes of :class:`core2d.result.SliceResult`:

* W2 -- the segment between the touches of two neighbouring lines of one
  direction when Dist(A, B) < eps (the paper's approximation rule, §3.1),
  oriented with the material on its right (the probe came from the left);
* W1 -- every touch that joins no neighbour, as a one-point polyline;
* no W3 and no unknown areas: finger probing proves nothing about what it
  did not touch.

It sees sensor readings only (this module lives with the planner and obeys
its walls).
"""
from __future__ import annotations

import time

import numpy as np

from core2d.planar import unit
from core2d.planner.robot import Robot, final_stats
from core2d.result import SliceResult

__all__ = ["finger_probe", "probe_lines"]


def probe_lines(center, radius, directions: int, spacing: float):
    """The probing grid: one (point, direction) per line, sweep by sweep.

    Parameters
    ----------
    center : (2,) float, radius : float -- the workspace circle.
    directions : int -- evenly spaced insertion directions.
    spacing : float -- distance between neighbouring parallel lines.

    Returns
    -------
    points : (m, 2) float -- a point on each line.
    dirs : (m, 2) float -- unit insertion direction of each line.
    sweep : (m,) int -- direction index of each line (lines of a sweep are
        consecutive and ordered along the sweep).
    """
    if directions < 1 or not spacing > 0:
        raise ValueError("directions must be >= 1 and spacing > 0")
    center = np.asarray(center, dtype=np.float64)
    k = int(np.floor(radius / spacing))
    offs = spacing * np.arange(-k, k + 1)
    pts, dirs, sweep = [], [], []
    for j in range(directions):
        t = unit(2 * np.pi * j / directions)
        n = np.array([-t[1], t[0]])
        order = offs if j % 2 == 0 else offs[::-1]  # boustrophedon: short transfers
        pts.append(center + order[:, None] * n)
        dirs.append(np.broadcast_to(t, (len(offs), 2)))
        sweep.append(np.full(len(offs), j))
    return np.concatenate(pts), np.concatenate(dirs), np.concatenate(sweep)


def _oriented(a, b, t):
    """(2, 2) segment a-b ordered so that the probe direction t points to its right."""
    e = b - a
    right = np.array([e[1], -e[0]])
    return np.stack([a, b]) if right @ t >= 0 else np.stack([b, a])


def finger_probe(probe: Robot, eps: float, directions: int = 32, spacing: float | None = None,
                 max_motions: int = 20000) -> SliceResult:
    """Probe a closed slice with straight insertions on a grid (see module doc).

    Parameters
    ----------
    probe : the simulator (only ``approach``, ``insert`` and the readings are used).
    eps : float -- the paper's eps: neighbouring touches closer than eps are joined (W2).
    directions : int -- insertion directions.
    spacing : float, optional -- line spacing, default eps / 2.
    max_motions : int -- motion budget (two motions per probe); reported when hit.

    Returns
    -------
    SliceResult in the slice's 2D frame.
    """
    t0 = time.perf_counter()
    spacing = eps / 2 if spacing is None else float(spacing)
    points, dirs, sweep = probe_lines(probe.center, probe.radius, directions, spacing)
    result = SliceResult()
    touches = np.full((len(points), 2), np.nan)
    at = np.full(len(points), -1)  # the insertion that touched, per line
    budget_hit = False
    for i, (p, t) in enumerate(zip(points, dirs)):
        if probe.motions + 2 > max_motions:
            budget_hit = True
            break
        probe.approach(p, t)
        c = probe.insert(2 * probe.radius).tip_contact
        if c is not None:
            touches[i], at[i] = c.point, probe.motions - 1
    joined = np.zeros(len(points), dtype=bool)
    for i in range(len(points) - 1):
        a, b = touches[i], touches[i + 1]
        if sweep[i] != sweep[i + 1] or np.isnan(a[0]) or np.isnan(b[0]):
            continue
        if np.linalg.norm(b - a) < eps:
            result.w2.append(_oriented(a, b, dirs[i]))
            result.known_at["w2"].append(int(at[i + 1]))
            joined[i] = joined[i + 1] = True
    single = [i for i in range(len(points)) if not joined[i] and not np.isnan(touches[i][0])]
    result.w1 = [touches[i][None].copy() for i in single]
    result.known_at["w1"] = [int(at[i]) for i in single]
    result.stats = final_stats(probe, budget_hit=budget_hit, seconds=time.perf_counter() - t0)
    return result
