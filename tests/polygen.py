"""Hypothesis strategies for planar test contours (``loops``) of ~100 units.

Every strategy draws a shapely geometry, regularises it morphologically so
that no neck, slot, spike or gap is narrower than ``min_feature`` (closing
then opening with radius ``min_feature / 2``, mitred joins), checks
``is_valid`` and returns contour loops in the project convention: a list of
(k, 2) float64 arrays, closed implicitly, outer loops counter-clockwise,
holes clockwise.

* :func:`simple_polygons` -- one simply connected polygon: star-shaped
  (random radii) or a "comb" (a box with straight slots, keyholes with an
  undercut chamber, bent channels and arms made of buffered lines);
* :func:`polygons_with_islands` -- such a polygon plus a disjoint second
  outer loop (often sitting in a pocket);
* :func:`polygons_with_holes` -- such a polygon with one or two holes.

``rounded=True`` rounds every corner to radius ``min_feature / 2``: then the
paper's eps/2-circle assumption (§3.2) holds for every eps < min_feature
(checked: no violation in 300 shapes). The default mitred shapes keep exact
right angles (slots, keyholes) but radial shapes have acute corners where it
fails locally. :func:`keyhole` and :func:`slotted_box` are fixed shapes with
hand-computed reachability.

Examples
--------
>>> from hypothesis import given
>>> @given(simple_polygons())
... def test_ccw(loops):
...     assert not hole_flags(loops).any()
"""
from __future__ import annotations

import numpy as np
import shapely
from hypothesis import strategies as st
from shapely.geometry import LineString, MultiPolygon, Point, Polygon, box
from shapely.geometry.polygon import orient

__all__ = [
    "SIZE",
    "loops_from_shapely",
    "shapely_from_loops",
    "hole_flags",
    "regularise",
    "radial_geoms",
    "slotted_geoms",
    "simple_polygons",
    "polygons_with_islands",
    "polygons_with_holes",
    "keyhole",
    "slotted_box",
]

#: overall size of the generated shapes (bounding box ~ SIZE x SIZE)
SIZE = 100.0
_MITRE = dict(join_style="mitre", mitre_limit=2.0)


def loops_from_shapely(geom) -> list[np.ndarray]:
    """Loops of a (Multi)Polygon: exteriors CCW then their interiors CW.

    Returns
    -------
    list of (k, 2) float64 arrays, the closing vertex not repeated.
    """
    polys = list(geom.geoms) if hasattr(geom, "geoms") else [geom]
    loops = []
    for poly in polys:
        if poly.is_empty:
            continue
        poly = orient(poly, sign=1.0)
        for ring in [poly.exterior, *poly.interiors]:
            loops.append(np.asarray(ring.coords, dtype=np.float64)[:-1].copy())
    return loops


def shapely_from_loops(loops):
    """Inverse of :func:`loops_from_shapely`: a Polygon or MultiPolygon (holes by orientation)."""
    flags = hole_flags(loops)
    outers = [Polygon(lp) for lp, h in zip(loops, flags) if not h]
    holes = [Polygon(lp) for lp, h in zip(loops, flags) if h]
    polys = [Polygon(o.exterior, [h.exterior for h in holes if o.contains(h)]) for o in outers]
    return polys[0] if len(polys) == 1 else MultiPolygon(polys)


def hole_flags(loops) -> np.ndarray:
    """(L,) bool: the loop runs clockwise (negative shoelace area)."""
    out = []
    for lp in loops:
        x, y = np.asarray(lp, dtype=np.float64).T
        out.append(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)) < 0)
    return np.array(out, dtype=bool)


def regularise(geom, min_feature: float, rounded: bool = False):
    """Morphological closing then opening with radius ``min_feature / 2``.

    Gaps, slots and necks narrower than ``min_feature`` are filled or cut,
    collinear vertices dropped. ``rounded`` uses round joins, so every corner
    becomes an arc of radius ``min_feature / 2`` (polygonised, 12 segments a
    circle): then a circle of radius < ``min_feature / 2`` around any contour
    point crosses the contour exactly twice (the paper's eps/2-circle
    assumption of §3.2 with eps < min_feature). Mitred joins (the default)
    keep rectilinear shapes exact but leave acute corners, where that
    assumption fails locally. Returns a valid (Multi)Polygon, maybe empty.
    """
    r = 0.5 * min_feature
    kw = dict(quad_segs=3) if rounded else _MITRE
    g = geom.buffer(r, **kw).buffer(-2 * r, **kw).buffer(r, **kw)
    g = shapely.make_valid(g.simplify(1e-3 * min_feature))
    return shapely.union_all([p for p in _polys(g) if p.area > min_feature**2])


