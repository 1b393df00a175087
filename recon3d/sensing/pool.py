"""Sense the slices of a run, in this process or in worker processes (internal).

The slices are cut once, in the parent (:func:`recon3d.sensing.mesh.sense_mesh`).
``jobs == 1`` senses them in this process. Otherwise ``jobs`` worker
processes, one task at a time each over a pipe of their own: forked workers
(where the platform can fork) inherit the parent's slices through the
module-level state set before they start -- nothing is cut again and the
caller's script is not re-imported, so no ``if __name__ == "__main__"``
guard is needed; spawned workers (elsewhere) cut them again from the mesh
arrays (Embree scenes do not pickle). Every path runs the same code on the
same slices, so the results are identical; they come back in task order
whatever the completion order. Workers are handed the costliest slices first
(:mod:`recon3d.sensing.order`), so no worker is left alone with a costly one at the end.

The workers live no longer than the call:

* they ignore SIGINT and SIGHUP (the parent decides: a Ctrl-C in a terminal
  reaches the whole process group) and die silently on SIGTERM, so stopping
  a run prints no worker traceback;
* on Linux each asks the kernel to SIGKILL it when its parent dies
  (``prctl(PR_SET_PDEATHSIG)``), so not even a SIGKILLed parent leaves one
  behind;
* when the call ends -- done, an error, an interrupt -- the parent stops
  them and waits for them;
* a worker that dies (killed, segfault) ends the call with
  :class:`WorkerDied`, naming the slice it was sensing; no hang.

Forked workers inherit every slice's contact model built
(:func:`~recon3d.sensing.worker.built_contacts`): building an
Embree scene runs TBB tasks, and TBB is not safe across a fork.
"""
from __future__ import annotations

import ctypes
import ctypes.util
import multiprocessing
import os
import signal
import sys
import threading
import traceback
from collections import deque
from collections.abc import Callable
from typing import Any
from multiprocessing.connection import wait

import numpy as np
import trimesh

from recon3d.io.side import Side, can_fork, frozen_heap, paused_collector
from recon3d.records import Family, SliceRun
from recon3d.score import compile_kernels as compile_scores
from recon3d.sensing.kernels import cold_kernels, load_numba_target
from recon3d.sensing.order import dispatch_order
from recon3d.sensing.worker import SenseSettings, WorkerState, built_contacts, own_contacts

__all__ = ["sense_all", "WorkerDied", "describe_exit"]

_STATE: WorkerState | None = None
"""The slices a worker senses: set in the parent before a fork (inherited), or by
the initializer of a spawned worker. The only module state: what a worker needs."""

_PR_SET_PDEATHSIG = 1
_STOP_SECONDS = 5.0


class WorkerDied(RuntimeError):
    """A sensing worker process died (killed by a signal, a crash): the run ends.

    Not the user's input (the command line exits with status 1, not 2).

    Attributes
    ----------
    exitcode : int or None -- the worker's exit code (``-N``: killed by signal N).
    slices : list of str -- the slices it was sensing (``'z#3'``), if any.
    """

    def __init__(self, message: str, exitcode: int | None = None, slices=()):
        super().__init__(message)
        self.exitcode = exitcode
        self.slices = list(slices)


class _RemoteTraceback(Exception):
    """The traceback of an exception raised in a worker (its ``__cause__``)."""


def describe_exit(exitcode: int | None) -> str:
    """How a process ended, from ``multiprocessing.Process.exitcode``.

    >>> describe_exit(-9), describe_exit(3), describe_exit(None)
    ('killed by SIGKILL', 'exit status 3', 'ended')
    """
    if exitcode is None:
        return "ended"
    if exitcode < 0:
        try:
            return f"killed by {signal.Signals(-exitcode).name}"
        except ValueError:
            return f"killed by signal {-exitcode}"
    return f"exit status {exitcode}"


