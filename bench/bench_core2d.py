"""Per-slice sensing cost of the pulling-motion algorithm on the built-in scenes.

For the middle z-slice of every scene: wall time, motions and rays per unit
length of contour, and the share of wall time spent inside ray casts (target
>= 50%). With ``--profile`` the slowest scene is profiled (cProfile) to show
where the rest goes.

Run from the repository root::

    python -m bench.bench_core2d [--backend embree|exact] [--slices N] [--profile]
"""
from __future__ import annotations

import argparse
import cProfile
import io
import pstats

import numpy as np

import meshes
import slicer
from core2d import sense_slice


def _slices(name, count):
    mesh = meshes.load(name)
    eps = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)) / 200)
    return eps, slicer.slice_mesh(mesh, axis="z", count=count)


def _sense(cut, eps, backend):
    center, radius = cut.bounding_circle()
    return sense_slice(cut.contact(backend), (center, radius + eps), eps)


def _length(cut):
    return sum(float(np.linalg.norm(np.roll(l, -1, 0) - l, axis=1).sum()) for l in cut.loops)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--backend", choices=("embree", "exact"), default="embree")
    ap.add_argument("--slices", type=int, default=1, help="slices per scene (default 1)")
    ap.add_argument("--profile", action="store_true", help="profile the slowest scene")
    args = ap.parse_args(argv)
    print(f"backend {args.backend}, {args.slices} z-slice(s) per scene")
    print(f"{'scene':18s} {'s/slice':>8s} {'motions/len':>11s} {'rays/len':>9s} "
          f"{'casts':>7s} {'cast share':>10s} {'us/cast':>8s} {'pushes':>6s}")
    rows = []
    for name in meshes.names():
        eps, cuts = _slices(name, args.slices)
        wall = cast = motions = rays = casts = length = pushes = 0.0
        for cut in cuts:
            res = _sense(cut, eps, args.backend)
            st = res.stats
            wall += st.seconds
            cast += st.cast_seconds
            motions += st.motions
            rays += st.rays
            casts += st.casts
            pushes += st.pushes
            length += _length(cut)
        rows.append((name, wall / len(cuts), cast / wall))
        print(f"{name:18s} {wall / len(cuts):8.2f} {motions / length:11.2f} "
              f"{rays / length:9.0f} {casts:7.0f} {cast / wall:10.1%} "
              f"{1e6 * cast / max(casts, 1):8.1f} {pushes:6.0f}")
    share = np.array([r[2] for r in rows])
    print(f"cast share: median {np.median(share):.1%}, min {share.min():.1%} "
          f"(target >= 50%)")
    if args.profile:
        name = max(rows, key=lambda r: r[1])[0]
        eps, cuts = _slices(name, 1)
        prof = cProfile.Profile()
        prof.enable()
        _sense(cuts[0], eps, args.backend)
        prof.disable()
        out = io.StringIO()
        pstats.Stats(prof, stream=out).sort_stats("tottime").print_stats(15)
        print(f"\nprofile of {name} (sorted by own time):")
        print("\n".join(out.getvalue().splitlines()[:40]))


if __name__ == "__main__":
    main()
