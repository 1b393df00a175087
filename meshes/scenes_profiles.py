"""Scenes that are one 2D profile extruded along z.

Every z-slice of these scenes is the same closed contour, so they test the
2D algorithm in isolation. Profiles lie in the x-y plane with "up" = +y: the
pockets, slots and overhangs open toward +y, where a probe coming from above
meets them first. Units are millimetres; each solid is placed with its
bounding-box minimum at the origin and fits in a 100 mm cube.
"""
from __future__ import annotations

import numpy as np
from manifold3d import CrossSection, Manifold

from .geometry import check_resolution, circle, place, polygon, rect, share
from .registry import scene

__all__ = [
    "fig17_pocket",
    "fig18_overhangs",
    "deep_slot",
    "mushroom",
    "dovetail",
    "comb",
    "gear",
    "bored_block",
]


def _prism(section: CrossSection, depth: float) -> Manifold:
    if not depth > 0:
        raise ValueError(f"depth must be > 0, got {depth!r}")
    return place(section.extrude(float(depth)))


def _bump(x0: float, x1: float, base: float, height: float, segments: int,
          *, descending: bool = True) -> np.ndarray:
    """Raised-cosine bump from ``x0`` to ``x1`` (C1 at both feet).

    Returns ``(segments + 1, 2)`` points, ordered by decreasing x when
    ``descending`` (the direction a counter-clockwise outline runs along a
    top edge). A negative ``height`` gives a dip.
    """
    x = np.linspace(x1, x0, segments + 1) if descending else \
        np.linspace(x0, x1, segments + 1)
    phase = 2.0 * np.pi * (x - x0) / (x1 - x0)
    return np.column_stack([x, base + height * 0.5 * (1.0 - np.cos(phase))])


@scene()
def fig17_pocket(*, resolution: int = 48, depth: float = 40.0) -> Manifold:
    """Block whose top edge has one smooth asymmetric concave pocket (paper Fig. 17).

    Profile 100 x 50 mm, pocket 50 mm wide and 25 mm deep, its left flank
    steeper (20 mm run) than its right (30 mm run); the pocket meets the flat
    top tangentially (C1). The top edge is a function graph y(x): every point
    of the contour is reachable from outside and the tip can trace it all,
    like the paper's first simulation example. ``resolution`` is the number
    of segments per 2*pi of pocket phase (each flank gets a quarter).
    """
    res = check_resolution(resolution)
    n = share(res, 0.25)
    w, h, top = 100.0, 50.0, 50.0
    x_l, x_b, x_r, d = 25.0, 45.0, 75.0, 25.0
    right = _bump(x_b - (x_r - x_b), x_r, top, -d, 2 * n)[: n + 1]
    left = _bump(x_l, x_b + (x_b - x_l), top, -d, 2 * n)[n + 1:]
    top_edge = np.vstack([right, left])
    outline = np.vstack([[[0.0, 0.0], [w, 0.0], [w, h]], top_edge, [[0.0, h]]])
    return _prism(polygon(outline), depth)


@scene()
def fig18_overhangs(*, resolution: int = 48, depth: float = 40.0) -> Manifold:
    """Wide pocket with two hills, overhanging lips and a hidden side notch (paper Fig. 18).

    Profile 100 x 45 mm. The pocket (floor y = 12) is covered at both ends by
    5 mm thick lips leaving a mouth x in [34, 78]; it holds an 18 mm hill and a
    6 mm hill (raised cosines), and its right wall has a 10 x 4 mm notch
    running sideways into the block. The lip undersides, the wall corners
    under them and the notch are never-touching areas: no straight ray from
    them reaches infinity, so a correct planner must close them with W3 lids.
    The top edge is not a function graph (vertical lines cross it up to
    four times). ``resolution``: segments per 2*pi of hill phase.
    """
    res = check_resolution(resolution)
    floor, lip_lo, top = 12.0, 40.0, 45.0
    outline = np.vstack([
        [[0.0, 0.0], [100.0, 0.0], [100.0, top]],
        [[78.0, top], [78.0, lip_lo], [88.0, lip_lo]],          # right lip
        [[88.0, 28.0], [98.0, 28.0], [98.0, 24.0], [88.0, 24.0]],  # notch
        [[88.0, floor]],
        _bump(70.0, 84.0, floor, 6.0, share(res, 0.5))[1:-1],   # small hill
        _bump(35.0, 65.0, floor, 18.0, share(res, 1.0))[1:-1],  # big hill
        [[22.0, floor], [22.0, lip_lo], [34.0, lip_lo], [34.0, top]],  # left lip
        [[0.0, top]],
    ])
    return _prism(polygon(outline), depth)


