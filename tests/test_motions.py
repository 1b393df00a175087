"""The motion log: one row per motion, tagged with the planner's phase, in motions.csv.

The recorder sits in the robot layer (:class:`core2d.sim.recorder.Recorder`);
these tests check that it logs what the probe did (poses chain from row to
row, one row per counted motion), that the planner's phase tags match what
each phase commands, that it changes no decision, and that motions.csv
round-trips through :func:`recon3d.io.motions.read_motions` with its world
columns on the slice planes.
"""
from __future__ import annotations

import numpy as np
import pytest

import recon3d
from core2d import sense_slice
from core2d.motionlog import KINDS, PHASES
from core2d.planner.run import explore
from core2d.sim.probe import Probe
from core2d.sim.recorder import Recorder
from figure_scenes import HILL, OVERHANG_LEFT, WORKSPACE, block
from recon3d.io.motions import COLUMNS, motions_text, other_points, read_motions
from slicer.contact.exact import ExactContact


def _scene():
    """A 2D block with an overhanging pocket and a hill (exact contact), eps = 1."""
    loops = block(OVERHANG_LEFT)
    return ExactContact(loops), WORKSPACE, 1.0


@pytest.fixture(scope="module")
def logged():
    contact, ws, eps = _scene()
    return sense_slice(contact, ws, eps)


def _names(codes, table):
    return np.array([table[c] for c in codes])


def test_one_row_per_motion_and_the_poses_chain(logged):
    log = logged.motions
    assert len(log) == logged.stats.motions > 50
    # nothing moves the joint between motions: each row starts where the last ended
    np.testing.assert_array_equal(log.before[1:], log.after[:-1])
    L = np.hypot(*(log.tip - log.after[:, :2]).T)
    np.testing.assert_allclose(L, L[0])
    has_tip = np.isfinite(log.tip_contact[:, 0])
    assert has_tip.any() and (~has_tip).any()
    # a tip contact lies within the tip zone (eps/2) of the tip (core2d.sim.probe.sense)
    assert np.all(np.hypot(*(log.tip_contact[has_tip] - log.tip[has_tip]).T) <= 0.5 + 1e-9)
    assert np.all(log.contacts >= has_tip) and len(log.other_start) == len(log) + 1


def test_phases_tag_what_each_step_commands(logged):
    log = logged.motions
    kind, phase = _names(log.kind, KINDS), _names(log.phase, PHASES)
    boot = phase == "bootstrap"
    assert boot[0] and np.all(log.area[boot] == -1)
    assert set(kind[boot]) == {"approach", "insert"}  # insertions from F (§4.1)
    assert set(kind[phase == "bisection"]) <= {"swing", "turn", "insert"}  # §4.2.2 (i)-(iii)
    assert set(kind[phase == "initial_pass"]) == {"approach", "insert"}  # Theorem 1
    assert "trace" in set(kind[phase == "tracing"]) and "trace" not in set(kind[~(
        phase == "tracing")])
    assert np.all((log.torque != 0) == (kind == "trace"))
    trace_events = set(log.event[kind == "trace"])
    assert trace_events and trace_events <= {"case1", "case2", "case2-3", "case3", "case4",
                                             "left", "reached-body", "limit", "done"}
    assert np.all((log.area >= 0) == ~boot) and log.area.max() < len(logged.areas)


def test_segments_know_the_motion_that_recorded_them(logged):
    log, at = logged.motions, logged.known_at
    assert [len(at[k]) for k in ("w1", "w2", "w3")] == [len(logged.w1), len(logged.w2),
                                                        len(logged.w3)]
    traces = np.flatnonzero(_names(log.kind, KINDS) == "trace")
    assert logged.w1
    for k in at["w1"]:
        # recorded in the tracing phase, right after a trace (and the pivot about
        # the tip of Fig. 6 that a Case 2-1 onto the body adds)
        assert PHASES[log.phase[k]] == "tracing"
        assert 0 <= k - traces[traces <= k][-1] <= 4
    for cls in ("w1", "w2", "w3"):
        assert np.all(np.diff(at[cls]) >= 0) and all(0 <= k < len(log) for k in at[cls])


def test_the_recorder_changes_no_decision():
    contact, ws, eps = _scene()
    bare = explore(Probe(contact, ws, eps), eps)
    rec = Recorder(Probe(contact, ws, eps))
    logged = explore(rec, eps)
    for key in ("w1", "w2", "w3", "unknown"):
        a, b = getattr(bare, key), getattr(logged, key)
        assert len(a) == len(b) and all(np.array_equal(x, y) for x, y in zip(a, b)), key
    assert [(r.rule, r.outcome) for r in bare.areas] == [(r.rule, r.outcome)
                                                       for r in logged.areas]
    assert bare.stats.motions == logged.stats.motions == len(rec.log())


def test_a_perfect_sensor_reports_the_postures_themselves(logged):
    """``seen`` (what the joint sensors reported) is ``after`` to the bit without noise."""
    np.testing.assert_array_equal(logged.motions.seen, logged.motions.after)


def test_a_noisy_sensor_reports_postures_off_by_its_noise():
    """With sigma = 0.05 on the joint position (sigma / L on its angle) the reported postures
    scatter about the true ones by about sigma, the angle unwrapped as the true one's."""
    from core2d.sim.sensor import SensorModel

    contact, ws, eps = _scene()
    res = sense_slice(contact, ws, eps, sensor=SensorModel(noise=0.05, seed=3))
    log = res.motions
    L = np.hypot(*(log.tip - log.after[:, :2]).T)[0]
    off = log.seen - log.after
    assert 0.03 < np.std(off[:, :2]) < 0.07  # about sigma per axis
    assert 0.03 < np.std(off[:, 2]) * L < 0.07  # about sigma / L radians
    assert np.abs(off[:, 2]).max() < 8 * 0.05 / L  # no turn lost or added


