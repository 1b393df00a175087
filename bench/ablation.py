"""What each of the planner's additions to Fig. 16 buys: the bench_planner set, one off at a time.

Runs the cases of :mod:`bench.bench_planner` (its case list and scoring,
unchanged) with the default planner (``pulling``), with the default minus
one addition of :class:`core2d.planner.flow.Flow` at a time, and with the
paper's Fig. 16 flow alone (``--method paper``). One row per variant:
slices, reachable coverage (minimum, mean weighted by the reachable contour
in eps, slices below 0.99), W3 lids and unsound lids, motions, budget hits, and how many
slices changed against the default (any of coverage, lids, motions).

    python -m bench.ablation --quick          # 2 outlines per kind, 1 slice per scene
    python -m bench.ablation --per-kind 8 --slices 3 --json out/ablation.json

Variants (``--variants`` picks a subset): ``pulling``; ``-covers`` (no map
closure of an area whose C_A^B was traced through other areas); ``-defer``
(deferral and revisits: a dead end is W3 at once, §4.2.1); ``-audit`` (no
registration of loose ends); ``-escape`` (§4.4's escape on the parent's A
and B only, not the whole ancestry nor stale generations); ``-w3_proof``
(Area(G_i) = 0 is W3 without the map's proof); ``paper``; ``paper +escape``
(the paper's flow with the escape over the whole ancestry). ``--decisions``
adds the paper's own decisions changed one at a time, under both flows
(:data:`DECISIONS`). Nothing is asserted: it measures.
"""
from __future__ import annotations

import argparse
import json
import subprocess
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import replace
from pathlib import Path

from bench.bench_planner import ROOT, _cases, _run, add_case_arguments
from core2d.planner.flow import PAPER, PULLING

__all__ = ["VARIANTS", "DECISIONS", "summary", "markdown", "main"]

VARIANTS = {
    "pulling": PULLING,
    "-covers": replace(PULLING, covers=False),
    "-defer": replace(PULLING, defer=False, revisit=False),
    "-audit": replace(PULLING, audit=False),
    "-escape": replace(PULLING, escape=False),
    "-w3_proof": replace(PULLING, w3_proof=False),
    "paper": PAPER,
    "paper +escape": replace(PAPER, escape=True),
}
"""Variant name -> Flow (the default minus one addition, or the paper's flow)."""

DECISIONS = {f"{name}{tag}": replace(base, **change)
             for name, base in (("pulling", PULLING), ("paper", PAPER))
             for tag, change in ((" -detection", {"detection": False}),
                                 (" -pair", {"pair": False}), (" lifo", {"lifo": True}),
                                 (" same=2eps", {"same": 4.0}))}
"""The paper's own decisions changed one at a time (``--decisions``): no single
probe detection (Fig. 6), no Case 2-1 (P_1st, P_2nd) (§4.3.3), areas last
registered first, the same-contact radius 2 eps instead of eps/2."""
ALL = {**VARIANTS, **DECISIONS}


def _job(job):
    variant, (fn, a) = job
    row = _run((fn, a + ({"flow": ALL[variant]},)))
    if row is not None:
        row["variant"] = variant
    return row


def summary(rows: list[dict], base: str = "pulling") -> list[dict]:
    """One summary per variant; ``changed`` counts slices differing from ``base``."""
    ref = {r["name"]: r for r in rows if r.get("variant") == base and "error" not in r}
    out = []
    for v in dict.fromkeys(r["variant"] for r in rows):
        rs = [r for r in rows if r["variant"] == v and "error" not in r]
        reach = sum(r["reachable_length"] / r["eps"] for r in rs)  # in eps: scale-free
        out.append({
            "variant": v, "runs": len(rs),
            "crashes": sum("error" in r for r in rows if r["variant"] == v),
            "cov_min": min(r["coverage"] for r in rs),
            "cov_mean": sum(r["coverage"] * r["reachable_length"] / r["eps"] for r in rs)
            / max(reach, 1e-12),
            "cov_lt99": sum(r["coverage"] < 0.99 for r in rs),
            "lids": sum(r["w3_count"] for r in rs),
            "unsound": sum(r["w3_unsound_count"] for r in rs),
            "unknown": sum(r["unknown_count"] for r in rs),
            "motions": sum(r["motions"] for r in rs),
            "budget": sum(bool(r["budget_hit"]) for r in rs),
            "changed": sum(r["name"] in ref and any(
                r[k] != ref[r["name"]][k] for k in ("coverage", "w3_count", "motions"))
                for r in rs),
        })
    return out


def markdown(rows: list[dict]) -> str:
    """The summary as the README's markdown table."""
    out = ["| variant | slices | coverage (min) | coverage (mean) | slices < 0.99 | W3 lids | "
           "unsound lids | unknown lids | motions | budget hits | slices changed |",
           "|" + "---|" * 11]
    for s in rows:
        out.append(f"| `{s['variant']}` | {s['runs']} | {s['cov_min']:.4f} | {s['cov_mean']:.4f} | "
                   f"{s['cov_lt99']} | {s['lids']} | {s['unsound']} | {s['unknown']} | "
                   f"{s['motions']} | "
                   f"{s['budget']} | {s['changed']} |")
    return "\n".join(out)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m bench.ablation", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--quick", action="store_true",
                   help="2 outlines per kind, 1 slice per scene (overrides --per-kind/--slices)")
    add_case_arguments(p)
    p.add_argument("--variants", default=",".join(VARIANTS),
                   help="comma-separated subset of " + ", ".join(ALL))
    p.add_argument("--decisions", action="store_true",
                   help="also every variant of DECISIONS (the paper's own decisions)")
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--json", help="write every row to this file")
    args = p.parse_args(argv)
    variants = [v.strip() for v in args.variants.split(",") if v.strip()]
    variants += list(DECISIONS) if args.decisions else []
    bad = [v for v in variants if v not in ALL]
    if bad or not variants:
        p.exit(2, f"ablation: unknown variants {bad} (known: {', '.join(ALL)})\n")
    if args.quick:
        args.per_kind, args.slices = 2, 1
    from outlines import KINDS  # bench_planner put tests/ on sys.path

    args.kinds = args.kinds or list(KINDS)
    cases = list(_cases(args))
    jobs = [(v, c) for c in cases for v in variants]
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                            capture_output=True, text=True).stdout.strip()
    print(f"{len(cases)} slices x {len(variants)} variants at {commit}", flush=True)
    t0 = time.perf_counter()
    rows = []
    with ProcessPoolExecutor(args.jobs) as ex:
        for k, r in enumerate(ex.map(_job, jobs, chunksize=1), 1):
            if r is not None:
                rows.append(r)
            if k % 20 == 0:
                print(f"  {k}/{len(jobs)} runs, {time.perf_counter() - t0:.0f} s", flush=True)
    for r in rows:
        if "error" in r:
            print("CRASH", r["variant"], r["name"], r["error"])
    print(markdown(summary(rows, variants[0])))
    print(f"{len(rows)} runs in {time.perf_counter() - t0:.0f} s")
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1, default=float))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