@scene()
def deep_slot(*, resolution: int = 8, depth: float = 30.0,
              width: float = 4.0) -> Manifold:
    """Block with one deep, narrow, square-bottomed slot in its top.

    Profile 60 x 60 mm, slot ``width`` mm wide (default 4) and 45 mm deep:
    its floor and sharp concave bottom corners are visible only through a
    narrow cone of directions (within 5 deg of vertical at the floor), a
    test of the bootstrap's adaptive refinement and of eps against width.
    Straight-sided: ``resolution`` is accepted for a uniform signature and
    has no effect.
    """
    check_resolution(resolution)
    if not 0 < width < 50:
        raise ValueError(f"width must be in (0, 50), got {width!r}")
    c, half, bottom = 30.0, 0.5 * width, 15.0
    outline = [(0, 0), (60, 0), (60, 60), (c + half, 60), (c + half, bottom),
               (c - half, bottom), (c - half, 60), (0, 60)]
    return _prism(polygon(outline), depth)


@scene()
def mushroom(*, resolution: int = 48, depth: float = 40.0) -> Manifold:
    """Block with an undercut bulb cavity: an 8 mm neck opening into a 32 mm round chamber.

    Profile 80 x 60 mm; neck x in [36, 44] from the top down to the circle
    of radius 16 centred at (40, 25). Most of the chamber wall hides behind
    the neck (never-touching); only a strip of the floor seen through the
    neck is reachable. ``resolution``: segments of the full circle.
    """
    res = check_resolution(resolution)
    cavity = rect(36.0, 35.0, 44.0, 61.0) + circle((40.0, 25.0), 16.0, res)
    return _prism(rect(0.0, 0.0, 80.0, 60.0) - cavity, depth)


@scene()
def dovetail(*, resolution: int = 8, depth: float = 40.0) -> Manifold:
    """Block with a dovetail groove: 20 mm mouth widening to 36 mm at the bottom.

    Profile 80 x 50 mm, groove 22 mm deep, flanks leaning 20 deg out of
    vertical. The flanks face downward (undercut), so a vertically inserted
    probe never touches them, yet the groove is convex: every point of it,
    acute corners included, is reachable through the mouth at an oblique
    angle (contrast with ``mushroom``). Straight-sided: ``resolution`` is
    accepted for a uniform signature and has no effect.
    """
    check_resolution(resolution)
    outline = [(0, 0), (80, 0), (80, 50), (50, 50), (58, 28), (22, 28),
               (30, 50), (0, 50)]
    return _prism(polygon(outline), depth)


