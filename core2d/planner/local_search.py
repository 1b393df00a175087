"""Local concave point search (§4.2): initial pass planning and bisection.

* :func:`initial_pass` -- Theorem 1: move the probe along the line through a
  point of L_{A0}^{B0} cap G_i cap V_i and the centre of L_{A_i}^{B_i} (or the
  common point of the two triangles of G_i, Fig. 5(c)). In a closed slice the
  known-free part of G_i cap V_i is what lies outside the workspace circle:
  it plays the role of L_{A0}^{B0}.
* :func:`bisection` -- §4.2.2 (i)-(iv): swing / divide / insert, the swing
  bounded so the probe never leaves the segments P_i^(j)A_i, P_i^(j)B_i (T_i^(j),
  Theorem 2) and the tip stays in T_i^(j) cap V_i cap G_i except across
  L_{A_i}^{B_i} (Theorem 3). Ends in a final state of Fig. 10 with (Y1, Y2)
  of Definition 5.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass, replace

import numpy as np
import shapely
from shapely.geometry import Point

from core2d.planar import wrap
from core2d.planner.regions import G_region, V_polygon, common_point, polygonal
from core2d.planner.robot import Robot
from core2d.planner.tip_bound import polygon_rings, tip_bound
from core2d.readings import TIP, Reading

__all__ = ["initial_pass", "bisection", "definition5", "reread_torque", "LocalResult"]


@functools.lru_cache(maxsize=16)
def _circle(cx, cy, radius):
    """The workspace circle as a shapely ring (built once per circle: immutable)."""
    return Point(cx, cy).buffer(radius, 256).exterior


def _start_point(probe: Robot, G, a, b):
    """A point of L_{A0}^{B0} cap G_i cap V_i: the centre of the longest piece
    of the workspace circle inside G_i cap V_i; when the circle barely
    touches it (postures converging there), the point of G_i cap V_i farthest
    from L_{A_i}^{B_i}. None when G_i cap V_i is empty (no pass)."""
    GV = polygonal(G.intersection(V_polygon(a, b, probe.radius + probe.length)))
    if GV.is_empty or GV.area <= 0:
        return None, GV
    ring = _circle(float(probe.center[0]), float(probe.center[1]), probe.radius)
    arc = ring.intersection(GV)
    if not arc.is_empty and arc.length > probe.resolution.tol:
        line = max(getattr(arc, "geoms", [arc]), key=lambda g: g.length)
        return np.array(line.interpolate(0.5, normalized=True).coords[0]), GV
    pts = shapely.get_coordinates(GV)
    lid = shapely.LineString([a, b])
    far = pts[int(np.argmax(shapely.distance(shapely.points(pts), lid)))]
    return np.asarray(far, float), GV


def initial_pass(probe: Robot, area, G=None):
    """Theorem 1 insertion for ``area``.

    Returns ``(Reading, G_i, None)`` or ``(None, G_i, why)``. G_i defaults to
    the region of the two postures (Definition 1); for a single probe
    detection the caller passes the triangle swept about the tip. Without a
    pass -- Area(G_i) = 0, or no point of L_{A0}^{B0} cap G_i cap V_i -- the
    caller categorises A_iB_i as W3 and ``why`` says which.
    """
    if G is None:
        G = G_region(area.a, area.b, area.pose_a, area.pose_b)
    if G.area <= probe.resolution.tol * max(area.dist, probe.resolution.tol):
        return None, G, "Area(G) = 0"
    start, GV = _start_point(probe, G, area.a, area.b)
    if start is None:
        return None, G, "no pass: G cap V is empty"
    # Two triangles (Fig. 5(c)/(d)): (c) when L_{A0}^{B0} -- here the
    # workspace circle -- crosses the joints' triangle, i.e. the common point
    # lies inside the circle: the pass must go through it. Otherwise (d) or a
    # convex G_i cap V_i: aim at the centre of L_{A_i}^{B_i}.
    aim = common_point(area.a, area.b, area.pose_a, area.pose_b)
    if aim is None or GV.geom_type == "Polygon" or \
            np.linalg.norm(aim - probe.center) >= probe.radius:
        aim = (area.a + area.b) / 2
    t = aim - start
    if np.linalg.norm(t) < probe.resolution.tol:
        return None, G, "Area(G) = 0"
    probe.approach(start, t)
    r = probe.insert(2.5 * probe.radius)
    if r.tip_contact is None:
        return None, G, "Theorem 1 pass found no contact"
    return r, G, None


@dataclass
class LocalResult:
    """Final state of the bisection (Fig. 10, Definition 5).

    reading : Reading at D_i. point : (2,) float -- D_i (tip contact).
    Y1 : 1 tip only, 2 multiple contacts. Y2 : 0 full constraint, 1 clockwise
    constrained, -1 counter-clockwise constrained.
    iterations : int.
    """

    reading: Reading
    point: np.ndarray
    Y1: int
    Y2: int
    iterations: int


def _bounds(joint, theta, a, b):
    """Signed angles from ``theta`` to the rays P->A and P->B (T_i^(j))."""
    da = wrap(np.arctan2(*(np.asarray(a) - joint)[::-1]) - theta)
    db = wrap(np.arctan2(*(np.asarray(b) - joint)[::-1]) - theta)
    ccw = max(da, db, 0.0)
    cw = max(-da, -db, 0.0)
    return ccw, cw


def bisection(probe: Robot, area, G, reading, max_iter=60):
    """Bisection local concave point search from an initial tip contact.

    Rotation is constrained in a direction when the torque sensor reports it
    blocked (environment) or when the swing bound of Theorems 2/3 is used up
    (the boundary of T_i^(n), Fig. 10(b)).
    """
    r = reading
    last = r.tip_contact.point
    small = 0
    G = polygon_rings(G.buffer(probe.resolution.tol))  # Theorem 3, tolerant to contact noise
    it = 0
    con_ccw = con_cw = False
    for it in range(1, max_iter + 1):
        ccw_lim, cw_lim = _bounds(probe.joint, probe.theta, area.a, area.b)
        ccw_lim = tip_bound(probe, G, area.a, area.b, probe.theta, 1, ccw_lim)
        cw_lim = tip_bound(probe, G, area.a, area.b, probe.theta, -1, cw_lim)
        con_ccw = r.blocked_ccw or ccw_lim <= probe.resolution.angle_tol(probe.length)
        con_cw = r.blocked_cw or cw_lim <= probe.resolution.angle_tol(probe.length)
        if con_ccw and con_cw:
            break  # Fig. 10(a)/(c), or (b) with one side held by the boundary
        limit, rot = max(((ccw_lim, 1),) * (not con_ccw) + ((cw_lim, -1),) * (not con_cw))
        theta0 = probe.theta
        probe.swing(rot, limit)  # (i) swing
        phi = probe.theta - theta0
        probe.turn_to(theta0 + phi / 2)  # (ii) dividing
        r = probe.insert(2.5 * probe.radius)  # (iii) inserting
        tip = r.tip_contact
        if tip is None:
            return None
        moved = np.linalg.norm(tip.point - last)
        last = tip.point
        small = small + 1 if moved < probe.resolution.tol else 0
        if small >= 2:
            con_ccw, con_cw = r.blocked_ccw or con_ccw, r.blocked_cw or con_cw
            break
    tip = r.tip_contact
    if tip is None:
        return None
    r = reread_torque(probe, r)
    Y1, Y2 = definition5(r)
    return LocalResult(r, tip.point, Y1, Y2, it)


def reread_torque(probe: Robot, reading: Reading) -> Reading:
    """``reading`` with each blocked-rotation flag taken by majority over
    :attr:`~core2d.resolution.Resolution.torque_reads` readings at the final
    state D_i. Y2 of Definition 5 decides which side Theorem 4 traces; one
    noisy torque reading flipping it sends the trace the wrong way (a detour
    and, under a threshold, a missed side), while a re-reading costs no
    motion. A noiseless torque sensor (one read) keeps the paper's flow."""
    k = probe.resolution.torque_reads
    if k <= 1:
        return reading
    again = probe.reread(k - 1).blocked.sum(axis=0)
    ccw = (reading.blocked_ccw + int(again[0])) * 2 > k
    cw = (reading.blocked_cw + int(again[1])) * 2 > k
    return replace(reading, blocked_ccw=ccw, blocked_cw=cw)


def definition5(reading) -> tuple[int, int]:
    """(Y1, Y2) of Definition 5 from what the sensors report at D_i.

    Y1: 1 when only the tip touches, 2 with other contacts. Y2: the rotational
    constraint the environment puts on the probe, from the torque sensor --
    0 both rotations blocked (Fig. 10(a), (c)), 1 clockwise only, -1
    counter-clockwise only (Fig. 10(b)). The bisection's own swing bounds
    (T_i^(n), G_i) are not a constraint of the environment and do not count.
    A probe free both ways (normal to a flat stretch, stopped by the bounds)
    has no value in Definition 5; it gets Y2 = 0, so Theorem 4 (A) traces
    both sides, each under its own torque.

    Examples
    --------
    >>> from core2d.readings import Contact, Reading
    >>> tip = Contact(np.zeros(2), "tip", 1.0)
    >>> r = Reading(np.zeros(2), np.array([0.0, -1.0]), (tip,), blocked_cw=True)
    >>> definition5(r)
    (1, 1)
    """
    Y1 = 1 if all(c.face == TIP for c in reading.contacts) else 2
    cw, ccw = reading.blocked_cw, reading.blocked_ccw
    return Y1, (0 if cw == ccw else (1 if cw else -1))
