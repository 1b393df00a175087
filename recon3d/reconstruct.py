"""From a sensed run to a labelled surface and its 3D metrics.

``reconstruct`` closes every slice (:mod:`recon3d.closure`), builds one
solid per family (:mod:`recon3d.surface`) and fuses them; ``score`` compares
the surface with the ground truth (:mod:`recon3d.evaluate`) and, with
several families, says what each added family gains: the fusion of the
first k families is scored in the final domain for k = 1, 2, ...
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from recon3d.closure import slice_region
from recon3d.evaluate import (FSCORE_SHARES, SAMPLES, Domain,
                              GroundTruthSamples, contour_cloud, surface_metrics)
from recon3d.field import grid_step
from recon3d.surface import family_solid, fuse

__all__ = ["Reconstruction", "reconstruct", "score"]


@dataclass
class Reconstruction:
    """The surface of a run and what it was built from.

    surface : trimesh.Trimesh -- watertight, ``face_attributes['label']`` (f,) int.
    regions : list of list of SliceRegion -- per family, per slice.
    solids : list of FamilySolid or None -- per family (None: no surface).
    step : float -- grid step of the level set.
    notes : list of str -- why a family gave no surface.
    """

    surface: object
    regions: list
    solids: list
    step: float
    notes: list = field(default_factory=list)

    @property
    def domain(self) -> Domain | None:
        solids = [s for s in self.solids if s is not None]
        return Domain.of(solids) if solids else None


def reconstruct(run) -> Reconstruction:
    """Close, stack and fuse the slices of a :class:`recon3d.pipeline.MeshRun`."""
    diag = float(np.linalg.norm(np.ptp(run.mesh.bounds, axis=0)))
    step = grid_step(run.eps, diag)
    snap = 2.0 * run.tol
    regions, solids, notes = [], [], []
    for fam in run.families:
        regs = [slice_region(s.result.w1, s.result.w2, s.result.w3, s.result.unknown, snap)
                for s in fam.slices]
        regions.append(regs)
        if len(fam.slices) < 2:
            solids.append(None)
            notes.append(f"family {fam.label}: a surface needs at least 2 slices")
            continue
        solid = family_solid(regs, [s.slice.plane for s in fam.slices], step)
        if solid is None:
            notes.append(f"family {fam.label}: nothing sensed, no surface")
        solids.append(solid)
    surface = fuse(solids, run.mesh.bounds)
    return Reconstruction(surface, regions, solids, step, notes)


def _gain(new: dict, old: dict) -> dict:
    keys = {"coverage": (new["coverage"], old["coverage"]),
            "fscore_1%": (new["surface"]["fscore"]["1%"], old["surface"]["fscore"]["1%"]),
            "chamfer_l1": (new["surface"]["chamfer_l1"], old["surface"]["chamfer_l1"])}
    return {k: (None if a is None or b is None else a - b) for k, (a, b) in keys.items()}


def score(run, recon: Reconstruction, samples: int = SAMPLES) -> tuple[dict | None, dict]:
    """3D metrics of a reconstruction.

    Returns
    -------
    surface : dict or None -- the ``total.surface`` block (None without a surface).
    info : dict -- domain, tau, sample counts, 3D coverage and per-family gains
        (the ``surface_eval`` block of metrics.json).
    """
    domain = recon.domain
    info = {"fscore_tau_share": FSCORE_SHARES, "grid_step": recon.step, "notes": recon.notes,
            "rule": "caps (label 5) and ground truth outside the domain are not scored"}
    if domain is None or len(recon.surface.faces) == 0:
        info["domain"] = None
        return None, info
    info["domain"] = domain.as_dict()
    gt = GroundTruthSamples(run.mesh, domain, samples)
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
