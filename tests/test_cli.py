"""The command line: listing, a run's output contract, and bad input."""
import json
import subprocess
import sys

import pytest

import meshes
from recon3d.cli import main


def _cli(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "recon3d", *args], capture_output=True,
                          text=True, cwd=cwd)


def test_scenes_lists_every_scene_tab_separated():
    r = _cli("scenes")
    assert r.returncode == 0
    rows = [line.split("\t") for line in r.stdout.strip().splitlines()]
    assert [row[0] for row in rows] == meshes.names() and len(rows) >= 10
    assert all(len(row) == 2 and row[1] for row in rows)


def test_run_writes_the_sensing_contract(tmp_path):
    out = tmp_path / "out"
    assert main(["run", "fig17_pocket", "--out", str(out), "--slices", "2", "--quiet"]) == 0
    doc = json.loads((out / "sensing.json").read_text())
    assert doc["mesh"] == "fig17_pocket" and doc["eps"] > 0 and doc["probe_length"] > 0
    assert len(doc["slices"]) == 2
    for s in doc["slices"]:
        assert {"index", "origin", "normal", "u", "v", "segments", "nudge", "stats"} <= set(s)
        assert set(s["stats"]) >= {"motions", "rays", "joint_path", "pushes", "areas",
                                   "escapes", "budget_hit", "seconds"}
        assert s["stats"]["pushes"] == 0
        log = s["areas"]  # the A_iB_i log: every area's rule and outcome
        assert len(log) == s["stats"]["areas"] and {a["outcome"] for a in log} <= {
            "traced", "W2", "W3", "split", "unknown"}
        assert all(a["rule"] for a in log) and log[0]["rule"] == "bootstrap"
        classes = {seg["class"] for seg in s["segments"]}
        assert classes <= {"W1", "W2", "W3"} and "W1" in classes
        z = s["origin"][2]
        for seg in s["segments"]:  # world coordinates, on the slice plane
            assert all(len(p) == 3 and abs(p[2] - z) < 1e-6 for p in seg["points"])
    metrics = json.loads((out / "metrics.json").read_text())
    assert metrics["total"]["coverage"] >= 0.99 and len(metrics["slices"]) == 2


@pytest.mark.parametrize("args, message", [
    (["run", "no_such_scene", "--out", "{out}"], "no_such_scene"),
    (["run", "{missing}", "--out", "{out}"], "missing.stl"),
    (["run", "fig17_pocket", "--out", "{out}", "--slices", "0"], "--slices"),
    (["run", "fig17_pocket", "--out", "{out}", "--eps", "-1"], "--eps"),
    (["run", "fig17_pocket", "--out", "{out}", "--axis", "0,0,0"], "--axis"),
    (["run", "fig17_pocket", "--out", "{out}", "--backend", "gpu"], "backend"),
])
def test_bad_input_is_one_line_exit_2_and_no_output(tmp_path, args, message):
    out = tmp_path / "out"
    args = [a.format(out=out, missing=tmp_path / "missing.stl") for a in args]
    r = _cli(*args)
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert message in lines[-1] and "Traceback" not in r.stderr
    assert not (out / "sensing.json").exists()


def test_empty_mesh_file_is_rejected(tmp_path):
    bad = tmp_path / "empty.stl"
    bad.write_bytes(b"")
    r = _cli("run", str(bad), "--out", str(tmp_path / "o"))
    assert r.returncode == 2 and "Traceback" not in r.stderr


def test_run_on_a_mesh_file_reports_it(tmp_path):
    path = tmp_path / "block.stl"
    meshes.load("deep_slot").export(path)
    r = _cli("run", str(path), "--out", str(tmp_path / "o"), "--slices", "1")
    assert r.returncode == 0, r.stderr
    assert "faces" in r.stderr  # the one-line mesh report (units / scale)
    assert json.loads((tmp_path / "o" / "sensing.json").read_text())["mesh"] == "block.stl"
