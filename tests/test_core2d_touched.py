"""A lid the revisit's passes touched along its length: :mod:`core2d.planner.touched`.

With a noisy sensor a revisit pass whose contact lies on recorded contour is no new
contact (no split); along a wall whose noisy trace left a gap every pass then touches
the wall at the lid, and the area ended ``unknown``. The rule closes it as W2 along the
touched contacts when no two neighbours are as far apart as eps + jitter.
"""
from __future__ import annotations

import numpy as np
import pytest
import shapely

import core2d.planner.revisit as revisit
from core2d import SensorModel, sense_slice
from core2d.planner.touched import Touches, applies
from core2d.resolution import Resolution
from core2d.truth.metrics import sensor_metrics

COARSE = Resolution.of(1.0, noise=0.3, taxel=0.25)  # W2 distance 2.52 eps
A, B = np.zeros(2), np.array([6.0, 0.0])  # a lid on y = 0, F above it (y > 0)


def _touches(points, joint=(3.0, 4.0), res=COARSE):
    t = Touches(res, A, B, end_radius=0.5)
    kept = [t.add(np.asarray(joint, float), np.asarray(p, float)) for p in points]
    return t, kept


@pytest.mark.parametrize("point, kept", [
    ((2.0, -0.3), True),    # behind the lid, a hair: the wall it lies along
    ((2.0, 1.0), True),     # in front, within eps/2 + 2 sigma (1.1 eps): a noisy reading
    ((2.0, 1.5), False),    # in front, farther: contour reached from F without the lid
    ((3.5, -4.0), True),    # far behind, but the probe crossed the lid to reach it
    ((6.5, -0.1), False),   # past B on the lid's line: the wall beyond the lid's end
    ((-0.2, 0.1), False),   # before A
])
def test_which_contacts_count(point, kept):
    assert _touches([point])[1] == [kept]


def test_a_far_contact_behind_counts_only_through_the_lid():
    # the same point 4 eps behind the lid, the probe coming from beside B: its segment
    # from the joint to the contact does not cross A_iB_i
    t, kept = _touches([(3.5, -4.0)], joint=(9.0, -4.0))
    assert kept == [False]


@pytest.mark.parametrize("xs, closes", [
    ((1.5, 3.0, 4.5), True),    # neighbours 1.5 eps apart
    ((2.0, 4.0), True),         # 2 eps < 2.52
    ((3.0,), False),            # 3 eps gaps: as far apart as a W2 may not be
    ((0.3, 5.7), False),        # only the ends touched again (the W3 by probing)
    ((1.5, 2.0, 4.5), True),
    ((1.0, 1.5, 2.0), False),   # a gap of 4 eps before B
])
def test_when_the_touches_close_the_lid(xs, closes):
    t, _ = _touches([(x, -0.2) for x in xs])
    assert t.closes() is closes
    chain = t.chain()
    assert np.array_equal(chain[0], A) and np.array_equal(chain[-1], B)
    assert np.all(np.diff(chain[:, 0]) >= 0)  # ordered along the lid


def test_the_middle_must_be_touched():
    # a lid 4 eps long with a short lid's end radius of 1.75 eps (Dist/2 - eps/4): passes
    # that touched only within that radius of A_i and B_i are the ends again, however
    # close together -- no W2 by touch (the revisit's W3 by probing decides such a lid)
    t = Touches(COARSE, A, np.array([4.0, 0.0]), end_radius=1.75)
    for x in (0.6, 1.2, 2.9, 3.4):
        assert t.add(np.array([2.0, 3.0]), np.array([x, -0.1]))
    assert float(t._gaps().max()) < COARSE.w2_dist and not t.middle_touched()
    assert not t.closes()
    t.add(np.array([2.0, 3.0]), np.array([2.0, -0.1]))
    assert t.middle_touched() and t.closes()


def test_the_chain_averages_readings_along_the_lid():
    # readings scattered +-0.4 eps across a wall on y = -0.1: block means along the lid
    # (eps/4 + jitter = 1.77 eps) lie nearer the wall than the readings
    rng = np.random.default_rng(0)
    xs = np.sort(rng.uniform(0.2, 5.8, 24))
    t, kept = _touches(np.c_[xs, -0.1 + rng.uniform(-0.4, 0.4, len(xs))])
    assert all(kept) and t.closes()
    inner = t.chain()[1:-1]
    assert len(inner) == len(np.unique(np.floor(xs / COARSE.hop)))  # one mean per block
    assert np.abs(inner[:, 1] + 0.1).max() < 0.2


