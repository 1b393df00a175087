"""Plain 2D vector helpers shared by the simulator and the planner.

Nothing here knows about the contour: these are the maths of angles and unit
vectors in the slice plane.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["unit", "angle_of", "wrap", "magnitude"]


def unit(angle) -> np.ndarray:
    """Unit vector(s) at ``angle`` (radians, counter-clockwise from +x).

    angle : float or (n,) float. Returns (2,) or (n, 2) float.

    Examples
    --------
    >>> unit(0.0).tolist()
    [1.0, 0.0]
    """
    a = np.asarray(angle, dtype=np.float64)
    out = np.empty(a.shape + (2,))
    np.cos(a, out=out[..., 0])
    np.sin(a, out=out[..., 1])
    return out


def angle_of(vec) -> float:
    """Angle of a 2D vector, radians in (-pi, pi]."""
    return float(np.arctan2(vec[1], vec[0]))


def wrap(angle):
    """Angle(s) wrapped to [-pi, pi)."""
    return (angle + np.pi) % (2 * np.pi) - np.pi


def magnitude(vec) -> float:
    """Euclidean length of a (2,) float64 vector: ``sqrt(v . v)``, the very
    operations of ``np.linalg.norm`` (same bits) without its overhead."""
    return math.sqrt(vec.dot(vec))
