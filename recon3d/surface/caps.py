"""Space a slice only closed, not sensed, ends at that slice between slices.

The closure (:mod:`recon3d.surface.closure`) fills everything its pieces enclose, unknown
chords A_iB_i (§3.3: the lid of an area G_i still unknown at the end) and bridges included.
Where two neighbouring slices disagree, the blend between them (:mod:`recon3d.surface.warp`)
moves one slice's boundary into the other's as if both were walls. When the boundary on one
side is a chord or a bridge -- no contact showed a surface there -- that makes surface the
sensing never saw: a tent over a triangle a chord closes in one slice and not in the next
(the Ravens cup's cavity along x, ``vtk_42400-IDGH`` along z), sheets along the thin slit
between two chords crossing the open teapot's pot.

The rule, per gap between slices ``a`` and ``b`` and per connected component of the nodes
where they disagree (inside ``a``, outside ``b``, or the other way round; the parts wider than
``2 thin + 1`` steps are decided on their own, so that a thin strip where a wall moved a
little does not join a wide fill to that wall):

* the component's boundary on each side -- where that slice's boundary bounds it, farther
  than ``reach`` steps from the other slice's boundary (where both run side by side a wall
  moved, which says nothing) -- is split by the kind of that slice's nearest piece: sensed
  (W1, W2, W3) or not (unknown chords, bridges), and called unsensed when more than
  ``share`` of it is;
* **a fill** of ``a`` ends at ``a`` when its boundary is unsensed, ``b``'s is not, and
  somewhere in it both slices' boundaries lie a gap (``deep``) away: a thinner disagreement
  is a face that moved under 45 degrees, which the blend keeps;
* **an empty** of ``b`` ends at ``b`` (only with ``slits``, off by default: see
  :class:`CapSettings`) when its boundary is unsensed, ``a``'s boundary along it is not sensed
  either and at most ``enclosed`` of ``b``'s (``a``'s fill encloses it: a slit between
  chords; a traced wall round it means the probe entered);
* otherwise the blend is left alone (both sides sensed: a true change of shape).

"Ends at its slice": the blend there is never more solid (more empty) than the plain blend
of the capped value, chosen to cross 0 at ``at`` x the gap from that slice, and the alignment
pairs no boundary sample of the capped component. A slice whose fill (empty) is capped
towards **both** neighbours drops (fills) it on its own plane too (:func:`own_caps`):
otherwise a flat plate of surface stays on the plane. The end slices keep theirs. There the
slice's confidence (for fusing families, :mod:`recon3d.surface.confidence`) becomes at least
its neighbours' mean (``own_trust``): the dropped value is their sensing, not the chord's
'unseen' fill, so another family's filled-in solid does not put the plate back (the Ravens
cup along z+x: a plate across the cavity on an x plane).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.ndimage import binary_dilation, binary_opening, label
from scipy.spatial import cKDTree

from recon3d.surface.closure import sample_pieces
from recon3d.surface.per_label import label_maximum

__all__ = ["CapSettings", "GapCaps", "unsensed_pieces", "cap_unsensed", "unsensed_side",
           "own_caps"]

UNSENSED = ("unknown", "bridge")
"""Piece kinds no contact showed: the closure's chords of unknown areas and its bridges."""


