"""Where a single family's surface misses: by the facing of the ground truth, by the face label.

For each ``case:axis`` (sensing from ``bench_surface``'s ``--cache``, 16 slices): the surface
(default route) is compared with the ground truth inside the family's slab at tau = 1% of the
diagonal. Printed: recall and precision; the share of the scored ground truth missed, split by
``|n . a|`` (n the true face normal, a the slicing axis): *lid* > 0.9 (a floor or lid parallel
to the planes: the probe, moving in the plane, meets it only if a plane cuts it), *slanted*,
*wall* <= 0.3; the missed share within a quarter gap of a slice plane; the share of the surface
farther than tau by face label (1 W1, 2 W2, 3 W3, 4 between slices); *unsensed*: the share of
the surface farther than tau whose nearest piece in the two neighbouring slices (in the plane,
within 3 grid steps) is an unknown chord or a bridge (:mod:`recon3d.surface.caps`).

``--caps JSON`` overrides :class:`recon3d.surface.caps.CapSettings` (``'{"enabled": false}'``:
the aligned blend without the rule). ``--png DIR`` also draws, per case, the gap holding the
surface farther than tau changes most with the rule: both slices' regions and pieces, and the
surface samples farther than tau in that gap, without the rule and with ``--caps``.

Run from the repository root::

    python -m bench.surface_misses --cache DIR comb:z ajc_teapot.obj:x --png /tmp/misses
"""
from __future__ import annotations

import argparse
import json
import pickle
from pathlib import Path

import numpy as np
import trimesh
from scipy.spatial import cKDTree

from recon3d.config import diagonal
from recon3d.surface import reconstruct
from recon3d.surface.caps import UNSENSED, CapSettings
from recon3d.surface.closure import sample_pieces

KEYS = ("recall", "precision", "lid", "slanted", "wall", "near_slice",
        "extra_1", "extra_2", "extra_3", "extra_4", "unsensed")
COLOURS = {"W1": "black", "W2": "tab:blue", "W3": "tab:green", "unknown": "tab:red",
           "bridge": "tab:purple"}


def _nearest_kind(rec, uv, gap_of, step) -> np.ndarray:
    """(n,) bool: the nearest piece of slice ``gap`` or ``gap + 1`` (within 3 steps) is
    unsensed, for in-plane points ``uv`` (n, 2) lying in gap ``gap_of`` (n,)."""
    regs = rec.regions[0]
    best = np.full(len(uv), np.inf)
    kind = np.zeros(len(uv), dtype=bool)
    for j, reg in enumerate(regs):
        sel = np.flatnonzero((gap_of == j) | (gap_of == j - 1))
        pts, owner = sample_pieces(reg.pieces, step / 4)
        if len(sel) == 0 or len(pts) == 0:
            continue
        d, i = cKDTree(pts).query(uv[sel])
        uns = np.array([p.kind in UNSENSED for p in reg.pieces])[owner[i]]
        better = d < best[sel]
        best[sel[better]], kind[sel[better]] = d[better], uns[better]
    return kind & (best <= 3 * step)


def misses(run, samples: int = 30000, caps: CapSettings = CapSettings()) -> dict:
    """The shares of the module doc for one single-family run (and what the figure needs)."""
    fam = run.families[0]
    axis = np.asarray(fam.normal, dtype=float)
    hs = np.sort([s.slice.plane.offset for s in fam.slices])
    rec = reconstruct(run, caps=caps)
    surface = rec.surface
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
    p0 = min((s.slice.plane for s in fam.slices), key=lambda p: p.offset)
    uv = np.column_stack([(sp - p0.origin) @ p0.u, (sp - p0.origin) @ p0.v])
    gap_of = np.clip(np.searchsorted(hs, sp @ axis) - 1, 0, len(hs) - 2)
    uns = _nearest_kind(rec, uv, gap_of, rec.step)
    return {"recall": 1 - miss.mean(), "precision": 1 - far.mean(),
            "lid": np.mean(miss & (facing > 0.9)),
            "slanted": np.mean(miss & (facing > 0.3) & (facing <= 0.9)),
            "wall": np.mean(miss & (facing <= 0.3)), "near_slice": np.mean(miss & near),
            **{f"extra_{k}": np.mean(far & (lab == k)) for k in (1, 2, 3, 4)},
            "unsensed": np.mean(far & uns),
            "_figure": (rec.regions[0], uv[far], gap_of[far], hs)}