def _polys(geom) -> list[Polygon]:
    if geom.is_empty:
        return []
    if geom.geom_type == "Polygon":
        return [geom]
    return [p for g in getattr(geom, "geoms", []) for p in _polys(g)]


def _largest(geom, drop_holes: bool = True):
    polys = _polys(geom)
    if not polys:
        return Polygon()
    p = max(polys, key=lambda q: q.area)
    return Polygon(p.exterior) if drop_holes else p


def _unit(draw, lo, hi):
    return draw(st.floats(lo, hi, allow_nan=False, allow_infinity=False))


@st.composite
def radial_geoms(draw, min_feature: float = 2.0, rounded: bool = False,
                 min_vertices: int = 6, max_vertices: int = 40):
    """A star-shaped polygon with random radii in [SIZE/8, SIZE/2] (shapely)."""
    n = draw(st.integers(min_vertices, max_vertices))
    jitter = np.array(draw(st.lists(st.floats(-0.4, 0.4), min_size=n, max_size=n)))
    radii = np.array(draw(st.lists(st.floats(0.25, 1.0), min_size=n, max_size=n)))
    theta = 2 * np.pi * (np.arange(n) + jitter) / n
    pts = 0.5 * SIZE * radii[:, None] * np.c_[np.cos(theta), np.sin(theta)]
    g = _largest(regularise(Polygon(pts), min_feature, rounded))
    if g.is_empty:  # cannot happen with radii >= SIZE/8, kept for safety
        g = Point(0, 0).buffer(SIZE / 4, quad_segs=4)
    return g


@st.composite
def slotted_geoms(draw, min_feature: float = 2.0, rounded: bool = False, max_cuts: int = 6):
    """A box with slots, keyholes (undercut chambers), bent channels and arms."""
    w, h = _unit(draw, 0.6 * SIZE, SIZE), _unit(draw, 0.4 * SIZE, 0.8 * SIZE)
    body = box(-w / 2, -h / 2, w / 2, h / 2)
    sides = {  # mouth centre, tangent, inward normal, side length, depth available
        "top": ((0, h / 2), (1, 0), (0, -1), w, h),
        "bottom": ((0, -h / 2), (-1, 0), (0, 1), w, h),
        "left": ((-w / 2, 0), (0, 1), (1, 0), h, w),
        "right": ((w / 2, 0), (0, -1), (-1, 0), h, w),
    }
    cuts, arms = [], []
    for _ in range(draw(st.integers(1, max_cuts))):
        c, t, nrm, length, depth = sides[draw(st.sampled_from(sorted(sides)))]
        c, t, nrm = (np.asarray(v, dtype=float) for v in (c, t, nrm))
        kind = draw(st.sampled_from(["slot", "keyhole", "bent", "arm"]))

        def at(u, v):
            return tuple(c + u * t + v * nrm)

        u0 = _unit(draw, -0.4, 0.4) * length
        width = _unit(draw, 1.5 * min_feature, max(1.5 * min_feature, 0.12 * SIZE))
        d = _unit(draw, 0.15, 0.45) * depth
        if kind == "arm":
            reach = _unit(draw, 2 * min_feature, 0.2 * SIZE)
            turn = _unit(draw, -0.2, 0.2) * SIZE
            line = LineString([at(u0, min_feature), at(u0, -reach), at(u0 + turn, -reach)])
            arms.append(line.buffer(width / 2, cap_style="flat", **_MITRE))
            continue
        neck = Polygon([at(u0 - width / 2, -1), at(u0 + width / 2, -1),
                        at(u0 + width / 2, d), at(u0 - width / 2, d)])
        cuts.append(neck)
        if kind == "keyhole":
            cw = _unit(draw, width + 2 * min_feature, width + 0.3 * SIZE)
            ch = _unit(draw, 2 * min_feature, 0.15 * SIZE)
            cuts.append(Polygon([at(u0 - cw / 2, d), at(u0 + cw / 2, d),
                                 at(u0 + cw / 2, d + ch), at(u0 - cw / 2, d + ch)]))
        elif kind == "bent":
            turn = _unit(draw, -0.25, 0.25) * SIZE
            line = LineString([at(u0, d - width / 2), at(u0 + turn, d - width / 2)])
            cuts.append(line.buffer(width / 2, cap_style="square", **_MITRE))
    g = shapely.union_all([body.difference(shapely.union_all(cuts)), *arms])
    g = _largest(regularise(g, min_feature, rounded))
    return g if not g.is_empty else body


def _simple_geoms(min_feature, rounded):
    return st.one_of(radial_geoms(min_feature, rounded), slotted_geoms(min_feature, rounded))