@dataclass(frozen=True)
class CapSettings:
    """Parameters of the rule (module doc).

    enabled : bool -- apply the rule (False: the plain aligned blend).
    share : float -- least share of a side's boundary on unsensed pieces to call it unsensed.
    reach : float -- a boundary node counts when a piece lies within this many grid steps.
    at : float -- where a capped component ends, fraction of the gap from its own slice
        (0: at the slice itself, 0.5: half-way).
    thin : int -- grid steps of the opening that splits a component's wide parts off its
        thin strips (0: whole components only).
    deep : float -- a fill is capped only where, somewhere in it, each slice's boundary lies
        at least this many gaps from the other's (the fields are truncated at the gap: at
        most 1).
    slits : bool -- also cap empties (off by default). Measured (``bench/surface_cases.py``,
        F@1%): it lifts the open teapot along x 0.8858 -> 0.9158 and along z 0.8270 ->
        0.8634, but z+x only to 0.9019 (z's probe swept channels inside the pot, which carve
        x's filled interior): z+x would fall 0.014 below x alone, where it is equal without.
    enclosed : float -- an empty is capped only where the filled slice's boundary along it
        is at most this share of the empty slice's (the fill encloses it: a slit).
    own : bool -- a slice's own unsensed fill (empty) that the rule caps towards both
        neighbouring slices is dropped (filled) on the slice itself (:func:`own_caps`).
    steps : bool -- a lid between two slices that neither neighbouring gap continues is a
        step at mid-gap, not a ramp (:mod:`recon3d.surface.steps`).
    step_tol : float -- grid steps: a wall that moved less stands still (same module).
    runs : bool -- a fill closed by chords on a run of two or more slices in a row, which
        the run's neighbouring slices show empty, is dropped on the run's slices
        (:mod:`recon3d.surface.runs`).
    own_trust : bool -- there the slice's confidence (for fusing families) becomes at least
        the mean of its neighbours': the value is their say (off: the slice keeps the
        'unseen' trust of its chord's fill, and another family's filled-in solid outweighs
        the dropped fill on the plane -- a plate across the Ravens cup's cavity along x).
    """

    enabled: bool = True
    share: float = 0.5
    reach: float = 2.0
    at: float = 0.0
    thin: int = 2
    own: bool = True
    own_trust: bool = True
    deep: float = 1.0
    slits: bool = False
    enclosed: float = 0.25
    runs: bool = True
    steps: bool = True
    step_tol: float = 0.5


def unsensed_pieces(region, step: float):
    """KD-tree over a region's pieces (every step / 4) and per sample whether it is unsensed.

    Returns
    -------
    tree : cKDTree or None (no pieces); unsensed : (n,) bool.
    """
    pts, owner = sample_pieces(region.pieces, step / 4)
    if len(pts) == 0:
        return None, np.zeros(0, dtype=bool)
    kinds = np.array([p.kind in UNSENSED for p in region.pieces])
    return cKDTree(pts), kinds[owner]


def _side_share(comp, ncomp, edge, nodes, pieces, reach):
    """Per component: the share of its edge nodes whose nearest piece is unsensed (nan: no
    edge node near a piece) and the number of edge nodes near a piece; (ncomp,) each."""
    tree, uns = pieces
    sel = np.flatnonzero(edge.ravel())
    if tree is None or len(sel) == 0:
        return np.full(ncomp, np.nan), np.zeros(ncomp)
    d, j = tree.query(nodes[sel], distance_upper_bound=reach)
    hit = np.isfinite(d)
    lab = comp.ravel()[sel][hit] - 1
    tot = np.bincount(lab, minlength=ncomp).astype(float)
    bad = np.bincount(lab, weights=uns[j[hit]].astype(float), minlength=ncomp)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(tot > 0, bad / tot, np.nan), tot


def _decide(comp, n, fa, fb, nodes, pa, pb, reach, deep, settings):
    """Per labelled component of ``comp`` (0: none): (cap a's fill, cap b's empty) masks."""
    if n == 0:
        none = np.zeros(comp.shape, dtype=bool)
        return none, none
    # where a's (b's) boundary bounds it, away from the other slice's boundary: where both
    # run side by side a wall moved a little, and that says nothing about the fill
    in_comp = comp > 0
    edge_a = in_comp & binary_dilation(fa <= 0) & (np.abs(fb) > reach)
    edge_b = in_comp & binary_dilation(fb > 0) & (np.abs(fa) > reach)
    sa, na = _side_share(comp, n, edge_a, nodes, pa, reach)
    sb, nb = _side_share(comp, n, edge_b, nodes, pb, reach)
    ua, ub = sa > settings.share, sb > settings.share  # nan compares False
    sensed_a = sa <= settings.share  # nan (no boundary of a there) compares False
    # a's fill: closed by chords where b's side is not, and somewhere in it each slice's
    # boundary lies ``deep`` from the other's (thinner: a wall that moved, under 45 degrees)
    deep_ab = label_maximum(np.minimum(fa, -fb), comp, n) >= deep
    # b's empty (``slits``): bounded by chords, a's fill around it not traced either (a traced
    # wall round it: the probe entered) and enclosing it (a's boundary along it is short)
    enclosed = na <= settings.enclosed * nb
    lut_a = np.concatenate([[False], ua & ~ub & deep_ab])
    lut_b = np.concatenate([[False], ub & ~sensed_a & enclosed & settings.slits])
    return lut_a[comp], lut_b[comp]


