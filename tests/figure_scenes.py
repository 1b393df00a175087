"""Hand-made polygons for the figure tests of Kaneko & Tsuji (WAFR 2000).

Every scene is a block about 100 units wide (0 <= x <= 100, bottom y = 0)
whose top edge carries a pocket, hill or overhang; eps = 1. Loops follow the
project convention (outer CCW). An unknown area (A, B) runs clockwise along
the outer loop -- left to right along a top edge -- with the material on the
right, so V_i (Def. 3) is the free side above L_A^B.

Only the tests use the ground truth defined here (distances to the contour,
the contour chain between A and B); the planner never sees it.
"""
from __future__ import annotations

import numpy as np
from shapely.geometry import LineString, Point, Polygon
from shapely.ops import substring

from core2d.planner.areas import Area
from core2d.planner.flow import PULLING
from core2d.planner.run import Budget, Exploration
from core2d.sim.probe import Probe
from core2d.planner.regions import Posture
from slicer.contact.exact import ExactContact

EPS = 1.0
WORKSPACE = ((50.0, 40.0), 80.0)
DOWN = np.array([0.0, -1.0])


def block(top, bottom=0.0):
    """Block loop from its top edge, given left (x = 0) to right (x = 100)."""
    top = [tuple(map(float, p)) for p in top]
    pts = [(top[0][0], bottom), (top[-1][0], bottom)] + top[::-1]
    return [np.array(pts, float)]


# --- the scenes -----------------------------------------------------------
#: Fig. 4 / Fig. 10(a): an asymmetric V pocket, local concave point (40, 30).
V_POCKET = [(0, 60), (30, 60), (40, 30), (70, 60), (100, 60)]
V_BOTTOM = np.array([40.0, 30.0])

#: Fig. 10(b): a straight slope inside the area, falling toward B (to the right).
SLOPE_RIGHT = [(0, 70), (20, 70), (80, 40), (100, 40)]
#: the mirror image, falling toward A.
SLOPE_LEFT = [(0, 40), (20, 40), (80, 70), (100, 70)]

#: Fig. 10(c) / 11(c) / 12(c): a pocket whose floor falls toward an overhang
#: lip on the left; the probe ends with the tip on the floor and Face(left)
#: on the lip corner (40, 55).
OVERHANG_LEFT = [(0, 60), (40, 60), (40, 55), (30, 55), (30, 20), (70, 30),
                 (70, 60), (100, 60)]
LIP_LEFT = np.array([40.0, 55.0])
#: mirror image (lip on the right, Face(right)).
OVERHANG_RIGHT = [(100 - x, y) for x, y in OVERHANG_LEFT[::-1]]
LIP_RIGHT = np.array([60.0, 55.0])

#: Fig. 12(b): pocket, hill, second pocket: tracing from the first pocket
#: toward B leaves the surface at the hill top (50, 55) and lands beyond.
HILL = [(0, 60), (20, 60), (35, 30), (50, 55), (65, 35), (80, 60), (100, 60)]
HILL_TOP = np.array([50.0, 55.0])


def loops_of(top):
    return block(top)


def polygon(loops):
    return Polygon(loops[0])


def make_probe(loops, length=None, eps=EPS):
    return Probe(ExactContact(loops), WORKSPACE, eps, length=length)


def dist_to_contour(loops, p) -> float:
    return float(polygon(loops).exterior.distance(Point(*np.asarray(p, float))))


def chain(loops, a, b) -> LineString:
    """Ground-truth contour C_A^B, clockwise (material on the right)."""
    ring = LineString(list(loops[0][::-1]) + [tuple(loops[0][-1])])
    sa, sb = ring.project(Point(*a)), ring.project(Point(*b))
    if sa <= sb:
        return substring(ring, sa, sb)
    first = substring(ring, sa, ring.length)
    second = substring(ring, 0.0, sb)
    return LineString(list(first.coords) + list(second.coords)[1:])


def on_int(loops, a, b, p, tol=1e-6, margin=None) -> bool:
    """Is p on the contour strictly between A and B (Int(A_iB_i), Def. 2)?"""
    margin = EPS / 20 if margin is None else margin
    p = np.asarray(p, float)
    c = chain(loops, a, b)
    return (c.distance(Point(*p)) <= tol
            and np.linalg.norm(p - a) > margin and np.linalg.norm(p - b) > margin)


def pose_to(probe, point, direction) -> Posture:
    """The posture whose tip is at ``point`` pointing along ``direction``."""
    d = np.asarray(direction, float)
    d = d / np.linalg.norm(d)
    return Posture(np.asarray(point, float) - probe.length * d, d)