def simple_polygons(min_feature: float = 2.0, rounded: bool = False):
    """Strategy: loops of one simply connected polygon (one CCW loop)."""
    return _simple_geoms(min_feature, rounded).map(loops_from_shapely)


@st.composite
def _with_island(draw, min_feature, rounded):
    g = draw(_simple_geoms(min_feature, rounded))
    x0, y0, x1, y1 = g.bounds
    cx, cy = _unit(draw, x0, x1), _unit(draw, y0, y1)
    size = _unit(draw, 2 * min_feature, 0.15 * SIZE)
    shape = draw(st.sampled_from(["pocket", "pocket", "box", "octagon", "beside"]))
    island = (box(cx - size, cy - size / 2, cx + size, cy + size / 2) if shape == "box"
              else Point(cx, cy).buffer(size, quad_segs=2))
    free = g.buffer(min_feature, quad_segs=16)
    pockets = sorted(_polys(regularise(g.convex_hull.difference(free), min_feature, rounded)),
                     key=lambda q: -q.area)
    if shape == "pocket" and pockets:  # fill (part of) a pocket of the convex hull
        pocket = pockets[draw(st.integers(0, len(pockets) - 1))]
        island = pocket.intersection(island.buffer(size)) if draw(st.booleans()) else pocket
    candidates = [] if shape == "beside" else [island, *pockets[:1]]
    candidates = [_largest(regularise(c.difference(free), min_feature, rounded)) for c in candidates]
    # beside the polygon: always possible
    candidates.append(box(x1 + 2 * min_feature, cy - size / 2, x1 + 2 * min_feature + size, cy + size / 2))
    island = next(c for c in candidates if not c.is_empty and c.distance(g) >= 0.999 * min_feature)
    geom = MultiPolygon([g, island])
    assert geom.is_valid
    return loops_from_shapely(geom)


def polygons_with_islands(min_feature: float = 2.0, rounded: bool = False):
    """Strategy: loops of a polygon plus a disjoint island (two CCW loops)."""
    return _with_island(min_feature, rounded)


@st.composite
def _with_holes(draw, min_feature, rounded):
    g = draw(_simple_geoms(min_feature, rounded))
    room = g.buffer(-min_feature, **_MITRE)  # holes keep walls >= min_feature
    holes = []
    circle = shapely.maximum_inscribed_circle(room)
    centre, edge = np.asarray(circle.coords)
    radius = float(np.hypot(*(edge - centre)))
    if radius > min_feature:
        r = _unit(draw, min_feature, max(min_feature, 0.8 * radius))
        holes.append(Point(*centre).buffer(r, quad_segs=2))
    for _ in range(draw(st.integers(0, 1))):
        x0, y0, x1, y1 = room.bounds
        cx, cy = _unit(draw, x0, x1), _unit(draw, y0, y1)
        size = _unit(draw, min_feature, 0.1 * SIZE)
        holes.append(box(cx - size, cy - size, cx + size, cy + size).intersection(room))
    hole = regularise(shapely.union_all(holes).intersection(room), min_feature, rounded) if holes else Polygon()
    geom = _largest(regularise(g.difference(hole), min_feature, rounded), drop_holes=False)
    if not geom.interiors:  # too thin for a hole anywhere: a box with a square hole
        geom = box(-SIZE / 2, -SIZE / 2, SIZE / 2, SIZE / 2).difference(box(-10, -10, 10, 10))
    assert geom.is_valid
    return loops_from_shapely(geom)


def polygons_with_holes(min_feature: float = 2.0, rounded: bool = False):
    """Strategy: loops of a polygon with one or two holes (CCW loop then CW loops)."""
    return _with_holes(min_feature, rounded)


def keyhole(neck: float = 3.0) -> list[np.ndarray]:
    """Box [-50, 50]^2 with a neck |x| < ``neck``, 20 < y < 50, over a chamber
    |x| < 30, -20 < y < 20 (an undercut cavity; one CCW loop).

    Exact reachability: the chamber ceiling (y = 20) and side walls
    (|x| = 30) are unreachable, the neck walls reachable, and a floor point
    (x, -20) is reachable iff |x| < 11 * neck / 3 (a line through it must
    pass both neck openings y = 20 and y = 50).
    """
    cut = box(-neck, 20, neck, 50).union(box(-30, -20, 30, 20))
    return loops_from_shapely(box(-50, -50, 50, 50).difference(cut))


def slotted_box(width: float, depth: float) -> list[np.ndarray]:
    """Box [-50, 50]^2 with a straight slot |x| < width / 2, y > 50 - depth."""
    return loops_from_shapely(box(-50, -50, 50, 50).difference(box(-width / 2, 50 - depth, width / 2, 50)))