def test_finger_probing_is_logged_too():
    contact, ws, eps = ExactContact(block(HILL)), WORKSPACE, 1.0
    res = sense_slice(contact, ws, eps, method="finger", directions=4, spacing=4.0)
    assert len(res.motions) == res.stats.motions
    assert set(_names(res.motions.phase, PHASES)) == {"none"}
    assert len(res.known_at["w1"]) == len(res.w1) and len(res.known_at["w2"]) == len(res.w2)


@pytest.fixture(scope="module")
def pocket_run():
    return recon3d.run("fig17_pocket", slices=2, eps=0.02 * 143.0, jobs=1)


def test_motions_csv_round_trip_and_world_columns(pocket_run, tmp_path):
    (tmp_path / "motions.csv").write_text(motions_text(pocket_run.slices))
    m = read_motions(tmp_path)
    assert m.dtype.names == COLUMNS
    assert len(m) == sum(len(s.result.motions) for s in pocket_run.slices)
    for srun in pocket_run.slices:
        rows = m[(m["family"] == srun.family) & (m["slice"] == srun.slice.plane.index)]
        log = srun.result.motions
        assert np.array_equal(rows["index"], np.arange(len(log)))
        np.testing.assert_allclose(np.c_[rows["joint_x1"], rows["joint_y1"], rows["theta1"]],
                                   log.after, rtol=1e-11, atol=1e-9)
        world = srun.slice.to_3d(log.after[:, :2])
        np.testing.assert_allclose(np.c_[rows["wx1"], rows["wy1"], rows["wz1"]], world,
                                   rtol=1e-11, atol=1e-9)
        d = np.c_[rows["wdx1"], rows["wdy1"], rows["wdz1"]]
        np.testing.assert_allclose(np.linalg.norm(d, axis=1), 1.0, atol=1e-9)
        assert np.allclose(d @ np.asarray(srun.slice.plane.normal), 0.0, atol=1e-9)
        assert list(rows["kind"]) == [KINDS[k] for k in log.kind]
        assert np.array_equal(rows["tip_contact"] == 1, np.isfinite(log.tip_contact[:, 0]))
        assert np.isnan(rows["tip_cx"][rows["tip_contact"] == 0]).all()
        k = int(np.argmax(np.diff(log.other_start)))
        np.testing.assert_allclose(other_points(rows["other_contacts"][k]), log.others(k),
                                   rtol=1e-11, atol=1e-9)
    with pytest.raises(ValueError, match="not a motions.csv"):
        (tmp_path / "x.csv").write_text("a,b\n1,2\n")
        read_motions(tmp_path / "x.csv")


def test_sensing_json_segments_carry_their_motion(pocket_run):
    doc = pocket_run.sensing_document()
    for s, srun in zip(doc["slices"], pocket_run.slices):
        n = len(srun.result.motions)
        assert s["segments"] and all(0 <= seg["motion"] < n for seg in s["segments"])
        assert [seg["class"] for seg in s["segments"]] == (
            ["W1"] * len(srun.result.w1) + ["W2"] * len(srun.result.w2)
            + ["W3"] * len(srun.result.w3))


def test_rows_made_in_the_worker_are_the_rows_made_when_written(pocket_run):
    """Each worker sends its slice's motions.csv rows back with the slice; the file is the
    one the parent would have made from the motion logs, and the rows are used as sent."""
    import dataclasses

    from recon3d.io.motions import slice_rows

    assert all(s.motion_rows for s in pocket_run.slices)
    for s in pocket_run.slices:
        assert s.motion_rows == slice_rows(s, s.slice.plane)
    plain = [dataclasses.replace(s, motion_rows=None) for s in pocket_run.slices]
    assert motions_text(pocket_run.slices) == motions_text(plain)
    marked = [dataclasses.replace(s, motion_rows=f"sent {k}")
              for k, s in enumerate(pocket_run.slices)]
    assert motions_text(marked).splitlines()[1:] == [f"sent {k}" for k in range(len(marked))]


def test_sensing_json_entries_made_in_the_worker_are_the_ones_made_when_written(pocket_run):
    """Each worker sends its slice's sensing.json entry back with the slice: the entry the
    parent would have made, and the document takes it as sent."""
    import dataclasses

    from recon3d.io.documents import sensing_document, slice_document

    def with_slices(slices):
        fam = dataclasses.replace(pocket_run.sensing.families[0], slices=slices)
        return dataclasses.replace(pocket_run.sensing, families=[fam])

    assert len(pocket_run.sensing.families) == 1
    assert all(s.document is not None for s in pocket_run.slices)
    for s in pocket_run.slices:
        assert s.document == slice_document(s)
    plain = [dataclasses.replace(s, document=None) for s in pocket_run.slices]
    assert sensing_document(with_slices(plain)) == pocket_run.sensing_document()
    marked = [dataclasses.replace(s, document={"sent": k})
              for k, s in enumerate(pocket_run.slices)]
    assert sensing_document(with_slices(marked))["slices"] == [{"sent": k}
                                                               for k in range(len(marked))]
