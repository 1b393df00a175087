"""``--method paper``: the paper's Fig. 16 flow alone takes no decision the paper does not.

Each addition of the default planner (its map, the map's closure of areas
traced through others, the escape over the whole ancestry, deferral of dead
ends, W3 only with a proof, revisits, the audit) sits behind one switch of
:class:`core2d.planner.flow.Flow`. Per addition: a spy shows it runs with the
default flow (so it is reachable on that scene), never with ``PAPER``, and
never with a flow where only its own switch is off (so each test fails when
that switch is removed). Scenes: the Fig. 6(b) slit of ``figure_scenes.py``
(exact contact) and one fig18_overhangs slice (Embree).
"""
from __future__ import annotations

import json
import sys

import numpy as np
import pytest

import core2d.planner.known as known_mod
import core2d.planner.run as run_mod
import meshes
import recon3d
import slicer
from core2d.planner.flow import PAPER, PULLING, Flow
from core2d.sim.probe import Probe
from figure_scenes import (EPS, GRAZE_DIR, LIP_LEFT, OVERHANG_LEFT, SLIT, WORKSPACE, block,
                           graze_point, make_probe, new_run, place, pose_to, run_one)
from core2d.planner.areas import Area
from recon3d.cli import main
from recon3d.sensing.worker import family_slices
from slicer.contact.exact import ExactContact

NO_MAP = Flow(map=False, covers=False, w3_proof=False, revisit=False, audit=False)


class Spy:
    """Count the calls of ``names`` of ``module`` (patched with ``monkeypatch``)."""

    def __init__(self, monkeypatch, module, names):
        self.calls = dict.fromkeys(names, 0)
        for name in names:
            real = getattr(module, name)

            def spy(*a, _real=real, _name=name, **kw):
                self.calls[_name] += 1
                return _real(*a, **kw)
            monkeypatch.setattr(module, name, spy)

    def reset(self):
        self.calls = dict.fromkeys(self.calls, 0)

    @property
    def total(self) -> int:
        return sum(self.calls.values())


@pytest.fixture(scope="module")
def overhangs():
    """(contact, workspace, eps) of fig18_overhangs z-slice 3 of 8 (defaults of a run)."""
    mesh = meshes.load("fig18_overhangs")
    eps = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0))) / 200
    cut = family_slices(mesh, slicer.parse_axis("z"), 8)[3]
    c, r = cut.bounding_circle()
    return cut.contact("embree"), (np.asarray(c, float), float(r) + eps), eps


def _explore(scene, flow):
    contact, ws, eps = scene
    return run_mod.explore(Probe(contact, ws, eps, tol=eps / 20), eps, flow=flow)


def _slit_area():
    """The Fig. 6(b) slit: A_i = lip corner, B_i = floor point on one posture."""
    loops = block(SLIT)
    probe = make_probe(loops)
    floor = place(make_probe(loops), graze_point(0.025), GRAZE_DIR).tip_contact.point
    pose = pose_to(probe, floor, GRAZE_DIR)
    return probe, Area(LIP_LEFT.copy(), floor, pose, pose)


ADDITIONS = ("map", "covers", "escape", "defer", "w3_proof", "revisit", "audit")


def test_the_presets():
    assert PULLING == Flow() and all(getattr(PULLING, k) for k in ADDITIONS)
    assert not any(getattr(PAPER, k) for k in ADDITIONS)
    for flow in (PULLING, PAPER):  # the paper's own decisions as the paper has them
        assert flow.detection and flow.pair and not flow.lifo and flow.same == 1.0
    with pytest.raises(ValueError, match="need the map"):
        Flow(map=False)


@pytest.mark.parametrize("flow, used", [(PULLING, True), (NO_MAP, False), (PAPER, False)])
def test_no_map_is_built_or_read(overhangs, monkeypatch, flow, used):
    spy = Spy(monkeypatch, known_mod.KnownContour,
              ["__init__", "add", "covers", "distance", "crosses", "chain", "free_lines",
               "loose_ends"])
    res = _explore(overhangs, flow)
    assert (spy.total > 0) == used, spy.calls
    assert res.w1 and res.w2
    if not used:
        assert not any("other areas" in a.note or "recorded contour" in a.note
                       for a in res.areas)


