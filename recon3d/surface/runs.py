"""A fill closed by chords on a run of consecutive slices ends where the run's neighbours
show the space empty.

The caps rule (:mod:`recon3d.surface.caps`) compares two neighbouring slices. A pocket whose
mouth the probe closed with unknown chords A_iB_i (§3.3: the lid of an area G_i still
unknown at the end) on several slices in a row -- slices ``i`` .. ``j`` -- is capped only at
the run's two ends (towards ``i - 1`` and ``j + 1``, which show it empty); inside the run the
slices agree, so the blend keeps the fill between them, and the two end slices keep a plate
each (``vtk_42400-IDGH`` along z, slices 6 - 9 of 16).

The rule: a fill of slice ``i`` that the caps rule ends at ``i`` towards ``i - 1`` is
followed upwards. On slice ``k > i`` it continues as the part of ``k``'s region that ``i - 1``
shows empty, within a gap of what was followed on ``k - 1`` (a face under 45 degrees moves
less), as long as ``k``'s boundary along it is unsensed
(:func:`recon3d.surface.caps.unsensed_side`: mostly unknown chords or bridges). When the caps
rule ends that part at ``k`` towards ``k + 1`` as well, the run ``i`` .. ``k`` is closed on
both sides by slices that show the space empty: on every slice of the run the followed fill
is dropped where both run neighbours show it empty, its value becoming the run neighbours'
fields interpolated by height (negative). A run that reaches the family's end slice, or
meets a traced wall, keeps its fill. Runs of one slice are
:func:`recon3d.surface.caps.own_caps`' case (it gives the same there).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.ndimage import binary_dilation, label

from recon3d.surface.caps import CapSettings, unsensed_pieces, unsensed_side

__all__ = ["RunDrop", "run_caps"]


@dataclass(frozen=True)
class RunDrop:
    """Where a slice took its run neighbours' say (for the confidence, too).

    slice : int -- the slice whose field changed.
    lo, hi : int -- the run's neighbouring slices (``lo < slice < hi``).
    t : float -- the slice's height as a fraction from ``lo`` to ``hi``.
    mask : (ny, nx) bool -- the nodes dropped.
    """

    slice: int
    lo: int
    hi: int
    t: float
    mask: np.ndarray


def _connected_to(mask: np.ndarray, seed: np.ndarray) -> np.ndarray:
    """(ny, nx) bool: the components of ``mask`` that meet ``seed``."""
    comp, n = label(mask)
    if n == 0:
        return mask
    keep = np.zeros(n + 1, dtype=bool)
    keep[np.unique(comp[seed & mask])] = True
    keep[0] = False
    return keep[comp]


def run_caps(f: list, capped: list, regions, grid, clip: list,
             settings: CapSettings = CapSettings()) -> tuple[list, list[RunDrop]]:
    """The slices' fields with the fills closed on runs of >= 2 slices dropped (module doc).

    Parameters
    ----------
    f : list of (ny, nx) float32 -- the slices' fields (ascending heights), m of them.
    capped : list of GapCaps or None -- the caps rule's decision per gap ``i`` (``i, i + 1``).
    regions : list of SliceRegion -- the slices' regions (for the pieces' kinds).
    grid : FamilyGrid
    clip : list of float -- per gap, the truncation the blend uses.
    settings : CapSettings -- ``runs`` switches the rule.

    Returns
    -------
    f : list of (ny, nx) float32 -- new arrays where something changed, else the same.
    drops : list of RunDrop
    """
    m = len(f)
    if not (settings.enabled and settings.runs) or m < 4:
        return list(f), []
    nodes, step = grid.nodes(), grid.step
    pieces = {}

    def pcs(i):
        if i not in pieces:
            pieces[i] = unsensed_pieces(regions[i], step)
        return pieces[i]

    heights = np.asarray(grid.heights, dtype=np.float64)
    out, drops = list(f), []
    tiny = np.float32(1e-3 * step)
    grow = max(1, int(np.ceil(max(clip) / step)))  # a face under 45 degrees moves <= a gap
    for i in range(1, m - 2):
        lo = capped[i - 1]
        if lo is None or not lo.fill_b.any():
            continue
        followed = [lo.fill_b]
        for k in range(i + 1, m - 1):
            near = binary_dilation(followed[-1], iterations=grow)
            part = (f[k] > 0) & (f[i - 1] <= 0) & near
            if not part.any() or not unsensed_side(part, f[k], nodes, pcs(k), step, settings):
                break
            followed.append(part)
            hi = capped[k]
            if hi is None or not (hi.fill_a & part).any():
                continue
            for j in range(len(followed) - 2, -1, -1):  # only the components of the run
                followed[j] = _connected_to(followed[j], followed[j + 1])
            empty = (f[i - 1] <= 0) & (f[k + 1] <= 0)
            span = heights[k + 1] - heights[i - 1]
            for j, mask in zip(range(i, k + 1), followed):
                drop = mask & empty
                if not drop.any():
                    continue
                w = float((heights[j] - heights[i - 1]) / span)
                say = (1 - w) * f[i - 1] + w * f[k + 1]
                g = out[j].copy()
                g[drop] = np.minimum(g[drop], np.minimum(say[drop], -tiny))
                out[j] = g
                drops.append(RunDrop(j, i - 1, k + 1, w, drop))
            break
    return out, drops
