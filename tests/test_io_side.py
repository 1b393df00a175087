"""The forked side process of a run's files (recon3d.io.side) and the writer that uses it:
coverage.png drawn by a child from the scene.vtm written by the parent, the same files
and picture as one process draws, errors and warnings of the child carried to the parent."""
import multiprocessing
import os
import signal
import time
import warnings

import numpy as np
import pytest

import recon3d
import recon3d.io.outputs as outputs
import recon3d.viz.plot as plot
from recon3d.io import without_timing
from recon3d.io.side import Side
from recon3d.spellings import make_config

pytestmark = pytest.mark.skipif("fork" not in multiprocessing.get_all_start_methods(),
                                reason="needs fork")


def _warn_and_return(x):
    warnings.warn("from the child", RuntimeWarning)
    return x * 2, os.getpid()


def _fail():
    raise ValueError("bad thing")


def _die():
    os.kill(os.getpid(), signal.SIGKILL)


def _sleep():
    time.sleep(60)


def test_side_returns_its_value_from_another_process_and_reissues_warnings():
    side = Side(_warn_and_return, 21)
    with pytest.warns(RuntimeWarning, match="from the child"):
        value, pid = side.result()
    assert value == 42 and pid != os.getpid()


def test_side_error_and_death_become_runtime_errors():
    with pytest.raises(RuntimeError, match="ValueError: bad thing"):
        Side(_fail).result()
    with pytest.raises(RuntimeError, match="without a result"):
        Side(_die).result()


def test_stop_ends_a_running_child():
    side = Side(_sleep)
    t0 = time.perf_counter()
    side.stop()
    assert time.perf_counter() - t0 < 10 and not side._proc.is_alive()


@pytest.fixture(scope="module")
def pocket():
    import meshes

    mesh = meshes.load("fig17_pocket")
    eps = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0))) / 50
    return recon3d.run("fig17_pocket", slices=2, eps=eps, jobs=1)


def _pid_png(blocks, path, title=""):
    """A stand-in for save_png: which process drew, and from what (no OpenGL needed)."""
    path.write_text(f"{os.getpid()} {type(blocks).__name__} {blocks.n_blocks}")


@pytest.fixture
def forking(monkeypatch):
    """The writer forks (the stand-ins below touch no OpenGL, whatever this process did)."""
    import recon3d.api as api

    monkeypatch.setattr(outputs, "can_fork", lambda: True)
    monkeypatch.setattr(api, "can_fork", lambda: True)


def test_picture_is_drawn_in_a_child_from_the_built_scene(pocket, tmp_path, monkeypatch,
                                                            forking):
    monkeypatch.setattr(plot, "save_png", _pid_png)
    monkeypatch.setattr(plot, "load_plotting", lambda: None)
    pocket.save(tmp_path / "fork")
    pid, kind, n = (tmp_path / "fork" / "coverage.png").read_text().split()
    assert int(pid) != os.getpid() and kind == "MultiBlock" and int(n) == 3
    monkeypatch.setattr(outputs, "can_fork", lambda: False)  # one process: drawn here
    pocket.save(tmp_path / "one")
    pid = (tmp_path / "one" / "coverage.png").read_text().split()[0]
    assert int(pid) == os.getpid()
    for name in ("sensing.json", "metrics.json", "motions.csv", "surface.ply", "scene.vtm",
                 "slices.png"):
        assert (tmp_path / "fork" / name).read_bytes() == (tmp_path / "one" / name).read_bytes()


def test_failed_picture_in_the_child_warns_here_and_writes_the_rest(pocket, tmp_path,
                                                                     monkeypatch, forking):
    def no_gl(*args, **kwargs):
        raise RuntimeError("no EGL")

    monkeypatch.setattr(plot, "save_png", no_gl)
    monkeypatch.setattr(plot, "load_plotting", lambda: None)
    with pytest.warns(RuntimeWarning, match="coverage.png not written: RuntimeError: no EGL"):
        files = pocket.save(tmp_path / "o")
    assert "coverage.png" not in {p.name for p in files} and "slices.png" in {p.name
                                                                                for p in files}


