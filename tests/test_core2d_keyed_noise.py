"""Keyed sensor noise (common random numbers, ``SensorModel(keyed=True)``): each reading's
draws depend on the seed, its true posture and how often that posture was read, not on the
readings before it (core2d.sim.sensor)."""
from __future__ import annotations

import numpy as np
import pytest

from core2d import SensorModel, sense_slice
from core2d.sim.probe import Probe
from slicer.contact.exact import ExactContact

SQUARE = [np.array([[-10.0, -10.0], [10.0, -10.0], [10.0, 0.0], [-10.0, 0.0]])]


def _probe(**kw):
    return Probe(ExactContact(SQUARE), (np.zeros(2), 15.0), 1.0,
                 sensor=SensorModel(noise=0.2, seed=11, **kw))


def _insert(probe, x):
    probe.approach(np.array([x, 0.0]), np.array([0.0, -1.0]))
    r = probe.insert()
    return np.concatenate([r.joint, r.tip_contact.point])


def test_a_reading_does_not_depend_on_the_readings_before_it():
    """Two probes read x = 2 after different motions: keyed, the same reading; one
    stream of draws, different readings (the later draws shifted by the earlier)."""
    for keyed, same in ((True, True), (False, False)):
        a, b = _probe(keyed=keyed), _probe(keyed=keyed)
        _insert(a, 1.0)
        for x in (-3.0, 4.0, 0.5):
            _insert(b, x)
        assert np.array_equal(_insert(a, 2.0), _insert(b, 2.0)) is same


def test_a_re_read_is_a_fresh_draw_and_the_run_is_reproducible():
    a, b = _probe(keyed=True), _probe(keyed=True)
    first, again = _insert(a, 2.0), _insert(a, 2.0)  # the same true posture twice
    assert not np.array_equal(first, again)
    assert np.array_equal(first, _insert(b, 2.0)) and np.array_equal(again, _insert(b, 2.0))
    other = Probe(ExactContact(SQUARE), (np.zeros(2), 15.0), 1.0,
                  sensor=SensorModel(noise=0.2, seed=12, keyed=True))
    assert not np.array_equal(first, _insert(other, 2.0))  # the seed keys it too


def test_keyed_noise_has_the_stated_spread():
    """Joint readings over 400 postures: mean 0, standard deviation sigma per axis, and
    no correlation between neighbouring postures' errors (independent draws)."""
    exact = Probe(ExactContact(SQUARE), (np.zeros(2), 15.0), 1.0)
    noisy = _probe(keyed=True)
    errs = []
    for x in np.linspace(-6, 6, 400):
        _insert(exact, x)
        errs.append(_insert(noisy, x)[:2] - exact.joint)
    errs = np.asarray(errs)
    assert errs.std(axis=0) == pytest.approx([0.2, 0.2], rel=0.15)
    assert np.all(np.abs(errs.mean(axis=0)) < 0.2 * 4 / np.sqrt(400))
    lag = np.corrcoef(errs[:-1, 0], errs[1:, 0])[0, 1]
    assert abs(lag) < 0.15


def test_a_keyed_slice_run_is_reproducible_and_finishes():
    loop = np.array([[0, 0], [20, 0], [20, 10], [11, 10], [11, 4], [9, 4], [9, 10],
                     [0, 10]], dtype=float)
    runs = [sense_slice(ExactContact([loop]), (np.array([10.0, 5.0]), 13.0), 1.0,
                        max_motions=5000,
                        sensor=SensorModel.of_eps(1.0, 0.3, 0.25, seed=3, keyed=True))
            for _ in range(2)]
    assert runs[0].stats.motions == runs[1].stats.motions < 5000
    assert not runs[0].stats.budget_hit
    assert all(np.array_equal(p, q) for p, q in zip(runs[0].w1, runs[1].w1))


@pytest.mark.filterwarnings("ignore:eps 1.5 is")
def test_recon3d_run_keys_the_noise_of_every_slice():
    """``keyed_noise`` (``--keyed-noise``) reaches the workers' sensor models and
    metrics.json: a keyed run repeats itself, draws otherwise than the one-stream
    run of the same seed, and says so in its sensor record."""
    import trimesh

    import recon3d
    from recon3d.sensing.worker import SenseSettings

    settings = SenseSettings((np.array([0.0, 0.0, 1.0]),), 2, 1.5, 0.075, "exact", 100, 4,
                             noise=0.3, keyed=True)
    assert settings.sensor(0, 1).keyed and not settings.sensor(0, 1).seed == 0
    box = trimesh.creation.box(extents=[20.0, 10.0, 10.0])
    kw = dict(slices=2, eps=1.5, jobs=1, backend="exact", noise=0.3, taxel=0.25, seed=1)
    a, b = recon3d.run(box, keyed_noise=True, **kw), recon3d.run(box, keyed_noise=True, **kw)
    plain = recon3d.run(box, **kw)
    assert a.metrics["sensor"]["keyed"] and not plain.metrics["sensor"]["keyed"]
    one = [s["detected_length"] for s in a.metrics["slices"]]
    assert one == [s["detected_length"] for s in b.metrics["slices"]]
    assert one != [s["detected_length"] for s in plain.metrics["slices"]]


@pytest.mark.parametrize("spelling, name", [("key", "keyed_noise"), ("flag", "--keyed-noise")])
def test_keyed_noise_without_noise_is_a_warning(spelling, name):
    """Keying draws that are never made changes nothing: the user is told, not stopped."""
    import trimesh

    from recon3d.config import validate
    from recon3d.spellings import make_config

    box = trimesh.creation.box(extents=[20.0, 10.0, 10.0])
    notes = validate(box, make_config(keyed_noise=True, taxel=0.25), spelling)
    assert any(n.startswith(f"{name} has no effect") for n in notes), notes
    for noisy in (dict(noise=0.3), dict(torque_noise=0.1)):
        notes = validate(box, make_config(keyed_noise=True, **noisy), spelling)
        assert not any("no effect" in n for n in notes), notes
