"""The point-to-mesh distances of the scores: the hierarchy's build and its queries, two commits.

For each commit (exported with ``git archive``; ``WORKTREE`` is this checkout as it is) a
fresh process builds the distance hierarchy of a mesh (``recon3d.score.closest._build``,
as :func:`recon3d.score.closest.mesh_distances` does) ``--repeat`` times and queries it with
points near the surface (the mesh's vertices moved by 1e-3 of its diagonal, seeded), after
one untimed call of each (numba's cache loaded). It prints the CPU seconds of one build and
of one query (medians), the ratio against the first commit, and whether every commit gave the
same distances, bit for bit.

The default mesh is the large mesh of :mod:`bench.bench_large` (``vtk_42400-IDGH.stl`` of
``../shared/meshes`` subdivided twice, 176,576 faces); without ``../shared``, the built-in
``gear`` subdivided twice.

    python -m bench.bench_distances [COMMIT ...] [--repeat 5] [--mesh FILE]
    python -m bench.bench_distances e7398f1 WORKTREE
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from bench.bench_compile import WORKTREE, _tree
from bench.bench_large import SHARED, subdivided

ROOT = Path(__file__).resolve().parents[1]

_SCRIPT = r"""
import json, sys, time
import numpy as np, trimesh
from recon3d.score import closest
mesh = trimesh.load(sys.argv[1], force="mesh", process=False)
repeat, out = int(sys.argv[2]), sys.argv[3]
tri = np.ascontiguousarray(mesh.vertices[mesh.faces], dtype=np.float64)
rng = np.random.default_rng(0)
pts = mesh.vertices + rng.normal(0.0, 1e-3 * float(np.linalg.norm(np.ptp(mesh.vertices, axis=0))),
                                 mesh.vertices.shape)
closest._query(pts[:10], tri, *closest._build(tri[:100]))  # numba's cache loaded
build, query = [], []
for _ in range(repeat):
    t = time.process_time()
    tree = closest._build(tri)
    build.append(time.process_time() - t)
    t = time.process_time()
    d = closest._query(pts, tri, *tree)
    query.append(time.process_time() - t)
np.save(out, d)
print(json.dumps({"faces": len(tri), "points": len(pts), "build": float(np.median(build)),
                  "query": float(np.median(query))}))
"""


def _mesh(path: str | None, tmp: Path) -> Path:
    if path:
        return Path(path)
    if (SHARED / "vtk_42400-IDGH.stl").is_file():
        return subdivided("vtk_42400-IDGH.stl", tmp)[0]
    import meshes

    out = tmp / "gear_x16.ply"
    meshes.load("gear").subdivide().subdivide().export(out)
    return out


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m bench.bench_distances",
                                description=__doc__.splitlines()[0])
    p.add_argument("commits", nargs="*", default=[WORKTREE],
                   help=f"commits to compare, the first the reference ({WORKTREE}: this checkout)")
    p.add_argument("--repeat", type=int, default=5, help="builds and queries per commit")
    p.add_argument("--mesh", default=None, help="a mesh file instead of the default")
    args = p.parse_args(argv)
    if args.repeat < 1:
        p.error("--repeat is at least 1")
    if args.mesh and not Path(args.mesh).is_file():
        p.error(f"no such mesh file: {args.mesh}")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        mesh = _mesh(args.mesh, tmp)
        for k, commit in enumerate(args.commits):
            label, src = _tree(commit, tmp)
            out = tmp / f"d{k}.npy"
            proc = subprocess.run([sys.executable, "-c", _SCRIPT, str(mesh), str(args.repeat),
                                   str(out)], cwd=src, capture_output=True, text=True,
                                  env=dict(os.environ, PYTHONPATH=str(src)))
            if proc.returncode:
                print(f"{label}: failed: {proc.stderr.strip().splitlines()[-1:]}")
                return 1
            rows.append((label, json.loads(proc.stdout.strip().splitlines()[-1]), out.read_bytes()))
    ref = rows[0][1]
    print(f"mesh {mesh.name}: {ref['faces']} faces, {ref['points']} query points; "
          f"CPU s, median of {args.repeat}")
    print("| commit | build s | query s | build / first | query / first | same distances |")
    print("|---|---|---|---|---|---|")
    for label, r, data in rows:
        print(f"| {label} | {r['build']:.3f} | {r['query']:.3f} | "
              f"{r['build'] / ref['build']:.2f} | {r['query'] / ref['query']:.2f} | "
              f"{'yes' if data == rows[0][2] else 'NO'} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
