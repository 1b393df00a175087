"""The whole run against its sensing: ``recon3d run`` wall time over sensing wall time.

For every built-in scene (8 z-slices, ``--jobs 2``, the defaults otherwise, pictures
included) ``recon3d run`` runs in a fresh process; a small driver times the whole process
(from the parent: interpreter start-up, imports, sensing, reconstruction, scores, files,
pictures) and, inside it, the wall time of the sensing call alone
(:func:`recon3d.sensing.sense_mesh`: slices sensed and scored by the workers, the pool's
start included). Printed per scene: the medians over ``--repeat`` runs of both, of
their ratio (target: whole run <= 2 x sensing) and of the CPU seconds of the whole
process tree (workers and side processes included: on a loaded machine the wall
seconds vary, the CPU seconds hardly). The load average is printed at the start and
the end. Then ``import recon3d`` in a fresh
interpreter (target <= 0.5 s; ``-X importtime``, start-up excluded) and the 176k-face
mesh -- ``vtk_42400-IDGH.stl`` of ``../shared/meshes`` subdivided twice -- at 64 slices,
``--jobs 2 --no-png`` (target <= 15 s wall).

With ``--before REV`` the same measurements run on the files of ``REV`` too (``git
archive``, :func:`bench.compare_commits.export`), the two checkouts alternating run by
run, so both see the same machine; the table adds the before column and whether
``sensing.json`` and ``metrics.json`` of the two are identical (timing keys aside,
:func:`bench.compare_commits.compare`). Each checkout senses one small slice first, so
compiled kernels are loaded from their cache, not built, in the timed runs.

    python -m bench.bench_run [--quick] [--before REV] [--repeat 3] [--scenes a,b]

``--quick``: three scenes, one repetition, the large mesh at 16 slices. The large mesh runs
``--repeat`` times too (alternating with ``--before``; medians, and the pairwise ratio).
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from bench.bench_large import SHARED, subdivided
from bench.compare_commits import compare, export

ROOT = Path(__file__).resolve().parents[1]
QUICK = ("fig18_overhangs", "bowl", "gear")
LARGE = "vtk_42400-IDGH.stl"
TARGETS = {"ratio": 2.0, "import": 0.5, "large": 15.0}
"""The targets: whole run / sensing, ``import recon3d`` seconds, large-mesh wall seconds."""

_DRIVER = """
import json, sys, time
from recon3d.cli import main, run
getattr(run, "libraries", lambda: None)()  # the libraries loaded as `recon3d run` loads them
import recon3d.api as api
box = {"sense": 0.0}
inner = api.sense_mesh
def timed(*a, **k):
    t0 = time.perf_counter()
    try:
        return inner(*a, **k)
    finally:
        box["sense"] += time.perf_counter() - t0
