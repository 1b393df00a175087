"""An object met once far from everything recorded: the bootstrap aimed at it
(:mod:`core2d.planner.orphans`).

* the orphans kept: only contacts farther than ``UNTOUCHED`` eps from the map;
* the aimed bootstrap on a block and a small island 10 eps beside it: its insertions aimed
  at the island meet it, and its areas pair contacts on the island (the first bootstrap,
  aimed at the workspace centre, touches the block alone); an orphan that the record has
  reached since, and a run past ``MAX_SEEKS`` rounds, register nothing;
* ``vtk_42400-IDGH`` z-plane 2 of 5 at sigma 0.1 eps, sensor seed 2 (skipped without
  ``../shared``): its square island, met once by a revisit pass 31 eps in front of the lid,
  is traced (0.974 without the aimed bootstrap).
"""
from __future__ import annotations

import numpy as np
import pytest
import shapely

from core2d import SensorModel
from core2d.planner.bootstrap import bootstrap
from core2d.planner.orphans import MAX_SEEKS, UNTOUCHED, seek
from core2d.planner.run import Budget, Exploration
from core2d.sim.probe import Probe
from core2d.sim.recorder import Recorder
from slicer.contact.exact import ExactContact

EPS = 1.0
BLOCK = np.asarray(shapely.box(-20.0, -20.0, 20.0, 20.0).exterior.coords)[:-1]
ISLAND = np.asarray(shapely.box(30.0, 25.0, 32.5, 27.5).exterior.coords)[:-1]
ON_ISLAND = np.array([30.0, 26.0])  # a point of its left face


def _ccw(loop):
    return loop if shapely.LinearRing(loop).is_ccw else loop[::-1]


def _run(noise=0.1):
    loops = [_ccw(BLOCK), _ccw(ISLAND)]
    sensor = SensorModel.of_eps(EPS, noise, 0.0, 0, reads=16)
    probe = Recorder(Probe(ExactContact(loops), (np.zeros(2), 50.0), EPS, None, None, sensor))
    return Exploration(probe, EPS, Budget(probe))


def _on_island(p, tol=0.5):
    lo, hi = ISLAND.min(0) - tol, ISLAND.max(0) + tol
    return bool(np.all((p >= lo) & (p <= hi)))


def test_the_first_bootstrap_touches_the_block_alone():
    run = _run()
    areas = bootstrap(run.probe, 12)
    assert areas and not any(_on_island(a.a) or _on_island(a.b) for a in areas)


def test_only_contacts_far_from_the_record_are_kept():
    run = _run()
    run.known.add([[x, 20.0] for x in np.arange(20.0, -20.1, -0.5)])  # the block's top
    run.orphans.note(run, ON_ISLAND)  # 10 eps from the record
    run.orphans.note(run, [0.0, 20.0 + UNTOUCHED * EPS - 0.5])  # within UNTOUCHED
    np.testing.assert_array_equal(run.orphans.points, [ON_ISLAND])


def test_the_aimed_bootstrap_pairs_contacts_on_the_island():
    run = _run()
    run.orphans.note(run, ON_ISLAND)
    added = seek(run)
    new = [a for a in run.queue if a.rule == "orphan"]
    assert added == len(new) > 0
    on = [a for a in new if _on_island(a.a) and _on_island(a.b)]
    assert on, [(a.a, a.b) for a in new]
    assert run.orphans.points == []  # each orphan sought once


def test_an_orphan_the_record_reached_or_a_run_past_its_rounds_seeks_nothing():
    run = _run()
    run.orphans.note(run, ON_ISLAND)
    run.known.add([[30.0, y] for y in np.arange(25.0, 27.6, 0.5)])  # traced since
    assert seek(run) == 0 and not run.queue
    run = _run()
    run.orphans.rounds = MAX_SEEKS
    run.orphans.note(run, ON_ISLAND)
    assert seek(run) == 0 and not run.queue


def test_an_island_met_once_far_from_the_record_is_traced(shared_meshes_dir, monkeypatch):
    """``vtk_42400-IDGH``, z-plane 2 of 5, sigma 0.1 eps, sensor seed 4002: a square island
    2.5 eps wide, 14 eps from every other object, which the first bootstrap passed by. A
    revisit pass met it 31 eps in front of a lid 24 eps long (``in_reach`` refuses it: more
    often a wall met through a gap in a noisy record), and it was never touched again:
    0.974. Bootstrapped again, aimed at it, it is traced. (The case was seed 2, the unseen
    study's draws, until the trace's controller read a probe's end hanging in a slot as a
    jump, :func:`core2d.sim.compliance.overhangs`: its runs part earlier since, and with
    seed 2 the island is reached without the second bootstrap.)"""
    import core2d.planner.run as run_module
    from core2d import sense_slice
    from core2d.resolution import repeated_reads
    from core2d.truth.metrics import sensor_metrics
    from noisy_runs import mesh_slice

    cut, eps, ws, loops = mesh_slice(shared_meshes_dir / "vtk_42400-IDGH.stl", 2, count=5)

    def run():
        sensor = SensorModel.of_eps(eps, 0.1, 0.0, 4002, reads=repeated_reads(1.0, 0.1, 0.0))
        res = sense_slice(cut.contact("embree"), ws, eps, max_motions=20000, sensor=sensor)
        return res, sensor_metrics(loops, res, eps, sensor.noise)

    res, m = run()
    assert not res.stats.budget_hit
    assert m["coverage_sensor"] >= 0.99, f"coverage {m['coverage_sensor']:.4f}"
    assert m["precision_sensor"] >= 0.98
    assert m["w3_unsound_count_sensor"] == 0
    assert any(a.rule == "orphan" for a in res.areas)
    monkeypatch.setattr(run_module, "seek", lambda run: 0)
    assert run()[1]["coverage_sensor"] < 0.98
