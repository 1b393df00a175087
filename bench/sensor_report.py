"""The sensor study's tables: one row per group and level, one line per case, the verdicts.

Read from the study's rows (:mod:`bench.sensor_study`, or its CSV): coverage and precision
length weighted over the slices, at the noiseless tolerance eps / 2 and at the sensor's
eps / 2 + 2 sigma; coverage over the part eps resolves (:mod:`core2d.truth.resolvable`:
openings narrower than eps are W2 by design, §3.1) and over the part eps + jitter resolves
(a noisy sensor's W2 distance, :attr:`core2d.resolution.Resolution.w2_dist`: an opening that
reads narrower is W2 by the planner's rule, so what lies behind it is out of the sensor's
reach, not the planner's); then which cases meet the issue's targets.
"""
from __future__ import annotations

import math

__all__ = ["summarise", "markdown", "per_case", "verdicts", "coverage_target"]


def summarise(rows) -> list[dict]:
    """One summary per (group, noise, taxel)."""
    keyed = {}
    for r in rows:
        if "error" not in r:
            keyed.setdefault((r["group"], r["noise"], r["taxel"]), []).append(r)
    out = []
    for (g, noise, taxel), rs in sorted(keyed.items()):
        def total(num, den):
            d = sum(r[den] for r in rs)
            return sum(r.get(num, math.nan) for r in rs) / d if d > 0 else 1.0
        base = sum(r["motions"] / r["ratio"] for r in rs)
        out.append({
            "group": g, "noise": noise, "taxel": taxel, "slices": len(rs),
            "reads": max(int(r.get("reads", 1)) for r in rs),  # 1: a CSV from before --reads
            "coverage": total("covered_length", "reachable_length"),
            "coverage_sensor": total("covered_length_sensor", "reachable_length"),
            "cov_sensor_min": min(r["coverage_sensor"] for r in rs),
            "w2_credit_sensor": total("w2_credit_length_sensor", "reachable_length"),
            "resolved_sensor": total("covered_resolvable_length_sensor", "resolvable_length"),
            "resolved_sensor_min": min(r["coverage_resolvable_sensor"] for r in rs),
            "band_sensor": _band(rs),
            "band_sensor_min": min((b for b in map(_band, ([r] for r in rs)) if _known(b)),
                                   default=math.nan),
            "precision": total("precise_length", "detected_length"),
            "precision_sensor": total("precise_length_sensor", "detected_length"),
            "prec_sensor_min": min(r["precision_sensor"] for r in rs),
            "lids": sum(r["w3_count"] for r in rs),
            "unsound": sum(r["w3_unsound_count"] for r in rs),
            "unsound_sensor": sum(r["w3_unsound_count_sensor"] for r in rs),
            "motions": sum(r["motions"] for r in rs),
            "ratio": sum(r["motions"] for r in rs) / max(base, 1),
            "ratio_max": max(r["ratio"] for r in rs),
            "budget": sum(bool(r["budget_hit"]) for r in rs),
        })
    return out


def markdown(summary) -> str:
    """The summary as a markdown table."""
    rows = ["| group | noise (eps) | taxel (eps) | reads | slices | coverage eps/2 | coverage eps/2+2σ "
            "(min) | of it behind W2 chords | over the part eps resolves (min) | over the part "
            "eps + jitter resolves (min) | precision eps/2 "
            "| precision eps/2+2σ (min) | W3 lids | unsound eps/2 | unsound eps/2+2σ | motions "
            "| × noiseless (max) | budget hits |", "|" + "---|" * 18]
    for s in summary:
        rows.append(
            f"| {s['group']} | {s['noise']:g} | {s['taxel']:g} | {s['reads']} | {s['slices']} | "
            f"{s['coverage']:.4f} | {s['coverage_sensor']:.4f} ({s['cov_sensor_min']:.4f}) | "
            f"{_credit(s)} | "
            f"{s['resolved_sensor']:.4f} ({s['resolved_sensor_min']:.4f}) | "
            f"{_figure(s['band_sensor'])} ({_figure(s['band_sensor_min'])}) | "
            f"{s['precision']:.4f} | {s['precision_sensor']:.4f} ({s['prec_sensor_min']:.4f}) | "
            f"{s['lids']} | {s['unsound']} | {s['unsound_sensor']} | {s['motions']} | {s['ratio']:.2f} "
            f"({s['ratio_max']:.2f}) | {s['budget']} |")
    return "\n".join(rows)


def _band(rs) -> float:
    """Coverage within eps/2 + 2 sigma over the reachable contour a disc of diameter
    eps + jitter reaches (the sensor's stated W2 distance,
    :attr:`~core2d.resolution.Resolution.w2_dist`: openings that read narrower are W2 by
    the planner's rule), length weighted over ``rs``; NaN for rows of a CSV written before
    the column existed."""
    rs = [r for r in rs if _known(r.get("band_length"))]
    if not rs:
        return math.nan
    d = sum(r["band_length"] for r in rs)
    return sum(r["covered_band_length_sensor"] for r in rs) / d if d > 0 else 1.0


