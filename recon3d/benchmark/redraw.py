"""``recon3d bench --redraw DIR[,DIR...]``: a bench's files re-made from its CSVs.

The CSVs of one or more earlier runs (each part may come from its own run,
e.g. ``--parts pareto`` and ``--parts stability`` run apart) are read back
(:func:`load_rows`) and handed to :func:`.run3d.write_outputs`, which
writes the CSVs, charts and table.txt again -- no sensing. Chart code fixed
after a long run re-draws its charts this way.
"""
from __future__ import annotations

import csv
import math
import re
from pathlib import Path

from recon3d.benchmark import pareto
from recon3d.benchmark.run3d import PARTS, write_outputs

__all__ = ["read_csv", "load_rows", "redraw"]

#: the CSV that holds each part's rows
PART_CSV = {"pareto": "pareto.csv", "backends": "backends.csv", "baseline": "baseline.csv",
            "stability": "stability.csv", "claims": "claims.csv"}

_INT = re.compile(r"^-?\d+$")


def _cell(text: str):
    """One CSV cell as written by :func:`.run3d.write_csv`: bool, int, float or str."""
    if text in ("True", "False"):
        return text == "True"
    if _INT.match(text):
        return int(text)
    try:
        return float(text)
    except ValueError:
        return text


def read_csv(path) -> list[dict]:
    """Rows of a bench CSV with their types back; an empty cell is NaN in a
    column that holds numbers and ``""`` in a column of text."""
    with open(path, newline="") as fh:
        raw = list(csv.DictReader(fh))
    rows = [{k: _cell(v) for k, v in r.items()} for r in raw]
    for key in (raw[0] if raw else {}):
        numeric = any(isinstance(r[key], (int, float)) and not isinstance(r[key], bool)
                      for r in rows if r[key] != "")
        for r in rows:
            if r[key] == "" and numeric:
                r[key] = math.nan
    return rows


def _quick(folder: Path) -> bool:
    table = folder / "table.txt"
    return table.is_file() and table.read_text().startswith("recon3d bench --quick")


def load_rows(folders) -> tuple[dict, list[dict], bool]:
    """The rows of every part found in ``folders`` (earlier bench outputs):
    ``(by part -> rows, tasks.csv rows, quick)``. A part found twice, a
    folder without ``tasks.csv`` or full and ``--quick`` runs mixed raise
    ValueError."""
    by, timing, quick = {}, [], set()
    for folder in map(Path, folders):
        if not (folder / "tasks.csv").is_file():
            raise ValueError(f"{folder}: no tasks.csv (not the output of recon3d bench)")
        quick.add(_quick(folder))
        timing += read_csv(folder / "tasks.csv")
        for part in PARTS:
            if (folder / PART_CSV[part]).is_file():
                if part in by:
                    raise ValueError(f"{folder}: {PART_CSV[part]} found twice")
                by[part] = read_csv(folder / PART_CSV[part])
    if len(quick) > 1:
        raise ValueError("full and --quick runs mixed")
    return by, timing, quick.pop()


def redraw(folders, out) -> list[str]:
    """Re-make every file of the bench runs in ``folders`` into ``out``; the table's lines."""
    by, timing, quick = load_rows(folders)
    return write_outputs(out, by, timing, pareto.QUICK if quick else pareto.FULL, quick)
