"""Checks of user input, done before any sensing starts.

Every check raises :class:`InputError` (a ``ValueError``) with one line
that names the offending parameter as the caller spells it (``--eps`` on
the command line, ``eps`` in Python).

Bounds relative to the mesh (``diag`` = bounding-box diagonal):

* ``diag / 10000 <= eps <= diag / 4``: below, a unit mix-up (mm vs m is a
  factor 1000 off the default diag / 200) or a run that cannot end in
  reasonable time; above, W2 chords could span the whole object. Above
  ``diag / 20`` a warning says the numbers are coarse.
* ``eps / 1000 <= tol < eps``: the contact resolution must be finer than
  the W2 threshold it serves.
* ``2 <= slices <= extent / eps`` along each axis: one slice gives no
  surface; above the bound the slices lie closer than eps, which the paper's
  algorithm cannot resolve and which only costs time (``force`` allows it).
* ``1 mm <= diagonal <= 10 m`` once read in ``units``: outside, the default
  probe speed (20 mm/s) makes the robot time absurd, so a warning asks
  whether ``units`` is right.
"""
from __future__ import annotations

import argparse
import errno
import math
import numbers
import os
import tempfile
from pathlib import Path

import numpy as np

import slicer

__all__ = ["InputError", "EPS_SHARE", "EPS_WARN_SHARE", "TOL_SHARE", "positive",
           "check_eps", "check_tol", "check_out_dir", "at_least", "check_slices",
           "check_backend", "check_axes", "check_slice_tol", "check_slice_count", "MM_PER_UNIT",
           "SIZE_MM", "check_slice_spacing", "units_note", "check_choice", "check_flag",
           "parse_count_or_auto"]

EPS_SHARE = (1e-4, 0.25)
"""eps bounds as shares of the mesh bounding-box diagonal."""

EPS_WARN_SHARE = 0.05
"""eps above this share of the diagonal gets a warning."""

TOL_SHARE = 1e-3
"""tol must be at least this share of eps (and below eps)."""

MM_PER_UNIT = {"mm": 1.0, "cm": 10.0, "m": 1000.0, "in": 25.4, "ft": 304.8}
"""Millimetres per mesh unit, for each ``units`` (the probe speed is in mm/s)."""

SIZE_MM = (1.0, 1e4)
"""Mesh diagonals (in mm, once read in ``units``) outside this range get a units warning."""


class InputError(ValueError):
    """Bad input: the message is one line."""


