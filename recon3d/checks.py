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
"""
from __future__ import annotations

import math
import numbers
import os
import tempfile
from pathlib import Path

import slicer

__all__ = ["InputError", "EPS_SHARE", "EPS_WARN_SHARE", "TOL_SHARE", "positive",
           "check_eps", "check_tol", "check_out_dir", "at_least", "check_slices",
           "check_backend", "check_axes", "check_slice_tol"]

EPS_SHARE = (1e-4, 0.25)
"""eps bounds as shares of the mesh bounding-box diagonal."""

EPS_WARN_SHARE = 0.05
"""eps above this share of the diagonal gets a warning."""

TOL_SHARE = 1e-3
"""tol must be at least this share of eps (and below eps)."""


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
        raise InputError(f"cannot create {name} {p}: {parent}: {exc.strerror}") from None
    return False


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
