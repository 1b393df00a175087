"""Bad input and odd requests at the command line and in the API: one line, exit 2.

Each case here once produced a traceback, a silent success or a misleading
message; each now gets one line ``recon3d: error: ...`` (exit status 2, nothing
written) or a documented warning.
"""
from __future__ import annotations

import importlib.metadata
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import trimesh

import recon3d
import slicer


def _cli(*args, env=None):
    env = dict(os.environ if env is None else env,
               VTK_DEFAULT_OPENGL_WINDOW="vtkEGLRenderWindow")
    # a timeout: a check that stopped working must fail the test, not start a long run
    return subprocess.run([sys.executable, "-m", "recon3d", *args], capture_output=True,
                          text=True, env=env, timeout=300)


def _one_error_line(r, code=2) -> str:
    assert r.returncode == code, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("recon3d: error: "), r.stderr
    assert "recon3d: error: recon3d" not in lines[0]  # no doubled prefix
    return lines[0]


def test_version_everywhere():
    version = importlib.metadata.version("pulling-probe-3d")
    assert recon3d.__version__ == version
    r = _cli("--version")
    assert r.returncode == 0 and r.stdout.strip() == f"recon3d {version}"
    assert (Path(recon3d.__file__).parent / "py.typed").is_file()


def test_no_command_is_one_line_without_a_doubled_prefix():
    line = _one_error_line(_cli())
    assert "COMMAND" in line or "command" in line


def test_a_single_triangle_file_is_one_line(tmp_path):
    path = tmp_path / "tri.stl"
    trimesh.Trimesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]]).export(path)
    line = _one_error_line(_cli("run", str(path), "--out", str(tmp_path / "o")))
    assert "flat" in line and not (tmp_path / "o").exists()


def test_the_api_raises_input_error_for_a_flat_or_nan_mesh():
    tri = trimesh.Trimesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    with pytest.raises(recon3d.InputError, match="flat"):
        recon3d.run(tri)
    box = trimesh.creation.box((10, 10, 10))
    v = box.vertices.copy()
    v[0] = np.nan
    with pytest.raises(recon3d.InputError, match="not finite"):
        recon3d.run(trimesh.Trimesh(v, box.faces, process=False))


def test_nan_vertex_file_is_refused_and_dropped_on_request(tmp_path):
    box = trimesh.creation.box((20.0, 20.0, 20.0))
    v = box.vertices.copy()
    v[0] = np.nan
    path = tmp_path / "nan.obj"
    trimesh.Trimesh(v, box.faces, process=False).export(path)
    line = _one_error_line(_cli("run", str(path), "--out", str(tmp_path / "o")))
    assert "not finite" in line and "--drop-nonfinite" in line
    r = _cli("run", str(path), "--out", str(tmp_path / "o"), "--drop-nonfinite",
             "--slices", "2", "--no-png", "--quiet")
    assert r.returncode == 0, r.stderr
    assert "dropped 1 of 8 vertices" in r.stderr


@pytest.mark.parametrize("text, same_as", [
    ("1e300,1e300,0", "1,1,0"),
    ("1e-200,1e-200,0", "1,1,0"),
    ("1e-30,0,0", "x"),
    ("-1e308,0,0", "-x"),
])
def test_axis_vectors_are_scale_free(text, same_as):
    np.testing.assert_allclose(slicer.parse_axis(text), slicer.parse_axis(same_as), atol=1e-15)


@pytest.mark.parametrize("text", ["0,0,0", "nan,0,0", "inf,0,0", "1,2", "0,0,1e-400"])
def test_bad_axis_vectors_are_one_line(tmp_path, text):
    line = _one_error_line(_cli("run", "bored_block", "--axis", text, "--out",
                                str(tmp_path / "o")))
    assert "--axis" in line and not (tmp_path / "o").exists()


def test_one_slice_is_a_clear_error(tmp_path):
    line = _one_error_line(_cli("run", "bored_block", "--slices", "1", "--out",
                                str(tmp_path / "o")))
    assert "at least 2" in line
    with pytest.raises(recon3d.InputError, match="at least 2"):
        recon3d.run("bored_block", slices=1)


def test_too_many_slices_need_force(tmp_path):
    line = _one_error_line(_cli("run", "bored_block", "--slices", "5000", "--out",
                                str(tmp_path / "o")))
    assert "--force" in line and not (tmp_path / "o").exists()


def test_proc_output_names_the_real_reason(tmp_path):
    line = _one_error_line(_cli("run", "bored_block", "--out", "/proc/recon3d-test"))
    assert "cannot create --out /proc/recon3d-test" in line
    assert "/proc: No such file or directory" not in line


def test_show_with_an_unreachable_display_is_one_line(tmp_path):
    scene = tmp_path / "s"
    r = _cli("run", "bored_block", "--slices", "2", "--out", str(scene), "--no-png", "--quiet")
    assert r.returncode == 0, r.stderr
    env = {k: v for k, v in os.environ.items() if k != "WAYLAND_DISPLAY"}
    env["DISPLAY"] = ":97"  # no X server there
    line = _one_error_line(_cli("show", str(scene), env=env))
    assert "display" in line and "vtk" not in line.lower().replace("scene.vtm", "")


def test_units_scale_the_probe_speed_and_are_recorded(tmp_path):
    mm, m = tmp_path / "mm", tmp_path / "m"
    base = ["run", "bored_block", "--slices", "2", "--no-png", "--quiet", "--eps", "2"]
    assert _cli(*base, "--out", str(mm)).returncode == 0
    r = _cli(*base, "--out", str(m), "--units", "m")
    assert r.returncode == 0, r.stderr
    a, b = (json.loads((d / "metrics.json").read_text()) for d in (mm, m))
    assert a["robot"]["units"] == "mm" and b["robot"]["units"] == "m"
    # the same 20 mm/s probe on a part read as metres travels 1000x longer
    ta, tb = a["total"], b["total"]
    assert tb["motions"] == ta["motions"]
    moving_a = ta["robot_time_s"] - ta["motions"] * a["robot"]["motion_overhead_s"]
    moving_b = tb["robot_time_s"] - tb["motions"] * b["robot"]["motion_overhead_s"]
    assert moving_b == pytest.approx(1000.0 * moving_a, rel=1e-9)


def test_a_huge_mesh_in_mm_warns_about_units(tmp_path):
    path = tmp_path / "big.stl"
    trimesh.creation.box((8e4, 6e4, 4e4)).export(path)  # 80 m long "in mm"
    r = _cli("run", str(path), "--slices", "2", "--no-png", "--quiet", "--out",
             str(tmp_path / "o"))
    assert r.returncode == 0, r.stderr
    assert "--units" in r.stderr and "warning" in r.stderr


@pytest.fixture(scope="module")
def small_result():
    return recon3d.run("bored_block", slices=2, eps=2.0, jobs=1)


def test_result_repr_is_short(small_result):
    text = repr(small_result)
    assert len(text) < 400 and "bored_block" in text and "F@1%" in text and "slices" in text


def test_plot_writes_the_screenshot_it_was_asked_for(tmp_path, small_result):
    pytest.importorskip("pyvista")
    path = tmp_path / "p.png"
    got = small_result.plot(off_screen=True, screenshot=path)
    assert path.is_file() and path.stat().st_size > 10_000
    assert got is not None
