"""What must hold where the methods are pushed to break (the curves are in ``recon3d bench``).

Termination, no crash, a clear error: planes a hair above a vertex and a
face with no nudge (every backend), contact noise up to eps, eps below the
mesh's own edge length, islands and holes, open and self-intersecting meshes.
"""
import numpy as np
import pytest
import trimesh

import meshes
import recon3d
import slicer
from recon3d.benchmark.cases import workspace
from recon3d.benchmark.stability import run_factor, stability_tasks
from core2d import SensorModel, sense_slice
from recon3d.cli import main


def _step_top_slice(delta):
    mesh = meshes.load("stepped_pyramid")
    z = np.unique(np.round(mesh.vertices[:, 2], 9))
    h = z[len(z) // 2]
    diag = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)))
    (s,) = slicer.slice_mesh(mesh, "z", offsets=[h + delta * diag], nudge=False)
    return s, diag


@pytest.mark.parametrize("backend", ["embree", "exact", "trimesh"])
def test_plane_1e9_above_a_face_and_its_vertices_senses_without_nudge(backend):
    s, diag = _step_top_slice(1e-9)
    assert s.plane.nudge == 0.0 and len(s.loops) == 1
    eps = diag / 40
    res = sense_slice(s.contact(backend), workspace(s, eps), eps, max_motions=3000)
    assert res.w1 and res.stats.motions <= 3000 + 50 and res.stats.pushes == 0


@pytest.mark.parametrize("method", ["pulling", "finger"])
def test_contact_noise_of_eps_ends_within_the_budget(method):
    mesh = meshes.load("fig18_overhangs")
    s = slicer.slice_mesh(mesh, "z", count=3)[1]
    eps = s.scale / 40
    noisy = SensorModel.of_eps(eps, noise=1.0, seed=1)
    res = sense_slice(s.contact("embree"), workspace(s, eps), eps, method=method,
                      max_motions=800, sensor=noisy)
    assert res.stats.motions <= 800 + 50
    # what the noise leaves unresolved is reported, never dropped: every area
    # ends with an outcome, and each "unknown" one is a lid of the result
    # (the sensor model also perturbs joint readings and trace contacts, so
    # areas may end unknown before the budget: passes that found nothing new)
    assert all(a.outcome not in ("pending", "deferred") for a in res.areas)
    assert len(res.unknown) == sum(a.outcome == "unknown" for a in res.areas)


def test_the_stability_study_senses_with_the_sensor_model():
    """The noise and taxel factors run every method through SensorModel (the
    project's one noise model): the readings, and so the runs, differ from
    the perfect sensor's, and the sensor's coverage is reported."""
    tasks = {(t["factor"], t["value"]): t for t in stability_tasks(quick=True)}
    assert {("noise", 1.0), ("taxel", 1.0), ("taxel", 0.25)} <= set(tasks)
    base = {r["method"]: r for r in run_factor(tasks[("taxel", 0.0)])}
    rows = run_factor(tasks[("taxel", 1.0)])
    assert {r["method"] for r in rows} == set(base) and len(base) >= 3
    # every method of core2d.sense_slice: the planners and finger probing
    assert {m.split("/")[0] for m in base} == {"pulling", "paper", "follow", "finger"}
    for r in rows:
        assert not r["crashed"] and 0 < r["coverage_sensor"] <= 1
    assert any(r["motions"] != base[r["method"]]["motions"] for r in rows)


def test_eps_below_the_mesh_edge_length_ends():
    mesh = meshes.load("bowl", resolution=8)
    s = slicer.slice_mesh(mesh, "z", count=3)[1]
    eps = float(mesh.edges_unique_length.mean()) / 8
    res = sense_slice(s.contact("embree"), workspace(s, eps), eps, max_motions=1500)
    assert res.stats.motions <= 1500 + 50 and res.w1


@pytest.mark.parametrize("scene", ["twin_posts", "bored_block"])
def test_islands_and_holes_end_and_report(scene):
    s = slicer.slice_mesh(meshes.load(scene), "z", count=3)[1]
    assert len(s.loops) >= 2  # several objects, or an object with a hole
    eps = s.scale / 50
    for method in ("pulling", "finger"):
        res = sense_slice(s.contact("embree"), workspace(s, eps), eps, method=method,
                          max_motions=4000)
        assert res.w1 or res.w2


def test_open_mesh_runs_with_a_warning_and_a_watertight_surface():
    mesh = meshes.load("fig18_overhangs")
    keep = np.random.default_rng(0).random(len(mesh.faces)) > 0.02
    holey = trimesh.Trimesh(mesh.vertices, mesh.faces[keep], process=False)
    assert not holey.is_watertight
    with pytest.warns(UserWarning, match="watertight"):
        res = recon3d.run(holey, slices=2, eps=res_eps(holey), jobs=1, max_motions=3000)
    assert res.surface.is_watertight and len(res.slices) == 2


def test_self_intersecting_mesh_runs():
    a = trimesh.creation.box(extents=[40, 40, 40])
    b = trimesh.creation.box(extents=[40, 40, 40]).apply_translation([20, 10, 5])
    both = trimesh.util.concatenate([a, b])
    assert both.is_watertight and both.body_count == 2  # closed, but the bodies overlap
    # 20 x 30 x 35 of the two 40^3 boxes is shared: 21000 = 16% of their 128000
    with pytest.warns(UserWarning, match=r"2 bodies overlap \(shared volume 2.1e\+04, 16%"):
        res = recon3d.run(both, slices=2, eps=res_eps(both), jobs=1, max_motions=3000)
    assert res.metrics["total"]["surface"]["fscore"]["1%"] > 0.5


def res_eps(mesh):
    return float(np.linalg.norm(np.ptp(mesh.bounds, axis=0))) / 40


@pytest.mark.parametrize("argv, message", [
    (["run", "bowl", "--out", "{d}", "--slices", "many"], "integer or 'auto'"),
    (["run", "bowl", "--out", "{d}", "--slices", "auto", "--max-slices", "2"], "at least 3"),
    (["run", "bowl", "--out", "{d}", "--slices", "auto", "--slice-tol", "0.7"], "--slice-tol"),
    (["bench", "--out", "{d}", "--parts", "speed"], "--parts"),
    (["bench", "--out", "{f}"], "--out"),
    (["bench", "--out", "{d}", "--workers", "0"], "--workers"),
    (["bench", "--out", "{d}", "--redraw", "{f}"], "--redraw: "),
])
def test_bad_bench_and_auto_flags_are_one_line_exit_2(tmp_path, capsys, argv, message):
    f = tmp_path / "file"
    f.write_text("x")
    argv = [a.format(d=tmp_path / "out", f=f) for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("recon3d: error:") and message in err[0]
    assert not (tmp_path / "out").exists()