def _die_with_parent(parent: int) -> None:
    """Quiet on SIGINT/SIGHUP, silent death on SIGTERM, SIGKILLed with the parent (Linux)."""
    for sig, how in ((signal.SIGINT, signal.SIG_IGN), (signal.SIGTERM, signal.SIG_DFL),
                     (getattr(signal, "SIGHUP", None), signal.SIG_IGN)):
        if sig is not None:
            signal.signal(sig, how)
    if sys.platform.startswith("linux"):
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6", use_errno=True)
        libc.prctl(_PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0)
    if os.getppid() != parent:  # the parent died before the request took effect
        os._exit(1)


def _worker(conn, parent: int, init, initargs) -> None:
    """A worker's life: set up, then sense the tasks the parent sends until ``None``."""
    global _STATE
    _die_with_parent(parent)
    if init is not None:
        _STATE = init(*initargs)
    while True:
        try:
            task = conn.recv()
        except EOFError:  # the parent is gone
            return
        if task is None:
            return
        try:
            reply = ("ok", _STATE.sense(*task))
        except Exception as exc:  # sent to the parent, raised there
            text = "".join(traceback.format_exception(exc))
            try:
                conn.send(("error", exc, text))
            except Exception:  # an exception that does not pickle
                conn.send(("error", RuntimeError(f"{type(exc).__name__}: {exc}"), text))
            continue
        conn.send(reply)


def _rebuild(vertices, faces, settings) -> WorkerState:
    return WorkerState.rebuild(vertices, faces, settings)


class _Workers:
    """``jobs`` worker processes, each with its pipe and its tasks in flight: the slice it
    senses, and its next one from when its reply starts to arrive (:func:`_run_pool`)."""

    def __init__(self):
        self.procs, self.conns, self.busy = [], [], []  # busy[w]: deque of task indices

    def start(self, ctx, jobs: int, init, initargs) -> None:
        """Start ``jobs`` workers (each one stopped by :meth:`stop` however far this got)."""
        for _ in range(jobs):
            here, there = ctx.Pipe()
            proc = ctx.Process(target=_worker, args=(there, os.getpid(), init, initargs),
                               daemon=True, name="recon3d-sensing")
            self.procs.append(proc)
            self.conns.append(here)
            self.busy.append(deque())
            proc.start()
            there.close()

    def send(self, w: int, k: int, task) -> None:
        self.busy[w].append(k)
        try:
            self.conns[w].send(task)
        except OSError:  # the worker died: its sentinel says so next
            pass

    def stop(self, graceful: bool) -> None:
        """Let idle workers leave (``graceful``) or terminate them; wait for each."""
        started = [w for w, proc in enumerate(self.procs) if proc.pid is not None]
        for w in started:
            proc = self.procs[w]
            if graceful and proc.is_alive():
                try:
                    self.conns[w].send(None)
                except OSError:
                    pass
            elif proc.is_alive():
                proc.terminate()
        for w in started:
            proc = self.procs[w]
            proc.join(_STOP_SECONDS)
            if proc.is_alive():
                proc.kill()
                proc.join()
        for conn in self.conns:
            conn.close()


def _died(workers: _Workers, w: int, tasks: list, settings: SenseSettings, left: int):
    proc = workers.procs[w]
    proc.join(_STOP_SECONDS)
    how = describe_exit(proc.exitcode)
    k = workers.busy[w][0] if workers.busy[w] else None
    if k is None:
        return WorkerDied(f"a sensing worker died ({how}) between slices; {left} of "
                          f"{len(tasks)} slices unfinished", proc.exitcode)
    family, index = tasks[k][:2]
    name = f"{Family(np.asarray(settings.axes[family])).label}#{index}"
    return WorkerDied(f"a sensing worker died ({how}) while sensing slice {name}",
                      proc.exitcode, [name])


