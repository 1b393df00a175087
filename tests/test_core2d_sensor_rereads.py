"""The probe's re-reads where it stands (:meth:`core2d.sim.probe.Probe.reread`) report what
as many :meth:`~core2d.sim.probe.Probe.sense` calls report of the joint, the tip's contact
and the torque, to the bit, and leave the sensor's generator where those calls leave it; a
noisy slice sensed with them is the slice sensed one read at a time, rays aside."""
from __future__ import annotations

import numpy as np
import pytest

from core2d import SensorModel, sense_slice
from core2d.readings import Rereads
from core2d.sim.probe import Probe
from outlines import outline
from slicer.contact.exact import ExactContact

#: a pocket with a floor and a wall: a probe in its corner touches both (tip and body)
POCKET = [np.array([[-10.0, -10.0], [10.0, -10.0], [10.0, 0.0], [2.0, 0.0], [2.0, -4.0],
                    [-2.0, -4.0], [-2.0, 0.0], [-10.0, 0.0]])]

MODELS = {
    "noise": SensorModel(noise=0.03, seed=1),
    "taxel": SensorModel(taxel=0.25, seed=2),
    "noise+taxel": SensorModel(noise=0.05, taxel=0.2, seed=3),
    "torque": SensorModel(torque_threshold=0.01, torque_noise=0.01, seed=4),
    "all": SensorModel(noise=0.05, taxel=0.2, torque_threshold=0.01, torque_noise=0.02, seed=5),
    "all keyed": SensorModel(noise=0.05, taxel=0.2, torque_threshold=0.01, torque_noise=0.02,
                             seed=6, keyed=True),
    "noise keyed reads": SensorModel(noise=0.2, seed=7, keyed=True, reads=16),
    "threshold only": SensorModel(torque_threshold=0.02, seed=8),
    "exact": SensorModel(),
}


def _placed(model, degrees):
    """A probe inserted towards the pocket's floor corner at ``degrees`` (ccw from +x),
    or (None) onto the floor's middle lying on the wall's top corner: a tip contact and
    a body contact; ("body") the same, stopped 1 short of the floor: the body's contact
    alone; ("free") on the workspace circle, touching nothing."""
    probe = Probe(ExactContact(POCKET), (np.zeros(2), 15.0), 1.0, sensor=model)
    if degrees == "free":
        probe.approach(np.array([0.0, -2.0]), np.array([0.0, -1.0]))
        return probe
    if degrees in (None, "body"):
        tip, t = np.array([0.0, -4.0]), np.array([-1.99, -4.0])
        probe.approach(tip - 0.5 * t / np.hypot(*t), t)
        if degrees == "body":
            probe.insert(float(np.hypot(*(probe.tip - tip))) - 1.0)
            return probe
    else:
        t = np.deg2rad(degrees)
        probe.approach(np.array([1.9, -3.9]), np.array([np.cos(t), np.sin(t)]))
    probe.insert()
    return probe


def _same(a, b):
    assert np.array_equal(a.joint, b.joint) and np.array_equal(a.direction, b.direction)
    assert (a.blocked_ccw, a.blocked_cw, a.event, a.angle) == \
        (b.blocked_ccw, b.blocked_cw, b.event, b.angle)
    assert len(a.contacts) == len(b.contacts)
    for p, q in zip(a.contacts, b.contacts):
        assert np.array_equal(p.point, q.point) and (p.face, p.along) == (q.face, q.along)


@pytest.mark.parametrize("name", list(MODELS))
@pytest.mark.parametrize("degrees", [-60.0, -90.0, -135.0, None, "body", "free"])
def test_rereads_are_the_readings_of_as_many_senses(name, degrees):
    one, many = _placed(MODELS[name], degrees), _placed(MODELS[name], degrees)
    rays = many.stats.rays
    looped = Rereads.of([one.sense() for _ in range(24)])
    got = many.reread(24)
    for field in ("joint", "direction", "tip", "blocked"):
        a, b = getattr(looped, field), getattr(got, field)
        assert a.shape == b.shape == (24, 2) and np.array_equal(a, b, equal_nan=True), field
    assert many.stats.rays - rays == 3  # the skin's three rays, cast once
    assert many.sensor.count == one.sensor.count
    # the generator is left where the senses leave it: the next reading is the same too
    _same(one.sense(), many.sense())
    one.insert(), many.insert()
    _same(one.sense(), many.sense())


def test_the_postures_read_what_the_comparison_needs():
    """The test above reads a tip and a body contact (whose draws the re-reads make and
    skip), a body contact alone, no contact at all, and both torque flags; the noise moves
    the tip between reads."""
    corner = _placed(MODELS["noise+taxel"], None).sense()
    assert [c.face for c in corner.contacts] == ["tip", "right"]
    assert [c.face for c in _placed(None, "body").sense().contacts] == ["right"]
    free = _placed(MODELS["all"], "free")
    assert free.sense().contacts == () and np.isnan(free.reread(2).tip).all()
    assert _placed(None, None).sense().blocked_ccw and not _placed(None, -90.0).sense().blocked_ccw
    got = _placed(MODELS["noise+taxel"], None).reread(3)
    assert not np.array_equal(got.tip[0], got.tip[1])


def test_a_noisy_slice_is_the_slice_sensed_one_read_at_a_time(monkeypatch):
    """The planner's re-reads (P_2nd of a jump, the final state's torque, the bootstrap's
    contacts) through :meth:`Probe.reread`, against a :meth:`Probe.sense` per read."""
    loops = outline("comb", np.random.default_rng(0), 1.0)
    pts = np.concatenate(loops)
    ws = ((pts.min(0) + pts.max(0)) / 2, float(np.linalg.norm(np.ptp(pts, axis=0)) / 2 + 1.0))
    eps = 1.0
    model = SensorModel.of_eps(eps, 0.1, 0.0, 3, reads=16)
    fast = sense_slice(ExactContact(loops), ws, eps, sensor=model)
    monkeypatch.setattr(Probe, "reread", lambda self, k: Rereads.of([self.sense() for _ in range(k)]))
    slow = sense_slice(ExactContact(loops), ws, eps, sensor=model)
    for kind in ("w1", "w2", "w3", "unknown"):
        a, b = getattr(fast, kind), getattr(slow, kind)
        assert len(a) == len(b) and all(np.array_equal(p, q) for p, q in zip(a, b)), kind
    assert fast.stats.motions == slow.stats.motions
    assert fast.stats.sensor_reads == slow.stats.sensor_reads
    assert fast.stats.rays < slow.stats.rays  # the re-reads cast the skin's rays once
