"""Where the camera of the coverage picture looks from, and the slicing arrows.

:func:`fit_view` turns the object's bounding box into a view: its longest
extent runs across the image; a flat object (shortest extent under half the
middle one) lies flat with its thin axis up; otherwise +y stays up (the
scenes' convention) unless +y is the longest extent. The camera looks down on
the object from ``ELEVATION`` and turns ``AZIMUTH`` about the up axis, so
three faces of a box show. :func:`frame` then zooms and shifts the picture
so that the object fills the part of a panel that no legend or colour bar holds.
"""
from __future__ import annotations

import numpy as np

__all__ = ["fit_view", "frame", "FREE", "ELEVATION", "AZIMUTH", "FLAT"]

ELEVATION = 30.0
"""Degrees the camera looks down onto the object."""
AZIMUTH = 30.0
"""Degrees the camera turns about the up axis (away from looking straight along the depth axis)."""
FLAT = 0.5
"""An object whose shortest extent is under FLAT x the middle one lies flat (thin axis up)."""
FREE = (0.03, 0.98, 0.22, 0.91)
"""The part of a panel the object is drawn in (x0, x1, y0, y1, shares of the panel): above
the colour bar, its title and the axis triad, below the panel's title."""


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


def frame(ndc, box=FREE, keep_out=(), steps: int = 16, most: int = 1500
          ) -> tuple[float, np.ndarray]:
    """The zoom and window centre that put projected points inside ``box`` and out of the
    ``keep_out`` rectangles (a legend), as large as that allows, as centred as it allows.

    A camera zoom by ``s`` scales normalised device coordinates about the image centre by
    ``s`` exactly (perspective too), and a window centre ``c`` (VTK's ``SetWindowCenter``)
    moves them by ``-c`` with no parallax. The largest zoom whose bounding box fits ``box`` is
    tried first, then smaller ones (``steps`` down to half), each at the positions inside
    ``box`` (a grid of ``steps`` x ``steps``), until one keeps every point (every k-th, at most
    ``most``) out of ``keep_out``; if none does, the largest zoom, centred.

    Parameters
    ----------
    ndc : (n, 2) float -- the points' normalised device coordinates (-1 .. 1) at the
        current camera (window centre 0).
    box : (4,) float -- x0, x1, y0, y1 as shares of the panel (0 .. 1).
    keep_out : sequence of (4,) float -- rectangles alike.

    Returns
    -------
    zoom : float -- the camera zoom factor.
    center : (2,) float -- the window centre to set after the zoom.

    >>> z, c = frame([[-1.0, -0.5], [0.5, 0.5]], box=(0.0, 1.0, 0.0, 1.0))
    >>> round(z, 6), c.round(6).tolist()
    (1.333333, [-0.333333, 0.0])
    >>> square = np.stack(np.meshgrid(*[np.linspace(-1, 1, 21)] * 2), -1).reshape(-1, 2)
    >>> z, c = frame(square, box=(0.0, 1.0, 0.0, 1.0), keep_out=[(0.0, 0.3, 0.7, 1.0)])
    >>> top = (z * square - c)[:, 1].max()  # smaller, moved down below the legend
    >>> 0.5 <= z < 0.75, bool(top <= 2 * 0.7 - 1)
    (True, True)
    """
    pts = np.asarray(ndc, dtype=np.float64).reshape(-1, 2)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    box = np.asarray(box, dtype=np.float64)
    target_lo, target_hi = 2.0 * box[[0, 2]] - 1.0, 2.0 * box[[1, 3]] - 1.0
    size = np.maximum(hi - lo, 1e-12)
    best = float(np.min((target_hi - target_lo) / size))
    centred = best * (lo + hi) / 2.0 - (target_lo + target_hi) / 2.0
    rects = [2.0 * np.asarray(r, dtype=np.float64) - 1.0 for r in keep_out]
    if not rects:
        return best, centred
    few = pts[::max(1, len(pts) // most)]
    fx, fy = np.meshgrid(np.linspace(0, 1, steps), np.linspace(0, 1, steps))
    slide = np.c_[fx.ravel(), fy.ravel()]
    slide = slide[np.argsort(np.hypot(*(slide - 0.5).T), kind="stable")]  # most centred first
    for zoom in best * np.geomspace(1.0, 0.5, steps):
        shifts = target_lo + slide * ((target_hi - target_lo) - zoom * size) - zoom * lo
        at = zoom * few[None] + shifts[:, None]  # (positions, points, 2)
        hit = np.zeros(len(shifts), dtype=bool)
        for r in rects:
            hit |= ((at[..., 0] > r[0]) & (at[..., 0] < r[1]) & (at[..., 1] > r[2])
                    & (at[..., 1] < r[3])).any(axis=1)
        if not hit.all():
            return float(zoom), -shifts[np.argmin(hit)]
    return best, centred
