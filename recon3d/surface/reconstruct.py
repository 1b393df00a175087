"""From a sensed run to a labelled surface.

``reconstruct`` closes every slice (:mod:`recon3d.surface.closure`), builds
one solid per family (:mod:`recon3d.surface.solid`) and fuses them; the 3D
scores are :mod:`recon3d.score`'s.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import trimesh

from recon3d.config import diagonal
from recon3d.records import MeshRun
from recon3d.surface.caps import CapSettings
from recon3d.surface.closure import SliceRegion, closure_lengths, result_region
from recon3d.surface.confidence import ConfidenceSettings
from recon3d.surface.field import grid_step
from recon3d.surface.fusion import FusionSettings
from recon3d.surface.solid import FamilySolid, family_solid, fuse
from recon3d.surface.warp import WarpSettings

__all__ = ["Reconstruction", "reconstruct"]


@dataclass
class Reconstruction:
    """The surface of a run and what it was built from.

    surface : trimesh.Trimesh -- watertight, ``face_attributes['label']`` (f,) int.
    regions : list of list of SliceRegion -- per family, per slice.
    solids : list of FamilySolid or None -- per family (None: no surface).
    step : float -- grid step of the level set.
    notes : list of str -- why a family gave no surface.
    route : str -- between-slice route; fusion : str -- rule for several families.
    """

    surface: trimesh.Trimesh
    regions: list[list[SliceRegion]]
    solids: list[FamilySolid | None]
    step: float
    notes: list[str] = field(default_factory=list)
    route: str = "warp"
    fusion: str = "weighted"


def reconstruct(run: MeshRun, route: str = "warp", fusion: str = "weighted",
                trust: ConfidenceSettings = ConfidenceSettings(),
                blend: FusionSettings = FusionSettings(),
                caps: CapSettings = CapSettings(),
                regions: list[list[SliceRegion]] | None = None,
                warp: WarpSettings = WarpSettings(), pair: Callable | None = None
                ) -> Reconstruction:
    """Close, stack and fuse the slices of a :class:`recon3d.records.MeshRun`.

    Parameters
    ----------
    run : MeshRun
    route : {'warp', 'linear'} -- between-slice route (:data:`recon3d.surface.field.ROUTES`).
    fusion : {'weighted', 'carve'} -- rule for several families
        (:data:`recon3d.surface.solid.FUSIONS`).
    trust : ConfidenceSettings -- how much each family knows where (weighted fusion).
    blend : FusionSettings -- parameters of the weighted fusion.
    caps : CapSettings -- with ``route='warp'``, space a slice only closed (unknown chords,
        bridges) ends at that slice between slices (:mod:`recon3d.surface.caps`).
    regions : list of list of SliceRegion, optional -- every slice's
        :func:`~recon3d.surface.closure.result_region` (snap ``2 * run.tol``), per family,
        already computed (e.g. as the slices were sensed); None: computed here.
    warp : WarpSettings -- the aligned blend (:mod:`recon3d.surface.warp`).
    pair : callable(first, second) -> (first(), second()), optional -- runs two halves of
        each family's field (:func:`recon3d.surface.field.family_volume`; the same field
        however they run), e.g. one in a forked child; None: here, one after the other.
    """
    step = grid_step(run.eps, diagonal(run.mesh))
    keep = fusion == "weighted" and len(run.families) > 1
    lengths = closure_lengths(run.eps, run.tol, run.read_noise, run.config.taxel)
    given, regions, solids, notes = regions, [], [], []
    for f, fam in enumerate(run.families):
        regs = (list(given[f]) if given is not None else
                [result_region(s.result, *lengths) for s in fam.slices])
        regions.append(regs)
        if len(fam.slices) < 2:
            solids.append(None)
            notes.append(f"family {fam.label}: a surface needs at least 2 slices")
            continue
        solid = family_solid(regs, [s.slice.plane for s in fam.slices], step, route, keep,
                             trust, caps, warp, pair)
        if solid is None:
            notes.append(f"family {fam.label}: nothing sensed, no surface")
        solids.append(solid)
    surface = fuse(solids, run.mesh.bounds, fusion, blend)
    return Reconstruction(surface, regions, solids, step, notes, route, fusion)
