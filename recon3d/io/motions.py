"""``motions.csv``: the motion log of a run, one row per motion (columns in the README).

Each sensed slice carries its :class:`core2d.motionlog.MotionLog` (slice
frame); this module adds the slice's family and plane index and the world
coordinates through the slice's frame (origin + x u + y v), and writes or
reads the table. :data:`COLUMNS` is the column contract.

>>> COLUMNS[:6]
('family', 'slice', 'index', 'kind', 'phase', 'area')
"""
from __future__ import annotations

import csv
import os
from pathlib import Path

import numpy as np

from core2d.motionlog import KINDS, PHASES
from recon3d.checks import InputError
from recon3d.records import SliceRun

__all__ = ["COLUMNS", "FILENAME", "slice_rows", "motions_text", "write_motions", "read_motions", "read_log",
           "other_points"]

FILENAME = "motions.csv"

COLUMNS = ("family", "slice", "index", "kind", "phase", "area", "event",
           "joint_x0", "joint_y0", "theta0", "joint_x1", "joint_y1", "theta1",
           "tip_x1", "tip_y1", "tip_contact", "tip_cx", "tip_cy", "contacts",
           "other_contacts", "blocked_ccw", "blocked_cw", "torque",
           "wx0", "wy0", "wz0", "wx1", "wy1", "wz1", "wdx1", "wdy1", "wdz1")
"""The columns of ``motions.csv``, in order."""

_INT = {"family", "slice", "index", "area", "tip_contact", "contacts", "blocked_ccw",
        "blocked_cw", "torque"}
_STR = {"kind", "phase", "event", "other_contacts"}
_ROW = ",".join("%d" if c in _INT else "%s" if c in _STR else "%.12g" for c in COLUMNS)


def _columns(srun: SliceRun, plane) -> dict | None:
    """The columns of one slice as lists (None without a log); NaN marks an empty cell."""
    log = srun.result.motions
    if log is None or not len(log):
        return None
    n = len(log)
    o, u, v = (np.asarray(x, dtype=np.float64) for x in (plane.origin, plane.u, plane.v))
    b, a = log.before, log.after
    w0 = o + b[:, :1] * u + b[:, 1:2] * v
    w1 = o + a[:, :1] * u + a[:, 1:2] * v
    wd = np.round(np.cos(a[:, 2:3]) * u + np.sin(a[:, 2:3]) * v, 12) + 0.0  # no -0
    cells = [f"{x:.12g} {y:.12g}" for x, y in log.other.tolist()]  # each point once
    start = log.other_start.tolist()
    others = [";".join(cells[start[k]:start[k + 1]]) if start[k + 1] > start[k] else ""
              for k in range(n)]
    floats = np.column_stack([b, a, log.tip])
    cols = {"family": [int(srun.family)] * n, "slice": [int(plane.index)] * n,
            "index": list(range(n)), "kind": [KINDS[k] for k in log.kind],
            "phase": [PHASES[p] for p in log.phase], "area": log.area.tolist(),
            "event": log.event.tolist(), "other_contacts": others,
            "tip_contact": np.isfinite(log.tip_contact[:, 0]).tolist(),
            "tip_cx": log.tip_contact[:, 0].tolist(), "tip_cy": log.tip_contact[:, 1].tolist(),
            "contacts": log.contacts.tolist(), "blocked_ccw": log.blocked[:, 0].tolist(),
            "blocked_cw": log.blocked[:, 1].tolist(), "torque": log.torque.tolist()}
    names = ("joint_x0", "joint_y0", "theta0", "joint_x1", "joint_y1", "theta1", "tip_x1",
             "tip_y1")
    for k, name in enumerate(names):
        cols[name] = floats[:, k].tolist()
    for pts, names in ((w0, ("wx0", "wy0", "wz0")), (w1, ("wx1", "wy1", "wz1")),
                       (wd, ("wdx1", "wdy1", "wdz1"))):
        for k, name in enumerate(names):
            cols[name] = pts[:, k].tolist()
    return cols


def slice_rows(srun: SliceRun, plane) -> str:
    """The rows of one slice's motions (no header, no final newline; "" without a log).

    plane : slicer.SlicePlane -- the slice's plane (its world frame; a worker passes its
        own, the SliceRun it sends back has no ``slice``)."""
    cols = _columns(srun, plane)
    if cols is None:
        return ""
    text = "\n".join(_ROW % row for row in zip(*(cols[c] for c in COLUMNS)))
    # only the float cells can read "nan" (the tip contact point): empty cells
    return text.replace(",nan", ",")


def motions_text(slices) -> str:
    """The CSV text of the motions of ``slices`` (SliceRuns with their ``slice``); the rows
    a worker made (``motion_rows``) are taken as they are."""
    rows = (s.motion_rows if s.motion_rows is not None else slice_rows(s, s.slice.plane)
            for s in slices)
    return "\n".join([",".join(COLUMNS), *(r for r in rows if r)]) + "\n"


def write_motions(path, slices) -> None:
    """Write ``motions.csv`` (:func:`motions_text`) to ``path``."""
    Path(path).write_text(motions_text(slices))


def read_motions(directory: str | os.PathLike) -> np.ndarray:
    """Read ``DIR/motions.csv`` (or the file itself) into a structured array.

    Returns
    -------
    (n,) structured array with the fields :data:`COLUMNS`: ints for the
    counts, flags and indices, str for kind, phase, event and
    other_contacts (:func:`other_points` parses it), float elsewhere (an
    empty cell is NaN).
    """
    path = Path(directory)
    path = path / FILENAME if path.is_dir() else path
    with open(path, newline="") as fh:
        reader = csv.reader(fh)
        header = tuple(next(reader))
        if header != COLUMNS:
            raise ValueError(f"{path}: not a motions.csv (columns {header[:4]}...)")
        rows = list(reader)
    cols = list(zip(*rows)) if rows else [()] * len(COLUMNS)
    dtype, data = [], []
    for name, cells in zip(COLUMNS, cols):
        if name in _STR:
            width = max((len(c) for c in cells), default=1) or 1
            dtype.append((name, f"<U{width}"))
            data.append(np.array(cells, dtype=f"<U{width}"))
        elif name in _INT:
            dtype.append((name, np.int64))
            data.append(np.array([int(c) for c in cells], dtype=np.int64))
        else:
            dtype.append((name, np.float64))
            data.append(np.array([float(c) if c else np.nan for c in cells], dtype=np.float64))
    out = np.zeros(len(rows), dtype=dtype)
    for (name, _), col in zip(dtype, data):
        out[name] = col
    return out


def other_points(cell: str) -> np.ndarray:
    """(k, 2) float: the points of an ``other_contacts`` cell (``x y;x y``).

    >>> other_points("1 2;3.5 -4").tolist()
    [[1.0, 2.0], [3.5, -4.0]]
    """
    if not cell:
        return np.zeros((0, 2))
    return np.array([[float(t) for t in p.split()] for p in cell.split(";")], dtype=np.float64)


def read_log(directory) -> np.ndarray | None:
    """:func:`read_motions` of ``DIR/motions.csv``, None when the run wrote none.

    Raises :class:`recon3d.checks.InputError` (one line) when the file is unreadable.
    """
    path = Path(directory) / FILENAME
    if not path.is_file():
        return None
    try:
        return read_motions(path)
    except (OSError, StopIteration, ValueError, csv.Error) as exc:
        raise InputError(f"cannot read the motion log {path}: {type(exc).__name__}: {exc}") from None

