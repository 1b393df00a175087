"""The command line: listing, a run's output contract, parallel runs, and bad input."""
import json
import os
import subprocess
import sys

import numpy as np
import pytest
import trimesh

import meshes
from recon3d.cli import main
from recon3d.io import without_timing

OUTPUTS = {"sensing.json", "metrics.json", "motions.csv", "surface.ply", "scene.vtm", "scene",
           "coverage.png", "slices.png"}


def _cli(*args, cwd=None, env=None):
    return subprocess.run([sys.executable, "-m", "recon3d", *args], capture_output=True,
                          text=True, cwd=cwd, env=env)




def test_scenes_lists_every_scene_tab_separated():
    r = _cli("scenes")
    assert r.returncode == 0
    rows = [line.split("\t") for line in r.stdout.strip().splitlines()]
    assert [row[0] for row in rows] == meshes.names() and len(rows) >= 10
    assert all(len(row) == 2 and row[1] for row in rows)


@pytest.fixture(scope="module")
def two_families(tmp_path_factory):
    """fig17_pocket along z and along -x (a negative axis: '--axis -1,0,0')."""
    out = tmp_path_factory.mktemp("cli") / "out"
    r = _cli("run", "fig17_pocket", "--out", str(out), "--slices", "2", "--eps", "2.0",
             "--axis", "z", "--axis", "-1,0,0", "--jobs", "2")
    assert r.returncode == 0, r.stderr
    return out, r


def test_run_writes_the_contract(two_families):
    out, _ = two_families
    assert {p.name for p in out.iterdir()} == OUTPUTS
    doc = json.loads((out / "sensing.json").read_text())
    assert doc["mesh"] == "fig17_pocket" and doc["eps"] == 2.0 and doc["probe_length"] > 0
    assert [f["normal"] for f in doc["families"]] == [[0.0, 0.0, 1.0], [-1.0, 0.0, 0.0]]
    assert [s["family"] for s in doc["slices"]] == [0, 0, 1, 1]
    for s in doc["slices"]:
        assert {"index", "origin", "normal", "u", "v", "segments", "nudge", "stats"} <= set(s)
        assert set(s["stats"]) >= {"motions", "rays", "joint_path", "pushes", "areas",
                                   "escapes", "budget_hit", "seconds"}
        assert s["stats"]["pushes"] == 0
        log = s["areas"]  # the A_iB_i log: every area's rule and outcome
        assert len(log) == s["stats"]["areas"] and log[0]["rule"] == "bootstrap"
        classes = {seg["class"] for seg in s["segments"]}
        assert classes <= {"W1", "W2", "W3"} and "W1" in classes
        n, o = np.array(s["normal"]), np.array(s["origin"])
        for seg in s["segments"]:  # world coordinates, on the slice plane
            assert np.allclose((np.array(seg["points"]) - o) @ n, 0.0, atol=1e-6)
    metrics = json.loads((out / "metrics.json").read_text())
    assert metrics["total"]["coverage"] >= 0.99 and len(metrics["slices"]) == 4
    assert metrics["robot"]["probe_speed"] == 20.0 and metrics["total"]["robot_time_s"] > 0
    fams = metrics["surface_eval"]["families"]
    assert [f["axis"] for f in fams] == ["z", "-x"]
    ev = metrics["surface_eval"]
    for entry in [ev] + fams:  # every scored surface says what it was scored over
        assert 0.0 <= entry["reachable_share"] <= entry["slab_share"] <= 1.0
    assert ev["fused_vs_best"]["axis"] in ("z", "-x") and "coverage" not in ev
    assert 0.5 < metrics["total"]["surface"]["fscore"]["1%"] <= 1.0
    surf = trimesh.load(out / "surface.ply")
    assert surf.is_watertight