def positive(value, name: str, allow_zero: bool = False) -> float:
    """``value`` as a finite float > 0 (>= 0 with ``allow_zero``)."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number (got {value!r})") from None
    if not math.isfinite(v) or v < 0 or (v == 0 and not allow_zero):
        kind = "a finite number >= 0" if allow_zero else "a finite positive number"
        raise InputError(f"{name} must be {kind} (got {value})")
    return v


def at_least(value, name: str, low: int = 1) -> int:
    """``value`` as an int >= ``low``."""
    integral = isinstance(value, numbers.Integral) or (
        isinstance(value, float) and value.is_integer())
    if isinstance(value, bool) or not integral:
        raise InputError(f"{name} must be an integer (got {value!r})")
    if int(value) < low:
        raise InputError(f"{name} must be at least {low} (got {value})")
    return int(value)


def check_eps(eps: float, diag: float, name: str = "eps") -> str | None:
    """Check eps against the mesh diagonal; return a warning line or None."""
    lo, hi = EPS_SHARE
    if eps < lo * diag or eps > hi * diag:
        raise InputError(
            f"{name} {eps:g} is {eps / diag:.3g} x the mesh diagonal ({diag:.4g}); "
            f"it must lie in [{lo:g}, {hi:g}] x diagonal = [{lo * diag:.4g}, {hi * diag:.4g}] "
            f"(wrong units?)")
    if eps > EPS_WARN_SHARE * diag:
        return (f"{name} {eps:g} is {100 * eps / diag:.1f}% of the mesh diagonal: gaps "
                f"narrower than eps count as W2 (touched) and coverage is measured within "
                f"eps/2, so the numbers are coarse")
    return None


def check_tol(tol: float, eps: float, name: str = "tol") -> None:
    """tol must lie in [eps / 1000, eps)."""
    if tol >= eps:
        raise InputError(f"{name} {tol:g} must be smaller than eps {eps:g} (the contact "
                         f"resolution serves the W2 threshold eps)")
    if tol < TOL_SHARE * eps:
        raise InputError(f"{name} {tol:g} is below eps / {1 / TOL_SHARE:g} = "
                         f"{TOL_SHARE * eps:.4g}")


def check_out_dir(path, name: str = "out") -> bool:
    """Check that ``path`` can receive the outputs, creating nothing.

    Returns
    -------
    bool -- True when the directory already exists.
    """
    p = Path(path)
    if p.exists():
        if not p.is_dir():
            raise InputError(f"{name} {p} exists and is not a directory")
        try:
            fd, tmp = tempfile.mkstemp(prefix=".recon3d-write-test-", dir=p)
        except OSError as exc:
            raise InputError(f"cannot write to {name} {p}: {exc.strerror}") from None
        os.close(fd)
        os.unlink(tmp)
        return True
    parent = p.absolute().parent
    while not parent.exists():
        parent = parent.parent
    if not parent.is_dir():
        raise InputError(f"cannot create {name} {p}: {parent} is not a directory")
    try:
        os.rmdir(tempfile.mkdtemp(prefix=".recon3d-write-test-", dir=parent))
    except OSError as exc:
        raise InputError(f"cannot create {name} {p}: {_why_not(parent, exc)}") from None
    return False


def _why_not(parent: Path, exc: OSError) -> str:
    """Why no directory can be made in ``parent`` (which exists), in words."""
    fs = _filesystem(parent)
    if fs in ("proc", "sysfs", "devtmpfs", "cgroup", "cgroup2", "debugfs", "securityfs"):
        return f"{parent} is on a {fs} filesystem, which takes no new directories"
    if exc.errno in (errno.EACCES, errno.EPERM):
        return f"no permission to create a directory in {parent}"
    if exc.errno == errno.EROFS:
        return f"{parent} is on a read-only filesystem"
    return f"making a directory in {parent} failed ({exc.strerror})"


def _filesystem(path: Path) -> str | None:
    """The type of the filesystem holding ``path`` (Linux /proc/self/mounts), or None."""
    try:
        with open("/proc/self/mounts") as fh:
            mounts = [line.split()[1:3] for line in fh if len(line.split()) > 2]
    except OSError:
        return None
    target = str(path.resolve())
    best = max((m for m in mounts if target == m[0] or target.startswith(m[0].rstrip("/") + "/")),
               key=lambda m: len(m[0]), default=None)
    return best[1] if best else None


def check_slices(value):
    """``slices``: an integer (checked later) or 'auto'."""
    if isinstance(value, str) and value != "auto":
        raise InputError(f"slices must be an integer or 'auto' (got {value!r})")
    return value


def check_backend(value):
    """``backend``: one of ``slicer.BACKENDS``."""
    if value not in slicer.BACKENDS:
        raise InputError(f"backend must be one of {', '.join(slicer.BACKENDS)} (got {value!r})")
    return value


def check_axes(axes, name: str) -> None:
    """At least one axis, each one ``slicer.parse_axis`` takes."""
    if not axes:
        raise InputError(f"give at least one {name}")
    for a in axes:
        try:
            slicer.parse_axis(a)
        except ValueError as exc:
            raise InputError(f"{name}: {exc}") from None


def check_slice_tol(value, name: str) -> None:
    """``slice_tol``: a share of the diagonal in (0, 0.5)."""
    if not 0 < positive(value, name) < 0.5:
        raise InputError(f"{name} is a share of the diagonal in (0, 0.5) (got {value})")


def check_slice_count(value, name: str) -> int:
    """``slices`` as an integer >= 2 (one slice gives no surface)."""
    n = at_least(value, name)
    if n < 2:
        raise InputError(f"{name} {n}: a surface needs at least 2 slices per axis")
    return n


def check_slice_spacing(count: int, mesh, axes, eps: float, name: str,
                        force_name: str) -> None:
    """Refuse more than ``extent / eps`` slices along an axis (closer than eps) unless forced.

    mesh : trimesh.Trimesh -- its extent along each axis is measured over its faces' vertices.

    >>> import trimesh
    >>> check_slice_spacing(100, trimesh.creation.box((9, 9, 50)), ["z"], 1.0, "--slices",
    ...                     "--force")
    Traceback (most recent call last):
    ...
    recon3d.checks.InputError: --slices 100 is more than extent / eps = 50 / 1 = 50 along axis z (slices closer than eps add time, not detail); pass --force to run it anyway
    """
    v = np.asarray(mesh.vertices, dtype=np.float64)[np.unique(mesh.faces)]
    for axis in axes:
        extent = float(np.ptp(v @ slicer.parse_axis(axis)))
        bound = int(extent / eps)
        if count > bound:
            label = axis if isinstance(axis, str) else ",".join(f"{c:.4g}" for c in np.ravel(axis))
            raise InputError(f"{name} {count} is more than extent / eps = {extent:.4g} / "
                             f"{eps:.4g} = {bound} along axis {label} (slices closer than eps "
                             f"add time, not detail); pass {force_name} to run it anyway")


def units_note(diag: float, units: str, name: str) -> str | None:
    """A warning line when a mesh of diagonal ``diag`` is implausibly sized in ``units``.

    >>> units_note(100.0, "mm", "--units") is None
    True
    >>> units_note(8e4, "mm", "--units")[:40]
    'the mesh is 8e+04 mm across (80 m): the '
    """
    mm = diag * MM_PER_UNIT[units]
    lo, hi = SIZE_MM
    if lo <= mm <= hi:
        return None
    guess = "is it in m" if mm < lo and units != "m" else "are its units right"
    metres = "" if units == "m" else f" ({mm / 1000:.4g} m)"
    return (f"the mesh is {diag:.4g} {units} across{metres}: the probe speed "
            f"(mm/s) makes its robot time absurd; {guess}? pass {name} "
            f"({', '.join(MM_PER_UNIT)})")


def check_choice(value, name: str, choices) -> None:
    """``value`` must be one of ``choices``."""
    if value not in choices:
        raise InputError(f"{name} must be one of {', '.join(choices)} (got {value!r})")


def check_flag(value, name: str) -> None:
    """An on/off parameter must be a bool."""
    if not isinstance(value, (bool, np.bool_)):
        raise InputError(f"{name} must be True or False (got {value!r})")


def parse_count_or_auto(text: str):
    """``--slices`` and ``--reads`` on the command line: an integer or 'auto' (argparse
    ``type``)."""
    if text == "auto":
        return text
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an integer or 'auto', got {text!r}") from None


def check_reads(value, name: str):
    """``reads``: 'auto' or an integer from 1 to ``core2d.resolution.MAX_READS``."""
    # lazy: core2d's package loads the simulator (numba, shapely); the parser loads none of it
    from core2d.resolution import MAX_READS

    if value == "auto":
        return value
    if isinstance(value, str):
        raise InputError(f"{name} must be 'auto' or an integer from 1 to {MAX_READS} "
                         f"(got {value!r})")
    n = at_least(value, name)
    if n > MAX_READS:
        raise InputError(f"{name} must be 'auto' or at most {MAX_READS} (got {n})")
    return n
