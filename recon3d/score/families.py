"""The 3D scores of a run: the fused surface and each family's own surface.

``score`` compares the surface the user gets with the ground truth
(:mod:`recon3d.score.evaluate`) over the union of the slabs and, with
several families, scores each family's own surface (the one a run along
that axis alone would give) over its own slab, so the summary compares
surfaces a user can see: the fused one against the best single family.
"""
from __future__ import annotations

from recon3d.records import Family, MeshRun
from recon3d.score.evaluate import (FSCORE_SHARES, SAMPLES, Domain, GroundTruthSamples,
                                    contour_cloud, one_after_other, surface_metrics)
from recon3d.surface.reconstruct import Reconstruction
from recon3d.surface.solid import fuse

__all__ = ["score", "domain", "SHARES"]

SHARES = ("slab_share", "reachable_share", "resolvable_share", "touched_share")
"""The shares of the ground truth that go with every scored surface (evaluate's module doc)."""


def domain(recon: Reconstruction) -> Domain | None:
    """The slabs of the families that gave a solid (None: no solid)."""
    solids = [s for s in recon.solids if s is not None]
    return Domain.of(solids) if solids else None


def _entry(surface: dict | None, extra: dict | None) -> dict:
    """One scored surface: its shares of the ground truth and its ``total.surface`` block."""
    out = {k: (None if extra is None else extra[k]) for k in SHARES}
    out["surface"] = surface
    return out


def _own(run: MeshRun, fam: Family, solid, samples: int, pair) -> dict:
    """A family's own surface (its solid alone) scored over its own slab."""
    if solid is None:
        return _entry(None, None)
    gt = GroundTruthSamples(run.mesh, Domain.of([solid]), samples)
    surface, extra = surface_metrics(fuse([solid], run.mesh.bounds), gt,
                                     contour_cloud([fam]), samples, pair=pair)
    return _entry(surface, extra)


def _f1(entry: dict) -> float | None:
    return ((entry.get("surface") or {}).get("fscore") or {}).get("1%")


def score(run: MeshRun, recon: Reconstruction, samples: int = SAMPLES,
          pair=one_after_other) -> tuple[dict | None, dict]:
    """3D metrics of a reconstruction.

    pair : callable -- how each surface's two distance calls run
    (:func:`recon3d.score.evaluate.surface_metrics`).

    Returns
    -------
    surface : dict or None -- the ``total.surface`` block (None without a surface).
    info : dict -- domain, tau, sample counts, the shares of the ground truth
        (``slab_share``, ``reachable_share``, ``resolvable_share``, ``touched_share``), and
        per family
        its own surface scored over its own slab (``families``) with, for 2+
        families, ``fused_vs_best``: fused F@1% minus the best family's own F@1%
        (the ``surface_eval`` block of metrics.json).
    """
    dom = domain(recon)
    info = {"fscore_tau_share": FSCORE_SHARES, "grid_step": recon.step, "notes": recon.notes,
            "rule": "caps (label 5) and ground truth outside the domain are not scored"}
    if dom is None or len(recon.surface.faces) == 0:
        info["domain"] = None
        return None, info
    info["domain"] = dom.as_dict()
    gt = GroundTruthSamples(run.mesh, dom, samples)
    surface, extra = surface_metrics(recon.surface, gt, contour_cloud(run.families), samples,
                                     pair=pair)
    info.update(extra)
    several = len(run.families) > 1
    families = []
    for fam, solid in zip(run.families, recon.solids):
        entry = _own(run, fam, solid, samples, pair) if several else _entry(surface, extra)
        families.append({"axis": fam.label, "slices": len(fam.slices), **entry})
    info["families"] = families
    if several:
        own = [(f1, fam["axis"]) for fam in families if (f1 := _f1(fam)) is not None]
        fused = surface["fscore"]["1%"]
        best = max(own, default=None)
        info["fused_vs_best"] = None if best is None or fused is None else {
            "axis": best[1], "fscore_1%": fused - best[0]}
    return surface, info
