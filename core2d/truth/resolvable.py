"""The contour the paper's resolution eps resolves: not inside an opening narrower than eps.

§3.1 regards the segment L_A^B as the approximate surface of C_A^B when Dist(A, B) < eps
(W2), and §3.2 assumes the contour smooth at the eps level. A slot narrower than eps is
therefore closed by a W2 chord across its mouth and never entered, by design: its walls are
reachable by a rod of no thickness (:mod:`core2d.truth.reachability`) but lie outside what
the method resolves. This module marks the contour the method is meant to resolve, so that a
score can be read over it beside the zero-width rod's reachable part.

Definition: a disc of diameter eps moves in the free plane from far away (from F, §3.1).
The contour it comes within eps / 2 of (the metrics' tolerance, DESIGN.md "Metrics") is
*resolvable*. A slot, gap or pocket mouth narrower than eps stops the disc, so the walls
behind it, farther than eps / 2 from where the disc can be, are not resolvable; an ordinary
concave corner is (its apex lies (eps / 2)(1 / sin(theta / 2) - 1) from the disc, under
eps / 2 for an opening angle theta above 39 degrees); space enclosed by the material (a
hole of the section) is not reachable by the disc at all.

Computed with shapely: the free plane around the section, eroded by eps / 2 (the disc
centres that fit), its component connected to the outside, dilated by eps / 2 (the swept
region); a sample is not resolvable when it lies in the rest of the plane eroded by eps / 2.
Circles are polygons of ``quad_segs`` segments a quarter (default 16: radius error 0.05 %).
The material is the even-odd union of the loops (islands inside holes are material again).

Examples
--------
>>> import numpy as np
>>> from core2d.truth.reachability import sample_contour
>>> comb = [np.array([[0., 0.], [9., 0.], [9., 6.], [5.3, 6.], [5.3, 1.], [5., 1.],
...                   [5., 6.], [2., 6.], [2., 1.], [1., 1.], [1., 6.], [0., 6.]])]
>>> s = sample_contour(comb, 0.25)
>>> ok = resolvable(comb, s.points, eps=0.5)
>>> bool(ok[(s.points[:, 1] > 2) & (abs(s.points[:, 0] - 1.5) < 0.6)].all())  # 1.0 wide
True
>>> deep = (s.points[:, 1] >= 1) & (s.points[:, 1] < 5)
>>> bool(ok[deep & (abs(s.points[:, 0] - 5.15) < 0.2)].any())  # 0.3 wide
False
"""
from __future__ import annotations

from functools import reduce

import numpy as np
import shapely

__all__ = ["resolvable", "swept_region"]


def _material(loops):
    """The section's material: the even-odd union of its loops (None without area)."""
    polys = [shapely.make_valid(shapely.Polygon(np.asarray(lp, dtype=np.float64)))
             for lp in loops if len(lp) >= 3]
    polys = [p for p in polys if p.area > 0]
    return reduce(shapely.symmetric_difference, polys) if polys else None


def swept_region(loops, eps: float, quad_segs: int = 16):
    """The region a disc of diameter ``eps`` sweeps, moving from outside the section.

    Parameters
    ----------
    loops : list of (k, 2) float -- the section's loops.
    eps : float -- the disc's diameter (the paper's eps).

    Returns
    -------
    (swept, box) : shapely geometries -- the swept region and the square it is cut to (the
    section's bounds padded by 2 eps); (None, None) without material.
    """
    material = _material(loops)
    if material is None or material.is_empty:
        return None, None
    r = 0.5 * float(eps)
    x0, y0, x1, y1 = material.bounds
    box = shapely.box(x0 - 4 * r, y0 - 4 * r, x1 + 4 * r, y1 + 4 * r)
    centres = shapely.buffer(shapely.difference(box, material), -r, quad_segs=quad_segs)
    outside = shapely.Point(x0 - 2 * r, y0 - 2 * r)  # 2 r from the box and the material
    parts = [g for g in shapely.get_parts(centres) if g.intersects(outside)]
    if not parts:
        return None, box
    return shapely.buffer(parts[0], r, quad_segs=quad_segs), box


def resolvable(loops, points, eps: float, quad_segs: int = 16) -> np.ndarray:
    """Which contour samples the paper's resolution resolves (module doc).

    Parameters
    ----------
    loops : list of (k, 2) float -- the section (outer loops CCW, holes CW).
    points : (m, 2) float -- samples on the contour.
    eps : float -- the paper's eps.

    Returns
    -------
    (m,) bool -- within eps / 2 of the region a disc of diameter eps sweeps from outside.
    """
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    swept, box = swept_region(loops, eps, quad_segs)
    if swept is None:
        return np.zeros(len(pts), dtype=bool)
    beyond = shapely.buffer(shapely.difference(box, swept), -0.5 * float(eps),
                            quad_segs=quad_segs)
    if beyond.is_empty:
        return np.ones(len(pts), dtype=bool)
    shapely.prepare(beyond)
    return ~shapely.contains_xy(beyond, pts[:, 0], pts[:, 1])
