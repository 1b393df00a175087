"""Between-slice surfaces and the fusion of families: before and after, per case.

For every case (the built-in scenes, two constructed thin shapes and the meshes of
``../shared/meshes``) the mesh is sensed once along each of z, x and y (``--slices`` planes
each, default eps); from the same sensing the surface is rebuilt

* **before** -- plain shape-based interpolation between slices (``route='linear'``) and the
  space-carving fusion (``fusion='carve'``),
* **after** -- the aligned interpolation (``route='warp'``, space only closed by unknown
  chords or bridges ending at its slice: :mod:`recon3d.surface.caps`) and the
  confidence-weighted fusion (``fusion='weighted'``),

for z, x and y alone and z+x, and scored with recon3d's own metrics
(:func:`recon3d.score.evaluate.surface_metrics`): slab share (ground truth scored), reachable
and resolvable shares (as shares of all the ground truth), F@1% over all scored ground truth,
over its reachable part and over the part eps resolves (no opening narrower than eps:
:mod:`core2d.truth.resolvable`), reconstruction seconds (CPU of this process: the machine is
shared). The z+x surface is built from the z-alone and x-alone sensing (what the two single
runs saw). The verdicts take the best single axis of the three by F@1% over all scored
ground truth (what a user would slice along), and z+x against the better of z and x.

Run from the repository root::

    python -m bench.bench_surface [--quick] [--slices 16] [--cases a,b] [--cache DIR]

``--quick``: four cases. ``--cache`` keeps the sensing (pickles) between runs.
``--axes z,x``: the single axes sensed (default z,x,y; z and x are always sensed, for z+x).
Prints the commit and a markdown table.
"""
from __future__ import annotations

import argparse
import pickle
import subprocess
import time
from pathlib import Path

import numpy as np
import trimesh

import meshes
from recon3d.api import load_input
from recon3d.config import validate
from recon3d.records import MeshRun
from recon3d.score.evaluate import Domain, GroundTruthSamples, contour_cloud, surface_metrics
from recon3d.sensing import sense_mesh
from recon3d.spellings import make_config
from recon3d.surface import reconstruct

SHARED = Path(__file__).resolve().parents[2] / "shared" / "meshes"
QUICK = ("fig18_overhangs", "bored_block", "cup_handle", "tilted_wall")
ROUTES = {"before": ("linear", "carve"), "after": ("warp", "weighted")}
AXES = ("z", "x", "y")


def tilted_wall(thickness: float = 1.0, size: float = 60.0, angle: float = 45.0
                ) -> trimesh.Trimesh:
    """A thin slab tilted about x: its z-section moves ~2.6 x its width between 16 slices."""
    m = trimesh.creation.box((size, size, thickness))
    m.apply_transform(trimesh.transformations.rotation_matrix(np.radians(angle), [1, 0, 0]))
    return m


def tilted_ring(major: float = 25.0, minor: float = 1.5, angle: float = 60.0
                ) -> trimesh.Trimesh:
    """A thin torus tilted about x (genus 1): z-slices cut it in two small moving blobs."""
    m = trimesh.creation.torus(major, minor, major_sections=128, minor_sections=24)
    m.apply_transform(trimesh.transformations.rotation_matrix(np.radians(angle), [1, 0, 0]))
    return m


CONSTRUCTED = {"tilted_wall": tilted_wall, "tilted_ring": tilted_ring}


def cases(arg: str | None, quick: bool) -> list[str]:
    """Case names: scenes, constructed shapes, then the shared meshes found."""
    if arg:
        return arg.split(",")
    if quick:
        return list(QUICK)
    shared = sorted(p.name for p in SHARED.glob("*") if p.suffix in (".stl", ".ply", ".obj"))
    if not shared:
        print(f"note: {SHARED} not found or empty: its meshes are skipped", flush=True)
    return meshes.names() + list(CONSTRUCTED) + shared


def source(name: str):
    """What ``load_input`` takes for a case name."""
    if name in CONSTRUCTED:
        return CONSTRUCTED[name]()
    return str(SHARED / name) if (SHARED / name).is_file() else name


def sensed(name: str, axis: str, slices: int, jobs: int, cache: Path | None) -> MeshRun:
    """One family sensed (from the cache when there)."""
    path = cache / f"{name}@{axis}{slices}.pkl" if cache else None
    if path is not None and path.is_file():
        with open(path, "rb") as fh:
            return pickle.load(fh)
    config = make_config(axis=axis, slices=slices, jobs=jobs)
    mesh, label, _ = load_input(source(name))
    validate(mesh, config)
    run = sense_mesh(mesh, label, config)
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        with open(path, "wb") as fh:
            pickle.dump(run, fh)
    return run


def scores(run: MeshRun, surface: trimesh.Trimesh) -> dict:
    """Slab share, reachable share, F@1% all / reachable of a surface of ``run``'s families."""
    fams = run.families
    dom = Domain(np.array([f.normal for f in fams]).reshape(-1, 3),
                 np.array([min(s.slice.plane.offset for s in f.slices) for f in fams]),
                 np.array([max(s.slice.plane.offset for s in f.slices) for f in fams]))
    gt = GroundTruthSamples(run.mesh, dom)
    m, extra = surface_metrics(surface, gt, contour_cloud(fams))
    return {"slab": len(gt.points) / gt.drawn, "reach": extra["reachable_share"],
            "resolv": extra["resolvable_share"], "f1": m["fscore"]["1%"],
            "f1r": m["reachable"]["fscore"]["1%"], "f1v": m["resolvable"]["fscore"]["1%"]}


