"""The sensor model (core2d.sim.sensor): each effect on the readings, seeded.

A probe hangs above a flat floor (y = 0) or beside a wall; the same motions
are made with an exact sensor and a degraded one, and the readings compared.
"""
from __future__ import annotations

import numpy as np
import pytest

from core2d import SensorModel, sense_slice
from core2d.readings import LEFT, TIP, Contact, Reading
from core2d.resolution import Resolution
from core2d.sim.probe import Probe
from core2d.sim.sensor import Sensor
from slicer.contact.exact import ExactContact

SQUARE = [np.array([[-10.0, -10.0], [10.0, -10.0], [10.0, 0.0], [-10.0, 0.0]])]
EPS = 1.0


def _probe(sensor=None):
    return Probe(ExactContact(SQUARE), (np.zeros(2), 15.0), EPS, sensor=sensor)


def _insert(probe, x=0.3):
    probe.approach(np.array([x, 0.0]), np.array([0.0, -1.0]))
    return probe.insert()


def test_exact_sensor_reports_the_truth():
    r = _insert(_probe())
    r0 = _insert(_probe(SensorModel()))
    assert np.array_equal(r.tip_contact.point, r0.tip_contact.point)
    assert np.array_equal(r.joint, r0.joint)
    assert abs(r.tip_contact.point[1]) <= Resolution.of(EPS).tol


def test_contact_noise_has_the_stated_spread_and_leaves_the_world_alone():
    sigma = 0.2
    exact, noisy = _probe(), _probe(SensorModel(noise=sigma, seed=4))
    errs, joints = [], []
    for x in np.linspace(-5, 5, 300):
        r, q = _insert(exact, x), _insert(noisy, x)
        errs.append(q.tip_contact.point - r.tip_contact.point)
        joints.append(q.joint - r.joint)
        assert np.array_equal(exact.joint, noisy.joint)  # the true posture is the same
    errs = np.asarray(errs)
    # contact noise and joint noise (sigma each, the tip's share sigma too) add up
    spread = errs.std(axis=0)
    assert np.all(spread > 0.8 * sigma) and np.all(spread < 1.6 * sigma * np.sqrt(3))
    assert np.asarray(joints).std(axis=0) == pytest.approx([sigma, sigma], rel=0.2)


def test_noise_is_seeded():
    a = [_insert(_probe(SensorModel(noise=0.1, seed=7)), x).tip_contact.point for x in (0, 1)]
    b = [_insert(_probe(SensorModel(noise=0.1, seed=7)), x).tip_contact.point for x in (0, 1)]
    c = [_insert(_probe(SensorModel(noise=0.1, seed=8)), x).tip_contact.point for x in (0, 1)]
    assert np.array_equal(np.stack(a), np.stack(b))
    assert not np.array_equal(np.stack(a), np.stack(c))
    m = SensorModel(noise=0.1, seed=7)
    assert m.reseeded(0, 1).seed == m.reseeded(0, 1).seed != m.reseeded(0, 2).seed


def test_taxels_report_the_centre_of_the_element():
    """A side contact 1.3 from the tip, taxels 0.5 apart: reported 1.5 from
    the tip (its element's centre), at the same distance across the probe."""
    L, T = 10.0, 0.5
    sensor = Sensor(SensorModel(taxel=T), L)
    joint, t = np.zeros(2), np.array([0.0, -1.0])
    true = np.array([0.02, -(L - 1.3)])
    c = sensor.contact(Contact(true, LEFT, L - 1.3), joint, t, (joint, t))
    assert c.along == pytest.approx(L - 1.5)
    assert c.point == pytest.approx([0.02, -(L - 1.5)])
    assert c.face == LEFT


def test_tip_taxel_holds_contacts_near_the_tip():
    """Within taxel / 2 of the tip a contact is the tip's, reported at the tip."""
    L, T = 10.0, 0.5
    sensor = Sensor(SensorModel(taxel=T), L)
    joint, t = np.zeros(2), np.array([0.0, -1.0])
    c = sensor.contact(Contact(np.array([0.0, -(L - 0.2)]), LEFT, L - 0.2), joint, t, (joint, t))
    assert c.face == TIP and c.along == L and c.point == pytest.approx([0.0, -L])
    # a tip contact a hair ahead of the tip is the tip taxel's too
    c = sensor.contact(Contact(np.array([0.0, -(L + 0.01)]), TIP, L), joint, t, (joint, t))
    assert c.point == pytest.approx([0.0, -L])