def test_summary_and_degenerate_plane_note(two_families):
    _, r = two_families
    assert "F@1%" in r.stdout and "Chamfer-L1/diagonal" in r.stdout and "robot time" in r.stdout
    assert "z alone: F@1%" in r.stdout and "-x alone: F@1%" in r.stdout
    assert "fused against the best single axis" in r.stdout
    assert "surface coverage" not in r.stdout and "-0.000" not in r.stdout
    assert "moved 2 of 2 planes" in r.stderr  # fig17_pocket's x planes hit vertices


def test_jobs_2_equals_jobs_1_and_quiet_is_quiet(tmp_path):
    docs = []
    for jobs in ("1", "2"):
        out = tmp_path / f"j{jobs}"
        r = _cli("run", "fig17_pocket", "--out", str(out), "--slices", "2", "--eps", "3.0",
                 "--axis", "x", "--jobs", jobs, "--quiet", "--no-png")
        assert r.returncode == 0, r.stderr
        assert r.stderr == ""  # no progress bar, no degenerate-plane note
        docs.append([without_timing(json.loads((out / f).read_text()))
                     for f in ("sensing.json", "metrics.json")])
        docs[-1].append((out / "surface.ply").read_bytes())
    assert docs[0] == docs[1]


def test_open_mesh_slices_have_no_reference_and_warnings_are_one_line(tmp_path):
    box = trimesh.creation.box(extents=[20.0, 20.0, 20.0])
    side = np.flatnonzero(box.face_normals[:, 0] > 0.5)  # drop the +x side: open box
    box.update_faces(np.setdiff1d(np.arange(len(box.faces)), side))
    path = tmp_path / "open_box.stl"
    box.export(path)
    out = tmp_path / "o"
    r = _cli("run", str(path), "--out", str(out), "--slices", "2", "--eps", "1.0",
             "--jobs", "1", "--quiet")
    assert r.returncode == 0, r.stderr
    warn = [line for line in r.stderr.splitlines() if line]
    assert warn and all(line.startswith("recon3d: warning: ") for line in warn)
    assert "not watertight" in r.stderr and "warnings.warn" not in r.stderr
    metrics = json.loads((out / "metrics.json").read_text())
    assert [s["reference"] for s in metrics["slices"]] == [False, False]
    assert all(s["coverage"] is None and s["precision"] is None for s in metrics["slices"])
    assert metrics["total"]["slices_without_reference"] == 2
    assert metrics["total"]["motions"] > 0  # cost still counted
    assert "no closed reference contour" in r.stdout


def _eps_bad(mesh):
    return str(float(np.linalg.norm(np.ptp(meshes.load(mesh).bounds, axis=0))) * 0.5)