def _one_way(fa, fb, nodes, pa, pb, reach, deep, settings):
    """Nodes inside ``a``, outside ``b``: (cap a's fill mask, cap b's empty mask).

    Decided per connected component; the parts of a component wider than ``2 thin + 1``
    steps (a morphological opening) are decided on their own first, so that a thin strip
    where a wall moved a little does not join a wide fill to that wall's sensed boundary.
    """
    mask = (fa > 0) & (fb <= 0)
    comp, n = label(mask)
    fill, empty = _decide(comp, n, fa, fb, nodes, pa, pb, reach, deep, settings)
    if settings.thin > 0:
        wide = binary_opening(mask, iterations=settings.thin)
        comp_w, n_w = label(wide)
        fill_w, empty_w = _decide(comp_w, n_w, fa, fb, nodes, pa, pb, reach, deep, settings)
        fill = np.where(wide, fill_w, fill)
        empty = np.where(wide, empty_w, empty)
    return fill, empty


def unsensed_side(mask, fa, nodes, pa, step: float, settings: CapSettings = CapSettings()
                  ) -> bool:
    """Whether slice ``a``'s boundary along ``mask`` ((ny, nx) bool, inside ``a``) is unsensed:
    more than ``share`` of the mask's nodes next to ``a``'s boundary have an unknown chord or
    a bridge as their nearest piece (within ``reach`` steps).

    fa : (ny, nx) float32 -- ``a``'s field; pa : its :func:`unsensed_pieces`.
    """
    edge = mask & binary_dilation(fa <= 0)
    share, _ = _side_share(mask.astype(np.int32), 1, edge, nodes, pa, settings.reach * step)
    return bool(share[0] > settings.share)


@dataclass(frozen=True)
class GapCaps:
    """The rule's decision for one gap (module doc); masks (ny, nx) bool.

    fill_a, fill_b : a's (b's) fill that ends at its own slice.
    empty_a, empty_b : a's (b's) empty space that ends at its own slice.
    ga, gb : (ny, nx) float32 -- the two fields with the capped side's value moved so that
        the plain blend ``(1 - w) ga + w gb`` crosses 0 at ``at`` from its own slice.
    """

    fill_a: np.ndarray
    fill_b: np.ndarray
    empty_a: np.ndarray
    empty_b: np.ndarray
    ga: np.ndarray
    gb: np.ndarray

    def skip(self) -> tuple[np.ndarray, np.ndarray]:
        """Nodes of a and b whose boundary samples the alignment must not pair (the capped
        components grown by a node: their boundary is a chord or a bridge)."""
        return (binary_dilation(self.fill_a | self.empty_a),
                binary_dilation(self.fill_b | self.empty_b))

    def apply(self, val: np.ndarray, w: np.ndarray) -> np.ndarray:
        """The blend ``val`` (k, ny, nx) with the capped components' plain capped blend:
        never more solid there than it (a capped fill), never more empty (a capped empty).

        w : (k, 1, 1) float -- fractions of the gap of the layers.
        """
        plain = (1 - w) * self.ga + w * self.gb
        out = np.where(self.fill_a | self.fill_b, np.minimum(val, plain), val)
        return np.where(self.empty_a | self.empty_b, np.maximum(out, plain),
                        out).astype(val.dtype)


