"""The first compile is announced: ``recon3d run`` prints the compile notice on stderr when
numba's cache misses (an empty ``NUMBA_CACHE_DIR``: the sensing kernels compile in this
run) and not when the same cache is hit on the next run. Both runs are real processes;
the notice is printed before the compile starts (``recon3d.sensing.cold_kernels``).

With two workers, every kernel is compiled once: the parent senses the first slice (and
compiles) before the workers fork, a child compiles the scores' kernels (distances, the
coloured ground truth's subdivision) meanwhile, which the workers do not wait for, and
numba's cache log (``NUMBA_DEBUG_CACHE``: one "data saved" line per compile, whichever
process compiles) shows each kernel saved once."""
import collections
import os
import re
import subprocess
import sys
import time

import pytest

from recon3d.sensing import COMPILE_NOTICE
from slicer.contact.embree_direct import available

pytestmark = pytest.mark.skipif(not available(), reason="no Embree 4 library to call directly")


def _run(cache, out, jobs):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache), NUMBA_DEBUG_CACHE="1")
    proc = subprocess.run([sys.executable, "-m", "recon3d", "run", "fig17_pocket", "--slices",
                           "3", "--jobs", str(jobs), "--no-png", "--out", str(out)], env=env,
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    saved = collections.Counter(re.findall(r"data saved to '.*?([^/]+)\.nbc'", proc.stdout))
    return proc.stderr, saved


def test_the_notice_appears_on_a_cache_miss_and_not_on_a_hit(tmp_path):
    cache = tmp_path / "numba"
    cold, saved = _run(cache, tmp_path / "a", jobs=2)
    assert list(cache.rglob("*.nbc"))  # this run compiled into the empty cache
    assert cold.count(COMPILE_NOTICE) == 1
    kernels = {name.split("-")[0] for name in saved}
    assert {"kernels.search", "embree_direct._ray", "closest._query", "subdivide._made",
            "subdivide._long_edges"} <= kernels
    assert max(saved.values()) == 1, saved  # no kernel compiled by two workers
    warm, saved = _run(cache, tmp_path / "b", jobs=2)
    assert COMPILE_NOTICE not in warm
    assert not saved


def test_the_workers_do_not_wait_for_the_scores_compile(tmp_path, monkeypatch):
    """On a cold cache the workers start once the first slice (sensed here) has compiled the
    sensing kernels, whether or not the child compiling the scores' kernels has finished;
    the sensing waits for that child at its end, before the scores need the kernels."""
    import recon3d
    from recon3d.sensing import pool

    flag = tmp_path / "compiled"

    def slow_compile():
        time.sleep(4.0)
        flag.write_text("done")

    monkeypatch.setattr(pool, "cold_kernels", lambda *backend: True)
    monkeypatch.setattr(pool, "compile_scores", slow_compile)
    # an earlier test of this process may have rendered (OpenGL mapped: no side process);
    # this child only sleeps
    monkeypatch.setattr(pool, "can_fork", lambda: True)
    seen = []
    recon3d.run("fig17_pocket", slices=4, jobs=2, progress=lambda s: seen.append(flag.exists()))
    assert len(seen) == 4 and not seen[0]
    assert not all(seen[1:]), seen  # a worker's slice came back while the child compiled
    assert flag.exists()  # and the sensing waited for it before returning
