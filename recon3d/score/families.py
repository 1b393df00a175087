"""The 3D scores of a run: the whole surface and what each added family gains.

``score`` compares the surface with the ground truth
(:mod:`recon3d.score.evaluate`) and, with several families, scores the
fusion of the first k families in the final domain for k = 1, 2, ...
"""
from __future__ import annotations

from recon3d.records import MeshRun
from recon3d.score.evaluate import (FSCORE_SHARES, SAMPLES, Domain, GroundTruthSamples,
                                    contour_cloud, surface_metrics)
from recon3d.surface.reconstruct import Reconstruction
from recon3d.surface.solid import fuse

__all__ = ["score", "domain"]


def domain(recon: Reconstruction) -> Domain | None:
    """The slabs of the families that gave a solid (None: no solid)."""
    solids = [s for s in recon.solids if s is not None]
    return Domain.of(solids) if solids else None


def _gain(new: dict, old: dict) -> dict:
    keys = {"coverage": (new["coverage"], old["coverage"]),
            "fscore_1%": (new["surface"]["fscore"]["1%"], old["surface"]["fscore"]["1%"]),
            "chamfer_l1": (new["surface"]["chamfer_l1"], old["surface"]["chamfer_l1"])}
    return {k: (None if a is None or b is None else a - b) for k, (a, b) in keys.items()}


def score(run: MeshRun, recon: Reconstruction,
          samples: int = SAMPLES) -> tuple[dict | None, dict]:
    """3D metrics of a reconstruction.

    Returns
    -------
    surface : dict or None -- the ``total.surface`` block (None without a surface).
    info : dict -- domain, tau, sample counts, 3D coverage and per-family gains
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
    surface, extra = surface_metrics(recon.surface, gt, contour_cloud(run.families), samples)
    info.update(extra)
    families = []
    for k, fam in enumerate(run.families):
        if k == len(run.families) - 1:
            entry_surface, entry_extra = surface, extra
        else:
            part = fuse(recon.solids[:k + 1], run.mesh.bounds)
            cloud = contour_cloud(run.families[:k + 1])
            entry_surface, entry_extra = surface_metrics(part, gt, cloud, samples)
        entry = {"axis": fam.label, "slices": len(fam.slices),
                 "coverage": entry_extra["coverage"], "surface": entry_surface}
        if families:
            entry["gain"] = _gain(entry, families[-1])
        families.append(entry)
    info["families"] = families
    return surface, info
