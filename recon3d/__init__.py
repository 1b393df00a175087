"""recon3d: slice-based pulling-motion tactile sensing of 3D meshes, end to end.

Sensing over slices (:mod:`recon3d.sensing`), the reconstructed watertight
surface (:mod:`recon3d.surface`), its 3D scores (:mod:`recon3d.score`),
files (:mod:`recon3d.io`), pictures (:mod:`recon3d.viz`), many runs on Dask
(:mod:`recon3d.jobs`) and the command line (``recon3d``, :mod:`recon3d.cli`);
the run parameters in one place (:mod:`recon3d.config`).

Example (the README has more)::

    import recon3d
    res = recon3d.run("fig17_pocket", axis=["z", "x"], slices=6)
    res.metrics["total"]["surface"]["fscore"]["1%"]
    res.save("out/pocket")

``import recon3d`` itself is light (no trimesh, SciPy, numba, pyvista or
matplotlib): the public names below are loaded from their modules on first
use (PEP 562 ``__getattr__``), so ``recon3d --help`` and ``import recon3d``
in a notebook start at once and the first ``recon3d.run`` pays for the rest.

Importing it first also holds numpy's and OpenBLAS's AVX-512 kernels back
(:mod:`recon3d.numerics`), so a run rounds alike on every x86-64 machine.
"""
from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

from recon3d import numerics as _numerics

_numerics.pin()  # before numpy loads: the same rounding on every x86-64 CPU

if TYPE_CHECKING:  # the same names, eagerly, for type checkers and IDEs
    from recon3d.api import Result, WorkerDied, __version__, run
    from recon3d.checks import InputError
    from recon3d.config import RunConfig
    from recon3d.io.ply import read_ply_labels
    from recon3d.records import LABELS

_PUBLIC = {  # public name -> the module that defines it (tests/test_recon3d_walls.py reads it)
    "run": "recon3d.api",
    "Result": "recon3d.api",
    "RunConfig": "recon3d.config",
    "InputError": "recon3d.checks",
    "WorkerDied": "recon3d.api",
    "LABELS": "recon3d.records",
    "read_ply_labels": "recon3d.io.ply",
    "__version__": "recon3d.api",
}

__all__ = ["run", "Result", "RunConfig", "InputError", "WorkerDied", "LABELS",
           "read_ply_labels", "__version__"]


def __getattr__(name: str):
    """Load a public name from its module on first use, then keep it here."""
    if name not in _PUBLIC:
        raise AttributeError(f"module 'recon3d' has no attribute {name!r}")
    value = getattr(importlib.import_module(_PUBLIC[name]), name)
    globals()[name] = value  # the next lookup is an ordinary attribute
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
