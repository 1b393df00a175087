"""The probe simulator (§3.2): motions resolve contacts to tol, readings
report faces and blocked rotations, and the push counter can count."""
import numpy as np
import pytest
import shapely

from slicer.contact.exact import ExactContact
from core2d.planar import unit
from core2d.sim.probe import Probe
from core2d.readings import LEFT, RIGHT, TIP

V_BLOCK = [np.array([[0, 0], [100, 0], [100, 50], [60, 50], [50, 20], [40, 50], [0, 50]], float)]
RING = shapely.LinearRing(V_BLOCK[0])


def _probe(eps=1.0):
    return Probe(ExactContact(V_BLOCK), (np.array([50.0, 25.0]), 57.0), eps)


def test_insert_stops_within_tol_of_the_surface():
    p = _probe()
    p.approach([20.0, 60.0], [0.0, -1.0])
    r = p.insert()
    assert r.event == "contact" and r.tip_contact.face == TIP
    gap = p.tip[1] - 50.0  # stopped just above the top face
    assert 0 < gap <= p.tol
    assert np.allclose(r.tip_contact.point, [20.0, 50.0])


@pytest.mark.parametrize("rot", [1, -1])
def test_swing_stops_at_the_first_contact(rot):
    p = _probe()
    p.approach([50.0, 60.0], [0.0, -1.0])
    p.insert(40.0)  # tip from the workspace circle (y ~ 82) into the V, y ~ 42
    r = p.swing(rot, np.pi / 4)
    assert r.event == "contact"
    seg = shapely.LineString([p.joint, p.tip])
    assert 0 < seg.distance(RING) <= p.tol  # touching, not penetrating
    # the pose a little further is blocked (independent check with shapely)
    further = p.joint + p.length * unit(p.theta + rot * 4 * p.ang_tol)
    assert shapely.LineString([p.joint, further]).intersects(RING)
    assert r.contacts[0].face in (LEFT, RIGHT, TIP)
    assert (r.blocked_ccw if rot > 0 else r.blocked_cw)


def test_local_concave_point_blocks_both_rotations():
    p = _probe()
    p.approach([50.0, 60.0], [0.0, -1.0])
    r = p.insert()
    assert r.blocked_cw and r.blocked_ccw and r.tip_contact is not None


def test_translate_stops_before_obstacle():
    p = _probe()
    p.approach([45.0, 60.0], [0.0, -1.0])
    p.insert(40.0)  # tip at y ~ 42 inside the V, left wall at x ~ 42.7
    r = p.translate([-1.0, 0.0], 20.0)
    assert r.event == "blocked" and p.tip[0] < 45.0
    assert 0 < shapely.LineString([p.joint, p.tip]).distance(RING) <= p.tol


def test_trace_pulls_without_pushing_and_counts_pushes_when_unguarded():
    p = _probe()
    p.approach([50.0, 60.0], [0.0, -1.0])
    p.insert()
    t = p.direction
    n = np.array([-t[1], t[0]])
    v = (-t + n) / np.sqrt(2)  # K1 cap K2: toward B (the right lip)
    r = p.trace(v, -1, 100.0, stop_at=[60.0, 50.0])
    assert r.event == "reached" and p.stats.pushes == 0
    d = shapely.distance(shapely.points(r.trace), RING)
    assert d.max() <= 2 * p.tol and len(r.trace) > 20
    q = _probe()
    q.approach([50.0, 60.0], [0.0, -1.0])
    q.insert()
    q.trace(-v * np.array([-1, 1]), -1, 5.0, guard_push=False)  # v.t > 0: pushing
    assert q.stats.pushes > 0


def _pressed_on(loop, x, eps=1.0):
    """A probe pointing straight down, inserted at ``x`` onto ``loop``."""
    p = Probe(ExactContact([np.asarray(loop, float)]), (np.array([50.0, 25.0]), 70.0), eps)
    p.approach([x, 80.0], [0.0, -1.0])
    return p, p.insert()


# a block with a shallow valley: faces fall 10 degrees towards (50, 50)
_DROP = 50 * np.tan(np.radians(10.0))
SHALLOW_V = [[0, 0], [100, 0], [100, 50 + _DROP], [50, 50], [0, 50 + _DROP]]
FLAT = [[0, 0], [100, 0], [100, 50], [0, 50]]
SLOPE = [[0, 0], [100, 0], [100, 50 + 2 * _DROP], [0, 50]]  # rising to the right


@pytest.mark.parametrize("offset", [0.0, 0.3, -0.3])
def test_torque_sensor_blocks_both_ways_at_a_shallow_concave_corner(offset):
    """Fig. 10(a), a 160-degree valley: with the tip within tol of the local
    concave point both rotations are blocked (the tip is pressed on the
    surface; the old model, with the tip's stand-off, saw both free)."""
    p, r = _pressed_on(SHALLOW_V, 50.0 + offset * p_tol())
    assert r.tip_contact is not None
    assert r.blocked_cw and r.blocked_ccw


def p_tol(eps=1.0):
    return eps / 20


def test_torque_sensor_free_on_a_flat_surface_normal_to_the_probe():
    """On a flat surface normal to the probe the tip's arc lifts off: both
    rotations free (no constraint, Definition 5 has no value)."""
    _, r = _pressed_on(FLAT, 30.0)
    assert r.tip_contact is not None
    assert not r.blocked_cw and not r.blocked_ccw


def test_torque_sensor_one_way_on_a_slope():
    """Fig. 10(b): on a slope rising to the right, rotating the tip to the
    right (counter-clockwise for a probe pointing down) pushes it into the
    surface: ccw blocked only."""
    _, r = _pressed_on(SLOPE, 30.0)
    assert r.blocked_ccw and not r.blocked_cw


def test_readings_are_frozen_slotted_and_share_one_read_only_empty_trace():
    from dataclasses import FrozenInstanceError

    p = _probe()
    p.approach([20.0, 60.0], [0.0, -1.0])
    a, b = p.insert(), p.sense()
    assert a.trace is b.trace and a.trace.shape == (0, 2)
    with pytest.raises(ValueError):  # shared: nobody can grow it in place
        a.trace.resize((1, 2))
    assert not a.trace.flags.writeable
    with pytest.raises(FrozenInstanceError):
        a.event = "done"
    assert not hasattr(a, "__dict__") and not hasattr(a.tip_contact, "__dict__")