def test_a_chain_closes_w2_off_the_map():
    """``Exploration.close`` writes a chain as W2 segments (their motion indices
    parallel) and leaves it off the robot's map; a lid closed W2 is on the map."""
    from types import SimpleNamespace

    from core2d.planner.known import KnownContour
    from core2d.planner.run import Exploration
    from core2d.result import AreaRecord, SliceResult

    run = Exploration.__new__(Exploration)
    run.result, run.probe, run.known = SliceResult(), SimpleNamespace(motions=7), KnownContour(2.5)
    area = SimpleNamespace(index=0, a=A, b=B, pose_a=None, pose_b=None)
    run.result.areas.append(AreaRecord(0, A.copy(), B.copy(), -1, "revisit"))
    chain = np.array([A, [2.0, -0.2], [4.0, -0.1], B])
    segments = [chain[i:i + 2] for i in range(3)]
    run.close(area, "W2", "touched", pieces={"W2": segments})
    assert [s.tolist() for s in run.result.w2] == [s.tolist() for s in segments]
    assert run.result.known_at["w2"] == [6, 6, 6] and run.known.pieces == []
    run.close(area, "unknown", "partly", pieces={"W2": segments[:1], "unknown": segments[1:]})
    assert len(run.result.w2) == 4 and [s.tolist() for s in run.result.unknown] == [
        s.tolist() for s in segments[1:]]
    assert run.result.areas[0].outcome == "unknown" and run.known.pieces == []
    run.close(area, "W2", "Dist(A,B) < eps")
    assert len(run.result.w2) == 5 and len(run.known.pieces) == 1


def test_a_lid_touched_in_part():
    """Touches at 1.5 and 2.5 eps along a lid 6 eps long, none beyond: W2 up to the last
    touch, the lid unknown (the 3.5 eps left to B untouched); ends only or a lone touch:
    nothing."""
    t, _ = _touches([(1.5, -0.2), (2.5, -0.1)])
    assert not t.closes()
    got = t.pieces()
    assert [s.round(2).tolist() for s in got["W2"]] == [[[0.0, 0.0], [1.5, -0.2]],
                                                        [[1.5, -0.2], [2.5, -0.1]]]
    assert [s.tolist() for s in got["unknown"]] == [[[0.0, 0.0], [6.0, 0.0]]]
    closed, _ = _touches([(1.5, -0.2), (3.0, -0.1), (4.5, 0.1)])
    assert closed.closes() and set(closed.pieces()) == {"W2"}
    assert _touches([(0.3, -0.1), (5.8, -0.1)])[0].pieces() is None  # ends only
    assert _touches([(3.0, -0.1)])[0].pieces() is None  # gaps of 3 eps either side


def test_perfect_sensing_keeps_the_paper_flow():
    perfect = Resolution.of(1.0)
    assert not applies(perfect) and applies(COARSE) and applies(Resolution.of(1.0, noise=0.1))
    t, _ = _touches([(x, -0.01) for x in (1.0, 2.0, 3.0, 4.0, 5.0)], res=perfect)
    assert not t.closes()


def _scene(name, index):
    import meshes
    import slicer

    mesh = meshes.load(name)
    eps = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)) / 200)
    cut = slicer.slice_mesh(mesh, axis="z", count=8)[index]
    center, radius = cut.bounding_circle()
    return [np.asarray(lp) for lp in cut.loops], cut.contact("embree"), \
        (center, radius + eps), eps