def _run_pool(workers: _Workers, tasks: list, settings: SenseSettings, out: list,
              progress, order: list) -> None:
    """Hand out ``tasks[k]`` for k in ``order``, one at a time per worker; collect the
    results into ``out`` (``out[k]``: task order whatever the completion order).

    A worker whose reply is arriving has finished its slice: it is sent its next task
    before its reply is read (1.2 MB pickled per slice of the large mesh, median), so that it
    starts that slice as soon as this process has the reply, not after this process has
    unpickled it and updated the progress."""
    todo = iter(order)
    left = len(order)

    def give(w: int) -> None:
        k = next(todo, None)
        if k is not None:
            workers.send(w, k, tasks[k])

    for w in range(len(workers.procs)):
        give(w)
    while left:
        ready = wait(workers.conns + [p.sentinel for p in workers.procs])
        for w, (conn, proc) in enumerate(zip(workers.conns, workers.procs)):
            if conn not in ready and proc.sentinel not in ready:
                continue
            if conn in ready and len(workers.busy[w]) == 1 and proc.is_alive():
                give(w)  # its slice is done: the next one first, then its reply
            try:
                reply = conn.recv() if conn.poll() else None
            except (EOFError, OSError):
                reply = None
            if reply is None:
                if proc.sentinel in ready or not proc.is_alive():
                    raise _died(workers, w, tasks, settings, left)
                continue
            if reply[0] == "error":
                raise reply[1] from _RemoteTraceback(f'\n"""\n{reply[2]}"""')
            k = workers.busy[w].popleft()
            out[k] = reply[1]
            left -= 1
            if not workers.busy[w]:
                give(w)
            if progress is not None:
                progress(out[k])


_STOP_SIGNALS = tuple(sig for sig in (signal.SIGINT, signal.SIGTERM,
                                      getattr(signal, "SIGHUP", None)) if sig is not None)
"""What stops a run (Ctrl-C, a kill, a closed terminal)."""


def _beside(fn: Callable[[], Any]) -> None:
    """``fn()`` in a thread, its error dropped (what it prepares is made again, and fails
    loudly, where it is used).

    The stop signals are blocked in this thread, so the kernel hands them to the main
    thread: its wait for the workers returns at once and Python raises there (delivered to
    this thread, the main thread would sleep on until a worker sent a slice back)."""
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_BLOCK, _STOP_SIGNALS)
    try:
        fn()
    except Exception:  # noqa: BLE001 - a preparation only
        pass


def sense_all(mesh: trimesh.Trimesh, families: list, settings: SenseSettings, tasks: list,
              jobs: int, progress: Callable[[SliceRun], None] | None = None,
              beside: Callable[[], Any] | None = None) -> list[SliceRun]:
    """Sense ``tasks``; return their SliceRuns (``slice`` None) in task order.

    Parameters
    ----------
    mesh : trimesh.Trimesh -- what ``families`` were cut from (spawned workers cut it again).
    families : list of list of slicer.Slice -- ``settings.slices`` planes per axis of ``settings``.
    settings : SenseSettings
    tasks : list of (family, index) or (family, index, eps)
    jobs : int -- worker processes (1: in this process).
    progress : callable(SliceRun) or None -- called as slices finish (workers: collector paused).
    beside : callable() or None -- with worker processes, run in a thread of this process
        (which only waits for them) once they are forked, and joined before returning (so
        nothing forks while it runs): the parent's own preparations, e.g. importing
        pyvista for the reconstruction. Not called with ``jobs=1``.

    Raises
    ------
    WorkerDied -- a worker process died; the other workers are stopped first.
    """
    out: list = [None] * len(tasks)
    fork = "fork" in multiprocessing.get_all_start_methods()
    first, compiling, done = 0, None, False
    try:
        if fork and min(int(jobs), len(tasks)) > 1:
            load_numba_target()  # once here, inherited by every worker (and later side process)
            first, compiling = _compile_here(families, settings, tasks, out, progress)
        jobs = max(1, min(int(jobs), len(tasks) - first))
        if jobs == 1:
            _sense_here(settings, families, tasks, out, progress, start=first)
        else:
            _sense_workers(mesh, families, settings, tasks, jobs, progress, beside, out, first,
                           fork)
        done = True
    finally:  # the scores' compile child: long done by now; stopped on an error or a Ctrl-C
        if compiling is not None and done:
            _finish(compiling)
        elif compiling is not None:
            compiling.stop()
    return out


