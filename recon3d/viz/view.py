"""Where the camera of the coverage picture looks from, and the slicing arrows.

:func:`fit_view` turns the object's bounding box into a view: its longest
extent runs across the image; a flat object (shortest extent under half the
middle one) lies flat with its thin axis up; otherwise +y stays up (the
scenes' convention) unless +y is the longest extent. The camera looks down on
the object from ``ELEVATION`` and turns ``AZIMUTH`` about the up axis, so
three faces of a box show.
"""
from __future__ import annotations

import numpy as np

__all__ = ["fit_view", "ELEVATION", "AZIMUTH", "FLAT"]

ELEVATION = 30.0
"""Degrees the camera looks down onto the object."""
AZIMUTH = 30.0
"""Degrees the camera turns about the up axis (away from looking straight along the depth axis)."""
FLAT = 0.5
"""An object whose shortest extent is under FLAT x the middle one lies flat (thin axis up)."""


def fit_view(bounds) -> tuple[np.ndarray, np.ndarray, int]:
    """The view of a bounding box.

    Parameters
    ----------
    bounds : (2, 3) float -- min and max corner.

    Returns
    -------
    direction : (3,) float -- unit vector from the focal point towards the camera.
    up : (3,) float -- unit view-up (a coordinate axis).
    across : int -- the axis (0, 1, 2) that runs across the image: the longest extent.

    >>> d, up, across = fit_view([[0, 0, 0], [100, 10, 60]])  # a pallet, thin along y
    >>> up.tolist(), across
    ([0.0, 1.0, 0.0], 0)
    >>> d, up, across = fit_view([[0, 0, 0], [10, 100, 60]])  # the same pallet on its edge
    >>> up.tolist(), across
    ([1.0, 0.0, 0.0], 1)
    """
    ext = np.ptp(np.asarray(bounds, dtype=np.float64).reshape(2, 3), axis=0)
    order = np.argsort(ext, kind="stable")  # shortest, middle, longest
    shortest, middle, longest = (int(k) for k in order)
    if ext[shortest] < FLAT * ext[middle] or longest == 1:
        up_axis = shortest
    else:
        up_axis = 1 if longest != 1 else shortest
    depth = 3 - longest - up_axis
    el, az = np.radians(ELEVATION), np.radians(AZIMUTH)
    eye = np.eye(3)
    direction = (np.cos(el) * (np.cos(az) * eye[depth] + np.sin(az) * eye[longest])
                 + np.sin(el) * eye[up_axis])
    return direction / np.linalg.norm(direction), eye[up_axis].copy(), longest
