"""The compile notice of the first run (issue 20): ``recon3d run`` says, once, before the
~20 s first compile of the numba kernels, that it compiles them; the library prints nothing.

Whether a run will compile is read from numba's cache indexes
(:func:`recon3d.sensing.cold_kernels`), so the cold case is tested against an empty
``NUMBA_CACHE_DIR`` without compiling anything.
"""
import json
import os
import subprocess
import sys

import pytest

import recon3d.api
from recon3d.cli import main
from recon3d.sensing import COMPILE_NOTICE, cold_kernels
from recon3d.sensing.kernels import sensing_kernels


def test_an_empty_numba_cache_means_every_kernel_is_cold_and_nothing_is_compiled(tmp_path):
    code = ("import json, time; from recon3d.sensing import cold_kernels; "
            "from recon3d.sensing.kernels import sensing_kernels; t = time.perf_counter(); "
            "print(json.dumps([sorted(sensing_kernels()), cold_kernels(), "
            "time.perf_counter() - t, cold_kernels('exact')]))")
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                         text=True, check=True)
    kernels, cold, seconds, cold_exact = json.loads(out.stdout)
    assert "core2d.sim.kernels.search" in kernels and "core2d.visibility._order" in kernels
    assert sorted(cold) == kernels
    assert "slicer.contact.exact._ray" in cold_exact and "core2d.sim.kernels.search" in cold_exact
    assert not list(tmp_path.rglob("*.nbi")) and not list(tmp_path.rglob("*.nbc"))
    assert seconds < 5  # the cache is read, not filled


@pytest.fixture(scope="module")
def one_run(tmp_path_factory):
    """A small run through the CLI, in this process (it fills numba's cache if need be)."""
    out = tmp_path_factory.mktemp("kernels") / "run"
    assert main(["run", "fig17_pocket", "--out", str(out), "--slices", "2", "--jobs", "1",
                 "--no-png", "--quiet"]) == 0
    return out


def test_after_a_run_no_kernel_is_cold(one_run):
    """Else the notice would print on every run (a kernel a default run never compiles)."""
    assert sensing_kernels()
    assert cold_kernels() == []


def test_each_backend_is_asked_about_its_own_ray_function(tmp_path):
    """The exact backend runs the compiled engine on its own ray function: a run on it is
    announced when its kernels are cold, and not after it compiled them; trimesh's backend
    (the Python engine) is never announced."""
    embree, exact = set(sensing_kernels()), set(sensing_kernels("exact"))
    assert {"slicer.contact.exact._ray", "slicer.contact.exact._cast"} <= exact
    assert "slicer.contact.exact._ray" not in embree
    assert "slicer.contact.embree_direct._ray" not in exact
    assert embree - exact <= {"slicer.contact.embree_direct._ray"}  # core2d's: the same
    assert cold_kernels("trimesh") == []
    out = tmp_path / "run"
    assert main(["run", "fig17_pocket", "--out", str(out), "--slices", "2", "--jobs", "1",
                 "--backend", "exact", "--no-png", "--quiet"]) == 0
    assert cold_kernels("exact") == []


@pytest.mark.parametrize("quiet", [False, True])
def test_the_cli_prints_the_notice_once_when_cold_and_not_with_quiet(one_run, tmp_path,
                                                                     capsys, monkeypatch,
                                                                     quiet):
    # the run command imports it from the API when it runs (recon3d.cli.run._run)
    monkeypatch.setattr(recon3d.api, "cold_kernels",
                        lambda *backend: ["core2d.sim.kernels.search"])
    args = ["run", "fig17_pocket", "--out", str(tmp_path / "o"), "--slices", "2",
            "--jobs", "1", "--no-png"] + (["--quiet"] if quiet else [])
    assert main(args) == 0
    err = capsys.readouterr().err
    assert err.count(COMPILE_NOTICE) == (0 if quiet else 1)


def test_warm_cache_no_notice_and_the_library_is_silent(one_run, tmp_path, capsys):
    import recon3d

    assert main(["run", "fig17_pocket", "--out", str(tmp_path / "o"), "--slices", "2",
                 "--jobs", "1", "--no-png"]) == 0
    assert COMPILE_NOTICE not in capsys.readouterr().err
    recon3d.run("fig17_pocket", slices=2, jobs=1)
    captured = capsys.readouterr()
    assert COMPILE_NOTICE not in captured.err + captured.out


_TWO_KERNELS = '''
from numba import njit


@njit(cache=True)
def pivot_like(x):
    return x + 1


@njit(cache=True)
def search_like(x):
    return x * 2
'''


def test_a_kernel_some_runs_never_compile_is_not_cold_once_its_file_is_cached(tmp_path,
                                                                           monkeypatch):
    """A kernel only some runs need (the pivot's ``search_from``) stays out of the cache after
    a run without a pivot; it must not make every later run cold. Cold again when the file
    changes; a file of its own with nothing cached stays cold."""
    import importlib
    from recon3d.sensing.kernels import cold_among

    (tmp_path / "rf4_two.py").write_text(_TWO_KERNELS)
    (tmp_path / "rf4_other.py").write_text(_TWO_KERNELS.replace("x * 2", "x * 3"))
    monkeypatch.syspath_prepend(str(tmp_path))
    two, other = importlib.import_module("rf4_two"), importlib.import_module("rf4_other")
    kernels = {"two.pivot": two.pivot_like.py_func, "two.search": two.search_like.py_func,
               "other.search": other.search_like.py_func}
    assert cold_among(kernels) == ["two.pivot", "two.search", "other.search"]
    assert two.search_like(3) == 6  # compiled and saved: the run "without a pivot"
    assert cold_among(kernels) == ["other.search"]  # two.pivot is not asked about
    assert other.search_like(3) == 9
    assert cold_among(kernels) == []
    (tmp_path / "rf4_two.py").write_text(_TWO_KERNELS + "\n# changed\n")  # a new stamp
    assert cold_among(kernels) == ["two.pivot", "two.search"]
