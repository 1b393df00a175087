"""Seeded random 2D outlines of six kinds, for the planner's property tests
and ``bench/bench_planner.py``.

Every function takes a ``numpy.random.Generator`` and ``eps`` (the planner's
epsilon) and returns contour loops in the project convention: a list of
(k, 2) float64 arrays, closed implicitly, outer loops counter-clockwise,
holes clockwise. Shapes are ~100 units across; feature widths are drawn in
units of ``eps`` so that pockets 0.5 - 2 eps wide occur on purpose.

* ``star`` -- a star with narrow radial pockets (0.5 - 2 eps wide);
* ``comb`` -- a box with slots 0.5 - 3 eps wide and teeth between them;
* ``undercut`` -- a box with keyhole chambers, dovetails and bent (L-shaped)
  pockets: contour no straight rod from outside can reach;
* ``islands`` -- two to four separate solids, gaps 1 - 10 eps, one often
  inside another's pocket;
* ``holes`` -- a solid with one to three holes (never reachable);
* ``numerics`` -- near-collinear runs, tiny edges, a large coordinate
  offset, sliver spikes one eps wide at their base.

:func:`slotted_block` is a fixed shape (no generator): a block with straight
slots of given widths in its top.

Examples
--------
>>> rng = np.random.default_rng(1)
>>> loops = outline("star", rng, eps=1.0)
>>> len(loops) >= 1 and loops[0].shape[1] == 2
True
"""
from __future__ import annotations

import numpy as np
import shapely
from shapely import affinity
from shapely.geometry import LineString, Polygon, box

try:
    from polygen import loops_from_shapely
except ImportError:  # tests/ imported as a package
    from tests.polygen import loops_from_shapely

__all__ = ["KINDS", "outline", "star", "comb", "undercut", "islands", "holes", "numerics",
           "slotted_block"]

KINDS = ("star", "comb", "undercut", "islands", "holes", "numerics")


def _clean(geom, keep_islands: bool = False):
    """Valid polygonal part; the largest polygon unless ``keep_islands``."""
    geom = shapely.make_valid(geom.buffer(0))
    polys = [g for g in getattr(geom, "geoms", [geom]) if g.geom_type == "Polygon" and g.area > 1.0]
    if not polys:
        raise ValueError("empty outline")
    if keep_islands:
        return shapely.MultiPolygon(polys) if len(polys) > 1 else polys[0]
    return max(polys, key=lambda g: g.area)


def _star_polygon(rng, n=None, r=(25.0, 50.0), center=(0.0, 0.0)):
    n = int(rng.integers(7, 18)) if n is None else n
    ang = np.sort(rng.uniform(0, 2 * np.pi, n))
    rad = rng.uniform(*r, n)
    return Polygon(np.c_[center[0] + rad * np.cos(ang), center[1] + rad * np.sin(ang)])


def _pocket(rng, poly, eps, width=(0.5, 2.0), depth=(3.0, 20.0)):
    """A straight pocket cut radially into ``poly`` from its boundary."""
    c = np.asarray(poly.centroid.coords[0])
    a = rng.uniform(0, 2 * np.pi)
    d = np.array([np.cos(a), np.sin(a)])
    far = LineString([c, c + 200 * d]).intersection(poly.exterior)
    pts = shapely.get_coordinates(far)
    if len(pts) == 0:
        return poly
    mouth = pts[np.argmax(pts @ d)]
    w, dep = rng.uniform(*width) * eps, rng.uniform(*depth) * eps
    slot = LineString([mouth + 2 * eps * d, mouth - dep * d]).buffer(w / 2, cap_style="flat")
    return poly.difference(slot)


def star(rng, eps=1.0):
    """A star with 1 - 4 narrow radial pockets 0.5 - 2 eps wide."""
    poly = _star_polygon(rng)
    for _ in range(int(rng.integers(1, 5))):
        poly = _clean(_pocket(rng, poly, eps))
    return loops_from_shapely(_clean(poly))


def comb(rng, eps=1.0):
    """A box with 3 - 8 vertical slots 0.5 - 3 eps wide, 5 - 40 eps deep."""
    poly = box(-50, -30, 50, 30)
    k = int(rng.integers(3, 9))
    xs = np.sort(rng.uniform(-45, 45, k))
    for x in xs:
        w, dep = rng.uniform(0.5, 3.0) * eps, rng.uniform(5, 40) * eps
        poly = poly.difference(box(x - w / 2, 30 - min(dep, 55), x + w / 2, 31))
    return loops_from_shapely(_clean(poly))


def undercut(rng, eps=1.0):
    """A box with keyholes (neck over a wider chamber), dovetails and L-pockets."""
    poly = box(-50, -50, 50, 50)
    for x in rng.choice(np.linspace(-35, 35, 5), size=int(rng.integers(1, 4)), replace=False):
        kind = rng.choice(["keyhole", "dovetail", "bent"])
        neck = rng.uniform(2.0, 6.0) * eps
        if kind == "keyhole":
            cut = box(x - neck / 2, 25, x + neck / 2, 51).union(box(x - 7, 5, x + 7, 25))
        elif kind == "dovetail":
            cut = Polygon([(x - neck / 2, 51), (x + neck / 2, 51), (x + 7, 20), (x - 7, 20)])
        else:
            side = rng.choice([-1.0, 1.0])
            cut = box(x - neck / 2, 15, x + neck / 2, 51).union(
                box(min(x, x + side * 12), 15, max(x, x + side * 12), 15 + neck))
        poly = poly.difference(cut)
    return loops_from_shapely(_clean(poly))


