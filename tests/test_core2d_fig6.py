"""Single probe detection (Fig. 6, §4.2.1) and the W3 it licenses.

Fig. 6(a): a pass grazing a convex corner, pivoted about the tip, sweeps a
triangle G_i; Fig. 6(b): in a slit the pass the probe holds is the only one
through its tip, Area(G_i) = 0. The planner makes W3 of it only when its own
map proves the lid (no free line crosses it); otherwise the area is deferred
and revisited. Scenes are in ``figure_scenes.py``; geometry is checked
against the ground-truth contour, never with the planner's own view.
"""
from __future__ import annotations

import numpy as np
import pytest
from shapely.geometry import Point

from core2d.planner.areas import Area, pivot_G
from core2d.planner.pass_plan import MAX_SWEEP, MAX_TRIES
from core2d.planner.revisit import revisit
from core2d.readings import LEFT, RIGHT, TIP
from figure_scenes import (GRAZE_AWAY, GRAZE_DIR, LIP_LEFT, OVERHANG_LEFT, SLIT, SLIT_CORNER, block,
                           chain, dist_to_contour, graze_point, make_probe, new_run, place, pose_to,
                           run_one)

EPS = 1.0
EPS_TOL = EPS / 20  # the probe's default contact resolution tol


def _graze(top, offset):
    """Probe along GRAZE_DIR, ``offset`` from the lip corner: tip on the cave
    floor, Face(left) on the lip (one posture touching A_i and B_i)."""
    loops = block(top)
    probe = make_probe(loops)
    r = place(probe, graze_point(offset), GRAZE_DIR)
    return loops, probe, r


def test_fig6a_pivot_about_the_tip_gives_a_triangle():
    """Def. 1: for a single probe detection G_i is made by rotating the probe
    around the tip till it touches; here it sweeps until the probe line meets
    the pocket's rim corner (70, 60)."""
    loops, probe, r = _graze(OVERHANG_LEFT, 0.5 * EPS_TOL)
    faces = {c.face: c.point for c in r.contacts}
    assert set(faces) == {TIP, LEFT} and r.blocked_cw  # Face(left) blocks cw
    assert np.linalg.norm(faces[LEFT] - LIP_LEFT) < 0.2
    tip, joint, theta = r.tip_contact.point, probe.joint.copy(), probe.theta
    assert np.linalg.norm(probe.tip - tip) < EPS_TOL
    assert dist_to_contour(loops, tip) < 1e-9
    G = pivot_G(probe, LEFT)
    assert G is not None and G.geom_type == "Polygon" and len(G.exterior.coords) == 4
    a0 = np.arctan2(-GRAZE_DIR[1], -GRAZE_DIR[0])  # joint side of the tip
    a1 = np.arctan2(60 - tip[1], 70 - tip[0])  # line from the tip through (70, 60)
    want = 0.5 * probe.length**2 * np.sin(a0 - a1)
    assert G.area == pytest.approx(want, rel=0.01)
    for vertex in (probe.tip, joint):  # the swept triangle starts at this posture
        assert Point(*vertex).distance(G) < 1e-9
    np.testing.assert_allclose(probe.joint, joint, atol=1e-9)  # posture restored
    assert probe.theta == pytest.approx(theta)


def test_fig6b_only_one_pass_gives_zero_area():
    """Fig. 6(b): the probe passes a slit between the lip (left) and a roof
    corner (right); no rotation about the tip is possible: Area(G_i) = 0."""
    loops, probe, r = _graze(SLIT, 2.5 * EPS_TOL)
    right = r.contact(RIGHT)  # the roof corner on the other face
    assert r.tip_contact is not None and right is not None
    assert np.linalg.norm(right.point - SLIT_CORNER) < 0.2
    assert pivot_G(probe, LEFT) is None


def _single_area(top):
    """A_i = lip corner, B_i = floor point, both on one recorded posture."""
    loops = block(top)
    probe = make_probe(loops)
    probe0 = make_probe(loops)
    floor = place(probe0, graze_point(0.5 * EPS_TOL), GRAZE_DIR).tip_contact.point
    pose = pose_to(probe, floor, GRAZE_DIR)
    return loops, probe, Area(LIP_LEFT.copy(), floor, pose, pose)


def _known_except(loops, area):
    """The robot's map after everything but C_A^B has been traced: the true
    contour minus the arc between A and B, material on the right."""
    arc = chain(loops, area.b, area.a)  # the rest of the loop, B -> A
    return np.asarray(arc.coords)


def test_fig6b_planner_W3_single_probe_detection():
    """§4.2.1: 'Once Area(G_i) = 0 is detected, the algorithm categorizes A_iB_i
    into never touching area W3'. The slit is SLIT_GAP = 0.13 wide: the pivot
    about the tip cannot resolve it, but the robot's map (everything else
    traced) still lets a thin fan of lines through, so the area is deferred;
    the revisit probes the lid every eps/2, every pass ends at a touched end
    of the lid, and the lid closes the loop of recorded contour: W3."""
    loops, probe, area = _single_area(SLIT)
    assert area.single
    run = new_run(probe)
    run.known.add(_known_except(loops, area))
    run.add(area)
    run.process(run.queue.popleft())
    rec = run.result.areas[0]
    assert rec.outcome == "deferred" and "Area(G) = 0" in rec.note
    before = probe.stats.motions
    revisit(run)
    assert rec.outcome == "W3" and "touched end" in rec.note and "held the lid" in rec.note
    assert len(run.result.w3) == 1 and not run.queue and not run.deferred
    np.testing.assert_allclose(run.result.w3[0], [area.a, area.b])
    sweep = min(MAX_SWEEP, np.ceil(2 * area.dist / EPS))  # one pass every eps/2
    assert area.tries == MAX_TRIES + sweep
    # approach + insert per pass, then the probe takes the lid's posture once
    assert probe.stats.motions - before == 2 * area.tries + 2


def test_fig6b_closed_slit_is_W3_at_once():
    """With the slit closed (the roof corner on the grazing line) the map
    leaves no line through the lid: Area(G_i) = 0 decides W3 at once."""
    loops, probe, area = _single_area(SLIT)
    run = new_run(probe)
    run.known.add(_known_except(loops, area))
    run.known.add([SLIT_CORNER, LIP_LEFT - 0.05 * GRAZE_AWAY])  # the slit shut above A
    run.add(area)
    run.process(run.queue.popleft())
    rec = run.result.areas[0]
    assert rec.outcome == "W3" and rec.note == "single probe detection, Area(G) = 0"
    assert not run.deferred


def test_fig6b_zero_area_is_not_W3_while_lines_still_cross_the_lid():
    """Area(G_i) = 0 on an empty map: lines from F through the lid are not
    excluded by anything the robot has recorded, so it is a dead end
    (deferred for a second look), not W3."""
    loops, probe, area = _single_area(SLIT)
    run = run_one(probe, area)
    rec = run.result.areas[0]
    assert rec.outcome == "deferred" and "Area(G) = 0" in rec.note
    assert not run.result.w3 and run.deferred == [area]
    revisit(run)  # nothing else recorded: passes find new contour; never W3
    assert rec.outcome != "W3" and not run.result.w3


def test_fig6a_planner_uses_the_triangle():
    loops, probe, area = _single_area(OVERHANG_LEFT)
    run = run_one(probe, area)
    rec = run.result.areas[0]
    assert rec.outcome != "W3" and not run.result.w3
    assert probe.stats.motions > 3  # pivot, initial pass, bisection, tracing