def _known(v) -> bool:
    """Neither None nor NaN (a CSV cell the row's writer did not fill)."""
    return v is not None and v == v


def _figure(v) -> str:
    """A share with four decimals, '-' for NaN or None (a column an older CSV lacks)."""
    return f"{v:.4f}" if _known(v) else "-"


def _credit(s: dict) -> str:
    """The share of the reachable contour counted covered only because it lies behind a
    W2 chord (never within eps/2 + 2 sigma of W1 or W2: the walls of a slot the chord
    closed); '-' for rows of a CSV written before the column existed."""
    return _figure(s.get("w2_credit_sensor"))


def per_case(rows) -> list[dict]:
    """One line per (group, case, noise, taxel): a scene or mesh over its slices (``name``
    before ``:z``), an outline alone; coverage and precision length weighted, motions over
    the noiseless run's."""
    keyed = {}
    for r in rows:
        if "error" not in r:
            name = r["name"].split(":")[0] + (f" (sensor seed +{1000 * r['repeat']})"
                                               if r.get("repeat") else "")
            keyed.setdefault((r["group"], name, r["noise"], r["taxel"]), []).append(r)
    out = []
    for (g, name, noise, taxel), rs in keyed.items():
        def total(num, den):
            d = sum(r[den] for r in rs)
            return sum(r.get(num, math.nan) for r in rs) / d if d > 0 else 1.0
        base = sum(r["motions"] / r["ratio"] for r in rs)
        out.append({"group": g, "case": name, "noise": noise, "taxel": taxel,
                    "coverage_sensor": total("covered_length_sensor", "reachable_length"),
                    "w2_credit_sensor": total("w2_credit_length_sensor", "reachable_length"),
                    "resolved_sensor": total("covered_resolvable_length_sensor",
                                             "resolvable_length"),
                    "band_sensor": _band(rs),
                    "precision_sensor": total("precise_length_sensor", "detected_length"),
                    "ratio": sum(r["motions"] for r in rs) / max(base, 1),
                    "budget": sum(bool(r["budget_hit"]) for r in rs)})
    return out


def verdicts(rows) -> str:
    """Per sensor level with a coverage target: how many cases meet each target, and the
    cases that miss one (their figures). The coverage over the part eps + jitter resolves
    is counted too but judges no case: it tells a miss behind openings the sensor reads as
    W2 from one elsewhere."""
    cases_ = per_case(rows)
    unit = "case runs (cases x sensor seeds)" if any(r.get("repeat") for r in rows) else "cases"
    lines = []
    for noise, taxel in sorted({(c["noise"], c["taxel"]) for c in cases_}):
        target = coverage_target(noise, taxel)
        if target is None:
            continue
        cs = [c for c in cases_ if (c["noise"], c["taxel"]) == (noise, taxel)]
        checks = {"coverage": lambda c: c["coverage_sensor"] >= target,
                  "coverage over the part eps resolves": lambda c: c["resolved_sensor"] >= target,
                  "precision >= 0.98": lambda c: c["precision_sensor"] >= 0.98,
                  "motions <= 2 x noiseless": lambda c: c["ratio"] <= 2.0,
                  "no budget hit": lambda c: c["budget"] == 0}
        counted = {**checks, "coverage over the part eps + jitter resolves (counted only)":
                   lambda c: c["band_sensor"] >= target}
        lines.append(f"sigma {noise:g} eps, taxel {taxel:g} eps (coverage target {target}), "
                     f"{len(cs)} {unit}: " + "; ".join(
                         f"{k} {sum(f(c) for c in cs)}" for k, f in counted.items()))
        for c in sorted(cs, key=lambda c: (c["group"], c["case"])):
            missed = [k for k, f in checks.items() if not f(c)]
            if missed:
                lines.append(f"  {c['group']} {c['case']}: coverage {c['coverage_sensor']:.4f} "
                             f"(behind W2 chords {_credit(c)}), "
                             f"over the part eps resolves {c['resolved_sensor']:.4f}, over the "
                             f"part eps + jitter resolves {_figure(c['band_sensor'])}, precision "
                             f"{c['precision_sensor']:.4f}, motions x{c['ratio']:.2f}, budget "
                             f"hits {c['budget']} (misses: {', '.join(missed)})")
    return "\n".join(lines)


def coverage_target(noise: float, taxel: float) -> float | None:
    """The reachable coverage (within eps/2 + 2 sigma) a sensor level is to reach: 0.99 at
    sigma 0.1 eps, 0.98 at sigma 0.3 eps with taxels 0.25 eps; None where none is set.

    >>> coverage_target(0.1, 0), coverage_target(0.3, 0.25), coverage_target(1, 0)
    (0.99, 0.98, None)
    """
    return {(0.1, 0.0): 0.99, (0.3, 0.25): 0.98}.get((float(noise), float(taxel)))