def test_joint_direction_noise_scales_with_probe_length():
    """Direction noise is noise / L: the reported tip moves by about noise."""
    L, sigma = 40.0, 0.1
    sensor = Sensor(SensorModel(noise=sigma, seed=2), L)
    r = Reading(joint=np.zeros(2), direction=np.array([1.0, 0.0]))
    ang = [np.arctan2(*sensor.reading(r).direction[::-1]) for _ in range(2000)]
    assert np.std(ang) * L == pytest.approx(sigma, rel=0.1)


def test_trace_contacts_are_noisy_too():
    sensor = Sensor(SensorModel(noise=0.05, seed=3), 10.0)
    pts = np.stack([np.linspace(0, 5, 400), np.zeros(400)], axis=1)
    r = Reading(joint=np.zeros(2), direction=np.array([0.0, -1.0]), trace=pts)
    got = sensor.reading(r).trace
    assert got.shape == pts.shape and np.std(got[:, 1]) == pytest.approx(0.05, rel=0.15)


def test_the_planner_is_told_the_data_sheet():
    p = _probe(SensorModel(noise=0.1, taxel=0.25))
    assert (p.resolution.noise, p.resolution.taxel) == (0.1, 0.25)
    assert p.resolution.sensor_tol == pytest.approx(EPS / 2 + 0.2)


def test_sense_slice_with_a_noisy_sensor_finishes():
    res = sense_slice(ExactContact(SQUARE), (np.zeros(2), 15.0), EPS,
                      sensor=SensorModel.of_eps(EPS, 0.1, 0.25, seed=1))
    assert not res.stats.budget_hit and res.w1


@pytest.mark.filterwarnings("ignore:eps 1.5 is")
def test_recon3d_run_records_the_sensor_and_reports_both_metrics():
    """noise / taxel / seed reach every slice: metrics.json gets the sensor
    model and the *_sensor metrics beside the noiseless ones; the same seed
    gives the same run, another seed another one."""
    import trimesh

    import recon3d

    box = trimesh.creation.box(extents=[20.0, 10.0, 10.0])
    kw = dict(slices=2, eps=1.5, jobs=1, backend="exact", noise=0.3, taxel=0.25,
              reads=1)  # one read per point: the sensor as stated (the default averages 15)
    a, b = recon3d.run(box, seed=1, **kw), recon3d.run(box, seed=1, **kw)
    c = recon3d.run(box, seed=2, **kw)
    total = a.metrics["total"]
    assert total["sensor_tol"] == pytest.approx(1.5 / 2 + 2 * 0.3 * 1.5)
    assert 0 < total["coverage"] <= total["coverage_sensor"] <= 1
    assert 0 < total["precision"] <= total["precision_sensor"] <= 1
    assert a.metrics["sensor"]["noise"] == 0.3 and a.metrics["sensor"]["seed"] == 1
    assert a.metrics["sensor"]["reads"] == 1
    assert total["motions"] == b.metrics["total"]["motions"]
    assert a.metrics["slices"][0]["precise_length"] == b.metrics["slices"][0]["precise_length"]
    assert a.metrics["slices"][0]["detected_length"] != c.metrics["slices"][0]["detected_length"]
    plain = recon3d.run(box, slices=2, eps=1.5, jobs=1, backend="exact")
    assert "sensor" not in plain.metrics and "coverage_sensor" not in plain.metrics["total"]
    # the summary leads with the sensor's tolerance, and says so; eps/2 on its own line
    from recon3d.cli.printing import summary_lines

    noisy = [ln for ln in summary_lines(a) if "coverage" in ln and "2D" in ln or "eps/2:" in ln]
    assert noisy[0].startswith(f"  2D  reachable coverage {total['coverage_sensor']:.4f}  "
                               f"precision {total['precision_sensor']:.4f}")
    assert noisy[0].endswith(f"within the sensor's tolerance eps/2 + 2 sigma = "
                             f"{total['sensor_tol']:.3g}")
    # within eps/2 the noisy pieces lie off the contour, and the arcs behind W2 chords are
    # much of the coverage: the line says how much (none within the sensor's tolerance)
    credit = total["w2_credit_length"] / total["reachable_length"]
    assert credit >= 1e-3 and total["w2_credit_length_sensor"] == 0.0
    assert noisy[1].startswith(f"      within eps/2: reachable coverage {total['coverage']:.4f}"
                               f" ({credit:.4f} of it behind W2 chords, never touched)"
                               f"  precision {total['precision']:.4f}")
    assert not any("sensor" in ln for ln in summary_lines(plain))
    # batch.csv's row names the sensor and its coverage; none for perfect sensing
    from recon3d.jobs.batch import Job, job_row

    row = job_row(Job(0, "box", dict(kw, seed=1)), a, 1.0, 1.0)
    assert (row["noise"], row["taxel"], row["coverage_sensor"]) == (0.3, 0.25,
                                                                    total["coverage_sensor"])
    row = job_row(Job(0, "box", {}), plain, 1.0, 1.0)
    assert (row["noise"], row["taxel"], row["coverage_sensor"]) == (0.0, 0.0, None)


