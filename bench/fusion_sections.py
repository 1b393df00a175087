"""Where a fused surface leaves the ground truth: sections, before and after a fusion setting.

For one case (``bench_surface``'s cached sensing, z and x, ``--slices`` each) the z+x surface is
built twice -- with the overrides ``--before`` (JSON: ``{"blend": {...}, "caps": {...},
"trust": {...}}`` of :class:`recon3d.surface.fusion.FusionSettings`,
:class:`recon3d.surface.caps.CapSettings`, :class:`recon3d.surface.confidence.ConfidenceSettings`)
and with the defaults -- and cut by the planes ``AXIS = h`` given. Each panel shows the true
section (black), z alone and x alone (thin), the fused surface (red), the other family's slice
planes (grey lines) and the fused surface samples farther than tau = 1% of the diagonal from
the mesh within a quarter gap of the section (orange), with F@1% and the share of far samples
in the title.

Run from the repository root::

    python -m bench.fusion_sections --cache DIR ravens_cup.ply z 0.05 \\
        --before '{"blend": {"filled": false}, "caps": {"own_trust": false}}' --png out.png
"""
from __future__ import annotations

import argparse
import json
import textwrap
from pathlib import Path

import numpy as np
import trimesh

from bench.bench_surface import scores
from bench.surface_cases import run_of
from recon3d.config import diagonal
from recon3d.surface import reconstruct
from recon3d.surface.caps import CapSettings
from recon3d.surface.confidence import ConfidenceSettings
from recon3d.surface.fusion import FusionSettings

AXES = {"x": 0, "y": 1, "z": 2}
STYLE = (("truth", "black", 2.4), ("z alone", "tab:blue", 0.8), ("x alone", "tab:green", 0.8),
         ("z+x", "tab:red", 1.4))


def surfaces(name: str, slices: int, cache: Path, over: dict) -> tuple:
    """(z run, z alone, x alone, z+x surface, z+x F@1%) with the overrides ``over``."""
    kw = dict(blend=FusionSettings(**over.get("blend", {})),
              caps=CapSettings(**over.get("caps", {})),
              trust=ConfidenceSettings(**over.get("trust", {})))
    z, x, zx = (run_of(name, w, slices, cache) for w in ("z", "x", "z+x"))
    fused = reconstruct(zx, **kw).surface
    return (z, reconstruct(z, **kw).surface, reconstruct(x, **kw).surface, fused,
            scores(zx, fused)["f1"])


def far_samples(mesh, surface, tau: float, n: int = 40000) -> np.ndarray:
    """(k, 3) samples of ``surface`` (caps left out) farther than ``tau`` from ``mesh``."""
    pts, fi = trimesh.sample.sample_surface(surface, n, seed=1)
    pts = pts[np.asarray(surface.face_attributes["label"])[fi] != 5]
    return pts[np.abs(trimesh.proximity.signed_distance(mesh, pts)) > tau]


def panel(ax, run, meshes, far, axis: int, h: float, band: float, planes) -> None:
    """One section ``axis = h`` of the truth and the surfaces (module doc)."""
    n = np.eye(3)[axis]
    a, b = [k for k in range(3) if k != axis]
    for (label, colour, lw), mesh in zip(STYLE, meshes):
        sec = mesh.section(plane_origin=n * h, plane_normal=n)
        for line in ([] if sec is None else sec.discrete):
            ax.plot(line[:, a], line[:, b], color=colour, lw=lw)
        ax.plot([], [], color=colour, lw=lw, label=label)
    for p in planes:
        ax.axvline(p, color="0.75", lw=0.5, zorder=0)
    if len(planes):
        ax.plot([], [], color="0.75", lw=0.5, label="x slice planes")
    near = far[np.abs(far[:, axis] - h) < band]
    ax.scatter(near[:, a], near[:, b], s=3, color="tab:orange", zorder=3,
               label="z+x farther than tau (within a quarter gap)")
    ax.set_aspect("equal")
    ax.set_xlabel("xyz"[a])
    ax.set_ylabel("xyz"[b])
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=3, fontsize=8)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.fusion_sections", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case")
    ap.add_argument("axis", choices=("x", "y", "z"), help="normal of the sections")
    ap.add_argument("heights", help="comma-separated section offsets")
    ap.add_argument("--cache", type=Path, required=True, help="bench_surface's sensing cache")
    ap.add_argument("--slices", type=int, default=16)
    ap.add_argument("--before", default="{}", help="overrides of the first surface (JSON)")
    ap.add_argument("--png", type=Path, required=True, help="the figure to write")
    args = ap.parse_args(argv)
    try:
        before, hs = json.loads(args.before), [float(v) for v in args.heights.split(",")]
    except ValueError as err:
        ap.error(f"bad --before or heights: {err}")
    from recon3d.viz import libs

    plt = libs.pyplot()
    axis = AXES[args.axis]
    rows = []
    for title, over in (("before " + args.before, before), ("after (defaults)", {})):
        z, sz, sx, fused, f1 = surfaces(args.case, args.slices, args.cache, over)
        tau = 0.01 * diagonal(z.mesh)
        far = far_samples(z.mesh, fused, tau)
        rows.append((title, z, (z.mesh, sz, sx, fused), far, f1, tau))
    other = run_of(args.case, "x" if args.axis == "z" else "z", args.slices, args.cache)
    planes = [s.slice.plane.offset for s in other.families[0].slices]
    band = 0.25 * float(np.diff(sorted(planes)).mean())
    fig, axes = plt.subplots(len(hs), 2, figsize=(13, 6.8 * len(hs)), squeeze=False)
    for j, (title, run, meshes, far, f1, tau) in enumerate(rows):
        for i, h in enumerate(hs):
            ax = axes[i, j]
            panel(ax, run, meshes, far, axis, h, band, planes if args.axis == "z" else [])
            ax.set_title(f"{args.case}, section {args.axis} = {h:g}, z+x F@1% {f1:.4f}, "
                         f"tau = {tau:.3g}\n" + "\n".join(textwrap.wrap(title, 70)),
                         fontsize=9)
    fig.tight_layout()
    args.png.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.png, dpi=90)
    plt.close(fig)
    print(f"wrote {args.png}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