def _sense_workers(mesh, families: list, settings: SenseSettings, tasks: list, jobs: int,
                   progress, beside, out: list, first: int, fork: bool) -> None:
    """:func:`sense_all` with ``jobs`` worker processes, from ``tasks[first]`` on."""
    global _STATE
    workers, done, thread = _Workers(), False, None
    # forked workers inherit the heap frozen (before the contact models are built: a full
    # collection there took 72 ms, large mesh) and every model built (built_contacts); the
    # collector is paused while this process waits for them (~0.25 CPU s, no cycles found)
    with frozen_heap():
        try:
            if fork:
                ctx, init, args = multiprocessing.get_context("fork"), None, ()
                _STATE = WorkerState(settings, built_contacts(families, tasks[first:],
                                                             settings.backend))
            else:  # pragma: no cover - no fork on this platform
                ctx, init = multiprocessing.get_context("spawn"), _rebuild
                args = (np.asarray(mesh.vertices, dtype=np.float64),
                        np.asarray(mesh.faces, dtype=np.int64), settings)
            workers.start(ctx, jobs, init, args)
            with paused_collector():
                if beside is not None:
                    thread = threading.Thread(target=_beside, args=(beside,), daemon=True,
                                              name="recon3d-beside")
                    thread.start()
                order = dispatch_order(families, tasks, settings.eps)
                order = [k for k in order if k >= first]
                _run_pool(workers, tasks, settings, out, progress, order)
                done = True
        finally:
            _STATE = None
            workers.stop(graceful=done)
            if thread is not None:
                thread.join()


def _sense_here(settings: SenseSettings, families: list, tasks: list, out: list,
                progress, start: int = 0) -> None:
    """Sense ``tasks[start:]`` in this process into ``out`` (contact caches of its own),
    the objects made before frozen out of the cyclic collector (:func:`frozen_heap`), as in
    a forked worker: each full collection the planner's allocations trigger walked every
    object of this process (imports, mesh, scenes): 2 - 12 % of the sensing CPU (4 scenes)."""
    state = WorkerState(settings, own_contacts(families))
    with frozen_heap():
        for k in range(start, len(tasks)):
            out[k] = state.sense(*tasks[k])
            if progress is not None:
                progress(out[k])


def _compile_here(families: list, settings: SenseSettings, tasks: list, out: list,
                  progress) -> tuple[int, Side | None]:
    """When the Embree kernels are not in numba's cache, sense the first task here (which
    compiles them, once) before any worker is forked; how many tasks that sensed (0 or 1),
    and the child compiling the scores' kernels (None: none).

    Forked workers inherit the compiled kernels. Without this, every worker compiles the
    same kernels at the same time (the compile paid twice in CPU, on cores that the machine
    may not have free). A child forked meanwhile compiles the point-to-mesh distances and the
    subdivision that the scores and the coloured ground truth use after the sensing
    (:func:`recon3d.score.compile_kernels`), on the core this process leaves idle; the
    workers do not wait for it (:func:`sense_all` does, at its end; stopped if the sensing
    raises: a Ctrl-C does not wait for it): the two compiles take about as long.
    :func:`cold_kernels` reads numba's cache indexes only (the Embree and exact backends'
    kernels; the trimesh backend has no ray function and compiles none of the ray engine's).
    """
    if len(tasks) < 2 or not cold_kernels(settings.backend):
        return 0, None
    # the other core compiles the kernels of the scores and coloured ground truth meanwhile
    side = Side(compile_scores) if can_fork() else None
    try:
        _sense_here(settings, families, tasks[:1], out, progress)
    except BaseException:  # a Ctrl-C or an error does not wait for that compile
        if side is not None:
            side.stop()
        raise
    return 1, side


def _finish(side: Side) -> None:
    """Wait for the scores' kernels' compile (its failure is the later call's to report)."""
    try:
        side.result()
    except RuntimeError:
        pass
