"""Two sensor studies side by side: what a change to the planner did, level by level.

Each study is a CSV of ``python -m bench.sensor_study --csv`` (one row per slice run),
made with the same arguments at two commits. For every sensor level both hold:

* slice runs whose reachable coverage within eps/2 + 2 sigma went up, down, or stayed,
  and how many runs' motions changed (a change that leaves a level alone leaves them all);
* per group, the pooled coverage and the total motions, before -> after, each change with
  its 95 % interval from a paired bootstrap over the slice runs, and a sign test of the
  runs that went up against those that went down (:mod:`bench.paired`: an interval that
  holds 0 is a change the sensor's lottery alone could make);
* case runs (cases x sensor seeds, as ``sensor_study`` judges them) meeting each target
  of the level, before -> after.

One seed's run of a slice is a lottery at +-0.01 to 0.03 under a coarse sensor, and a
change tuned while looking at some seeds fits their lottery. With ``--seeds K``, K >= 2, the
targets and pooled figures are printed again for the first half of the sensor seeds and
for the second: judge a change on the half it was not tuned on.

    python -m bench.sensor_study --slices 8 --levels 0.3:0.25 --seeds 6 --csv before.csv
    python -m bench.sensor_study --slices 8 --levels 0.3:0.25 --seeds 6 --csv after.csv
    python -m bench.sensor_compare before.csv after.csv

Nothing is asserted: it compares.
"""
from __future__ import annotations

import argparse
import csv
import math
import sys
from pathlib import Path

from bench.paired import pooled_change, sign_test
from bench.sensor_study import coverage_target, per_case

__all__ = ["read_rows", "compare", "main"]

_INT = ("motions", "repeat", "reads", "sensor_seed", "w3_count", "w3_unsound_count",
        "w3_unsound_count_sensor")
_TEXT = ("group", "name", "error")
_NEEDED = ("group", "name", "noise", "taxel", "sensor_seed", "repeat", "coverage_sensor",
           "covered_length_sensor", "reachable_length", "motions", "ratio", "budget_hit",
           "precision_sensor", "precise_length_sensor", "detected_length",
           "covered_resolvable_length_sensor", "resolvable_length")


def read_rows(path: Path) -> list[dict]:
    """The rows of a ``sensor_study`` CSV with their numbers as numbers (crashed runs,
    which carry an ``error``, left out)."""
    rows = []
    with open(path, newline="") as fh:
        reader = csv.DictReader(fh)
        if not set(_NEEDED) <= set(reader.fieldnames or ()):
            raise ValueError(f"{path}: not a CSV of python -m bench.sensor_study --csv")
        for r in reader:
            if r.get("error"):
                continue
            try:
                rows.append({k: _value(k, v) for k, v in r.items() if v != "" or k in _TEXT})
            except (TypeError, ValueError):
                raise ValueError(f"{path}, line {reader.line_num}: not a row of "
                                 "python -m bench.sensor_study --csv") from None
    return rows


def _value(key, text):
    if key in _TEXT:
        return text
    if key in ("budget_hit", "keyed"):
        return text == "True"
    return int(float(text)) if key in _INT else float(text)


def _key(r) -> tuple:
    return r["group"], r["name"], r["noise"], r["taxel"], r["sensor_seed"]


def _pooled(before, after) -> dict:
    """{group: (coverage change, motions change)} of paired runs (:func:`pooled_change`:
    coverage within eps/2 + 2 sigma, length weighted; total motions, relative)."""
    out = {}
    for g in sorted({r["group"] for r in before}):
        pairs = [(x, y) for x, y in zip(before, after) if x["group"] == g]
        col = {k: ([x[k] for x, _ in pairs], [y[k] for _, y in pairs])
               for k in ("covered_length_sensor", "motions")}
        reach = [x["reachable_length"] for x, _ in pairs]
        out[g] = (pooled_change(*col["covered_length_sensor"], weight=reach),
                  pooled_change(*col["motions"], relative=True))
    return out


def _interval(c, scale=1.0, digits=4, unit="") -> str:
    """The 95 % interval of the change ``c`` as text ("" when the runs were too few)."""
    if math.isnan(c.low):  # too few runs
        return ""
    return f", 95 % interval {c.low * scale:+.{digits}f} .. {c.high * scale:+.{digits}f}{unit}"


