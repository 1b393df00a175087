"""F@1% of single surfaces from ``bench_surface``'s cached sensing, with settings overridden.

Each ``CASE:WHAT:N`` (``WHAT`` one of ``z``, ``x``, ``y``, ``z+x``; ``N`` slices per axis) is
rebuilt with the default route and fusion, :class:`recon3d.surface.fusion.FusionSettings`,
:class:`recon3d.surface.confidence.ConfidenceSettings` and
:class:`recon3d.surface.caps.CapSettings` and :class:`recon3d.surface.warp.WarpSettings`
overridden by ``--blend``, ``--trust``, ``--caps`` and ``--warp`` (JSON objects), and scored as ``bench_surface`` scores it (F@1% over the scored
ground truth, over its reachable part and over the part eps resolves, 4 decimals). For
measuring a fusion parameter on a few cases without the whole table.

Run from the repository root::

    python -m bench.surface_cases --cache out/cache fig18_overhangs:z+x:8 gear:z+x:16 \
        --blend '{"cap": 0.1}'
"""
from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from bench.bench_surface import scores, sensed
from recon3d.records import MeshRun
from recon3d.surface import reconstruct
from recon3d.surface.caps import CapSettings
from recon3d.surface.confidence import ConfidenceSettings
from recon3d.surface.fusion import FusionSettings
from recon3d.surface.warp import WarpSettings


def run_of(name: str, what: str, slices: int, cache: Path) -> MeshRun:
    """The cached run of one family, or z and x together."""
    if what in ("z", "x", "y"):
        return sensed(name, what, slices, 1, cache)
    z, x = (sensed(name, a, slices, 1, cache) for a in ("z", "x"))
    return MeshRun(z.name, z.mesh, z.config, z.eps, z.tol, z.probe_length,
                   z.families + x.families)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.surface_cases", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("specs", nargs="+", help="CASE:WHAT:N, WHAT in z, x, y, z+x")
    ap.add_argument("--cache", type=Path, required=True, help="bench_surface's sensing cache")
    ap.add_argument("--blend", default="{}", help="FusionSettings overrides (JSON)")
    ap.add_argument("--trust", default="{}", help="ConfidenceSettings overrides (JSON)")
    ap.add_argument("--caps", default="{}", help="CapSettings overrides (JSON), e.g. "
                    "'{\"enabled\": false}'")
    ap.add_argument("--warp", default="{}", help="WarpSettings overrides (JSON), e.g. "
                    "'{\"bend\": false}'")
    args = ap.parse_args(argv)
    warp = WarpSettings(**json.loads(args.warp))
    blend = FusionSettings(**json.loads(args.blend))
    trust = ConfidenceSettings(**json.loads(args.trust))
    caps = CapSettings(**json.loads(args.caps))
    for spec in args.specs:
        name, what, n = spec.rsplit(":", 2)
        t0 = time.perf_counter()
        run = run_of(name, what, int(n), args.cache)
        s = scores(run, reconstruct(run, trust=trust, blend=blend, caps=caps,
                                       warp=warp).surface)
        print(f"{name:26s} {what:4s} {n:>3s}  F@1% {s['f1']:.4f}  reachable {s['f1r']:.4f}"
              f"  resolvable {s['f1v']:.4f}  {time.perf_counter() - t0:.0f} s", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