api.sense_mesh = timed
code = main(sys.argv[1:])
print(json.dumps({"code": code, "sense": box["sense"]}))
import recon3d.cli.main as cli  # end as the console script ends (a checkout without it: exit)
getattr(cli, "end", sys.exit)(code)
"""


def _env(root: Path) -> dict:
    return dict(os.environ, PYTHONPATH=str(root), VTK_DEFAULT_OPENGL_WINDOW="vtkEGLRenderWindow")


def _children_cpu() -> float:
    """User + system CPU seconds of every finished child process (their own children too)."""
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def run_once(root: Path, source: str, out: Path, flags: list[str]) -> tuple[float, float, float]:
    """(whole-process wall s, sensing wall s, CPU s of the whole process tree) of one
    ``recon3d run`` with the files of ``root`` (the CPU seconds -- workers and side
    processes included -- hardly depend on what else the machine runs; the wall seconds do)."""
    cmd = [sys.executable, "-c", _DRIVER, "run", source, "--out", str(out), "--quiet", *flags]
    c0, t0 = _children_cpu(), time.perf_counter()
    proc = subprocess.run(cmd, cwd=str(root), env=_env(root), capture_output=True, text=True)
    wall, cpu = time.perf_counter() - t0, _children_cpu() - c0
    if proc.returncode != 0:
        raise SystemExit(f"bench_run: recon3d run {source} failed ({root}):\n"
                         f"{proc.stderr[-2000:]}")
    return wall, json.loads(proc.stdout.strip().splitlines()[-1])["sense"], cpu


def import_seconds(root: Path) -> float:
    """Cumulative ``import recon3d`` seconds in a fresh interpreter (``-X importtime``)."""
    proc = subprocess.run([sys.executable, "-X", "importtime", "-c", "import recon3d"],
                          cwd=str(root), env=_env(root), capture_output=True, text=True,
                          check=True)
    line = [ln for ln in proc.stderr.splitlines() if ln.rstrip().endswith("| recon3d")][-1]
    return int(line.split("|")[1]) / 1e6


def _load() -> str:
    """The 1, 5 and 15 minute load averages (other jobs on the machine)."""
    return " / ".join(f"{x:.1f}" for x in os.getloadavg())


def _median(values) -> float:
    return statistics.median(values) if values else float("nan")


def _flag(ok: bool) -> str:
    return "ok" if ok else "MISSED"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.bench_run", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="3 scenes, 1 repetition, large at 16")
    ap.add_argument("--before", help="commit to measure too, run by run alternating")
    ap.add_argument("--repeat", type=int, default=3, help="runs per scene and checkout")
    ap.add_argument("--scenes", help="comma-separated built-in scenes (default: all)")
    ap.add_argument("--slices", type=int, default=8, help="z-slices of the scenes (8)")
    ap.add_argument("--large-slices", type=int, default=None, help="slices of the large mesh "
                    "(64; --quick 16; 0 skips it)")
    args = ap.parse_args(argv)
    repeat = 1 if args.quick else args.repeat
    large_n = args.large_slices if args.large_slices is not None else (16 if args.quick else 64)
    if args.scenes:
        scenes = [s for s in args.scenes.split(",") if s]
    elif args.quick:
        scenes = list(QUICK)
    else:
        scenes = [ln.split("\t")[0] for ln in subprocess.run(
            [sys.executable, "-m", "recon3d", "scenes"], cwd=ROOT, env=_env(ROOT), check=True,
            capture_output=True, text=True).stdout.splitlines() if ln.strip()]
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                          text=True).stdout.strip()
    dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=ROOT,
                           capture_output=True, text=True).stdout.strip()
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        trees = [("after", ROOT)]
        if args.before:
            short, src = export(args.before, ROOT / "out" / "compare")
            trees.insert(0, (f"before {short}", src))
        print(f"after: commit {head}{' + uncommitted changes' if dirty else ''}"
              + (f"; {trees[0][0]}" if args.before else "")
              + f"; {args.slices} z-slices, --jobs 2, {repeat} run(s) each, medians; "
              f"load average {_load()}", flush=True)
        for tag, root in trees:  # compiled kernels loaded (or built) before timing
            run_once(root, scenes[0] if scenes else "fig18_overhangs", tmp / "warm",
                     ["--slices", "2", "--jobs", "1", "--no-png"])
        cols = f"{'scene':18s} {'run s':>6s} {'sense s':>7s} {'ratio':>6s} {'CPU s':>6s}"
        if args.before:
            cols += (f" | {'before run s':>12s} {'sense s':>7s} {'ratio':>6s} {'CPU s':>6s}"
                     f"  run speed-up  CPU ratio  same")
        print(cols, flush=True)
        ratios = []
        flags = ["--slices", str(args.slices), "--jobs", "2"]
        for scene in scenes:
            got = {tag: [] for tag, _ in trees}
            for r in range(repeat):
                for tag, root in (trees if r % 2 == 0 else trees[::-1]):
                    got[tag].append(run_once(root, scene, tmp / tag.split()[0] / scene, flags))
            med = {tag: (_median([w for w, _, _ in v]), _median([s for _, s, _ in v]),
                         _median([w / s for w, s, _ in v]), _median([c for _, _, c in v]))
                   for tag, v in got.items()}
            w, s, q, c = med["after"]
            ratios.append(q)
            line = f"{scene:18s} {w:6.2f} {s:7.2f} {q:5.1f}x {c:6.1f}"
            if args.before:
                bw, bs, bq, bc = med[trees[0][0]]
                same = compare(tmp / "before" / scene, tmp / "after" / scene)
                line += (f" | {bw:12.2f} {bs:7.2f} {bq:5.1f}x {bc:6.1f}  {bw / w:11.2f}x"
                         f"  {bc / c:8.2f}x  {same}")
            print(line, flush=True)
        if ratios:
            print(f"whole run / sensing: median {_median(ratios):.1f}x, worst {max(ratios):.1f}x "
                  f"(target <= {TARGETS['ratio']:.0f}x: {_flag(max(ratios) <= TARGETS['ratio'])})")
        for tag, root in trees:
            imp = _median([import_seconds(root) for _ in range(max(repeat, 3))])
            print(f"import recon3d ({tag}): {imp:.3f} s "
                  f"(target <= {TARGETS['import']}: {_flag(imp <= TARGETS['import'])})",
                  flush=True)
        if large_n and (SHARED / LARGE).is_file():
            path, faces = subdivided(LARGE, tmp)
            large = ["--slices", str(large_n), "--jobs", "2", "--no-png"]
            got = {tag: [] for tag, _ in trees}
            for r in range(repeat):  # alternating, as the scenes
                for tag, root in (trees if r % 2 == 0 else trees[::-1]):
                    got[tag].append(run_once(root, str(path), tmp / f"large-{tag.split()[0]}",
                                             large))
            for tag, _ in trees:
                w, s, c = (_median([x[i] for x in got[tag]]) for i in range(3))
                print(f"{LARGE} x16 ({faces:,} faces), {large_n} slices, --jobs 2 --no-png "
                      f"({tag}, median of {repeat}): {w:.1f} s wall, sensing {s:.1f} s, CPU "
                      f"{c:.1f} s (target <= {TARGETS['large']:.0f} s at 64: "
                      f"{_flag(w <= TARGETS['large']) if large_n == 64 else 'not at 64'})",
                      flush=True)
            if args.before:
                pairs = [a[0] / b[0] for a, b in zip(got["after"], got[trees[0][0]])]
                print(f"large mesh wall after / before, run by run: median {_median(pairs):.3f}")
                print(f"large mesh outputs: {compare(tmp / 'large-before', tmp / 'large-after')}")
        elif large_n:
            print(f"large mesh skipped: {SHARED / LARGE} not found")
        print(f"load average at the end: {_load()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
