"""A run as a process: signals, a worker that dies, a locked output directory.

Every test here starts a real ``recon3d`` process and acts on it with real
signals: SIGTERM and SIGHUP end a run like SIGINT (one line, exit status
128 + signal, nothing written, no worker left behind); a worker that dies
ends the run with one line naming the slices, exit status 1, no hang and no
orphan; a second run into a directory in use is refused with exit status 2.
"""
from __future__ import annotations

import multiprocessing
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from recon3d.sensing import pool
from stoppable import default_actions

pytestmark = pytest.mark.skipif(sys.platform != "linux", reason="reads /proc (Linux)")

# long enough to be caught while sensing on a loaded machine, short when let run
LONG_RUN = ["run", "comb", "--slices", "24", "--jobs", "2", "--no-png"]
DEADLINE = 60.0
# prepended to a ``python -c`` run: SIGUSR1 prints every thread's stack (see _finish)
_DUMP = "import faulthandler, signal; faulthandler.register(signal.SIGUSR1, all_threads=True); "


def _start(args, out: Path) -> subprocess.Popen:
    env = dict(os.environ, VTK_DEFAULT_OPENGL_WINDOW="vtkEGLRenderWindow")
    return subprocess.Popen([sys.executable, "-m", "recon3d", *args, "--out", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                            start_new_session=True, preexec_fn=default_actions)


def _children(pid: int) -> list[int]:
    """Direct children of ``pid`` (Linux /proc)."""
    out = []
    for task in Path(f"/proc/{pid}/task").glob("*"):
        try:
            out += [int(c) for c in (task / "children").read_text().split()]
        except OSError:
            pass
    return out


def _alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state != "Z"


def _wait_for_workers(proc: subprocess.Popen, count: int = 2) -> list[int]:
    """The worker pids once ``count`` are up and sensing (the main process is busy)."""
    t0 = time.monotonic()
    while time.monotonic() - t0 < DEADLINE:
        assert proc.poll() is None, proc.communicate()
        kids = [k for k in _children(proc.pid) if _alive(k)]
        if len(kids) >= count:
            time.sleep(1.0)  # let them take their first slices
            return kids
        time.sleep(0.1)
    pytest.fail("the run started no workers")


def _finish(proc: subprocess.Popen) -> tuple[int, str, str]:
    try:
        out, err = proc.communicate(timeout=DEADLINE)
    except subprocess.TimeoutExpired:
        # a process that registered faulthandler on SIGUSR1 (_DUMP) prints every
        # thread's stack first: where it hung
        os.kill(proc.pid, signal.SIGUSR1)
        time.sleep(2.0)
        os.killpg(proc.pid, signal.SIGKILL)
        _, err = proc.communicate()
        pytest.fail(f"the run hung; its stacks:\n{err[-6000:]}")
    return proc.returncode, out, err


def _assert_gone(pids: list[int]) -> None:
    t0 = time.monotonic()
    while any(_alive(p) for p in pids) and time.monotonic() - t0 < 10.0:
        time.sleep(0.1)
    left = [p for p in pids if _alive(p)]
    for p in left:
        os.kill(p, signal.SIGKILL)
    assert not left, f"workers left behind: {left}"


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGHUP, signal.SIGINT])
def test_a_signal_ends_the_run_cleanly(tmp_path, sig):
    out = tmp_path / "out"
    proc = _start(LONG_RUN, out)
    workers = _wait_for_workers(proc)
    os.kill(proc.pid, sig)
    code, _, err = _finish(proc)
    assert code == 128 + sig, err
    lines = err.strip().splitlines()
    assert lines[-1] == f"recon3d: interrupted ({signal.Signals(sig).name})", err
    assert "Traceback" not in err
    _assert_gone(workers)
    assert not out.exists()  # created by the run, removed again


def _ignoring(sig):
    def set_up():
        default_actions()
        signal.signal(sig, signal.SIG_IGN)
    return set_up


