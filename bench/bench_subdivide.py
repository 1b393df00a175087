"""The coloured ground truth's subdivision: trimesh's ``subdivide_to_size`` against
:func:`recon3d.score.subdivide.subdivide_to_size` (the same arrays, fewer faces looked at).

Per built-in scene, the mesh subdivided to the edge a run uses (2 x the grid step at
eps = diagonal / 200), both ways in one process, alternating; CPU seconds, median of
``--repeat``; "same arrays": vertices and faces equal.

    python -m bench.bench_subdivide [--scenes bored_block,gear] [--repeat 3]
"""
from __future__ import annotations

import argparse
import statistics
import time

import trimesh

import meshes
from recon3d.config import diagonal
from recon3d.score.subdivide import subdivide_to_size
from recon3d.surface.field import grid_step

DEFAULT = ("bored_block", "fig18_overhangs", "stepped_pyramid", "gear")


def _cpu(fn) -> tuple[float, object]:
    t = time.process_time()
    out = fn()
    return time.process_time() - t, out


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--scenes", default=",".join(DEFAULT), help="comma-separated scenes")
    p.add_argument("--repeat", type=int, default=3, help="runs per scene and way")
    args = p.parse_args(argv)
    print("| scene | faces after | trimesh s | here s | speed-up | same arrays |")
    print("|---|---|---|---|---|---|")
    for name in args.scenes.split(","):
        mesh = meshes.load(name)
        d = diagonal(mesh)
        edge = 2 * grid_step(d / 200, d)
        a, b = [], []
        for _ in range(args.repeat):
            s, (v0, f0) = _cpu(lambda: trimesh.remesh.subdivide_to_size(
                mesh.vertices, mesh.faces, edge, max_iter=12))
            a.append(s)
            s, (v1, f1) = _cpu(lambda: subdivide_to_size(mesh.vertices, mesh.faces, edge, 12))
            b.append(s)
        same = v0.shape == v1.shape and f0.shape == f1.shape and (v0 == v1).all() \
            and (f0 == f1).all()
        ta, tb = statistics.median(a), statistics.median(b)
        print(f"| `{name}` | {len(f0):,} | {ta:.3f} | {tb:.3f} | {ta / tb:.2f}x | {same} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