def _count(x: float) -> int:
    """A pooled total (motions) as the integer it is."""
    return int(round(x))


def _met(rows, target) -> dict:
    """Case runs meeting each target (``sensor_study``'s verdicts) of ``rows``, one level."""
    cases = per_case(rows)
    checks = {"precision >= 0.98": lambda c: c["precision_sensor"] >= 0.98,
              "motions <= 2 x noiseless": lambda c: c["ratio"] <= 2.0,
              "no budget hit": lambda c: c["budget"] == 0}
    if target is not None:
        checks = {f"coverage >= {target}": lambda c: c["coverage_sensor"] >= target, **checks}
    return {k: sum(f(c) for c in cases) for k, f in checks.items()} | {"case runs": len(cases)}


def _block(before, after, target, indent="  ") -> list[str]:
    lines = []
    for g, (cov, mot) in _pooled(before, after).items():
        lines.append(f"{indent}{g}: coverage {cov.before:.4f} -> {cov.after:.4f} "
                     f"({cov.change:+.4f}{_interval(cov)}), motions {_count(mot.before)} -> "
                     f"{_count(mot.after)} ({mot.change * 100:+.1f} %"
                     f"{_interval(mot, 100, 1, ' %')})")
    if before and "ratio" in before[0]:
        ma, mb = _met(before, target), _met(after, target)
        lines.append(indent + "; ".join(f"{k} {ma[k]} -> {mb[k]}" for k in ma))
    return lines


def compare(before: list[dict], after: list[dict]) -> str:
    """The comparison of two studies' rows (see the module doc), as text."""
    a = {_key(r): r for r in before}
    b = {_key(r): r for r in after}
    common = [k for k in b if k in a]
    lines = [f"{len(common)} slice runs in both ({len(a)} before, {len(b)} after)"]
    keyed = [{bool(r.get("keyed", False)) for r in rows} for rows in (before, after)]
    if keyed[0] != keyed[1]:  # one study keyed, the other not: every run is a new draw
        lines.append("warning: one study's noise is keyed by reading (--keyed-noise) and the "
                     "other's is not, so no slice run is paired")
    for noise, taxel in sorted({k[2:4] for k in common}):
        ks = [k for k in common if k[2:4] == (noise, taxel)]
        up = sum(b[k]["coverage_sensor"] > a[k]["coverage_sensor"] + 1e-9 for k in ks)
        down = sum(b[k]["coverage_sensor"] < a[k]["coverage_sensor"] - 1e-9 for k in ks)
        moved = sum(b[k]["motions"] != a[k]["motions"] for k in ks)
        target = coverage_target(noise, taxel)
        lines.append(f"sigma {noise:g} eps, taxel {taxel:g} eps: {len(ks)} slice runs, "
                     f"coverage up {up}, down {down}, same {len(ks) - up - down}; "
                     f"motions changed in {moved}; up against down: sign test p = "
                     f"{sign_test(up, down):.2g}")
        rows_a, rows_b = [a[k] for k in ks], [b[k] for k in ks]
        lines += _block(rows_a, rows_b, target)
        repeats = sorted({r.get("repeat", 0) for r in rows_b})
        if len(repeats) >= 2 and (noise, taxel) != (0.0, 0.0):
            half = repeats[len(repeats) // 2]
            for name, keep in ((f"sensor seeds j < {half}", lambda r: r.get("repeat", 0) < half),
                               (f"sensor seeds j >= {half}",
                                lambda r: r.get("repeat", 0) >= half)):
                lines.append(f"  {name}:")
                lines += _block([r for r in rows_a if keep(r)], [r for r in rows_b if keep(r)],
                                target, indent="    ")
    return "\n".join(lines)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m bench.sensor_compare",
                                description=__doc__.splitlines()[0])
    p.add_argument("before", type=Path, help="CSV of python -m bench.sensor_study --csv")
    p.add_argument("after", type=Path, help="CSV of the same study at another commit")
    args = p.parse_args(argv)
    try:
        before, after = read_rows(args.before), read_rows(args.after)
    except (OSError, ValueError, KeyError) as exc:
        print(f"sensor_compare: {exc}", file=sys.stderr)
        return 2
    print(compare(before, after))
    return 0


if __name__ == "__main__":
    sys.exit(main())
