"""A single family's surface cut by a plane across its slices: before and after a caps setting.

For one ``CASE:AXIS`` (``bench_surface``'s cached sensing, ``--slices`` planes) the surface
is built with :class:`recon3d.surface.caps.CapSettings` overridden by ``--before`` (JSON) and
with the defaults, and both are cut by the plane ``SECTION = h`` (an axis other than the
slicing one). One panel: the true section (black), the surface before (blue) and after
(red), the family's slice planes (grey lines); F@1% of both in the title.

Run from the repository root::

    python -m bench.surface_sections --cache DIR stepped_pyramid:z y 0 \\
        --before '{"steps": false}' --png docs/steps_stepped_pyramid.png
"""
from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

from bench.bench_surface import scores, sensed
from recon3d.surface import reconstruct
from recon3d.surface.caps import CapSettings
from recon3d.viz import libs

AXES = {"x": 0, "y": 1, "z": 2}


def _draw(ax, mesh, axis: int, h: float, colour: str, width: float, label: str) -> None:
    """The section ``axis = h`` of ``mesh`` in the two other coordinates."""
    normal = np.eye(3)[axis]
    sec = mesh.section(plane_origin=normal * h, plane_normal=normal)
    keep = [i for i in range(3) if i != axis]
    for line in ([] if sec is None else sec.discrete):
        ax.plot(line[:, keep[0]], line[:, keep[1]], color=colour, lw=width)
    ax.plot([], [], color=colour, lw=width, label=label)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.surface_sections", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("spec", help="CASE:AXIS, AXIS the slicing axis (z or x)")
    ap.add_argument("section", choices=tuple(AXES), help="the section plane's normal axis")
    ap.add_argument("h", type=float, help="the section plane's coordinate")
    ap.add_argument("--cache", type=Path, required=True, help="bench_surface's sensing cache")
    ap.add_argument("--slices", type=int, default=16)
    ap.add_argument("--before", default='{"steps": false}', help="CapSettings overrides (JSON)")
    ap.add_argument("--png", type=Path, required=True, help="the picture to write")
    args = ap.parse_args(argv)
    name, family = args.spec.rsplit(":", 1)
    axis = AXES[args.section]
    if axis == AXES[family]:
        ap.error("the section must cut across the slices: pick another axis than the slicing one")
    try:
        before = CapSettings(**json.loads(args.before))
    except (TypeError, ValueError) as err:
        ap.error(f"--before: {err}")
    run = sensed(name, family, args.slices, 1, args.cache)
    surf = {w: reconstruct(run, caps=c).surface for w, c in (("before", before),
                                                              ("after", CapSettings()))}
    f1 = {w: scores(run, s)["f1"] for w, s in surf.items()}
    plt = libs.pyplot()
    fig, ax = plt.subplots(figsize=(11, 7))
    _draw(ax, run.mesh, axis, args.h, "black", 2.4, "truth")
    _draw(ax, surf["before"], axis, args.h, "tab:blue", 1.2,
          f"before {args.before}: F@1% {f1['before']:.4f}")
    _draw(ax, surf["after"], axis, args.h, "tab:red", 1.2, f"after (defaults): F@1% {f1['after']:.4f}")
    keep = [i for i in range(3) if i != axis]
    fam = AXES[family]
    for s in run.families[0].slices:
        off = s.slice.plane.offset
        (ax.axvline if keep[0] == fam else ax.axhline)(off, color="grey", lw=0.6, zorder=0)
    ax.plot([], [], color="grey", lw=0.6, label=f"the {len(run.families[0].slices)} "
            f"{family}-slice planes")
    ax.set_aspect("equal")
    ax.set_xlabel("xyz"[keep[0]])
    ax.set_ylabel("xyz"[keep[1]])
    ax.set_title(f"{name} along {family}: section {args.section} = {args.h:g}", fontsize=11)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=2, fontsize=9)
    fig.tight_layout()
    args.png.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.png, dpi=90)
    plt.close(fig)
    print(f"{args.png}: F@1% before {f1['before']:.4f}, after {f1['after']:.4f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
