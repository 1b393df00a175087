"""The planner against ground truth: random outlines, built-in scenes, real meshes.

Runs :func:`core2d.sense_slice` on every case, scores it with
:func:`core2d.truth.metrics.slice_metrics`, and prints one row per group:
runs, minimum reachable coverage and precision, W3 lids and how many are
unsound (per-lid definition), budget hits, executed pushes and push
attempts, and motions per eps of reachable contour.

    python -m bench.bench_planner                      # outlines + scenes
    python -m bench.bench_planner --per-kind 50 --meshes --jobs 2 --json out.json

Cases: ``--per-kind`` seeded outlines of each kind of ``tests/outlines.py``
(eps 1, ~100 units across), the middle z-slices of every built-in scene,
``--meshes`` the slices of ``../shared/meshes`` (skipped when absent), and
``../shared/cases/*.json``. Nothing is asserted: it measures.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SHARED = ROOT.parent / "shared"
sys.path.insert(0, str(ROOT / "tests"))

KEYS = ("coverage", "precision", "w3_count", "w3_unsound_count", "w3_hidden_reachable_length",
        "w3_cross_loop", "budget_hit", "motions", "pushes", "push_attempts", "reachable_length",
        "unknown_count", "unknown_reachable_length", "eps", "seconds")


def _score(loops, result, eps, name, group) -> dict:
    from core2d.truth.metrics import slice_metrics

    m = slice_metrics(loops, result, eps)
    row = {k: m.get(k) for k in KEYS}
    row.update(name=name, group=group, loops=len(loops))
    return row


def _outline_case(kind, seed, budget, opts=None):
    from outlines import outline

    from core2d import sense_slice
    from slicer import ExactContact

    loops = outline(kind, np.random.default_rng(seed), 1.0)
    pts = np.concatenate(loops)
    lo, hi = pts.min(0), pts.max(0)
    ws = ((lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2 + 1.0))
    res = sense_slice(ExactContact(loops), ws, 1.0, max_motions=budget, **(opts or {}))
    return _score(loops, res, 1.0, f"{kind}-{seed}", f"outline:{kind}")


def _file_case(path, budget, opts=None):
    from core2d import sense_slice
    from slicer import ExactContact

    d = json.loads(Path(path).read_text())
    loops = [np.asarray(lp, float) for lp in d["loops"]]
    eps = float(d["eps"])
    pts = np.concatenate(loops)
    lo, hi = pts.min(0), pts.max(0)
    ws = ((lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2 + eps))
    res = sense_slice(ExactContact(loops), ws, eps, max_motions=budget, **(opts or {}))
    return _score(loops, res, eps, Path(path).stem, "cases")


def _mesh_case(source, axis, count, index, budget, group, opts=None):
    import meshes
    import slicer
    from core2d import sense_slice

    mesh = meshes.load(source)
    eps = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)) / 200)
    cut = slicer.slice_mesh(mesh, axis=axis, count=count)[index]
    if not cut.loops:
        return None
    center, radius = cut.bounding_circle()
    res = sense_slice(cut.contact("embree"), (center, radius + eps), eps, max_motions=budget,
                      **(opts or {}))
    loops = [np.asarray(lp) for lp in cut.loops]
    return _score(loops, res, eps, f"{Path(str(source)).name}:{axis}{index}/{count}", group)


def _cases(args):
    import meshes

    for kind in args.kinds:
        for seed in range(args.per_kind):
            yield _outline_case, (kind, seed, args.budget)
    for path in sorted((SHARED / "cases").glob("*.json")):
        yield _file_case, (str(path), args.budget)
    for name in meshes.names() if args.scenes else ():
        for i in range(args.slices):
            yield _mesh_case, (name, "z", args.slices, i, args.budget, f"scene:{name}")
    if args.meshes and (SHARED / "meshes").is_dir():
        for path in sorted((SHARED / "meshes").glob("*.*")):
            if path.suffix in (".stl", ".obj", ".ply"):
                for i in range(args.mesh_slices):
                    yield _mesh_case, (str(path), "z", args.mesh_slices, i, args.budget, "mesh:" + path.stem)


def _run(job):
    fn, a = job
    t0 = time.perf_counter()
    try:
        row = fn(*a)
    except Exception as exc:  # a crash is a finding, reported, not fatal
        return {"name": repr(a[:2]), "group": "CRASH", "error": f"{type(exc).__name__}: {exc}"}
    if row is not None:
        row["wall"] = time.perf_counter() - t0
    return row


def summarise(rows) -> list[dict]:
    """One summary per group (and one for all)."""
    groups = {}
    for r in rows:
        groups.setdefault(r["group"], []).append(r)
    out = []
    for g, rs in sorted(groups.items()) + [("ALL", [r for r in rows if "error" not in r])]:
        if g == "CRASH":
            out.append({"group": g, "runs": len(rs)})
            continue
        reach = sum(r["reachable_length"] for r in rs)
        out.append({
            "group": g, "runs": len(rs),
            "cov_min": min(r["coverage"] for r in rs),
            "cov_lt99": sum(r["coverage"] < 0.99 for r in rs),
            "prec_min": min(r["precision"] for r in rs),
            "lids": sum(r["w3_count"] for r in rs),
            "unsound": sum(r["w3_unsound_count"] for r in rs),
            "budget": sum(bool(r["budget_hit"]) for r in rs),
            "pushes": sum(r["pushes"] for r in rs),
            "attempts": sum(r.get("push_attempts") or 0 for r in rs),
            "motions": sum(r["motions"] for r in rs),
            "mot_per_eps": sum(r["motions"] for r in rs) / max(sum(
                r["reachable_length"] / r["eps"] for r in rs), 1e-9),
            "reach": reach,
            "wall": sum(r.get("wall", 0.0) for r in rs),
        })
    return out


def _print(summary):
    cols = ["group", "runs", "cov_min", "cov_lt99", "prec_min", "lids", "unsound", "budget",
            "pushes", "attempts", "motions", "mot_per_eps", "wall"]
    print("  ".join(f"{c:>10}" for c in cols))
    for s in summary:
        print("  ".join(f"{s.get(c, ''):>10.4f}" if isinstance(s.get(c), float) else
                        f"{str(s.get(c, '')):>10}" for c in cols))


def markdown(summary) -> str:
    """The summary as a markdown table (the README's results tables)."""
    head = ("| group | slices | coverage (min) | slices < 0.99 | precision (min) | W3 lids | unsound "
            "lids | pushes | push attempts | motions | motions / eps | budget hits |")
    rows = [head, "|" + "---|" * 12]
    for s in summary:
        if "cov_min" not in s:
            rows.append(f"| {s['group']} | {s['runs']} | crashed | | | | | | | | | |")
            continue
        rows.append(f"| {s['group'].replace(':', ' ')} | {s['runs']} | {s['cov_min']:.4f} | {s['cov_lt99']} | "
                    f"{s['prec_min']:.4f} | {s['lids']} | {s['unsound']} | {s['pushes']} | "
                    f"{s['attempts']} | {s['motions']} | {s['mot_per_eps']:.2f} | {s['budget']} |")
    return "\n".join(rows)


def add_case_arguments(p) -> None:
    """The flags that choose the case set (shared with ``bench.ablation``)."""
    p.add_argument("--per-kind", type=int, default=8, help="outlines per kind (default 8)")
    p.add_argument("--kinds", nargs="*", default=None, help="outline kinds (default all)")
    p.add_argument("--no-scenes", dest="scenes", action="store_false", help="skip built-in scenes")
    p.add_argument("--slices", type=int, default=3, help="z slices per built-in scene (default 3)")
    p.add_argument("--meshes", action="store_true", help="also ../shared/meshes")
    p.add_argument("--mesh-slices", type=int, default=8, help="z slices per real mesh (default 8)")
    p.add_argument("--budget", type=int, default=20000, help="motion budget per slice")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_case_arguments(p)
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--json", help="write every row to this file")
    p.add_argument("--markdown", action="store_true", help="print the summary as a markdown table")
    args = p.parse_args(argv)
    from outlines import KINDS

    args.kinds = args.kinds or list(KINDS)
    jobs = list(_cases(args))
    t0 = time.perf_counter()
    with ProcessPoolExecutor(args.jobs) as ex:
        rows = [r for r in ex.map(_run, jobs, chunksize=1) if r is not None]
    for r in rows:
        if "error" in r:
            print("CRASH", r["name"], r["error"])
    bad = [r for r in rows if "error" not in r and (
        r["coverage"] < 0.99 or r["w3_unsound_count"] or r["budget_hit"] or r["precision"] < 0.99)]
    for r in bad:
        print(f"  {r['name']:<40} cov {r['coverage']:.4f} prec {r['precision']:.4f} "
              f"lids {r['w3_count']} unsound {r['w3_unsound_count']} "
              f"hidden/eps {r['w3_hidden_reachable_length'] / r['eps']:.1f} "
              f"budget {r['budget_hit']} motions {r['motions']} loops {r['loops']}")
    summary = summarise(rows)
    _print(summary)
    if args.markdown:
        print(markdown(summary))
    print(f"{len(rows)} runs in {time.perf_counter() - t0:.0f} s")
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1, default=float))


if __name__ == "__main__":
    main()
