"""The numerics are pinned before numpy loads (:mod:`recon3d.numerics`): on an AVX-512
CPU OpenBLAS runs its Haswell kernels and numpy its AVX2 loops, so the planner rounds as
on every other x86-64 machine."""
from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
from threadpoolctl import threadpool_info

from recon3d import numerics

PROBE = ("import recon3d, numpy, threadpoolctl, json\n"
         "from numpy._core._multiarray_umath import __cpu_features__ as f\n"
         "print(json.dumps([sorted({i.get('architecture') for i in threadpoolctl.threadpool_info()"
         " if i.get('internal_api') == 'openblas'}), bool(f.get('X86_V4'))]))")


def _fresh(env: dict) -> list:
    import json
    out = subprocess.run([sys.executable, "-c", PROBE], capture_output=True, text=True,
                         env=env, check=True)
    return json.loads(out.stdout)


def _bare_env() -> dict:
    import os
    return {k: v for k, v in os.environ.items()
            if k not in ("OPENBLAS_CORETYPE", "NPY_DISABLE_CPU_FEATURES")}


@pytest.mark.skipif(not numerics.avx512(), reason="this CPU has no AVX-512: nothing to pin")
def test_a_fresh_process_runs_the_avx2_kernels():
    blas, v4 = _fresh(_bare_env())
    assert blas == [numerics.BLAS_CORETYPE] and not v4


@pytest.mark.skipif(not numerics.avx512(), reason="this CPU has no AVX-512: nothing to pin")
def test_this_test_process_was_pinned_before_numpy_loaded():
    arch = {i.get("architecture") for i in threadpool_info() if i.get("internal_api") == "openblas"}
    assert arch == {numerics.BLAS_CORETYPE}


def test_a_users_own_choice_is_kept():
    env = {"OPENBLAS_CORETYPE": "Prescott"}
    done = numerics.pin(env, cpu_has_avx512=True)
    assert env["OPENBLAS_CORETYPE"] == "Prescott" and "OPENBLAS_CORETYPE" not in done


def test_nothing_is_pinned_once_numpy_is_loaded(monkeypatch):
    monkeypatch.delenv("OPENBLAS_CORETYPE", raising=False)
    assert numerics.pin(cpu_has_avx512=True) == {}  # this process imported numpy long ago


def test_the_dot_of_two_vectors_rounds_without_a_fused_multiply_add():
    """What the pin is for: ``a @ b`` of (2,) vectors as two roundings (a0 b0 + a1 b1),
    on every machine. With SkylakeX's kernel one of these 2000 pairs differs."""
    rng = np.random.default_rng(3)
    a, b = rng.normal(size=(2000, 2)), rng.normal(size=(2000, 2))
    dots = np.array([x @ y for x, y in zip(a, b)])
    assert np.array_equal(dots, a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1])


def test_numpys_version_is_read_without_importing_it():
    """The pin reads numpy's version from its ``version.py`` (numpy is not loaded yet when it
    runs): the same answer as the loaded numpy's own ``__version__``."""
    major, minor = (int(v) for v in np.__version__.split(".")[:2])
    assert numerics._numpy_dispatch_names() == ((major, minor) >= (2, 4))