@pytest.mark.parametrize("flow, deferred", [(PULLING, True), (Flow(defer=False), False),
                                            (PAPER, False)])
def test_no_dead_end_is_deferred(monkeypatch, flow, deferred):
    """Fig. 6(b) with lines still crossing the lid: the default defers it; without
    deferral the dead end is W3 at once (§4.2.1)."""
    seen = []
    real = run_mod.Exploration.defer

    def defer(self, area, why):
        real(self, area, why)
        seen.append(area in self.deferred)
    monkeypatch.setattr(run_mod.Exploration, "defer", defer)
    probe, area = _slit_area()
    run = run_one(probe, area, flow)
    rec = run.result.areas[0]
    assert any(seen) == deferred and bool(run.deferred) == deferred
    assert (rec.outcome == "deferred") == deferred
    if not deferred:
        assert rec.outcome == "W3" and "§4.2.1" in rec.note
        np.testing.assert_allclose(run.result.w3[0], [area.a, area.b])


@pytest.mark.parametrize("flow, proved", [(PULLING, True), (Flow(w3_proof=False), False),
                                          (PAPER, False)])
def test_area_G_zero_needs_no_proof(monkeypatch, flow, proved):
    """Area(G_i) = 0: the default asks its map for a proof (lid_like, closes_loop,
    proof_lines) and defers; the paper's flow makes W3 at once."""
    spy = Spy(monkeypatch, run_mod, ["lid_like", "closes_loop", "proof_lines"])
    probe, area = _slit_area()
    run = run_one(probe, area, flow)
    rec = run.result.areas[0]
    assert (spy.total > 0) == proved, spy.calls
    if not proved:
        assert rec.outcome == "W3" and rec.note == "single probe detection, Area(G) = 0 (§4.2.1)"


@pytest.mark.parametrize("flow, used", [(PULLING, True), (Flow(revisit=False), False),
                                        (PAPER, False)])
def test_no_revisit(overhangs, monkeypatch, flow, used):
    spy = Spy(monkeypatch, run_mod, ["revisit"])
    res = _explore(overhangs, flow)
    assert (spy.calls["revisit"] > 0) == used
    assert any(a.rule == "revisit" for a in res.areas) == used


@pytest.mark.parametrize("flow, used", [(PULLING, True), (Flow(covers=False), False),
                                        (PAPER, False)])
def test_no_map_closure(monkeypatch, flow, used):
    """The map closes an area whose C_A^B was traced through other areas when
    the area is processed (``covers``); off, ``process`` never asks the map
    (the revisit's own closure of a deferred area stays with the revisit).
    Whole slice: the OVERHANG_LEFT block of ``figure_scenes.py`` (exact contact)."""
    asked = []
    real = known_mod.KnownContour._chain

    def chain(self, *a, **kw):  # who asked, past the map's and the mouths' wrappers
        frame = sys._getframe(1)
        while frame.f_code.co_name in ("covers", "chain", "hops", "covered",
                                       "traced_gaps"):
            frame = frame.f_back
        asked.append(frame.f_code.co_name)
        return real(self, *a, **kw)
    monkeypatch.setattr(known_mod.KnownContour, "_chain", chain)
    loops = block(OVERHANG_LEFT)
    res = run_mod.explore(Probe(ExactContact(loops), WORKSPACE, EPS), EPS, flow=flow)
    assert ("process" in asked) == used
    assert res.w1 and not res.stats.budget_hit


@pytest.mark.parametrize("flow, asked", [(PULLING, [True, True, False]),
                                         (Flow(escape=False), [False, True, False]),
                                         (PAPER, [False, True, False])])