def case_rows(name: str, slices: int, jobs: int, cache: Path | None,
              axes: tuple[str, ...] = AXES) -> list[dict]:
    """Rows of one case: per (each axis, z+x) x (before, after)."""
    single = {a: sensed(name, a, slices, jobs, cache) for a in dict.fromkeys(("z", "x") + axes)}
    z, x = single["z"], single["x"]
    both = MeshRun(z.name, z.mesh, z.config, z.eps, z.tol, z.probe_length,
                   z.families + x.families)
    rows = []
    for what, run in (*single.items(), ("z+x", both)):
        for when, (route, fusion) in ROUTES.items():
            t0 = time.process_time()
            recon = reconstruct(run, route, fusion)
            seconds = time.process_time() - t0
            rows.append(dict(case=name, what=what, when=when, seconds=seconds,
                             **scores(run, recon.surface)))
    return rows


def _f(v) -> str:
    return "n/a" if v is None else f"{v:.3f}"


HEADER = ("| case | surface | slab share | reachable share | resolvable share "
          "| F@1% all before | after | F@1% reachable before | after | F@1% resolvable after "
          "| s before | s after |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|")


def table(rows: list[dict]) -> str:
    """Markdown rows: one line per case and family set, before -> after."""
    out = []
    key = {(r["case"], r["what"], r["when"]): r for r in rows}
    for case in dict.fromkeys(r["case"] for r in rows):
        for what in dict.fromkeys(r["what"] for r in rows if r["case"] == case):
            b, a = key[(case, what, "before")], key[(case, what, "after")]
            out.append(f"| {case} | {what} | {b['slab']:.2f} | {_f(b['reach'])} "
                       f"| {_f(b['resolv'])} | {_f(b['f1'])} | {_f(a['f1'])} | {_f(b['f1r'])} "
                       f"| {_f(a['f1r'])} | {_f(a['f1v'])} | {b['seconds']:.1f} "
                       f"| {a['seconds']:.1f} |")
    return "\n".join(out)


def verdicts(rows: list[dict]) -> str:
    """The issue's targets over the 'after' rows."""
    key = {(r["case"], r["what"], r["when"]): r for r in rows}
    names = list(dict.fromkeys(r["case"] for r in rows))
    lines, best_all, fused_gap = [], [], []
    for c in names:
        singles = [r for r in rows if r["case"] == c and r["when"] == "after"
                   and r["what"] != "z+x"]
        z, x, zx = (key[(c, w, "after")] for w in ("z", "x", "z+x"))
        best = max(singles, key=lambda r: r["f1"] or 0)
        best_all.append((c, best["f1"], best["f1r"], best["f1v"], best["what"]))
        fused_gap.append((c, (zx["f1"] or 0) - (max(z["f1"] or 0, x["f1"] or 0))))
    worst_r = min(best_all, key=lambda t: t[2] or 0)
    worst_v = min(best_all, key=lambda t: t[3] or 0)
    by_reach = [max((r for r in rows if r["case"] == c and r["when"] == "after"
                     and r["what"] != "z+x"), key=lambda r: r["f1r"] or 0) for c in names]
    lines.append("best single axis per case: " + ", ".join(f"{t[0]} {t[4]}" for t in best_all))
    lines.append(f"best single axis: median F@1% all {np.median([t[1] for t in best_all]):.3f}"
                 f" (target >= 0.90); least F@1% reachable {worst_r[2]:.3f} ({worst_r[0]};"
                 f" target >= 0.95), below 0.95 in {sum((t[2] or 0) < 0.95 for t in best_all)}"
                 f" of {len(names)}; least F@1% over the part eps resolves {worst_v[3]:.3f}"
                 f" ({worst_v[0]}), below 0.95 in {sum((t[3] or 0) < 0.95 for t in best_all)}")
    low = min(by_reach, key=lambda r: r["f1r"] or 0)
    lines.append(f"the axis best over the reachable part instead: least F@1% reachable "
                 f"{low['f1r']:.3f} ({low['case']} {low['what']}), below 0.95 in "
                 f"{sum((r['f1r'] or 0) < 0.95 for r in by_reach)} of {len(names)}")
    worst = min(fused_gap, key=lambda t: t[1])
    lines.append(f"z+x minus the better of z and x: least {worst[1]:+.3f} ({worst[0]}); "
                 f"below -0.005 in {sum(g < -0.005 for _, g in fused_gap)} of {len(names)} "
                 "cases (target: none)")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.bench_surface", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help=f"only {', '.join(QUICK)}")
    ap.add_argument("--slices", type=int, default=16, help="planes per axis (default 16)")
    ap.add_argument("--cases", help="comma-separated case names")
    ap.add_argument("--jobs", type=int, default=1, help="sensing processes (default 1)")
    ap.add_argument("--cache", type=Path, help="directory keeping the sensing between runs")
    ap.add_argument("--axes", default=",".join(AXES),
                    help="single axes sensed, comma-separated (default z,x,y)")
    args = ap.parse_args(argv)
    axes = tuple(a for a in args.axes.split(",") if a)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, cwd=Path(__file__).parent).stdout.strip()
    print(f"bench_surface at commit {commit or 'unknown'}, {args.slices} slices per axis",
          flush=True)
    rows = []
    names = cases(args.cases, args.quick)
    print(HEADER, flush=True)
    for i, name in enumerate(names, 1):
        t0 = time.perf_counter()
        try:
            new = case_rows(name, args.slices, args.jobs, args.cache, axes)
        except (ValueError, RuntimeError) as err:  # e.g. an open mesh: say so, go on
            print(f"<!-- [{i}/{len(names)}] {name} skipped: {err} -->", flush=True)
            continue
        rows += new
        print(table(new), flush=True)
        print(f"<!-- [{i}/{len(names)}] {name} {time.perf_counter() - t0:.0f} s -->", flush=True)
    if rows:
        print(verdicts(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
