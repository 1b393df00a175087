"""SIGTERM and SIGHUP end a command like SIGINT: one line, exit status 128 + signal.

While :func:`interrupts` is active, SIGINT, SIGTERM and SIGHUP raise
:class:`Interrupted` (a ``KeyboardInterrupt``) in the main thread, so the
run unwinds the same way whichever signal stopped it: the sensing workers
are stopped (:mod:`recon3d.sensing.pool`), the staged writer removes what it
was writing, the output directory lock removes a directory the run created.
:func:`interrupted_line` and :func:`exit_status` are what ``main`` reports;
:func:`closed_stdout` ends a command whose stdout reader went away.

A signal that arrives while Python code runs where a raised exception would be
printed and dropped (a ctypes callback LLVM makes during a numba compile, a
``__del__``: :func:`would_be_lost`) is sent again a moment later instead, so
it still stops the command.

A process forked while the handlers are installed (a sensing worker, before
its own set-up resets them) does not raise: it takes the signal's default
action, as if no handler were installed.

A signal the command was started with ignored stays ignored (the rule of every
Unix tool): ``nohup recon3d run ...`` survives a closed terminal (SIGHUP), and a
run a non-interactive shell put in the background survives the terminal's
Ctrl-C (SIGINT), as Python itself does for SIGINT.
"""
from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading

__all__ = ["Interrupted", "interrupts", "interrupted_line", "exit_status", "closed_stdout",
           "would_be_lost", "SIGNALS"]

SIGNALS = tuple(getattr(signal, n) for n in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, n))
"""The signals that stop a command cleanly."""

SIGPIPE = 13
"""SIGPIPE's number on Linux and macOS (``signal.SIGPIPE`` is missing on Windows)."""


class Interrupted(KeyboardInterrupt):
    """A stopping signal arrived; ``signum`` says which."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = int(signum)


RETRY = 0.05
"""Seconds after which a signal that arrived where an exception would be lost is sent again."""


def _callback_codes() -> tuple:
    """Code objects of the Python functions C calls back into during a numba compile
    (llvmlite's object-cache hooks), when llvmlite is loaded."""
    engine = sys.modules.get("llvmlite.binding.executionengine")
    if engine is None:
        return ()
    ee = engine.ExecutionEngine
    return (ee._raw_object_cache_notify.__code__, ee._raw_object_cache_getbuffer.__code__)


def would_be_lost(frame) -> bool:
    """Whether an exception raised in ``frame`` would be printed and dropped, not propagated.

    A ctypes callback (llvmlite's object-cache hooks, which LLVM calls while numba
    compiles) and a finalizer (``__del__``) print what they raise ("Exception ignored
    ...") and go on: an :class:`Interrupted` raised there would be lost and the command
    would run on.

    >>> would_be_lost(sys._getframe())
    False
    """
    codes = _callback_codes()
    while frame is not None:
        if frame.f_code in codes or frame.f_code.co_name == "__del__":
            return True
        frame = frame.f_back
    return False


def _handler(owner: int):
    def handle(signum, frame):
        if os.getpid() != owner:  # a forked child that has not set its own handlers yet
            signal.signal(signum, signal.SIG_DFL)
            os.kill(os.getpid(), signum)
            return
        if would_be_lost(frame):  # raised here, it would vanish: ask again shortly
            again = threading.Timer(RETRY, os.kill, (owner, signum))
            again.daemon = True
            again.start()
            return
        raise Interrupted(signum)
    return handle


@contextlib.contextmanager
def interrupts():
    """Within the block, SIGINT / SIGTERM / SIGHUP raise :class:`Interrupted`
    (main thread only; elsewhere the block changes nothing), except a signal
    ignored when the block starts (``nohup``: SIGHUP), which stays ignored."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    handle = _handler(os.getpid())
    before = {sig: signal.signal(sig, handle) for sig in SIGNALS
              if signal.getsignal(sig) is not signal.SIG_IGN}
    try:
        yield
    finally:
        for sig, old in before.items():
            signal.signal(sig, old)


def _signum(exc: KeyboardInterrupt) -> int:
    return getattr(exc, "signum", int(signal.SIGINT))


def interrupted_line(exc: KeyboardInterrupt) -> str:
    """The one line a stopped command prints.

    >>> interrupted_line(Interrupted(signal.SIGTERM)), interrupted_line(KeyboardInterrupt())
    ('recon3d: interrupted (SIGTERM)', 'recon3d: interrupted (SIGINT)')
    """
    return f"recon3d: interrupted ({signal.Signals(_signum(exc)).name})"


def exit_status(exc: KeyboardInterrupt) -> int:
    """128 + the signal number, as a shell reports a process the signal ended.

    >>> exit_status(Interrupted(signal.SIGTERM)), exit_status(KeyboardInterrupt())
    (143, 130)
    """
    return 128 + _signum(exc)


def closed_stdout() -> int:
    """The reader of stdout went away (``recon3d run ... | head``): no traceback, and
    nothing more to write; the status a process SIGPIPE ended gets, 141 (128 + 13)."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())  # the flush at exit must not fail again
        os.close(devnull)
    except (OSError, ValueError, AttributeError):  # stdout is no file (a test's capture)
        pass
    return 128 + SIGPIPE
