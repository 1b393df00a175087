"""Are the compiled sensing kernels in numba's cache? (the first run on a machine compiles them).

The sensing runs numba kernels compiled with ``cache=True``: core2d's ray engine, planner
and visibility, and the backend's ray function (Embree's of
:mod:`slicer.contact.embree_direct`, or the exact backend's of :mod:`slicer.contact.exact`
with its batched cast). The
first run on a machine (or after their source changed) compiles them, about 10 s before
the first slice, so ``recon3d run`` says so first (:func:`cold_kernels`; the library
itself prints nothing).

How it knows, without compiling anything: numba keeps one index file per kernel
(``<module>.<function>-<line>.pyXY.nbi``, next to the source in ``__pycache__`` or under
``NUMBA_CACHE_DIR``), stamped with the numba version and the source file's time and size;
each entry is keyed by the signature, the machine (numba's "magic tuple": target triple,
CPU name and features) and a hash of the function's bytecode. :func:`cold_kernels` reads
these indexes through numba's own ``FunctionCache`` (the same locator and the same
staleness rules as a compile) and calls a kernel cold when no entry fits this numba, this
source, this machine and this bytecode. That is exactly when numba would compile it: no
timing guess, a few milliseconds once the modules are imported.

Some kernels are compiled only by the runs that need them (``search_from``: the pivot
about the tip, Definition 1, which many scenes never make), so a scene without a pivot
would leave that kernel out of the cache for good and every later run would be announced
as compiling (and sense its first slice alone, :func:`recon3d.sensing.pool._compile_here`).
A kernel out of the cache is therefore cold only when no kernel of its source file is
cached: the file's kernels share its stamp, so one cached kernel says the file has not
changed since the runs that compiled what they needed (:func:`cold_among`). The price: a
run that first needs such a kernel compiles it (one small kernel) without the notice.

Kernels of other paths (``slicer.contact.refine``, used by the batched Embree path) are not
asked about: they are small, and a default run never compiles them, so asking would
announce a compile on every run. The trimesh backend has no ray function (the Python
engine) and is not asked about.
"""
from __future__ import annotations

import hashlib
import importlib
import pkgutil
from collections.abc import Mapping

import core2d
import numba
from numba.core.caching import FunctionCache
from numba.core.dispatcher import Dispatcher

from slicer.contact import embree_direct, exact

__all__ = ["COMPILE_NOTICE", "sensing_kernels", "cold_among", "cold_kernels", "load_numba_target"]

COMPILE_NOTICE = "recon3d: compiling sensing kernels (once per machine, about 10 s)…"
"""What ``recon3d run`` prints (stderr, not with ``--quiet``) when :func:`cold_kernels`."""


def sensing_kernels(backend: str = "embree") -> dict[str, object]:
    """``module.function`` -> Python function of every cached kernel a run on ``backend``
    ("embree" or "exact") compiles.

    Every ``cache=True`` dispatcher of core2d (found by importing the core2d modules whose
    source mentions numba, so a new kernel is seen without a list to keep) and the
    backend's: when Embree loads, the ray function that :mod:`slicer.contact.embree_direct`
    compiles on first use; the exact backend's ray function and batched cast.
    """
    found = {}
    for info in pkgutil.walk_packages(core2d.__path__, "core2d."):
        spec = info.module_finder.find_spec(info.name, None)
        if info.ispkg or spec is None or not spec.origin or not spec.origin.endswith(".py"):
            continue
        with open(spec.origin, encoding="utf-8") as fh:
            if "numba" not in fh.read():
                continue
        module = importlib.import_module(info.name)
        for name, value in vars(module).items():
            if (isinstance(value, Dispatcher) and value.py_func.__module__ == info.name
                    and isinstance(value._cache, FunctionCache)):
                found[f"{info.name}.{name}"] = value.py_func
    if backend == "exact":
        found["slicer.contact.exact._ray"] = exact._ray
        found["slicer.contact.exact._cast"] = exact._cast.py_func
    elif embree_direct.available():
        found["slicer.contact.embree_direct._ray"] = embree_direct._ray
    return found


def _cached(py_func, magic: tuple) -> bool:
    """Does numba's cache hold ``py_func`` compiled for this machine from this source?"""
    index = FunctionCache(py_func)._cache_file._load_index()  # {} if absent or stale
    code = hashlib.sha256(py_func.__code__.co_code).hexdigest()
    return any(key[1] == magic and key[2][0] == code for key in index)


def cold_among(kernels: Mapping[str, object]) -> list[str]:
    """The names of ``kernels`` (name -> Python function of a ``cache=True`` dispatcher) that
    a run would compile: not in numba's cache, and no kernel of the same source file in it
    (module docstring). An error reading an index counts as not cached."""
    magic = numba.core.registry.cpu_target.target_context.codegen().magic_tuple()
    missing, warm_files = [], set()
    for name, py_func in kernels.items():
        try:
            ok = _cached(py_func, magic)
        except Exception:  # noqa: BLE001 - an unreadable index: numba would recompile too
            ok = False
        if ok:
            warm_files.add(py_func.__code__.co_filename)
        else:
            missing.append(name)
    return [name for name in missing
            if kernels[name].__code__.co_filename not in warm_files]


def cold_kernels(backend: str = "embree") -> list[str]:
    """The kernels of :func:`sensing_kernels` that a run on ``backend`` would compile (empty:
    all cached, or a backend without kernels of its own to ask about; :func:`cold_among`).
    Reads numba's cache indexes only; the notice is then at worst one line too many."""
    if backend not in ("embree", "exact"):
        return []
    return cold_among(sensing_kernels(backend))


def load_numba_target() -> None:
    """Initialise numba's CPU target in this process (its implementation registries: about
    0.25 s of CPU, paid by the first kernel a process loads from the cache, compiled or not).

    Called before the sensing workers are forked, so that the workers and the run's side
    processes (the compiled distances of :mod:`recon3d.score.closest`) inherit it instead of
    each paying it again; nothing is compiled or loaded from the cache here.
    """
    numba.core.registry.cpu_target.target_context.refresh()
