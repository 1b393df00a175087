"""Child processes that a stop signal reaches, whatever the test runner inherited.

A command a non-interactive shell puts in the background starts with SIGINT
ignored, ``nohup`` with SIGHUP ignored, and a child inherits an ignored signal
across ``exec``: Python then keeps ignoring SIGINT, and ``recon3d`` leaves an
ignored stop signal ignored (:func:`recon3d.cli.signals.interrupts`). The signal
tests start their children with the default actions, as an interactive shell
does, so they test the run and not how the suite was started.
"""
from __future__ import annotations

import signal

__all__ = ["default_actions"]

STOP = tuple(getattr(signal, n) for n in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, n))


def default_actions() -> None:
    """``preexec_fn`` of a child: SIGINT, SIGTERM and SIGHUP at their default actions."""
    for sig in STOP:
        signal.signal(sig, signal.SIG_DFL)
