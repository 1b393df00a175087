"""A coarse sensor's revisit: swing passes into the gaps the straight passes' touches left
(:func:`core2d.planner.swing_passes.swing_gaps`) and the sweep spaced by what the sensor
resolves (:func:`core2d.planner.grazing.sweep_length`), on ``deep_slot`` (Embree, a
built-in scene) with keyed sensor noise, so both runs of a pair read the same noise
wherever their motions are the same."""
from __future__ import annotations

import numpy as np
import pytest
import shapely

import core2d.planner.revisit as revisit
import meshes
import slicer
from core2d import SensorModel, sense_slice
from core2d.planner.grazing import sweep_length
from core2d.resolution import Resolution
from core2d.truth.metrics import sensor_metrics

GAPS, SWEEP = revisit.swing_gaps, revisit.sweep  # unpatched


def _run(monkeypatch, z, noise, taxel, seed, gaps=True):
    """``deep_slot`` z of 8 sensed with keyed noise: the result, the loops, eps, and the
    contacts of the swings :func:`swing_gaps` made; ``gaps`` False: it makes none."""
    contacts, spacings = [], []

    def swing_gaps(run, area, touches):
        if not gaps:  # what the revisit had without them
            return touches.pieces() if touches.points else None
        before = len(touches.points)
        part = GAPS(run, area, touches)
        contacts.extend(touches.points[before:])
        return part

    def sweep(lines, length, eps, **kw):
        spacings.append(eps)
        return SWEEP(lines, length, eps, **kw)

    monkeypatch.setattr(revisit, "swing_gaps", swing_gaps)
    monkeypatch.setattr(revisit, "sweep", sweep)
    mesh = meshes.load("deep_slot")
    eps = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)) / 200)
    cut = slicer.slice_mesh(mesh, axis="z", count=8)[z]
    center, radius = cut.bounding_circle()
    res = sense_slice(cut.contact("embree"), (center, radius + eps), eps,
                      sensor=SensorModel.of_eps(eps, noise, taxel, seed, keyed=True))
    return res, [np.asarray(lp) for lp in cut.loops], eps, contacts, spacings


def test_the_sweep_length_is_what_the_sensor_resolves():
    assert sweep_length(Resolution.of(1.0)) == 1.0  # perfect sensing: eps
    fine = Resolution.of(1.0, noise=0.1)
    assert sweep_length(fine) == 1.0  # two readings within eps/2: eps
    coarse = Resolution.of(1.0, noise=0.3, taxel=0.25)
    assert sweep_length(coarse) == pytest.approx(coarse.w2_dist) and coarse.w2_dist > 2.5


@pytest.mark.parametrize("noise, taxel", [(0.3, 0.25), (0.1, 0.0)])
def test_the_revisit_sweeps_by_the_sensor_s_resolution(monkeypatch, noise, taxel):
    res, _, eps, contacts, spacings = _run(monkeypatch, 3, noise, taxel, 3003)
    assert spacings  # the slice has lids whose sweep was planned
    want = sweep_length(Resolution.of(eps, noise=noise * eps, taxel=taxel * eps))
    assert spacings == pytest.approx([want] * len(spacings))
    if noise < 0.3:
        assert contacts == []  # a fine sensor swings into no gaps


def test_swings_into_the_gaps_touch_the_wall_straight_passes_missed(monkeypatch):
    """z3 with sensor seed 3003 (sigma 0.3 eps, taxels 0.25 eps): lids along the slot's
    walls whose straight passes found nothing new; the swings into their touches' gaps
    raise the reachable coverage within eps/2 + 2 sigma (0.988 -> 0.994 here), their
    contacts lie on the walls (shapely, against the true section), at a motion cost of
    at most 1.25 x."""
    before, loops, eps, _, _ = _run(monkeypatch, 3, 0.3, 0.25, 3003, gaps=False)
    after, _, _, contacts, _ = _run(monkeypatch, 3, 0.3, 0.25, 3003)
    m0 = sensor_metrics(loops, before, eps, 0.3 * eps)
    m1 = sensor_metrics(loops, after, eps, 0.3 * eps)
    assert m1["coverage_sensor"] >= m0["coverage_sensor"] + 0.004, \
        (m0["coverage_sensor"], m1["coverage_sensor"])
    assert m1["precision_sensor"] >= 0.98 and not after.stats.budget_hit
    assert after.stats.motions <= 1.25 * before.stats.motions
    assert len(contacts) >= 10
    boundary = shapely.union_all([shapely.LinearRing(lp) for lp in loops])
    off = shapely.distance(shapely.points(np.asarray(contacts)), boundary)
    assert np.mean(off <= eps / 2 + 2 * 0.3 * eps) >= 0.95