def test_a_cup_wall_the_passes_touched_is_w2(monkeypatch):
    """``cup_handle`` z5, sigma 0.3 eps, taxels 0.25 eps, the sensor study's seed: a lid
    4.9 eps down the cup's wall, 20 passes that touched the wall within 0.7 eps of it and
    were refused (on recorded contour). Against the same run without the rule: the same
    motions, the lid W2 along its contacts instead of unknown, and the coverage within
    eps/2 + 2 sigma (ground truth: core2d.truth) 0.994 -> 1.0."""
    loops, contact, ws, eps = _scene("cup_handle", 5)
    sensor = SensorModel.of_eps(eps, 0.3, 0.25, 5)
    res = sense_slice(contact, ws, eps, sensor=sensor)
    with monkeypatch.context() as m:
        m.setattr(revisit.Touches, "pieces", lambda self: None)
        without = sense_slice(contact, ws, eps, sensor=sensor)
    touched = [r for r in res.areas if "touched C_A^B along the lid" in r.note]
    assert touched and all(r.outcome == "W2" for r in touched)
    assert not any("touched C_A^B" in r.note for r in without.areas)
    assert res.stats.motions == without.stats.motions
    before = {(tuple(r.a), tuple(r.b)): r.outcome for r in without.areas}
    assert {before[(tuple(r.a), tuple(r.b))] for r in touched} == {"unknown"}
    m_on, m_off = (sensor_metrics(loops, r, eps, 0.3 * eps) for r in (res, without))
    assert m_on["coverage_sensor"] > m_off["coverage_sensor"] + 0.004
    assert m_on["precision_sensor"] >= 0.98
    # the W2 segments of the touched lids lie on the true contour within eps/2 + 2 sigma
    # (shapely on the section's loops: independent of the planner and of core2d.truth)
    boundary = shapely.MultiLineString([np.vstack([lp, lp[:1]]) for lp in loops])
    w2 = shapely.MultiLineString([np.asarray(s) for s in res.w2])
    w2_old = shapely.MultiLineString([np.asarray(s) for s in without.w2])
    new = w2.difference(w2_old.buffer(1e-9))
    assert new.length > 2 * eps
    pts = shapely.get_coordinates(shapely.segmentize(new, eps / 8))
    assert shapely.distance(boundary, shapely.points(pts)).max() <= 0.5 * eps + 0.6 * eps


def test_a_mushroom_lid_touched_in_part(monkeypatch):
    """``mushroom`` z7, sigma 0.3 eps, taxels 0.25 eps, sensor seed 1: a lid whose
    passes touched part of it ends unknown only across its gaps, W2 where touched (on seed
    7, the study's, the Fill's passes through free lid samples reach those gaps, and the
    W2 pieces add nothing: 0.9985 with or without them). Against
    the run where such a lid stays wholly unknown: the same motions, more coverage within
    eps/2 + 2 sigma, its W2 pieces on the true contour (shapely) and shorter than the W2
    distance, its lid reported unknown as before."""
    loops, contact, ws, eps = _scene("mushroom", 7)
    sensor = SensorModel.of_eps(eps, 0.3, 0.25, 1)
    res = sense_slice(contact, ws, eps, sensor=sensor)
    whole = Touches.pieces
    with monkeypatch.context() as m:
        m.setattr(revisit.Touches, "pieces",
                  lambda self: whole(self) if self.closes() else None)
        without = sense_slice(contact, ws, eps, sensor=sensor)
    part = [r for r in res.areas if "W2 where they touched" in r.note]
    assert part and all(r.outcome == "unknown" for r in part)
    assert res.stats.motions == without.stats.motions
    m_on, m_off = (sensor_metrics(loops, r, eps, 0.3 * eps) for r in (res, without))
    assert m_on["coverage_sensor"] > m_off["coverage_sensor"]
    assert m_on["precision_sensor"] >= 0.98
    res_of = Resolution.of(eps, noise=0.3 * eps, taxel=0.25 * eps)
    old = {tuple(np.round(np.asarray(s), 12).ravel()) for s in without.w2}
    new = [np.asarray(s) for s in res.w2 if tuple(np.round(np.asarray(s), 12).ravel()) not in old]
    assert new and all(np.hypot(*(s[1] - s[0])) < res_of.w2_dist for s in new)
    boundary = shapely.MultiLineString([np.vstack([lp, lp[:1]]) for lp in loops])
    pts = shapely.get_coordinates(shapely.segmentize(shapely.MultiLineString(new), eps / 8))
    assert shapely.distance(boundary, shapely.points(pts)).max() <= res_of.sensor_tol
    assert len(res.unknown) == len(without.unknown) == sum(
        r.outcome == "unknown" for r in res.areas)
    assert all(np.array_equal(u, w) for u, w in zip(res.unknown, without.unknown))