def draw(path: Path, panels: list) -> None:
    """One PNG, a panel per ``(title, figure)``: the regions of the two slices around the gap
    where the far surface changes most from the first panel to the last (one panel: where
    most of it lies), and the far surface samples in it."""
    from recon3d.viz import libs

    plt = libs.pyplot()
    regions, _, _, hs = panels[0][1]
    counts = np.array([np.bincount(f[2], minlength=len(hs) - 1) for _, f in panels])
    gap = int(np.abs(counts[-1] - counts[0]).argmax() if len(panels) > 1 else counts[0].argmax())
    fig, axes = plt.subplots(1, len(panels), figsize=(6.5 * len(panels), 7.5), sharey=True)
    for ax, (title, (_, uv, gaps, _)) in zip(np.atleast_1d(axes), panels):
        for j, style in ((gap, "-"), (gap + 1, "--")):
            for p in regions[j].pieces:
                ax.plot(*p.points.T, style, color=COLOURS[p.kind], lw=1.2)
        sel = gaps == gap
        ax.scatter(*uv[sel].T, s=3, color="tab:orange", zorder=3,
                   label=f"surface farther than tau ({sel.sum()} samples)")
        for kind, c in COLOURS.items():
            ax.plot([], [], color=c, label=kind)
        ax.plot([], [], "-", color="grey", label=f"slice {gap} (h = {hs[gap]:.5g})")
        ax.plot([], [], "--", color="grey", label=f"slice {gap + 1} (h = {hs[gap + 1]:.5g})")
        ax.set_aspect("equal")
        ax.set_title(title, fontsize=10)
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.09), ncol=3, fontsize=8)
        ax.set_xlabel("u (slice frame)")
    np.atleast_1d(axes)[0].set_ylabel("v (slice frame)")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.surface_misses", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cases", nargs="+", help="case:axis, e.g. comb:z")
    ap.add_argument("--cache", type=Path, required=True, help="bench_surface's sensing cache")
    ap.add_argument("--slices", type=int, default=16)
    ap.add_argument("--caps", default="{}", help="CapSettings overrides (JSON)")
    ap.add_argument("--png", type=Path, help="directory for one figure per case")
    args = ap.parse_args(argv)
    caps = CapSettings(**json.loads(args.caps))
    print("| case | axis | " + " | ".join(KEYS) + " |\n|" + "---|" * (len(KEYS) + 2))
    for spec in args.cases:
        name, axis = spec.rsplit(":", 1)
        path = args.cache / f"{name}@{axis}{args.slices}.pkl"
        if not path.is_file():
            print(f"<!-- {spec}: {path} not cached (run bench_surface --cache first) -->")
            continue
        with open(path, "rb") as fh:
            run = pickle.load(fh)
        row = misses(run, caps=caps)
        print(f"| {name} | {axis} | " + " | ".join(f"{row[k]:.3f}" for k in KEYS) + " |",
              flush=True)
        if args.png:
            args.png.mkdir(parents=True, exist_ok=True)
            off = misses(run, caps=CapSettings(enabled=False))
            draw(args.png / f"{name}_{axis}.png",
                 [(f"{name} along {axis}, without the rule: precision {off['precision']:.3f}",
                   off["_figure"]),
                  (f"with the rule (caps.py{'' if args.caps == '{}' else ', ' + args.caps}):"
                   f" precision {row['precision']:.3f}",
                   row["_figure"])])
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
