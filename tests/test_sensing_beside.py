"""The parent's own preparation runs while its sensing workers sense (``beside``).

:func:`recon3d.sensing.sense_mesh` hands ``beside`` to the pool: with worker processes it
runs once per pool in a thread of the parent, after the workers are forked, and is done
before the sensing returns (nothing forks while it runs); with ``jobs=1`` it is not called.
"""
import multiprocessing
import os
import threading
import time

import meshes
from recon3d.sensing import sense_mesh
from recon3d.spellings import make_config


def _record(calls, back=None):
    def beside():
        children = [p.name for p in multiprocessing.active_children()]
        if back is not None:  # still running when every slice is back
            back.wait(60)
            time.sleep(0.5)
        calls.append((os.getpid(), threading.current_thread() is threading.main_thread(),
                      children))
    return beside


def test_beside_runs_in_a_thread_of_the_parent_while_workers_sense():
    mesh = meshes.load("stepped_pyramid")
    calls, seen, back = [], [], threading.Event()

    def progress(srun):
        seen.append(srun)
        if len(seen) == 2:
            back.set()

    run = sense_mesh(mesh, "stepped_pyramid", make_config(slices=2, jobs=2), progress,
                     beside=_record(calls, back))
    assert len(run.slices) == 2
    assert len(calls) == 1  # done before sense_mesh returned
    pid, main, children = calls[0]
    assert pid == os.getpid() and not main
    assert "recon3d-sensing" in children  # the workers were forked before it started
    assert not [t for t in threading.enumerate() if t.name == "recon3d-beside"]


def test_beside_not_called_in_one_process():
    mesh = meshes.load("stepped_pyramid")
    calls = []
    sense_mesh(mesh, "stepped_pyramid", make_config(slices=2, jobs=1), beside=_record(calls))
    assert calls == []


_PICTURES = """
import sys
import meshes
from recon3d.api import execute
from recon3d.spellings import make_config
execute(meshes.load("stepped_pyramid"), "stepped_pyramid", make_config(slices=2, jobs=2),
        pictures={pictures})
print("pyvista.plotting" in sys.modules)
"""


def _plotting_loaded_by_execute(pictures: bool) -> bool:
    import subprocess
    import sys

    proc = subprocess.run([sys.executable, "-c", _PICTURES.format(pictures=pictures)],
                          capture_output=True, text=True, timeout=300, check=True)
    return proc.stdout.strip().splitlines()[-1] == "True"


def test_a_run_with_pictures_loads_pyvista_plotting_while_it_senses():
    """``execute(pictures=True)`` (``recon3d run`` without ``--no-png``) loads pyvista's
    plotting beside the sensing, so the picture child forked later inherits it; without
    pictures the run never loads it (a fresh process: this one may have loaded it)."""
    assert _plotting_loaded_by_execute(True)
    assert not _plotting_loaded_by_execute(False)


_NUMBA_TARGET = """
import meshes
from numba.core.imputils import builtin_registry
from numba.core.registry import cpu_target
from recon3d.sensing import sense_mesh
from recon3d.spellings import make_config
mesh = meshes.load("stepped_pyramid")
before = builtin_registry in cpu_target.target_context._registries
sense_mesh(mesh, "stepped_pyramid", make_config(slices=2, jobs={jobs}))
print(before, builtin_registry in cpu_target.target_context._registries)
"""


def _numba_target_in_parent(jobs: int) -> str:
    import subprocess
    import sys

    proc = subprocess.run([sys.executable, "-c", _NUMBA_TARGET.format(jobs=jobs)],
                          capture_output=True, text=True, timeout=300, check=True)
    return proc.stdout.strip().splitlines()[-1]


def test_numba_target_loaded_once_in_the_parent_before_the_workers_fork():
    """With worker processes, the parent initialises numba's CPU target before forking
    them (they and the run's side processes inherit it); the parent itself loads no kernel,
    so without the workers' fork nothing in it would (a fresh process)."""
    assert _numba_target_in_parent(2) == "False True"


def test_beside_thread_leaves_the_stop_signals_to_the_main_thread():
    """A Ctrl-C delivered to the beside thread would leave the main thread waiting for a
    worker's next slice: the thread blocks SIGINT, SIGTERM and SIGHUP, so they reach the
    main thread (whose mask is untouched)."""
    import signal

    if not hasattr(signal, "pthread_sigmask"):
        return
    mesh = meshes.load("stepped_pyramid")
    masks = []

    def beside():
        masks.append(signal.pthread_sigmask(signal.SIG_BLOCK, []))

    sense_mesh(mesh, "stepped_pyramid", make_config(slices=2, jobs=2), beside=beside)
    assert len(masks) == 1
    assert {signal.SIGINT, signal.SIGTERM, signal.SIGHUP} <= set(masks[0])
    assert signal.SIGINT not in signal.pthread_sigmask(signal.SIG_BLOCK, [])