@scene()
def comb(*, resolution: int = 8, depth: float = 30.0, teeth: int = 10,
         first_gap: float = 8.0, ratio: float = 0.6) -> Manifold:
    """Comb of 4 mm teeth whose gaps shrink geometrically from 8 mm to ~0.13 mm.

    Base 15 mm high, teeth 35 mm long. Gap k is ``first_gap * ratio**k``
    (defaults: 8, 4.8, 2.9, 1.7, 1.0, 0.62, 0.37, 0.22, 0.13 mm), so some gaps
    are wider and some narrower than a typical eps: the narrow ones should be
    closed as W2 (Dist(A, B) < eps), the wide ones traced (W1). Many
    neighbouring pockets also stress the bookkeeping of unknown areas.
    Straight-sided: ``resolution`` has no effect.
    """
    check_resolution(resolution)
    if int(teeth) != teeth or teeth < 2 or not 0 < ratio <= 1 or first_gap <= 0:
        raise ValueError("need integer teeth >= 2, 0 < ratio <= 1, first_gap > 0")
    tooth, base, tip = 4.0, 15.0, 50.0
    gaps = first_gap * ratio ** np.arange(int(teeth) - 1)
    width = tooth * teeth + gaps.sum()
    if width > 100.0:
        raise ValueError(f"comb would be {width:.1f} mm wide (> 100 mm)")
    left = tooth * np.arange(1, teeth) + np.concatenate([[0.0], np.cumsum(gaps)[:-1]])
    section = rect(0.0, 0.0, width, tip)
    for x0, g in zip(left, gaps):
        section = section - rect(x0, base, x0 + g, tip + 1.0)
    return _prism(section, depth)


def _involute_angle(rb: float, rho: np.ndarray) -> np.ndarray:
    """Polar angle inv(phi) of the involute of circle ``rb`` at radius ``rho``."""
    phi = np.arccos(np.clip(rb / rho, -1.0, 1.0))
    return np.tan(phi) - phi


@scene()
def gear(*, resolution: int = 64, depth: float = 20.0, teeth: int = 18,
         module: float = 4.0) -> Manifold:
    """Spur gear prism with involute teeth (default 18 teeth, module 4, 80 mm tip diameter).

    Pressure angle 20 deg, addendum 1 m, dedendum 1.25 m, flat root. Every
    z-slice is a star-shaped contour with ``teeth`` pockets opening in all
    directions, so the bootstrap must probe all around the bounding circle;
    the involute flanks are convex and reachable. ``resolution``: segments
    per full turn of the involute roll; each flank gets ``resolution // 16``.
    """
    res = check_resolution(resolution)
    n = int(teeth)
    if n != teeth or n < 6:
        raise ValueError(f"teeth must be an integer >= 6, got {teeth!r}")
    r = module * n / 2.0
    ra, rf, rb = r + module, r - 1.25 * module, r * np.cos(np.radians(20.0))
    if 2 * ra > 100.0:
        raise ValueError(f"gear tip diameter {2 * ra:.1f} mm exceeds 100 mm")
    half_pitch = np.pi / (2 * n) + _involute_angle(rb, np.array(r))
    rho = np.linspace(max(rb, rf), ra, share(res, 1 / 16) + 1)
    psi = half_pitch - _involute_angle(rb, rho)       # tooth half-angle at rho
    if psi[-1] <= 0:
        raise ValueError("teeth are pointed: use more teeth or a larger module")
    radii = np.concatenate([[rf], rho, rho[::-1], [rf]]) if rf < rb else \
        np.concatenate([rho, rho[::-1]])
    offs = np.concatenate([[-psi[0]], -psi, psi[::-1], [psi[0]]]) if rf < rb \
        else np.concatenate([-psi, psi[::-1]])
    angles = (2 * np.pi * np.arange(n)[:, None] / n + offs[None, :]).ravel()
    radii = np.tile(radii, n)
    outline = np.column_stack([radii * np.cos(angles), radii * np.sin(angles)])
    return _prism(polygon(outline), depth)


@scene()
def bored_block(*, resolution: int = 48, depth: float = 40.0) -> Manifold:
    """Block 80 x 60 x 40 mm with a 30 mm through-bore along z.

    Every z-slice is a rectangle with a circular inner loop (a hole) that a
    probe from outside can never reach: the run must report it, not crash.
    x-slices through the bore split into two separate rectangles (two outer
    loops). ``resolution``: segments of the bore circle.
    """
    res = check_resolution(resolution)
    section = rect(0.0, 0.0, 80.0, 60.0) - circle((40.0, 30.0), 15.0, res)
    return _prism(section, depth)
