"""A lid between two slices that neither neighbouring gap continues is a step, not a ramp.

A probe moving in the slice plane meets a face parallel to the planes (a lid: a stair's
tread, a floor, the underside of a cap) only where a plane cuts it; between two planes the
lid's height is unknown within the gap. The aligned blend (:mod:`recon3d.surface.warp`)
matches the walls on both sides of the lid (same in-plane normal, a move within reach) and
makes a ramp from one slice's wall to the other's -- which is right for a slanted wall (a
cone moves its edge the same way) and wrong for a step.

Two slices cannot tell the two apart; their neighbours can: a slanted wall moves in the
neighbouring gaps too (a cone's edge moves in every gap), a step's walls stand still there
(a prism below the tread, a prism above). Per gap ``(a, b)`` = ``(i, i + 1)`` with both
neighbouring slices ``i - 1`` and ``i + 2`` (an end gap keeps the blend), and per connected
component of the nodes where ``a`` and ``b`` disagree (inside ``a``, outside ``b``, or the
other way round):

* the component's walls: ``a``'s boundary where it bounds the component, compared with slice
  ``i - 1``, and ``b``'s, compared with slice ``i + 2``; a wall **stands still** when the
  median of ``|f_neighbour - f_own|`` along it is at most ``tol`` grid steps;
* the component is a **step** when every wall it has stands still and it has one (a block
  that ends between two slices has only ``a``'s walls), and it is wider than ``tol`` steps
  somewhere; otherwise the blend is left alone (a wall that moves in a neighbouring gap: a
  slope, a thin tilted wall, the rounded end of a bent tube).

A step's component gets the nearest slice's field (``a``'s up to half the gap, ``b``'s
beyond): both walls run straight (in the slicing direction) to the middle of the gap and
the lid lies flat there, the least worst guess for a height the sensing does not know
(within half a gap). Its boundary samples are not matched by the alignment.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.ndimage import binary_dilation, label

from recon3d.surface.per_label import label_maximum, label_median

__all__ = ["GapSteps", "gap_steps"]


@dataclass(frozen=True)
class GapSteps:
    """The steps of one gap; masks (ny, nx) bool.

    mask : the components blended as steps (the nearest slice's field).
    """

    mask: np.ndarray

    @property
    def grown(self) -> np.ndarray:
        """The steps grown by two nodes: the nodes next to them (where the two slices agree)
        take the nearest slice's field too, so that the walls' zero crossings lie between
        values of one field (the blend's would pull them by up to a node)."""
        return binary_dilation(self.mask, iterations=2)

    def skip(self) -> np.ndarray:
        """Nodes whose boundary samples the alignment must not pair (the steps grown by three
        nodes)."""
        return binary_dilation(self.mask, iterations=3)

    def apply(self, val: np.ndarray, fa: np.ndarray, fb: np.ndarray, w: np.ndarray
              ) -> np.ndarray:
        """The blend ``val`` (k, ny, nx) with the steps' nearest-slice field (on a layer
        exactly half-way, the two fields' mean).

        fa, fb : (ny, nx) float32 -- the two slices' fields; w : (k, 1, 1) -- the layers'
        fractions of the gap.
        """
        near = np.where(w < 0.5, fa[None], np.where(w > 0.5, fb[None], 0.5 * (fa + fb)[None]))
        return np.where(self.grown[None], near, val).astype(val.dtype)


def _still(comp, n, edge, f_own, f_next, tol) -> tuple[np.ndarray, np.ndarray]:
    """Per component (n,): whether ``edge`` has nodes and a neighbouring slice, and whether
    the wall there stands still from the slice (``f_own``) to that neighbour (``f_next``):
    the median of |f_next - f_own| along ``edge`` within ``tol``."""
    if f_next is None:
        return np.zeros(n, dtype=bool), np.zeros(n, dtype=bool)
    lab = np.where(edge, comp, 0)
    has = label_maximum(edge, lab, n)
    med = np.asarray(label_median(np.abs(f_next - f_own), lab, n), dtype=np.float64)
    return has, has & (np.nan_to_num(med, nan=np.inf) <= tol)


def _one_way(fa, fb, f_before, f_after, tol):
    """Nodes inside ``a``, outside ``b`` blended as steps (module doc)."""
    mask = (fa > 0) & (fb <= 0)
    comp, n = label(mask)
    if n == 0:
        return mask
    has_a, still_a = _still(comp, n, mask & binary_dilation(fa <= 0), fa, f_before, tol)
    has_b, still_b = _still(comp, n, mask & binary_dilation(fb > 0), fb, f_after, tol)
    # a step: every wall along it stands still in the neighbouring gap, and one does
    step = (has_a | has_b) & (still_a | ~has_a) & (still_b | ~has_b)
    wide = label_maximum(np.minimum(fa, -fb), comp, n) > tol
    lut = np.concatenate([[False], step & wide])
    return lut[comp]


def gap_steps(fa, fb, before, after, step: float, tol: float = 0.5) -> GapSteps | None:
    """The steps of the gap between slices ``a`` and ``b`` (module doc).

    Parameters
    ----------
    fa, fb : (ny, nx) float32 -- the two slices' fields, truncated alike.
    before, after : (ny, nx) float32 or None -- the fields of the slice below ``a`` and of
        the one above ``b`` (same truncation); None at the family's ends.
    step : float -- grid step.
    tol : float -- grid steps: a wall that moved less stands still.

    Returns
    -------
    GapSteps, or None when the gap has no step or no neighbouring gap.
    """
    if before is None or after is None:  # an end gap: one side unknown
        return None
    t = tol * step
    # a's fill recedes from a to b; b's fill is the same seen from b (the neighbours swap)
    mask = _one_way(fa, fb, before, after, t) | _one_way(fb, fa, after, before, t)
    return GapSteps(mask) if mask.any() else None