def _tilted(sensor=None, degrees=-60.0):
    """A probe pressed on the floor at ``degrees`` (ccw from +x): the
    clockwise check rotation drives the tip into the floor."""
    probe = _probe(sensor)
    t = np.deg2rad(degrees)
    probe.approach(np.array([0.3, 0.0]), np.array([np.cos(t), np.sin(t)]))
    return probe, probe.insert()


def test_torque_threshold_hides_slight_obstructions():
    # the check's intrusion is about tol tan(angle from the normal): 0.029 at
    # 30 degrees off the normal, 0.0009 at 1 degree (tol 0.05)
    for degrees in (-60.0, -89.0):
        assert _tilted(None, degrees)[1].blocked_cw
    held = SensorModel(torque_threshold=0.01)
    assert _tilted(held, -60.0)[1].blocked_cw  # a steep slope is still felt
    r = _tilted(held, -89.0)[1]
    assert not r.blocked_cw and not r.blocked_ccw  # a shallow one reads free


def test_torque_noise_flips_readings_at_the_stated_rate():
    # a free side reads blocked when the noise reaches the threshold: 1 - Phi(1) = 0.159
    sensor = Sensor(SensorModel(torque_threshold=0.01, torque_noise=0.01, seed=3), 10.0)
    reads = np.array([sensor.blocked((-np.inf, 0.02)) for _ in range(4000)])
    assert abs(reads[:, 0].mean() - 0.159) < 0.03  # free: false blocks
    assert abs(reads[:, 1].mean() - 0.841) < 0.03  # intruding 2 thresholds: 1 - Phi(-1)
    exact = Sensor(SensorModel(), 10.0)
    assert exact.blocked((-np.inf, 0.0)) == (False, True)


def test_torque_defaults_are_the_papers_sensor():
    assert SensorModel().exact_torque and SensorModel().ideal
    assert not SensorModel(torque_noise=0.1).ideal
    assert SensorModel.of_eps(2.0, torque_threshold=0.1, torque_noise=0.2).torque_noise == 0.4
    probe = _probe(SensorModel.of_eps(EPS, torque_threshold=0.1, torque_noise=0.2))
    assert probe.resolution.torque_noise == 0.2 and probe.resolution.torque_reads > 1
    assert _probe().resolution.torque_reads == 1


def test_the_planner_rereads_a_noisy_torque_sensor():
    """Y2 of Definition 5 at a final state is taken by majority of repeated
    readings: over many seeds it is wrong less often than one reading."""
    from core2d.planner.local_search import definition5, reread_torque

    wrong_one = wrong_voted = 0
    for seed in range(200):
        probe, r = _tilted(SensorModel(torque_threshold=0.015, torque_noise=0.015, seed=seed))
        truth = (1, 1)  # the clockwise rotation is blocked: Fig. 10(b)
        wrong_one += definition5(r) != truth
        wrong_voted += definition5(reread_torque(probe, r)) != truth
    assert wrong_one > 40  # one noisy reading errs often at this noise
    assert wrong_voted < wrong_one / 2


@pytest.mark.filterwarnings("ignore:eps 1.5 is")
def test_recon3d_run_passes_the_torque_sensor_on(tmp_path):
    """--torque-threshold / --torque-noise reach the slices' sensor model
    and metrics.json; a bad value is a one-line error."""
    import trimesh

    import recon3d
    from recon3d.checks import InputError

    box = trimesh.creation.box(extents=[20.0, 10.0, 10.0])
    kw = dict(slices=2, eps=1.5, jobs=1, backend="exact")
    got = recon3d.run(box, torque_threshold=0.02, torque_noise=0.02, seed=1, **kw)
    assert got.metrics["sensor"]["torque_threshold"] == 0.02
    assert got.metrics["sensor"]["torque_noise"] == 0.02
    plain = recon3d.run(box, **kw)
    assert got.metrics["total"]["motions"] != plain.metrics["total"]["motions"]
    with pytest.raises(InputError, match="torque"):
        recon3d.run(box, torque_noise=-1.0, **kw)