def test_error_in_the_parent_stops_the_child_and_leaves_nothing(pocket, tmp_path, monkeypatch,
                                                                  forking):
    monkeypatch.setattr(plot, "load_plotting", lambda: time.sleep(60))

    def broken(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(outputs, "write_motions", broken)
    t0 = time.perf_counter()
    with pytest.raises(OSError, match="disk full"):
        pocket.save(tmp_path / "new")
    assert time.perf_counter() - t0 < 30 and not (tmp_path / "new").exists()
    assert not multiprocessing.active_children()  # the child was stopped, not left behind


def test_scene_ground_truth_computed_beside_the_scores_is_the_one_saved(pocket, monkeypatch,
                                                                        forking):
    import recon3d.api as api

    config = make_config(slices=2, eps=pocket.sensing.eps, jobs=1)
    res = api.execute(pocket.mesh, "fig17_pocket", config, scene=True)
    assert without_timing(res.metrics) == without_timing(pocket.metrics)
    here = api._coverage(res.mesh, res.sensing, res.recon)
    assert res._coverage is not None
    assert np.array_equal(res._coverage.vertices, here.vertices)
    assert np.array_equal(res._coverage.faces, here.faces)
    assert np.array_equal(res._coverage.face_attributes["coverage"],
                          here.face_attributes["coverage"])
    assert np.array_equal(res._coverage.vertex_attributes["distance"],
                          here.vertex_attributes["distance"])

    def again(*args):
        raise AssertionError("the scene's ground truth computed twice")

    monkeypatch.setattr(api, "_coverage", again)
    assert res.blocks()["ground_truth"].n_cells == len(here.faces)
    assert res.blocks() is res.blocks()  # built once: save and plot draw the same scene


def test_without_pictures_the_child_writes_the_scene(pocket, tmp_path, monkeypatch, forking):
    """--no-png: scene.vtm is written by a forked child, the same bytes as written here."""
    saved = []
    real = outputs._save_scene

    def tagged(scene, stage):
        saved.append(os.getpid())
        real(scene, stage)

    monkeypatch.setattr(outputs, "_save_scene", tagged)
    files = pocket.save(tmp_path / "fork", png=False)
    assert saved == [] and "scene.vtm" in {p.name for p in files}  # not called here
    monkeypatch.setattr(outputs, "can_fork", lambda: False)
    pocket.save(tmp_path / "one", png=False)
    assert saved == [os.getpid()]
    for part in ["scene.vtm", *(f"scene/{p.name}" for p in (tmp_path / "one" / "scene").iterdir())]:
        assert (tmp_path / "fork" / part).read_bytes() == (tmp_path / "one" / part).read_bytes()


def _can_fork_here(_):
    from recon3d.io.side import can_fork

    return can_fork()


def test_no_side_process_inside_a_daemonic_worker():
    """A pool (or Dask) worker is daemonic and may not have children: it runs one process."""
    ctx = multiprocessing.get_context("fork")
    with ctx.Pool(1) as pool:
        assert pool.map(_can_fork_here, [0]) == [False]


def test_slices_png_drawn_beside_the_scores_is_the_one_saved(pocket, tmp_path, monkeypatch,
                                                             forking):
    """``execute(pictures=True)`` draws slices.png in a side process while it reconstructs;
    ``save`` writes those bytes, the very bytes drawn here from the finished documents."""
    import recon3d.api as api

    config = make_config(slices=2, eps=pocket.sensing.eps, jobs=1)
    monkeypatch.setattr(plot, "load_plotting", lambda: None)  # no beside thread with jobs=1
    res = api.execute(pocket.mesh, "fig17_pocket", config, pictures=True)
    assert res._slices_png is not None and res._slices_png[:8] == b"\x89PNG\r\n\x1a\n"
    here = tmp_path / "here.png"
    outputs.write_slices_png(here, res.sensing_document(), res.metrics, res.slices,
                             res.sensing.name)
    assert res._slices_png == here.read_bytes()

    def again(*args, **kwargs):
        raise AssertionError("slices.png drawn twice")

    monkeypatch.setattr(outputs, "write_slices_png", again)
    monkeypatch.setattr(plot, "save_png", _pid_png)
    monkeypatch.setattr(outputs, "can_fork", lambda: False)
    res.save(tmp_path / "out")
    assert (tmp_path / "out" / "slices.png").read_bytes() == here.read_bytes()


_GL_PROBE = """
import sys
from recon3d.io.side import can_fork, gl_loaded
import pyvista.plotting
import pyvista as pv
print((gl_loaded(), can_fork()), flush=True)
p = pv.Plotter(off_screen=True)
print((gl_loaded(), can_fork()))
p.close()
"""


def test_pyvista_plotting_loaded_still_forks_a_render_window_does_not():
    """Importing pyvista's plotting (beside the sensing) maps no OpenGL library: the run can
    still fork its side processes; once a render window exists it may not (a fresh process:
    this one may have made windows)."""
    import subprocess
    import sys

    env = dict(os.environ, VTK_DEFAULT_OPENGL_WINDOW="vtkEGLRenderWindow")
    proc = subprocess.run([sys.executable, "-c", _GL_PROBE], capture_output=True, text=True,
                          timeout=300, env=env)
    lines = proc.stdout.split("\n")
    assert lines[0] == "(False, True)", proc.stderr[-400:]  # the import alone maps no GL
    if proc.returncode != 0:  # only the render window itself may be missing here
        pytest.skip(f"no off-screen render window here: {proc.stderr.strip()[-200:]}")
    assert lines[1] == "(True, False)"


def test_gl_loaded_reads_the_mapped_libraries(tmp_path):
    from recon3d.io.side import gl_loaded

    maps = tmp_path / "maps"
    maps.write_text("7f0-7f1 r-xp 0 08:01 1 /usr/lib/x86_64-linux-gnu/libm.so.6\n"
                    "7f2-7f3 rw-p 0 00:00 0 [heap]\n")
    assert not gl_loaded(str(maps))
    maps.write_text(maps.read_text() + "7f4-7f5 r-xp 0 08:01 2 /usr/lib/libEGL_mesa.so.0\n")
    assert gl_loaded(str(maps))