def place(probe, point, direction):
    """Approach through F on the line through ``point`` and insert: the
    tip touches the first contour point on that line."""
    probe.approach(np.asarray(point, float), np.asarray(direction, float))
    return probe.insert(2.5 * probe.radius)


def vertical_area(probe, a, b, **kw) -> Area:
    """Area (A, B) found by two vertical insertions from above (Fig. 5(a))."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    return Area(a, b, pose_to(probe, a, DOWN), pose_to(probe, b, DOWN), **kw)


def new_run(probe, flow=PULLING):
    """The planner's per-slice state without the bootstrap: areas added by
    hand are processed by the flowchart of Fig. 16 (with ``flow``'s additions)."""
    return Exploration(probe, probe.eps, Budget(probe), flow)


def run_one(probe, area, flow=PULLING):
    """Process ``area`` (only it, not its children); returns the Exploration."""
    run = new_run(probe, flow)
    run.add(area)
    run.process(run.queue.popleft())
    return run


# --- Fig. 6: single probe detection -----------------------------------------
#: a probe line through the cave of OVERHANG_LEFT, down-left, grazing the lip
#: corner LIP_LEFT on its left face, tip on the floor near (32, 20.5).
GRAZE_DIR = np.array([-8.0, -34.5]) / np.hypot(8.0, 34.5)
GRAZE_AWAY = np.array([-GRAZE_DIR[1], GRAZE_DIR[0]])  # unit normal, away from the lip
#: distance of the roof corner of SLIT from the line through LIP_LEFT. A
#: recorded posture passes tol/2 = 0.025 off the lip; for a single probe
#: detection the planner comes back 2 tol = 0.1 farther from the lip
#: (core2d.planner.detection.single_detection), which leaves the roof corner
#: 0.005 from the probe line: less than one angular step of the pivot about the tip.
SLIT_GAP = 0.13


def graze_point(offset):
    """A point of the line along GRAZE_DIR passing ``offset`` away from the lip."""
    return LIP_LEFT + offset * GRAZE_AWAY


def _slit_top():
    s = (64.0 - LIP_LEFT[1]) / -GRAZE_DIR[1]
    c2 = LIP_LEFT - s * GRAZE_DIR + SLIT_GAP * GRAZE_AWAY  # roof corner, y ~ 64
    return [(0, 60), (40, 60), (40, 55), (30, 55), (30, 20), (70, 30), (70, c2[1]),
            tuple(c2), (c2[0] + 4, c2[1] + 4), (100, c2[1] + 4)], c2


#: OVERHANG_LEFT with a roof over the pocket: the only opening is a slit
#: between the lip corner (left) and the roof corner SLIT_CORNER (right),
#: SLIT_GAP wide across the grazing line -- the one pass of Fig. 6(b).
SLIT, SLIT_CORNER = _slit_top()


# --- Fig. 9: Ext(A_iB_i) inside T_i^(1) cap V_i -----------------------------
#: A hill top H (initial contact), B on its right flank found by a posture from
#: the upper left (direction FIG9_DIR_B); beyond B the contour turns back up
#: under that posture into a small Ext pocket with its bottom FIG9_EXT, which
#: lies in T_i^(1) cap V_i but outside G_i.
FIG9 = [(0, 60), (20, 60), (50, 57), (75, 36), (55, 56), (60, 53), (63, 58),
        (63, 80), (100, 80)]
FIG9_A = np.array([20.0, 60.0])
FIG9_H = np.array([50.0, 57.0])
FIG9_B = FIG9_H + 0.6 * (np.array([75.0, 36.0]) - FIG9_H)  # (65, 44.4)
FIG9_DIR_B = np.array([1.0, -1.0]) / np.sqrt(2.0)
FIG9_EXT = np.array([60.0, 53.0])

#: Fig. 12(b) mirrored: tracing toward A crosses the hill (rule (i)).
HILL_MIRROR = [(100 - x, y) for x, y in HILL[::-1]]

#: Fig. 5(b): the V pocket at the right end of a 70-wide block; B = (70, 60)
#: is the top-right corner, touched by a posture from the lower right.
V_CORNER = [(0, 60), (30, 60), (40, 30), (70, 60)]


def posture_touches(probe, pose, point, tol=1e-6) -> bool:
    """Does the ray of ``pose`` from its joint first hit the contour at ``point``?"""
    _, p, _ = probe.contact.cast(pose.joint[None], pose.direction[None], probe.length + 1)
    return bool(np.all(np.isfinite(p[0])) and np.linalg.norm(p[0] - point) <= tol)


def seg_param(joint, direction, a, b):
    """Where the line (joint, direction) crosses L_A^B: parameter along A->B."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    e = b - a
    den = direction[0] * e[1] - direction[1] * e[0]
    w = a - joint
    return float((direction[1] * w[0] - direction[0] * w[1]) / den)
