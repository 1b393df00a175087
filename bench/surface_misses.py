"""Where a single family's surface misses: by the facing of the ground truth, by the face label.

For each ``case:axis`` (sensing from ``bench_surface``'s ``--cache``, 16 slices): the surface
(default route) is compared with the ground truth inside the family's slab at tau = 1% of the
diagonal. Printed: recall and precision; the share of the scored ground truth missed, split by
``|n . a|`` (n the true face normal, a the slicing axis): *lid* > 0.9 (a floor or lid parallel
to the planes: the probe, moving in the plane, meets it only if a plane cuts it), *slanted*,
*wall* <= 0.3; the missed share within a quarter gap of a slice plane; the share of the surface
farther than tau by face label (1 W1, 2 W2, 3 W3, 4 between slices).

Run from the repository root::

    python -m bench.surface_misses --cache DIR comb:z ajc_teapot.obj:x
"""
from __future__ import annotations

import argparse
import pickle
from pathlib import Path

import numpy as np
import trimesh

from recon3d.config import diagonal
from recon3d.surface import reconstruct


def misses(run, samples: int = 30000) -> dict:
    """The shares of the module doc for one single-family run."""
    fam = run.families[0]
    axis = np.asarray(fam.normal, dtype=float)
    hs = np.sort([s.slice.plane.offset for s in fam.slices])
    surface = reconstruct(run).surface
    tau = 0.01 * diagonal(run.mesh)
    pts, fi = trimesh.sample.sample_surface(run.mesh, samples, seed=1)
    h = pts @ axis
    keep = (h >= hs[0]) & (h <= hs[-1])
    pts, fi, h = pts[keep], fi[keep], h[keep]
    miss = np.abs(trimesh.proximity.signed_distance(surface, pts)) > tau
    facing = np.abs(run.mesh.face_normals[fi] @ axis)
    near = np.min(np.abs(h[:, None] - hs[None]), axis=1) < 0.25 * np.diff(hs).mean()
    labels = np.asarray(surface.face_attributes["label"])
    sp, sf = trimesh.sample.sample_surface(surface, samples, seed=1)
    sp, lab = sp[labels[sf] != 5], labels[sf][labels[sf] != 5]
    far = np.abs(trimesh.proximity.signed_distance(run.mesh, sp)) > tau
    return {"recall": 1 - miss.mean(), "precision": 1 - far.mean(),
            "lid": np.mean(miss & (facing > 0.9)),
            "slanted": np.mean(miss & (facing > 0.3) & (facing <= 0.9)),
            "wall": np.mean(miss & (facing <= 0.3)), "near_slice": np.mean(miss & near),
            **{f"extra_{k}": np.mean(far & (lab == k)) for k in (1, 2, 3, 4)}}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.surface_misses", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cases", nargs="+", help="case:axis, e.g. comb:z")
    ap.add_argument("--cache", type=Path, required=True, help="bench_surface's sensing cache")
    ap.add_argument("--slices", type=int, default=16)
    args = ap.parse_args(argv)
    keys = ("recall", "precision", "lid", "slanted", "wall", "near_slice",
            "extra_1", "extra_2", "extra_3", "extra_4")
    print("| case | axis | " + " | ".join(keys) + " |\n|" + "---|" * (len(keys) + 2))
    for spec in args.cases:
        name, axis = spec.rsplit(":", 1)
        path = args.cache / f"{name}@{axis}{args.slices}.pkl"
        if not path.is_file():
            print(f"<!-- {spec}: {path} not cached (run bench_surface --cache first) -->")
            continue
        with open(path, "rb") as fh:
            row = misses(pickle.load(fh))
        print(f"| {name} | {axis} | " + " | ".join(f"{row[k]:.3f}" for k in keys) + " |",
              flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