def islands(rng, eps=1.0):
    """Two to four separate solids with gaps of 1 - 10 eps."""
    main = _star_polygon(rng, r=(30.0, 50.0))
    if rng.random() < 0.5:  # an island sitting in a wide pocket of the main solid
        a = rng.uniform(0, 2 * np.pi)
        d = np.array([np.cos(a), np.sin(a)])
        main = main.difference(box(-9, -9, 9, 9).union(
            LineString([[0, 0], 80 * d]).buffer(9, cap_style="flat")))
        isl = _star_polygon(rng, r=(3.0, 6.0), center=tuple(25 * d))
        parts = [_clean(main), isl.difference(main.buffer(rng.uniform(1, 4) * eps))]
    else:
        parts = [_clean(main)]
    for _ in range(int(rng.integers(1, 3))):
        a = rng.uniform(0, 2 * np.pi)
        gap = rng.uniform(1, 10) * eps
        blob = _star_polygon(rng, r=(8.0, 18.0))
        d = np.array([np.cos(a), np.sin(a)])
        blob = affinity.translate(blob, *(80 * d))
        while blob.distance(shapely.union_all(parts)) > gap and np.linalg.norm(
                np.asarray(blob.centroid.coords[0])) > 1:
            blob = affinity.translate(blob, *(-0.5 * d))
        blob = blob.difference(shapely.union_all(parts).buffer(gap))
        parts.append(blob)
    geom = _clean(shapely.union_all([p for p in parts if not p.is_empty]), keep_islands=True)
    return loops_from_shapely(geom)


def holes(rng, eps=1.0):
    """A star with 1 - 3 holes."""
    poly = _star_polygon(rng, r=(35.0, 50.0))
    for _ in range(int(rng.integers(1, 4))):
        c = rng.uniform(-15, 15, 2)
        poly = poly.difference(_star_polygon(rng, r=(2.0, 6.0), center=tuple(c)))
    return loops_from_shapely(_clean(poly))


def numerics(rng, eps=1.0):
    """Awkward numbers: near-collinear runs, tiny edges, an offset, slivers."""
    poly = _star_polygon(rng, n=int(rng.integers(6, 10)))
    loop = np.asarray(poly.exterior.coords)[:-1]
    out = []
    for p, q in zip(loop, np.roll(loop, -1, axis=0)):
        out.append(p)
        k = int(rng.integers(0, 6))  # near-collinear points with 1e-9 wobble
        for t in np.sort(rng.uniform(0, 1, k)):
            out.append(p + t * (q - p) + rng.normal(0, 1e-9, 2))
        if rng.random() < 0.3:  # a tiny edge
            out.append(p + 1e-6 * (q - p) / np.linalg.norm(q - p))
    poly = _clean(Polygon(out))
    if rng.random() < 0.5:  # a sliver spike one eps wide at its base
        c = np.asarray(poly.representative_point().coords[0])
        a = rng.uniform(0, 2 * np.pi)
        d = np.array([np.cos(a), np.sin(a)])
        n = np.array([-d[1], d[0]])
        poly = _clean(poly.union(Polygon([c + 0.5 * eps * n, c + 70 * d, c - 0.5 * eps * n])))
    loops = loops_from_shapely(poly)
    shift = rng.choice([0.0, 1e5, 1e6])
    return [lp + shift for lp in loops]


_KIND_FN = {"star": star, "comb": comb, "undercut": undercut, "islands": islands,
            "holes": holes, "numerics": numerics}


def outline(kind: str, rng, eps: float = 1.0) -> list[np.ndarray]:
    """One outline of ``kind`` (one of :data:`KINDS`); retries degenerate draws."""
    for _ in range(20):
        try:
            return _KIND_FN[kind](rng, eps)
        except ValueError:
            continue
    raise RuntimeError(f"could not draw a {kind} outline")


def slotted_block(slots, tooth: float, depth: float, base: float):
    """Counter-clockwise outline of a block with straight slots ``slots``
    wide (left to right) and ``depth`` deep in its top, teeth ``tooth`` wide
    between them and ``base`` of solid below; and the workspace circle
    around it. Returns ``(loops, (centre (2,), radius))``."""
    width = tooth * (len(slots) + 1) + sum(slots)
    top = base + depth
    pts = [(0.0, 0.0), (width, 0.0), (width, top)]
    x = width - tooth
    for s in slots[::-1]:
        pts += [(x, top), (x, base), (x - s, base), (x - s, top)]
        x -= s + tooth
    pts.append((0.0, top))
    loops = [np.array(pts, float)]
    lo, hi = loops[0].min(0), loops[0].max(0)
    return loops, ((lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2 + 1.0))
