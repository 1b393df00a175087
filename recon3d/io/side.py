"""One function in a forked child while this process goes on (internal).

A run's files are written on one core while the other idles: the sensing pool
has finished. :class:`Side` forks a child that runs one function on what this
process holds (nothing is pickled but the function's small return value) and
hands back its result, its warnings re-issued here, or its error as a
``RuntimeError``. The child ignores SIGINT and SIGHUP (the parent decides);
:meth:`Side.stop` ends it when the parent gives up early. Where a process
cannot fork, :func:`can_fork` is False and the caller runs the function itself.

>>> side = Side(sum, [1, 2, 3]) if can_fork() else None
>>> side.result() if side else 6
6

A fork is made with this process's objects frozen (:func:`frozen_heap`): the child's cyclic
collector never walks what it inherited. :func:`paused_collector` holds the collector back
where a process makes many objects and no garbage cycles (imports; the parent waiting for
its workers).
"""
from __future__ import annotations

import gc
import multiprocessing
import signal
import sys
import traceback
import warnings
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

__all__ = ["Side", "can_fork", "frozen_heap", "paused_collector", "gl_loaded"]

_GL = "vtkmodules.vtkRenderingOpenGL2"
"""VTK's OpenGL module: where the process maps can not be read, loading it counts as a
render window that may exist."""

_GL_LIBS = ("libEGL", "libGL", "libOpenGL")
"""Names of the OpenGL libraries (EGL, GLX, glvnd's dispatch): VTK maps them when it makes
its first render window, not when its OpenGL module is imported."""


def gl_loaded(maps: str = "/proc/self/maps") -> bool:
    """True once this process may hold an OpenGL context: an OpenGL library is mapped
    (Linux: ``maps`` lists the mapped files), or, where that cannot be read, VTK's OpenGL
    module is loaded. pyvista's plotting imported with no render window made yet is not
    (measured: the libraries appear with the first ``Plotter``)."""
    try:
        with open(maps) as fh:
            text = fh.read()
    except OSError:
        return _GL in sys.modules
    return any(line.rsplit("/", 1)[-1].startswith(_GL_LIBS)
               for line in text.splitlines() if "/" in line)


def can_fork() -> bool:
    """True where a child can be forked safely: POSIX fork, no OpenGL context made yet
    (:func:`gl_loaded`), and not inside a daemonic process (a Dask or pool worker: those
    may have no children)."""
    return ("fork" in multiprocessing.get_all_start_methods()
            and not multiprocessing.current_process().daemon and not gl_loaded())


@contextmanager
def frozen_heap() -> Iterator[bool]:
    """This process's objects out of the cyclic collector's reach while the block runs.

    :func:`gc.freeze` on entry, :func:`gc.unfreeze` on exit: a child forked inside the block
    keeps them frozen for its life, so its full collections walk only what it made (a
    sensing worker's took 0.24 - 0.30 s of its ~9.6 CPU s on the large mesh's 64 slices,
    0.004 - 0.007 s with its inherited objects frozen), and the pages holding them are not
    written to (no copy on write). In this process the collector skips them until the
    block ends; a cycle that became garbage meanwhile is collected after it. When something
    else froze objects already (``gc.get_freeze_count() > 0``) nothing is done: that
    freeze is its owner's to undo. Yields whether this block froze.

    >>> import gc
    >>> with frozen_heap() as froze:
    ...     froze == (gc.get_freeze_count() > 0)
    True
    >>> gc.get_freeze_count()
    0
    """
    if gc.get_freeze_count() > 0:
        yield False
        return
    gc.freeze()
    try:
        yield True
    finally:
        gc.unfreeze()


@contextmanager
def paused_collector() -> Iterator[None]:
    """The cyclic collector paused while the block runs (:func:`gc.disable`), as it was on
    exit.

    For stretches that allocate many objects and make no garbage cycles worth finding: the
    imports of a run's libraries (about 280 collections, 0.09 - 0.13 s of a run's serial
    start, that free nothing: every object made is a module's, alive for the run), and the
    parent process while its sensing workers run (it only takes their slices back and
    closes each slice's region: 0.23 - 0.27 CPU s of collections on the large mesh's 64 slices,
    on a core the workers need). Whatever became garbage meanwhile is found by the first
    collection after the block. The block's own objects are not frozen (:func:`frozen_heap`
    is for what exists before a fork).

    >>> import gc
    >>> with paused_collector():
    ...     gc.isenabled()
    False
    >>> gc.isenabled()
    True
    """
    was = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was:
            gc.enable()


def _child(conn, fn: Callable, args: tuple) -> None:
    for sig in (signal.SIGINT, getattr(signal, "SIGHUP", None)):
        if sig is not None:
            signal.signal(sig, signal.SIG_IGN)
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            value = fn(*args)
        notes = [(str(w.message), w.category) for w in caught]
        conn.send(("ok", value, notes))
    except BaseException as exc:  # reported to the parent, which raises it
        conn.send(("error", "".join(traceback.format_exception_only(exc)).strip(), []))
    finally:
        conn.close()


class Side:
    """``fn(*args)`` running in a forked child from construction on.

    Parameters
    ----------
    fn : callable -- runs in the child; its return value must pickle.
    *args -- passed as they are (inherited by the fork, not pickled).
    """

    def __init__(self, fn: Callable, *args: Any):
        ctx = multiprocessing.get_context("fork")
        self._conn, send = ctx.Pipe(duplex=False)
        self._proc = ctx.Process(target=_child, args=(send, fn, args), daemon=True)
        with frozen_heap():
            self._proc.start()
        send.close()

    def result(self) -> Any:
        """Wait for the child: its return value (its warnings re-issued here).

        Raises RuntimeError when it raised or died."""
        try:
            status, value, notes = self._conn.recv()
        except EOFError:
            self._proc.join()
            raise RuntimeError(f"side process ended without a result "
                               f"(exit code {self._proc.exitcode})") from None
        finally:
            self._conn.close()
        self._proc.join()
        if status != "ok":
            raise RuntimeError(value)
        for message, category in notes:
            warnings.warn(message, category, stacklevel=2)
        return value

    def stop(self) -> None:
        """End the child if it still runs (the parent is giving up) and reap it."""
        if self._proc.is_alive():
            self._proc.terminate()
        self._proc.join()
        self._conn.close()
