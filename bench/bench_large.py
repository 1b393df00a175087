"""Large meshes end to end: ``recon3d run`` on ~100k-face meshes, 16 / 32 / 64 slices.

Each mesh of ``../shared/meshes`` given is subdivided twice (x16 faces, still
watertight) and run with ``recon3d run FILE --slices N --jobs J --no-png``:
sense, reconstruct, score and write. Per run it prints the wall seconds
(the whole command, imports included), the CPU seconds of the command and
its workers, wall seconds per slice (time should grow about linearly with
the slices), the peak resident memory of the main process and of the
largest worker, and the 2D coverage, precision and W3 soundness.

With ``--before REV`` the same runs are made first with the files of commit
``REV`` (``git archive`` into a temporary directory, run from there), side
by side, and the table adds their wall and CPU seconds, the speed-up and whether
both wrote the same ``metrics.json`` and ``sensing.json`` (timing fields aside).
The load average is printed before and after the runs.
Each checkout senses a small slice once before timing, so compiled kernels are
loaded from their cache, not built.

    python -m bench.bench_large [--meshes mujoco_spot.ply,trimesh_fandisk.obj]
                                [--slices 16,32,64] [--jobs 2] [--before REV]
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SHARED = ROOT.parent / "shared" / "meshes"
DEFAULT = ("mujoco_spot.ply", "trimesh_fandisk.obj", "ravens_cup.ply", "vtk_42400-IDGH.stl")
_RUN = """
import json, resource, sys
from recon3d.cli import main
code = main(sys.argv[1:])
mib = lambda who: resource.getrusage(who).ru_maxrss / 1024.0
print(json.dumps({"code": code, "main_mib": mib(resource.RUSAGE_SELF),
                  "worker_mib": mib(resource.RUSAGE_CHILDREN)}))
"""


def subdivided(name: str, into: Path) -> tuple[Path, int]:
    """``name`` from ../shared/meshes subdivided twice, written as PLY; its face count."""
    import trimesh

    mesh = trimesh.load(SHARED / name, force="mesh").subdivide().subdivide()
    path = into / (Path(name).stem + "_x16.ply")
    mesh.export(path)
    return path, len(mesh.faces)


def run(root: Path, mesh: Path, slices: int, jobs: int, out: Path) -> dict:
    """One ``recon3d run`` with the files under ``root``: times, memory, metrics."""
    env = dict(os.environ, PYTHONPATH=str(root))
    args = [str(mesh), "--slices", str(slices), "--jobs", str(jobs), "--no-png", "--quiet",
            "--out", str(out)]
    before = os.times()
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", _RUN, "run", *args], cwd=str(root), env=env,
                          capture_output=True, text=True)
    wall = time.perf_counter() - t0
    after = os.times()
    if proc.returncode != 0:
        raise SystemExit(f"recon3d run failed ({root}):\n{proc.stderr[-2000:]}")
    mem = json.loads(proc.stdout.strip().splitlines()[-1])
    metrics = json.loads((out / "metrics.json").read_text())
    sensing = json.loads((out / "sensing.json").read_text())
    cpu = (after.children_user - before.children_user) + (after.children_system -
                                                          before.children_system)
    return dict(wall=wall, cpu=cpu, main_mib=mem["main_mib"], worker_mib=mem["worker_mib"],
                metrics=metrics, sensing=sensing)


def _same(a: dict, b: dict) -> bool:
    """``metrics.json`` and ``sensing.json`` of two runs equal, timing fields aside."""
    sys.path.insert(0, str(ROOT))
    from recon3d.io import without_timing

    return all(without_timing(a[k]) == without_timing(b[k]) for k in ("metrics", "sensing"))


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--meshes", default=",".join(DEFAULT),
                   help="files of ../shared/meshes, comma-separated")
    p.add_argument("--slices", default="16,32,64", help="slice counts (default 16,32,64)")
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--before", help="commit to compare with, side by side")
    args = p.parse_args(argv)
    if not SHARED.is_dir():
        p.error(f"{SHARED} not found: this benchmark needs the shared meshes")
    names = [m for m in args.meshes.split(",") if m]
    missing = [m for m in names if not (SHARED / m).is_file()]
    if missing:
        p.error(f"not in {SHARED}: {', '.join(missing)}")
    counts = [int(s) for s in args.slices.split(",")]
    from bench.bench_sensing import export

    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        roots = [("after", ROOT)]
        if args.before:
            roots.insert(0, ("before", export(args.before, tmp)))
        files = [(name, *subdivided(name, tmp)) for name in names]
        for _, root in roots:  # load (or build) every compiled kernel before timing
            run(root, files[0][1], 4, 1, tmp / "warm")
        print(f"load average at the start: {_load()}", flush=True)
        print(f"{'mesh':22s} {'faces':>7s} {'slices':>6s} {'wall s':>7s} {'cpu s':>7s} "
              f"{'wall/slice':>10s} {'MiB main/worker':>16s} {'coverage':>8s} {'prec.':>6s} "
              f"{'W3 sound':>8s}" + ("  before s  cpu s  speed-up  same" if args.before else ""),
              flush=True)
        for name, path, faces in files:
            for n in counts:
                res = {tag: run(root, path, n, args.jobs, tmp / f"{tag}-{n}")
                       for tag, root in roots}
                a, t = res["after"], res["after"]["metrics"]["total"]
                line = (f"{name:22s} {faces:7d} {n:6d} {a['wall']:7.1f} {a['cpu']:7.1f} "
                        f"{a['wall'] / n:10.2f} {a['main_mib']:7.0f}/{a['worker_mib']:<8.0f} "
                        f"{t['coverage']:8.4f} {t['precision']:6.4f} {t['w3_soundness']:8.4f}")
                if args.before:
                    b = res["before"]
                    line += (f"  {b['wall']:8.1f} {b['cpu']:6.1f} {b['wall'] / a['wall']:8.2f}x  "
                             f"{'yes' if _same(b, a) else 'NO'}")
                print(line, flush=True)
        print(f"load average at the end: {_load()}", flush=True)
    return 0


def _load() -> str:
    """The 1, 5 and 15 minute load averages (the runs share the machine with them)."""
    return " / ".join(f"{x:.1f}" for x in os.getloadavg())


if __name__ == "__main__":
    raise SystemExit(main())
