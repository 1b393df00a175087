"""One sensing worker's share of a large run, phase by phase, in CPU seconds.

Cuts ``--slices`` z-planes of a mesh of ``../shared/meshes`` subdivided twice (as
:mod:`bench.bench_large` does), then, in one process per checkout, senses and scores
the planes ``--take`` (every 8th by default) with
:meth:`recon3d.sensing.worker.WorkerState.sense` -- exactly what a worker of
``recon3d run FILE --slices N`` does per slice -- and adds up the CPU seconds of
each phase: the contact model's build (``contact``: the plane cut and the Embree
scene), ``core2d.sense_slice``, core2d's ground truth (``reachable_samples``,
``slice_metrics``, ``_covered``), ``on_holes`` and the two documents
(``slice_rows``, ``slice_document``). One slice is sensed first, untimed (kernels
loaded from numba's cache). ``--before REV`` runs the files of commit ``REV`` too,
the two alternating ``--repeat`` times; the answers of both (``sensing.json`` entry,
metrics, motion rows, contour samples) are compared.

    python -m bench.worker_share [--mesh vtk_42400-IDGH.stl] [--slices 64]
                                 [--take 0,8,...] [--before REV] [--repeat 1]
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PHASES = ("contact", "sense_slice", "reachable_samples", "slice_metrics", "_covered",
          "on_holes", "slice_rows", "slice_document")
_CHILD = r"""
import hashlib, json, sys, time
import numpy as np, trimesh
import recon3d.sensing.mesh as rm
import recon3d.sensing.worker as W
from recon3d.config import RunConfig
mesh_path, slices, take = sys.argv[1], int(sys.argv[2]), [int(k) for k in sys.argv[3].split(",")]
got = {}
class _Stop(Exception):
    pass
def _catch(mesh, cuts, settings, tasks, jobs, progress=None, beside=None):
    got.update(cuts=cuts, settings=settings)
    raise _Stop
rm.sense_all = _catch
try:
    rm.sense_mesh(trimesh.load(mesh_path, force="mesh"), "m", RunConfig(slices=slices, jobs=2))
except _Stop:
    pass
state = W.WorkerState(got["settings"], got["cuts"])
cpu = {}
def timed(owner, name, key):
    fn = getattr(owner, name)
    def wrapper(*a, **k):
        t = time.process_time()
        try:
            return fn(*a, **k)
        finally:
            cpu[key] = cpu.get(key, 0.0) + time.process_time() - t
    setattr(owner, name, wrapper)
state.sense(0, take[-1])  # untimed: kernels from the cache
for name in ("reachable_samples", "slice_metrics", "_covered", "on_holes", "slice_rows",
             "slice_document"):
    timed(W, name, name)
timed(W.core2d, "sense_slice", "sense_slice")
timed(type(got["cuts"][0][0]), "contact", "contact")
digest = hashlib.sha256()
t0 = time.process_time()
for k in take:
    run = state.sense(0, k)
    doc = run.document
    doc.get("stats", {}).pop("seconds", None)
    metrics = {m: v for m, v in run.metrics.items() if "second" not in m}
    digest.update(json.dumps([doc, metrics], sort_keys=True, default=str).encode())
    digest.update(run.motion_rows.encode())
    for arr in (run.truth.points, run.truth.reachable, run.truth.covered):
        digest.update(np.ascontiguousarray(arr).tobytes())
cpu["total"] = time.process_time() - t0
print(json.dumps({"cpu": cpu, "digest": digest.hexdigest()}))
"""


def share(root: Path, mesh: Path, slices: int, take: list) -> dict:
    """Phase CPU seconds of ``take`` with the files under ``root``, and a digest of the answers."""
    env = dict(os.environ, PYTHONPATH=str(root))
    proc = subprocess.run([sys.executable, "-c", _CHILD, str(mesh), str(slices),
                           ",".join(map(str, take))], cwd=str(root), env=env,
                          capture_output=True, text=True)
    if proc.returncode != 0:
        raise SystemExit(f"worker share failed ({root}):\n{proc.stderr[-2000:]}")
    return json.loads(proc.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--mesh", default="vtk_42400-IDGH.stl", help="file of ../shared/meshes")
    p.add_argument("--slices", type=int, default=64, help="z-planes cut (default 64)")
    p.add_argument("--take", help="planes sensed, comma-separated (default every 8th)")
    p.add_argument("--before", help="commit to compare with")
    p.add_argument("--repeat", type=int, default=1, help="runs per checkout (median shown)")
    args = p.parse_args(argv)
    from bench.bench_large import SHARED, subdivided
    from bench.bench_sensing import export

    if not (SHARED / args.mesh).is_file():
        p.error(f"not in {SHARED}: {args.mesh}")
    take = ([int(k) for k in args.take.split(",")] if args.take
            else list(range(0, args.slices, 8)))
    if not take or min(take) < 0 or max(take) >= args.slices:
        p.error(f"--take: planes 0 .. {args.slices - 1}")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        roots = [("after", ROOT)]
        if args.before:
            roots.insert(0, ("before", export(args.before, tmp)))
        print(f"subdividing {args.mesh} ...", file=sys.stderr, flush=True)
        mesh, faces = subdivided(args.mesh, tmp)
        runs = {tag: [] for tag, _ in roots}
        for r in range(args.repeat):
            for tag, root in roots:
                print(f"run {r + 1}/{args.repeat}: {tag}", file=sys.stderr, flush=True)
                runs[tag].append(share(root, mesh, args.slices, take))
    med = {tag: {k: sorted(x["cpu"].get(k, 0.0) for x in rs)[len(rs) // 2]
                 for k in (*PHASES, "total")} for tag, rs in runs.items()}
    print(f"{args.mesh} ({faces} faces), {len(take)} of {args.slices} z-planes, CPU s "
          f"(median of {args.repeat})")
    tags = [t for t, _ in roots]
    print(f"{'phase':20s}" + "".join(f"{t:>10s}" for t in tags) + ("   after/before" if
                                                                    args.before else ""))
    for k in (*PHASES, "total"):
        line = f"{k:20s}" + "".join(f"{med[t][k]:10.2f}" for t in tags)
        if args.before and med["before"][k] > 0:
            line += f"   {med['after'][k] / med['before'][k]:8.2f}"
        print(line)
    if args.before:
        same = {x["digest"] for rs in runs.values() for x in rs}
        print("answers:", "identical" if len(same) == 1 else "DIFFERENT")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
