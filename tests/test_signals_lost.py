"""A stopping signal that lands where Python would drop the exception still stops the command.

LLVM calls back into Python (llvmlite's object-cache hooks) while numba compiles, and a
ctypes callback prints what it raises and goes on; so does a ``__del__``. A Ctrl-C
there was lost and the run went on (seen once: a Ctrl-C during the first compile). Each
child below sleeps inside such a place, the test sends SIGINT while it sleeps, and the
child must end by :class:`recon3d.cli.signals.Interrupted`, not finish.
"""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from stoppable import default_actions

ROOT = Path(__file__).resolve().parents[1]

_FRAME = """
import sys, time
from recon3d.cli.signals import interrupts
{setup}
try:
    with interrupts():
{body}
        print("FINISHED", flush=True)
except KeyboardInterrupt:
    print("INTERRUPTED", flush=True)
    sys.exit(130)
"""

CASES = {
    "llvm_callback": (
        """
import numba
from numba.core.registry import cpu_target
ee = cpu_target.target_context.codegen()._engine._ee  # numba's execution engine
notify = ee._object_cache_notify
def slow_notify(module, buf):  # runs inside llvmlite's ctypes callback
    print("INSIDE", flush=True)
    time.sleep(1.0)
    ee._object_cache_notify = notify
    return notify(module, buf)
ee._object_cache_notify = slow_notify
""",
        """
        @numba.njit
        def f(x):
            return x + 1
        f(1)
        time.sleep(0.5)
"""),
    "finalizer": (
        """
class Slow:
    def __del__(self):
        print("INSIDE", flush=True)
        time.sleep(1.0)
""",
        """
        s = Slow()
        del s
        time.sleep(0.5)
"""),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_sigint_inside_a_place_that_drops_exceptions_still_stops(case, tmp_path):
    setup, body = CASES[case]
    script = tmp_path / "child.py"
    script.write_text(_FRAME.format(setup=textwrap.dedent(setup),
                                    body=textwrap.indent(textwrap.dedent(body), " " * 8)))
    env = dict(os.environ, PYTHONPATH=str(ROOT), NUMBA_CACHE_DIR=str(tmp_path / "numba"))
    proc = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=env,
                            preexec_fn=default_actions)
    first = proc.stdout.readline()
    assert first == "INSIDE\n", (first, proc.stderr.read())
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=120)
    assert (proc.returncode, out) == (130, "INTERRUPTED\n"), err
    assert "Exception ignored" not in err, err
