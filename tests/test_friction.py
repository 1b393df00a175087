"""Coulomb friction at the tip (core2d.sim.friction): the jam condition on
constructed slices, in both engines, and mu = 0 changing nothing.

A trace step pushed (v.t > 0) with the rod axis inside the friction cone --
within atan(mu) of the contact normal -- jams: the joint does not move, the
reading says Case 4 ("blocked"), ``jams`` counts it. The same step pulled
slides. mu = 0 is the frictionless simulator bit for bit.
"""
import math

import numpy as np
import pytest

import meshes
from core2d import sense_slice
from core2d.planner.regions import sgn
from core2d.sim.friction import self_locked
from core2d.sim.probe import Probe
from slicer import slice_mesh
from slicer.contact.exact import ExactContact
from test_core2d_kernels import _PythonPath


FLOOR = [np.array([[0, 0], [100, 0], [100, 50], [0, 50]], float)]


def _pressed(lean_deg, mu):
    """A probe leaning ``lean_deg`` from the floor's normal (tip to the right of
    the joint), inserted onto the floor at (50, 50): the rod axis lies
    ``lean_deg`` from the contact normal."""
    p = Probe(ExactContact(FLOOR), (np.array([50.0, 25.0]), 75.0), 1.0, friction=mu)
    b = math.radians(lean_deg)
    p.approach([50.0, 50.0], [math.sin(b), -math.cos(b)])
    r = p.insert()
    assert r.tip_contact is not None and r.blocked_cw and not r.blocked_ccw
    return p


def _step(p, v):
    """One trace of 2 joint units along ``v``, the clockwise torque pressing
    the tip onto the floor (rotating the rod towards the normal)."""
    v = np.asarray(v, float) / np.linalg.norm(v)
    joint = p.joint.copy()
    r = p.trace(v, 1, 2.0, guard_push=False)
    return r, float(np.linalg.norm(p.joint - joint))


def test_self_locked_is_the_friction_cone():
    t = (0.0, -1.0)  # rod pointing down; a slide d at angle a from the surface normal's tangent
    for deg in (10.0, 30.0, 60.0):
        d = (math.cos(math.radians(deg)), -math.sin(math.radians(deg)))  # surface tilted deg
        phi = math.radians(deg)  # axis to normal
        assert self_locked(math.tan(phi) * 1.01, *t, *d)
        assert not self_locked(math.tan(phi) * 0.99, *t, *d)
    assert not self_locked(0.0, 0.0, -1.0, 1.0, 0.0)  # no friction never locks
    assert not self_locked(5.0, 0.0, -1.0, 0.0, 0.0)  # no slide, nothing to lock


PUSH, PULL = (1.0, -0.3), (-1.0, 0.3)  # along the floor, v.t > 0 / v.t < 0


@pytest.mark.parametrize("lean", [15.0, 30.0])
def test_a_push_inside_the_cone_jams_and_the_same_push_without_friction_slides(lean):
    p = _pressed(lean, math.tan(math.radians(lean)) + 0.05)
    r, moved = _step(p, PUSH)
    assert r.event == "blocked" and p.stats.jams == 1 and p.stats.pushes == 0
    assert moved == 0.0  # the tip stuck: the step was not executed
    q = _pressed(lean, 0.0)
    r, moved = _step(q, PUSH)
    assert q.stats.jams == 0 and q.stats.pushes > 0 and moved > 1.0 and len(r.trace) > 3


@pytest.mark.parametrize("lean", [15.0, 30.0])
def test_a_push_outside_the_cone_slides(lean):
    p = _pressed(lean, math.tan(math.radians(lean)) - 0.05)  # mu below tan(lean)
    r, moved = _step(p, PUSH)
    assert p.stats.jams == 0 and p.stats.pushes > 0 and moved > 1.0


@pytest.mark.parametrize("lean", [15.0, 30.0])
def test_the_same_step_pulled_slides(lean):
    p = _pressed(lean, 2.0)
    r, moved = _step(p, PULL)
    assert p.stats.jams == 0 and p.stats.pushes == 0
    assert moved > 1.0 and len(r.trace) > 3 and r.event != "blocked"


def _cut(name, index, count=4):
    mesh = meshes.load(name)
    eps = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)) / 200)
    cut = slice_mesh(mesh, axis="z", count=count)[index]
    center, radius = cut.bounding_circle()
    return cut, (center, radius + eps), eps


def _everything(res, rays=True):
    out = {k: [np.asarray(a).tolist() for a in getattr(res, k)]
           for k in ("w1", "w2", "w3", "unknown")}
    st = res.stats.as_dict()
    st.pop("seconds")
    if not rays:  # the compiled windows stop at their first hit: fewer rays, same casts
        st.pop("rays")
    out["stats"] = st
    log = res.motions
    out["log"] = [np.asarray(getattr(log, k)).tolist() for k in ("kind", "event", "after")]
    return out


@pytest.mark.parametrize("name,index", [("fig17_pocket", 1), ("fig18_overhangs", 1),
                                        ("textured_pocket", 1)])
@pytest.mark.parametrize("engine", ["compiled", "python"])
def test_mu_zero_reproduces_the_frictionless_run_bit_for_bit(name, index, engine):
    cut, ws, eps = _cut(name, index)
    contact = cut.contact("embree")
    if engine == "python":
        contact = _PythonPath(contact)
    for method in ("pulling", "follow"):
        default = sense_slice(contact, ws, eps, method=method)
        zero = sense_slice(contact, ws, eps, method=method, friction=0.0)
        assert _everything(default) == _everything(zero)
    assert default.stats.pushes > 0  # the follower pushed, and no jam without friction
    assert default.stats.jams == 0


@pytest.mark.parametrize("name,index", [("fig17_pocket", 1), ("textured_pocket", 1)])
def test_both_engines_jam_alike(name, index):
    cut, ws, eps = _cut(name, index)
    contact = cut.contact("embree")
    fast = sense_slice(contact, ws, eps, method="follow", friction=0.6)
    slow = sense_slice(_PythonPath(contact), ws, eps, method="follow", friction=0.6)
    assert fast.stats.jams > 0
    assert _everything(fast, rays=False) == _everything(slow, rays=False)


def test_friction_must_not_be_negative():
    with pytest.raises(ValueError, match="friction"):
        Probe(ExactContact(FLOOR), (np.array([50.0, 25.0]), 75.0), 1.0, friction=-0.1)
