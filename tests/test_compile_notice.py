"""The first compile is announced: ``recon3d run`` prints the compile notice on stderr when
numba's cache misses (an empty ``NUMBA_CACHE_DIR``: the sensing kernels compile in this
run) and not when the same cache is hit on the next run. Both runs are real processes;
the notice is printed before the compile starts (``recon3d.sensing.cold_kernels``)."""
import os
import subprocess
import sys

import pytest

from recon3d.sensing import COMPILE_NOTICE
from slicer.contact.embree_direct import available

pytestmark = pytest.mark.skipif(not available(), reason="no Embree 4 library to call directly")


def _run(cache, out):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache))
    proc = subprocess.run([sys.executable, "-m", "recon3d", "run", "fig17_pocket", "--slices",
                           "2", "--jobs", "1", "--no-png", "--out", str(out)], env=env,
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    return proc.stderr


def test_the_notice_appears_on_a_cache_miss_and_not_on_a_hit(tmp_path):
    cache = tmp_path / "numba"
    cold = _run(cache, tmp_path / "a")
    assert list(cache.rglob("*.nbc"))  # this run compiled into the empty cache
    assert cold.count(COMPILE_NOTICE) == 1
    warm = _run(cache, tmp_path / "b")
    assert COMPILE_NOTICE not in warm
