"""Reference contours for 64 planes on a ~100k-face mesh.

Compares ``slicer.slice_mesh`` (plane family, degeneracy nudging, one
manifold3d ``Manifold``, 64 ``slice`` calls, loop cleaning/orientation,
``Slice`` objects) with raw manifold3d (build the ``Manifold`` from the
arrays, ``slice(z).to_polygons()`` at the same heights) and with trimesh
``section_multiplane``. The default mesh is Spot (../shared/meshes)
subdivided twice (93,696 faces), else a manifold3d sphere of ~100k faces.
Prints numbers, asserts nothing.

    python -m bench.bench_slicing [--mesh NAME_OR_PATH] [--subdivide 2] [--planes 64]
"""
from __future__ import annotations

import argparse
import logging
import sys
from pathlib import Path

import numpy as np
import trimesh

if __package__ in (None, ""):  # ``python bench/bench_slicing.py`` from the repo root
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from bench.bench_cast import SHARED, best_time, load_mesh  # noqa: E402
from slicer import make_planes, slice_mesh  # noqa: E402


def default_mesh(subdivide: int):
    if (SHARED / "mujoco_spot.ply").is_file():
        mesh = load_mesh("mujoco_spot.ply")
        for _ in range(subdivide):
            mesh = mesh.subdivide()
        return f"mujoco_spot.ply subdivided x{subdivide}", mesh
    import manifold3d

    m = manifold3d.Manifold.sphere(50.0, 224).to_mesh()
    return "manifold sphere", trimesh.Trimesh(m.vert_properties[:, :3], m.tri_verts)


def fresh(mesh):
    """A copy with empty caches (trimesh caches watertightness, edges...)."""
    return trimesh.Trimesh(mesh.vertices.copy(), mesh.faces.copy(), process=False)


def run(label, mesh, planes: int = 64) -> dict:
    import manifold3d

    logging.disable(logging.WARNING)
    heights = np.array([p.offset for p in make_planes(mesh, "z", count=planes)])
    verts = np.asarray(mesh.vertices)
    faces = np.asarray(mesh.faces)

    def ours():
        slice_mesh(fresh(mesh), "z", count=planes)

    def raw_manifold():
        man = manifold3d.Manifold(
            manifold3d.Mesh64(
                vert_properties=np.array(verts, dtype=np.float64, order="C"),
                tri_verts=np.array(faces, dtype=np.uint64, order="C"),
            )
        )
        return [man.slice(h).to_polygons() for h in heights]

    def raw_trimesh():
        fresh(mesh).section_multiplane([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], heights)

    t = {k: best_time(f, min_seconds=1.0, runs=3)
         for k, f in (("ours", ours), ("manifold", raw_manifold), ("trimesh", raw_trimesh))}
    print(f"{label}: {len(faces)} faces, {planes} planes along z")
    print(f"  slice_mesh          {t['ours'] * 1e3:8.1f} ms")
    print(f"  raw manifold3d      {t['manifold'] * 1e3:8.1f} ms   ours/manifold {t['ours'] / t['manifold']:.2f}")
    print(f"  trimesh multiplane  {t['trimesh'] * 1e3:8.1f} ms   ours/trimesh  {t['ours'] / t['trimesh']:.2f}")
    print("target: slice_mesh <= 1.5 x raw manifold3d")
    return t


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--mesh", help="scene name or mesh path (default: Spot)")
    p.add_argument("--subdivide", type=int, default=2)
    p.add_argument("--planes", type=int, default=64)
    args = p.parse_args(argv)
    if args.mesh:
        mesh = load_mesh(args.mesh)
        for _ in range(args.subdivide):
            mesh = mesh.subdivide()
        label = f"{args.mesh} subdivided x{args.subdivide}"
    else:
        label, mesh = default_mesh(args.subdivide)
    run(label, mesh, args.planes)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