def cap_unsensed(fa, fb, ra, rb, grid, gap: float, settings: CapSettings = CapSettings()
                 ) -> GapCaps | None:
    """The rule's decision for the gap between slices ``a`` and ``b`` (module doc).

    Parameters
    ----------
    fa, fb : (ny, nx) float32 -- slice ``a`` and ``b`` fields (positive inside), truncated.
    ra, rb : SliceRegion -- their regions (for the pieces' kinds).
    grid : FamilyGrid
    gap : float -- distance between the two planes.

    Returns
    -------
    GapCaps, or None when the rule is off or caps nothing.
    """
    if not settings.enabled:
        return None
    nodes = grid.nodes()
    s = grid.step
    pa, pb = unsensed_pieces(ra, s), unsensed_pieces(rb, s)
    reach = settings.reach * s
    deep = 0.999 * settings.deep * gap
    fill_a, empty_b = _one_way(fa, fb, nodes, pa, pb, reach, deep, settings)
    fill_b, empty_a = _one_way(fb, fa, nodes, pb, pa, reach, deep, settings)
    if not (fill_a.any() or fill_b.any() or empty_a.any() or empty_b.any()):
        return None
    r = settings.at / (1 - settings.at) if settings.at < 1 else np.inf
    tiny = np.float32(1e-3 * s)
    ga, gb = fa.copy(), fb.copy()
    # fill of a ending at ``at``: (1 - at) ga + at fb = 0, ga >= tiny, never raised
    ga[fill_a] = np.minimum(fa[fill_a], np.maximum(tiny, -r * fb[fill_a]))
    gb[fill_b] = np.minimum(fb[fill_b], np.maximum(tiny, -r * fa[fill_b]))
    # empty of b ending at ``at`` from b: at fa + (1 - at) gb = 0, gb <= -tiny, never lowered
    gb[empty_b] = np.maximum(fb[empty_b], np.minimum(-tiny, -r * fa[empty_b]))
    ga[empty_a] = np.maximum(fa[empty_a], np.minimum(-tiny, -r * fb[empty_a]))
    return GapCaps(fill_a, fill_b, empty_a, empty_b, ga, gb)


def own_caps(f: list, capped: list, step: float) -> list:
    """The slices' own fields, with what the rule caps towards both neighbours undone.

    A fill of slice ``i`` that both its gaps end at slice ``i`` would still leave a flat
    plate of surface on the plane (a chord's triangle in an open cavity, two faces of it);
    both neighbouring slices show the space empty and slice ``i`` only closed it, so the
    slice drops it: its value there becomes the mean of the neighbours' (negative), so that
    the fusion reads it as empty on this plane too. Likewise an unsensed empty (a slit between
    two chords) both neighbours fill is filled. End slices (one neighbour) keep theirs.

    Parameters
    ----------
    f : list of (ny, nx) float32 -- the slices' fields.
    capped : list of GapCaps or None -- per gap ``i`` (slices ``i``, ``i + 1``).
    step : float -- grid step.

    Returns
    -------
    list of (ny, nx) float32 -- new arrays where something changed, else the same.
    """
    out = list(f)
    tiny = np.float32(1e-3 * step)
    for i in range(1, len(f) - 1):
        lo, hi = capped[i - 1], capped[i]
        if lo is None or hi is None:
            continue
        drop = lo.fill_b & hi.fill_a
        fill = lo.empty_b & hi.empty_a
        if drop.any() or fill.any():
            g = f[i].copy()
            mean = 0.5 * (f[i - 1] + f[i + 1])  # the neighbours' say (both empty / both solid)
            g[drop] = np.minimum(g[drop], np.minimum(mean[drop], -tiny))
            g[fill] = np.maximum(g[fill], np.maximum(mean[fill], tiny))
            out[i] = g
    return out
