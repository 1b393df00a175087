"""Per-call cost of ``EmbreeContact.cast`` against the raw embreex call.

Both use the same per-slice scene (only the triangles crossing the plane,
in the plane's frame). "raw output=1" is ``scene.run(o, d, dists=max.copy(),
output=1)`` (primID, tfar, Ng...); "raw INTERSECT" is ``scene.run(o, d,
query='INTERSECT')``, the call ``cast`` makes (primID only; distances and
normals are then refined in float64). Rays come from a circle around the
section aimed at random points of its bounding box. Prints numbers, asserts
nothing.

    python -m bench.bench_cast [--mesh NAME_OR_PATH] [--axis z]
"""
from __future__ import annotations

import argparse
import logging
import sys
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:  # ``python bench/bench_cast.py`` from the repo root
    sys.path.insert(0, str(ROOT))

from slicer import slice_mesh  # noqa: E402
from slicer.agreement import random_rays  # noqa: E402

SHARED = ROOT.parent / "shared" / "meshes"


def best_time(func, min_seconds: float = 0.2, runs: int = 5) -> float:
    """Seconds per call: min over ``runs`` runs of a loop lasting ~min_seconds."""
    func()
    reps, t = 1, 0.0
    while True:
        t0 = time.perf_counter()
        for _ in range(reps):
            func()
        t = time.perf_counter() - t0
        if t >= min_seconds / 4 or reps >= 1 << 24:
            break
        reps *= 2
    reps = max(1, int(reps * min_seconds / max(t, 1e-9)))
    best = float("inf")
    for _ in range(runs):
        t0 = time.perf_counter()
        for _ in range(reps):
            func()
        best = min(best, (time.perf_counter() - t0) / reps)
    return best


def load_mesh(name_or_path: str):
    """A scene name, a path, or a file name in ../shared/meshes."""
    import meshes

    candidate = SHARED / name_or_path
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if name_or_path not in meshes.names() and candidate.is_file():
            return meshes.load(candidate)
        return meshes.load(name_or_path)


SIZES = (1, 10, 100, 1000)


def run(mesh_name: str, axis: str = "z", sizes=SIZES) -> list[dict]:
    logging.disable(logging.WARNING)
    mesh = load_mesh(mesh_name)
    slc = slice_mesh(mesh, axis=axis, count=3)[1]
    model = slc.contact("embree")
    exact = slc.contact("exact")
    rng = np.random.default_rng(0)
    rows = []
    for n in sizes:
        o, d, _ = random_rays(slc, n, rng, inside_share=0.0)
        o, d = np.ascontiguousarray(o), np.ascontiguousarray(d)
        reach = float(2.6 * slc.bounding_circle()[1])
        o3, d3 = model.rays3d(o, d)
        m32 = np.full(n, reach, np.float32)
        scene = model.scene
        t_ours = best_time(lambda: model.cast(o, d, reach))
        t_raw1 = best_time(lambda: scene.run(o3, d3, dists=m32.copy(), output=1))
        t_rawi = best_time(lambda: scene.run(o3, d3, query="INTERSECT"))
        t_exact = best_time(lambda: exact.cast(o, d, reach), min_seconds=0.1, runs=3)
        rows.append(dict(n=n, ours=t_ours, raw1=t_raw1, rawi=t_rawi, exact=t_exact))
    print(
        f"mesh {mesh_name}, axis {axis}: slice {slc.index}, "
        f"{len(model.face_index)} of {len(mesh.faces)} faces in the scene, "
        f"exact backend {len(exact.starts)} segments"
    )
    print(f"{'rays':>6} {'cast us':>9} {'raw output=1':>13} {'ratio':>6} "
          f"{'raw INTERSECT':>14} {'ratio':>6} {'exact us':>10}")
    for r in rows:
        print(
            f"{r['n']:6d} {r['ours'] * 1e6:9.2f} {r['raw1'] * 1e6:13.2f} "
            f"{r['ours'] / r['raw1']:6.2f} {r['rawi'] * 1e6:14.2f} "
            f"{r['ours'] / r['rawi']:6.2f} {r['exact'] * 1e6:10.1f}"
        )
    print("target: cast <= 1.5 x raw at 1-10 rays")
    return rows


def main(argv=None) -> int:
    default = "mujoco_spot.ply" if (SHARED / "mujoco_spot.ply").is_file() else "fig17_pocket"
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--mesh", default=default, help="scene name or mesh path")
    p.add_argument("--axis", default="z")
    args = p.parse_args(argv)
    run(args.mesh, args.axis)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