@pytest.mark.parametrize("args, message", [
    (["no_such_scene"], "no_such_scene"),
    (["{missing}"], "missing.stl"),
    (["fig17_pocket", "--slices", "0"], "--slices"),
    (["fig17_pocket", "--eps", "-1"], "--eps"),
    (["fig17_pocket", "--eps", "inf"], "--eps"),
    (["fig17_pocket", "--eps", "nan"], "--eps"),
    (["fig17_pocket", "--tol", "inf"], "--tol"),
    (["fig17_pocket", "--eps", "1e-9"], "wrong units"),
    (["fig17_pocket", "--eps", "1e-6"], "wrong units"),
    (["fig17_pocket", "--eps", "1e9"], "wrong units"),
    (["fig17_pocket", "--eps", "2", "--tol", "5"], "smaller than eps"),
    (["fig17_pocket", "--eps", "2", "--tol", "2"], "smaller than eps"),
    (["fig17_pocket", "--eps", "2", "--tol", "1e-9"], "--tol"),
    (["fig17_pocket", "--axis", "0,0,0"], "--axis"),
    (["fig17_pocket", "--axis", "up"], "--axis"),
    (["fig17_pocket", "--backend", "gpu"], "backend"),
    (["fig17_pocket", "--jobs", "0"], "--jobs"),
    (["fig17_pocket", "--probe-speed", "0"], "--probe-speed"),
    (["fig17_pocket", "--motion-overhead", "-1"], "--motion-overhead"),
    (["fig17_pocket", "--max-motions", "0"], "--max-motions"),
    (["fig17_pocket", "--noise", "0.3", "--reads", "0"], "--reads"),
    (["fig17_pocket", "--noise", "0.3", "--reads", "65"], "--reads"),
    (["fig17_pocket", "--noise", "0.3", "--reads", "some"], "--reads"),
    (["fig17_pocket", "--noise", "0.3", "--read-time", "-1"], "--read-time"),
])
def test_bad_input_is_one_line_exit_2_and_nothing_left(tmp_path, capsys, args, message):
    out = tmp_path / "out"
    args = [a.format(missing=tmp_path / "missing.stl") for a in args]
    assert main(["run", *args, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and message in err and "Traceback" not in err
    assert not out.exists()


@pytest.mark.parametrize("out, message", [
    ("/proc", "cannot write"),  # exists, not writable even as root
    ("/proc/recon3d-test/out", "cannot create"),
    ("{file}/out", "cannot create"),
])
def test_unwritable_output_is_found_before_sensing(tmp_path, capsys, out, message):
    (tmp_path / "f").write_text("x")
    out = out.format(file=tmp_path / "f")
    assert main(["run", "fig17_pocket", "--out", out, "--slices", "2"]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and message in err
    assert "sensing" not in err  # no progress bar: nothing was sensed


def test_existing_file_as_output_is_rejected(tmp_path, capsys):
    (tmp_path / "f").write_text("x")
    assert main(["run", "fig17_pocket", "--out", str(tmp_path / "f")]) == 2
    assert "not a directory" in capsys.readouterr().err


def test_negative_axis_values_parse():
    from recon3d.cli.main import build_parser, join_axis_values

    argv = join_axis_values(["run", "s", "--out", "o", "--axis", "-1,0,0", "--axis", "-x",
                              "--axis", "z"])
    assert build_parser().parse_args(argv).axis == ["-1,0,0", "-x", "z"]


def test_show_without_display_or_scene_is_one_line_exit_2(tmp_path, two_families):
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    r = _cli("show", str(two_families[0]), env=env)
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1
    assert "no display" in r.stderr and "coverage.png" in r.stderr
    r = _cli("show", str(tmp_path), env=env)
    assert r.returncode == 2 and "no scene.vtm" in r.stderr


def test_empty_mesh_file_is_rejected(tmp_path):
    bad = tmp_path / "empty.stl"
    bad.write_bytes(b"")
    r = _cli("run", str(bad), "--out", str(tmp_path / "o"))
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert not (tmp_path / "o").exists()


def test_run_on_a_mesh_file_reports_it(tmp_path):
    path = tmp_path / "block.stl"
    meshes.load("deep_slot").export(path)
    r = _cli("run", str(path), "--out", str(tmp_path / "o"), "--slices", "2", "--eps", "3",
             "--no-png")
    assert r.returncode == 0, r.stderr
    assert "faces" in r.stderr  # the one-line mesh report (units / scale)
    assert json.loads((tmp_path / "o" / "sensing.json").read_text())["mesh"] == "block.stl"
    assert "wrote" in r.stdout


@pytest.mark.parametrize("ending, teardown", [("end(3)", False), ("sys.exit(3)", True)])
def test_the_command_ends_without_teardown_but_with_its_exit_handlers(ending, teardown):
    """``recon3d`` ends through ``recon3d.cli.main.end``: buffered output is flushed and the
    exit handlers run (child processes, logging, temporary directories), the interpreter's
    module teardown (a run's meshes, VTK, numba: ~1 s) is skipped; sys.exit, the control,
    tears down."""
    code = ("import atexit, sys\n"
            "from recon3d.cli.main import end\n"
            "class Held:\n"
            "    def __del__(self):\n"
            "        print('torn down', flush=True)\n"
            "held = Held()\n"
            "atexit.register(lambda: print('handler ran', flush=True))\n"
            "print('buffered', end='')\n"
            f"{ending}\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 3
    assert r.stdout.startswith("buffered") and "handler ran" in r.stdout
    assert ("torn down" in r.stdout) is teardown
