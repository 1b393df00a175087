"""The same floating-point results on every x86-64 machine: numpy's and OpenBLAS's
AVX-512 kernels held back.

The planner's decisions hang on the last bits of small computations: a dot product of
two (2,) vectors, an ``arctan2``, a projection onto a segment. On a CPU with AVX-512
two libraries round those differently from every other x86-64 CPU:

* OpenBLAS picks its SkylakeX kernels, whose dot product of two 2-vectors fuses the
  multiply and the add (``a @ b`` and ``np.linalg.norm`` of a 2-vector change in the
  last bit);
* numpy dispatches its ``X86_V4`` / ``AVX512_ICL`` / ``AVX512_SPR`` loops, whose
  ``exp``, ``log``, ``arctan``, ``arctan2``, ``tan``, ``arcsin`` ... differ from the
  AVX2 ones by an ulp here and there.

One ulp moves a noisy sensor's walk onto another path: the same run gave other
coverage, motions and W3 lids on an AVX-512 machine than on an AVX2 one. Both
libraries read their choice from the environment once, when they load, so
:func:`pin` sets ``OPENBLAS_CORETYPE=Haswell`` and ``NPY_DISABLE_CPU_FEATURES``
before numpy is imported, on x86-64 Linux CPUs with AVX-512 only (the Haswell
kernels need AVX2 and FMA, which every AVX-512 CPU has). A variable the user set is
kept. ``import recon3d`` calls it, and so do the test suite and ``python -m bench.*``;
code that imports numpy first runs with the libraries' own choice.

Pure standard library: importing this module imports nothing heavy.
"""
from __future__ import annotations

import os
import platform
import sys
import importlib.util

__all__ = ["pin", "avx512", "NUMPY_HELD_BACK", "BLAS_CORETYPE"]

BLAS_CORETYPE = "Haswell"
"""OpenBLAS kernels used on AVX-512 CPUs (those of AVX2 machines)."""

NUMPY_HELD_BACK = "X86_V4 AVX512_ICL AVX512_SPR"
"""numpy's AVX-512 dispatch targets (numpy >= 2.4 names; older numpy is left alone:
its target names differ and an unknown name is an ImportWarning)."""


def avx512(cpuinfo: str = "/proc/cpuinfo") -> bool:
    """Whether this is an x86-64 Linux CPU with AVX-512 (``avx512f`` in its flags).

    >>> isinstance(avx512(), bool)
    True
    >>> avx512("/no/such/file")
    False
    """
    if platform.machine() not in ("x86_64", "AMD64"):
        return False
    try:
        with open(cpuinfo, encoding="ascii", errors="replace") as fh:
            for line in fh:
                if line.startswith("flags"):
                    return "avx512f" in line.split()
    except OSError:
        pass
    return False


def _numpy_dispatch_names() -> bool:
    """Whether the installed numpy names its AVX-512 targets as :data:`NUMPY_HELD_BACK`:
    numpy >= 2.4, read from its ``version.py`` without importing numpy (and without
    ``importlib.metadata``, which alone took 20 ms of a 28 ms ``import recon3d``)."""
    spec = importlib.util.find_spec("numpy")
    for folder in (spec.submodule_search_locations or []) if spec is not None else []:
        try:
            with open(os.path.join(folder, "version.py"), encoding="utf-8") as fh:
                lines = fh.read().splitlines()
        except OSError:
            continue
        for line in lines:
            name, _, value = line.partition("=")
            if name.strip() == "version" and value:
                try:
                    major, minor = (int(v) for v in value.strip().strip("'\"").split(".")[:2])
                except ValueError:
                    return False
                return (major, minor) >= (2, 4)
    return False


def pin(environ=None, *, cpu_has_avx512: bool | None = None) -> dict:
    """Hold numpy's and OpenBLAS's AVX-512 kernels back, if they are not loaded yet.

    Parameters
    ----------
    environ : mapping, optional -- the environment to set (default ``os.environ``).
    cpu_has_avx512 : bool, optional -- default :func:`avx512`.

    Returns
    -------
    dict -- the variables set now (empty when nothing was to be done: no AVX-512,
    numpy already imported, or the user's own settings).

    Examples
    --------
    >>> env = {}
    >>> pin(env, cpu_has_avx512=True) == env and env["OPENBLAS_CORETYPE"]
    'Haswell'
    >>> pin({"OPENBLAS_CORETYPE": "Zen"}, cpu_has_avx512=True).get("OPENBLAS_CORETYPE")
    >>> pin({}, cpu_has_avx512=False)
    {}
    """
    environ = os.environ if environ is None else environ
    if "numpy" in sys.modules and environ is os.environ:
        return {}  # too late: the libraries have read their settings
    if not (avx512() if cpu_has_avx512 is None else cpu_has_avx512):
        return {}
    wanted = {"OPENBLAS_CORETYPE": BLAS_CORETYPE}
    if _numpy_dispatch_names():
        wanted["NPY_DISABLE_CPU_FEATURES"] = NUMPY_HELD_BACK
    done = {k: v for k, v in wanted.items() if k not in environ}
    environ.update(done)
    return done