def test_escape_over_the_ancestry(flow, asked):
    """§4.4: a kid repeating its grandparent's A and B asks for the escape only
    over the whole ancestry (``escape``); one repeating its parent's always."""
    probe, area = _slit_area()
    run = new_run(probe, flow)
    grand = (area.a + [0.0, 30.0], area.b + [0.0, 30.0])
    area.lineage = (grand,)
    kids = [Area(grand[0].copy(), grand[1].copy(), area.pose_a, area.pose_b),
            Area(area.a.copy(), area.b.copy(), area.pose_a, area.pose_b),
            Area(area.a + [5.0, 0.0], area.b, area.pose_a, area.pose_b)]
    run.add(area)
    run.children(run.queue.popleft(), kids, traced=10.0)
    assert [k.escape for k in kids] == asked


@pytest.mark.parametrize("flow, asked", [(PULLING, True), (Flow(escape=False), False)])
def test_escape_after_stale_generations(flow, asked):
    """The STALE-th generation in a row that traced nothing new asks for the
    escape only with ``escape`` on."""
    probe, area = _slit_area()
    run = new_run(probe, flow)
    area.stale = run_mod.STALE - 1
    kid = Area(area.a + [5.0, 0.0], area.b, area.pose_a, area.pose_b)
    run.add(area)
    run.children(run.queue.popleft(), [kid], traced=0.0)
    assert kid.escape == asked


@pytest.mark.parametrize("flow, used", [(PULLING, True), (Flow(audit=False), False),
                                        (PAPER, False)])
def test_no_audit(overhangs, monkeypatch, flow, used):
    spy = Spy(monkeypatch, run_mod, ["audit"])
    _explore(overhangs, flow)
    assert (spy.calls["audit"] > 0) == used


def test_paper_takes_no_decision_of_the_additions_on_a_whole_slice(overhangs, monkeypatch):
    """One run with every spy at once: the paper's flow calls none of them, and
    every area ends by a rule of Fig. 16 (W2, W3, split, traced)."""
    spies = [Spy(monkeypatch, run_mod, ["revisit", "audit", "lid_like", "closes_loop",
                                        "proof_lines", "finish"]),
             Spy(monkeypatch, known_mod.KnownContour, ["__init__"])]
    res = _explore(overhangs, PAPER)
    assert [s.total for s in spies] == [1, 0]  # finish() alone: it only reports waiting lids
    assert {a.outcome for a in res.areas} <= {"W2", "W3", "split", "traced"}
    assert not res.unknown and not res.stats.budget_hit
    for s in spies:
        s.reset()
    _explore(overhangs, PULLING)
    assert spies[0].calls["revisit"] and spies[0].calls["audit"] and spies[1].total


@pytest.mark.parametrize("scene", meshes.names())
def test_paper_runs_on_every_built_in_scene(scene):
    mesh = meshes.load(scene)
    eps = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0))) / 60
    res = recon3d.run(scene, slices=2, eps=eps, method="paper", jobs=1)
    assert res.metrics["method"] == "paper" and res.sensing.config.method == "paper"
    tot = res.metrics["total"]
    assert tot["budget_hits"] == 0 and tot["motions"] > 0
    assert res.surface.is_watertight
    for s in res.slices:
        assert not any(a.outcome in ("deferred", "open") or a.rule in ("revisit", "audit")
                       for a in s.result.areas)


def test_cli_method_paper_and_a_bad_method(tmp_path, capsys):
    out = tmp_path / "p"
    assert main(["run", "fig17_pocket", "--slices", "2", "--method", "paper", "--no-png",
                 "--quiet", "--out", str(out)]) == 0
    assert json.loads((out / "metrics.json").read_text())["method"] == "paper"
    assert json.loads((out / "sensing.json").read_text())["method"] == "paper"
    assert (out / "motions.csv").stat().st_size > 0
    capsys.readouterr()
    assert main(["run", "fig17_pocket", "--method", "kaneko", "--out", str(tmp_path / "q")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert "--method" in err[-1] and "Traceback" not in "\n".join(err)
    assert not (tmp_path / "q").exists()
    with pytest.raises(recon3d.InputError, match="method must be one of pulling, paper"):
        recon3d.run("fig17_pocket", method="kaneko")