@pytest.mark.parametrize("sig", [signal.SIGHUP, signal.SIGINT])
def test_a_signal_ignored_at_start_stays_ignored(tmp_path, sig):
    """``nohup recon3d run ...`` survives a closed terminal (SIGHUP), a run a script put in
    the background survives the terminal's Ctrl-C (SIGINT): the run ends as if not signalled."""
    out = tmp_path / "out"
    env = dict(os.environ, VTK_DEFAULT_OPENGL_WINDOW="vtkEGLRenderWindow")
    # two of comb's slices, one per worker: a few seconds of sensing, when the signal comes
    proc = subprocess.Popen([sys.executable, "-m", "recon3d", "run", "comb", "--slices", "2",
                             "--jobs", "2", "--no-png", "--quiet", "--out", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                            start_new_session=True, preexec_fn=_ignoring(sig))
    workers = _wait_for_workers(proc)
    os.killpg(proc.pid, sig)
    sensing = all(_alive(w) for w in workers)  # the signal reached the workers too
    code, _, err = _finish(proc)
    assert code == 0, err
    assert (out / "metrics.json").is_file()
    assert sensing
    _assert_gone(workers)


def test_ctrl_c_to_the_whole_process_group_is_one_line(tmp_path):
    """A terminal's Ctrl-C reaches the workers too: they leave it to the main process."""
    out = tmp_path / "out"
    proc = _start(LONG_RUN, out)
    workers = _wait_for_workers(proc)
    os.killpg(proc.pid, signal.SIGINT)
    code, _, err = _finish(proc)
    assert code == 128 + signal.SIGINT, err
    assert err.strip().splitlines()[-1] == "recon3d: interrupted (SIGINT)", err
    assert "Traceback" not in err and "error" not in err, err
    _assert_gone(workers)
    assert not out.exists()


def test_ctrl_c_during_the_first_compile_does_not_wait_for_it(tmp_path):
    """On an empty numba cache the main process compiles while a side child compiles the
    distance kernels: a Ctrl-C then ends the run at once, stopping that child before it
    saves them (waiting for it would leave them in the cache)."""
    cache, out = tmp_path / "numba", tmp_path / "out"
    env = dict(os.environ, VTK_DEFAULT_OPENGL_WINDOW="vtkEGLRenderWindow",
               NUMBA_CACHE_DIR=str(cache))
    proc = subprocess.Popen([sys.executable, "-m", "recon3d", *LONG_RUN, "--out", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                            start_new_session=True, preexec_fn=default_actions)
    side = _wait_for_workers(proc, count=1)  # the compile child: no worker before the compile
    os.killpg(proc.pid, signal.SIGINT)
    code, _, err = _finish(proc)
    assert code == 128 + signal.SIGINT, err
    assert err.strip().splitlines()[-1] == "recon3d: interrupted (SIGINT)", err
    _assert_gone(side)
    assert not list(cache.rglob("closest._query*")), "the run waited for the side compile"
    assert not out.exists()


def test_a_signal_leaves_an_existing_directory_as_it_was(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("mine")
    proc = _start(LONG_RUN, out)
    workers = _wait_for_workers(proc)
    os.kill(proc.pid, signal.SIGTERM)
    code, _, err = _finish(proc)
    assert code == 128 + signal.SIGTERM, err
    _assert_gone(workers)
    assert sorted(p.name for p in out.iterdir()) == ["keep.txt"]


def test_a_worker_that_dies_ends_the_run_with_one_line(tmp_path):
    out = tmp_path / "out"
    proc = _start(LONG_RUN, out)
    workers = _wait_for_workers(proc)
    os.kill(workers[0], signal.SIGKILL)
    code, _, err = _finish(proc)
    assert code == 1, err
    lines = [ln for ln in err.strip().splitlines() if ln.startswith("recon3d: error:")]
    assert len(lines) == 1 and "worker" in lines[0] and "died" in lines[0], err
    assert "SIGKILL" in lines[0] and "slice" in lines[0]
    assert "Traceback" not in err
    _assert_gone(workers)
    assert not out.exists()


def test_a_second_run_into_a_directory_in_use_is_refused(tmp_path):
    out = tmp_path / "out"
    first = _start(LONG_RUN, out)
    workers = _wait_for_workers(first)
    second = _start(["run", "bored_block", "--slices", "2", "--no-png"], out)
    code, _, err = _finish(second)
    assert code == 2 and "in use by another recon3d run" in err, err
    assert len(err.strip().splitlines()) == 1
    os.kill(first.pid, signal.SIGTERM)
    _finish(first)
    _assert_gone(workers)


def test_batch_refuses_an_existing_batch_directory_without_overwrite(tmp_path):
    manifest = tmp_path / "m.toml"
    manifest.write_text('meshes = ["bored_block"]\n[params]\nslices = 2\neps_share = 0.02\n')
    out = tmp_path / "b"
    args = [sys.executable, "-m", "recon3d", "batch", str(manifest), "--out", str(out),
            "--scheduler", "serial", "--quiet"]
    first = subprocess.run(args, capture_output=True, text=True)
    assert first.returncode == 0, first.stderr
    before = (out / "batch.csv").read_bytes()
    again = subprocess.run(args, capture_output=True, text=True)
    assert again.returncode == 2 and "--overwrite" in again.stderr
    assert (out / "batch.csv").read_bytes() == before
    forced = subprocess.run([*args, "--overwrite"], capture_output=True, text=True)
    assert forced.returncode == 0, forced.stderr


def test_workers_die_with_a_parent_killed_by_sigkill(tmp_path):
    """No handler runs on SIGKILL: the kernel ends the workers (PR_SET_PDEATHSIG)."""
    proc = _start(LONG_RUN, tmp_path / "out")
    workers = _wait_for_workers(proc)
    os.kill(proc.pid, signal.SIGKILL)
    try:
        proc.communicate(timeout=15.0)  # a worker left behind would hold stderr open
    except subprocess.TimeoutExpired:
        pass
    _assert_gone(workers)


def test_a_closed_stdout_is_no_traceback(tmp_path):
    """``recon3d scenes | head``: the reader went away; status 141 (128 + SIGPIPE)."""
    read, write = os.pipe()
    os.close(read)
    try:
        out = subprocess.run([sys.executable, "-m", "recon3d", "scenes"], stdout=write,
                             stderr=subprocess.PIPE, text=True, timeout=DEADLINE)
    finally:
        os.close(write)
    assert out.returncode == 128 + signal.SIGPIPE and out.stderr == "", out.stderr


def test_ctrl_c_to_an_api_run_prints_no_worker_traceback():
    """Python's own SIGINT handler (no CLI): the workers ignore Ctrl-C; only the
    caller's KeyboardInterrupt is raised, and no worker is left behind."""
    code = _DUMP + "import recon3d; recon3d.run('comb', slices=24, jobs=2)"
    env = dict(os.environ, VTK_DEFAULT_OPENGL_WINDOW="vtkEGLRenderWindow")
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=env, start_new_session=True, preexec_fn=default_actions)
    workers = _wait_for_workers(proc)
    os.killpg(proc.pid, signal.SIGINT)
    _, _, err = _finish(proc)
    assert err.count("Traceback") == 1 and "KeyboardInterrupt" in err, err
    assert "recon3d-sensing" not in err, err
    _assert_gone(workers)


def _set_up_then_wait(parent, ready):
    pool._die_with_parent(parent)
    ready.set()
    time.sleep(60)


def test_a_worker_leaves_sigint_and_sighup_to_its_parent_and_dies_quietly_on_sigterm():
    """The worker set-up itself: a signal that reaches a worker while it runs Python
    code would otherwise print a traceback (Python's SIGINT handler) or kill it."""
    ctx = multiprocessing.get_context("fork")
    ready = ctx.Event()
    proc = ctx.Process(target=_set_up_then_wait, args=(os.getpid(), ready))
    proc.start()
    try:
        assert ready.wait(10)
        os.kill(proc.pid, signal.SIGINT)
        os.kill(proc.pid, signal.SIGHUP)
        time.sleep(0.5)
        assert proc.is_alive()
        proc.terminate()
        proc.join(10)
        assert proc.exitcode == -signal.SIGTERM
    finally:
        proc.kill()
        proc.join()
