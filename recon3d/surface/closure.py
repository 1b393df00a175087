"""The closed region of one sensed slice, built from its W1/W2/W3 pieces.

The planner reports pieces, not loops: W1 polylines, W2 segments, W3 lids
and the chords ``A B`` of areas still unknown when a budget hit. They do not
always close: an area can stay unknown, two separate objects can leave an
opening with no segment, a piece can be stray. The rule, in order:

0. **chords the probe went through** -- an unknown chord
   that a posture of the probe crosses farther than ``margin`` from both its
   ends is left out: the rod, from its joint to its tip, held that posture and
   touched the contour only at its contacts (§3.2: it does not penetrate), so
   the space on both sides of the chord there is empty, and the chord closes
   nothing the probe did not see through. Such chords (a lid from a slot's
   floor across a tooth to the next slot's wall, laid by a split of an area that
   ended unknown) would otherwise fill the slots the probe traced.
1. **snap** -- piece end points closer than ``snap`` become one node (their
   mean), so pieces that meet up to the contact resolution share an end;
2. **bridge** -- nodes of odd degree (free ends) are paired greedily,
   closest pair first, and joined by a straight *bridge*; bridges are not
   sensed (surface label 4);
3. **fill** -- the pieces and bridges are noded and polygonised (shapely);
   the region is the union of every bounded face, i.e. everything a path
   from infinity cannot reach without crossing a piece. Holes are therefore
   filled (the probe cannot see them), stray pieces outside add at most a
   sliver between the piece and its bridge, and pieces inside the material
   change nothing.
3b. **the sensed pieces' own region** (a noisy sensor only) -- the region
   that the W1 / W2 / W3 pieces close without the unknown chords (steps 1 - 3)
   is added. An unknown chord ends where its area's A_i and B_i were read,
   and a noisy revisit's split can lay one through material, from one wall
   to another; its ends then take the free ends that the bridges would have
   joined, the traced contour stays open there, and the faces between such
   chords are lost (``gear`` z4 of 8 at sigma 0.3 eps: a third of the
   section). Unknown chords add what they close, never take away what the
   traced contour closes. Without noise the step is left out: it would
   bridge free ends the chords kept apart (``comb``: F@1 % 0.897 -> 0.870),
   and only a noisy sensor's region is carved by what the probe swept (step 4).
4. **carve** (a noisy sensor only) -- what the probe's motions swept, away from the
   sensed pieces, is cut from the region (:func:`recon3d.surface.sweep.carve`): the
   noisy pieces' loose ends are bridged closest first, and a bridge across a slot's
   mouth would fill the slot the probe went down; a chamber behind a neck, or a slot
   merged with the body through a gap in a wall, keeps its material less the swept part.

Examples
--------
>>> sq = [np.array([[0., 0.], [4., 0.], [4., 4.]]), np.array([[4., 4.], [0., 4.], [0., 0.2]])]
>>> reg = slice_region(sq, [], [], [], snap=1e-6)
>>> round(reg.area, 6), [p.kind for p in reg.pieces]
(16.0, ['W1', 'W1', 'bridge'])
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import shapely
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from core2d.resolution import Resolution
from recon3d.surface.sweep import carve, probe_length, swept_areas, unit

__all__ = ["Piece", "SliceRegion", "slice_region", "result_region", "probe_postures",
           "closure_lengths", "ClosureLengths", "sample_pieces", "KIND_LABEL"]

KIND_LABEL = {"W1": 1, "W2": 2, "W3": 3, "unknown": 4, "bridge": 4}
"""Surface label of the faces nearest to a piece of each kind."""


@dataclass(frozen=True)
class Piece:
    """One polyline of a slice's closed curve.

    points : (k, 2) float -- in the slice's 2D frame (ends snapped).
    kind : str -- 'W1', 'W2', 'W3', 'unknown' or 'bridge'.
    """

    points: np.ndarray
    kind: str


@dataclass(frozen=True)
class SliceRegion:
    """The filled region of one slice.

    geometry : shapely (Multi)Polygon, possibly empty.
    pieces : tuple of Piece -- the sensed pieces (ends snapped) and the bridges.
    """

    geometry: shapely.Polygon | shapely.MultiPolygon
    pieces: tuple[Piece, ...]

    @property
    def area(self) -> float:
        return float(self.geometry.area)

    @property
    def bridge_length(self) -> float:
        """Total length of the bridges added to close the curve."""
        return float(sum(np.hypot(*np.diff(p.points, axis=0).T).sum()
                         for p in self.pieces if p.kind == "bridge"))


def _raw_pieces(w1, w2, w3, unknown) -> list[Piece]:
    out = []
    for kind, group in (("W1", w1), ("W2", w2), ("W3", w3), ("unknown", unknown)):
        for pts in group:
            pts = np.asarray(pts, dtype=np.float64).reshape(-1, 2)
            if len(pts) >= 2 and np.isfinite(pts).all():
                out.append(Piece(pts.copy(), kind))
    return out


def _snap(pieces, snap) -> tuple[list[Piece], np.ndarray, np.ndarray]:
    """Merge end points closer than ``snap``; return pieces, node of each end, node points."""
    ends = np.array([p.points[i] for p in pieces for i in (0, -1)]).reshape(-1, 2)
    if len(ends) == 0:
        return [], np.zeros(0, dtype=np.int64), np.zeros((0, 2))
    pairs = cKDTree(ends).query_pairs(snap, output_type="ndarray")
    n = len(ends)
    adj = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, node = connected_components(adj, directed=False)
    counts = np.bincount(node)
    where = np.zeros((len(counts), 2))
    np.add.at(where, node, ends)
    where /= counts[:, None]
    out = []
    for k, p in enumerate(pieces):
        pts = p.points.copy()
        pts[0], pts[-1] = where[node[2 * k]], where[node[2 * k + 1]]
        out.append(Piece(pts, p.kind))
    return out, node, where


def _bridges(node, where) -> list[Piece]:
    """Pair the odd-degree nodes greedily, closest first."""
    odd = np.flatnonzero(np.bincount(node, minlength=len(where)) % 2 == 1)
    if len(odd) < 2:
        return []
    pts = where[odd]
    d = np.hypot(*(pts[:, None, :] - pts[None, :, :]).transpose(2, 0, 1))
    i, j = np.triu_indices(len(odd), k=1)
    order = np.lexsort((j, i, d[i, j]))  # deterministic on ties
    free = np.ones(len(odd), dtype=bool)
    out = []
    for a, b in zip(i[order], j[order]):
        if free[a] and free[b]:
            free[a] = free[b] = False
            out.append(Piece(np.stack([pts[a], pts[b]]), "bridge"))
    return out


def slice_region(w1, w2, w3, unknown, snap: float, free=None,
                 margin: float | None = None, jitter: float = 0.0, swept=None,
                 close: float = 0.0) -> SliceRegion:
    """Close the sensed pieces of one slice and fill them (see module doc).

    Parameters
    ----------
    w1 : list of (k, 2) float -- traced polylines.
    w2, w3, unknown : list of (2, 2) float -- W2 segments, W3 lids, unknown chords.
    snap : float -- end points closer than this are joined.
    free : (p, 2, 2) float, optional -- probe postures, joint to tip (:func:`probe_postures`):
        unknown chords they cross are left out (step 0); None: no step 0.
    margin : float, optional -- how far from a chord's ends a posture must cross it
        (default ``snap``).
    jitter : float -- how far two readings of one point may lie apart (a noisy sensor's,
        :attr:`core2d.resolution.Resolution.jitter`); above 0: step 3b, and with ``swept``
        step 4.
    swept : (s,) shapely geometries, optional -- the areas the probe's motions swept
        (:func:`recon3d.surface.sweep.swept_areas`); with ``jitter`` above 0, cut from the
        region away from the sensed pieces (step 4); None: no step 4.
    close : float -- step 4's closing radius: gaps narrower than ``2 close`` between the
        swept areas count as swept.

    Returns
    -------
    SliceRegion
    """
    if free is not None and len(free) and len(unknown):
        gone = _pierced(unknown, free, snap if margin is None else margin)
        unknown = [c for c, g in zip(unknown, gone) if not g]
    pieces, geom = _closed(_raw_pieces(w1, w2, w3, unknown), snap)
    if not pieces:
        return SliceRegion(shapely.Polygon(), ())
    if jitter > 0 and any(p.kind == "unknown" for p in pieces):  # step 3b
        geom = shapely.union(geom, _closed(_raw_pieces(w1, w2, w3, []), snap)[1])
    if jitter > 0 and swept is not None:
        sensed = [p.points for p in pieces if p.kind in ("W1", "W2", "W3")]
        geom = carve(geom, sensed, swept, snap, jitter, close)
    return SliceRegion(geom, tuple(pieces))


def _closed(pieces, snap: float) -> tuple[list[Piece], shapely.Geometry]:
    """Steps 1 - 3: the pieces snapped and bridged, and the union of their bounded faces."""
    pieces, node, where = _snap(pieces, snap)
    pieces = pieces + _bridges(node, where)
    if not pieces:
        return [], shapely.Polygon()
    coords = np.concatenate([p.points for p in pieces])
    lines = shapely.linestrings(coords, indices=np.repeat(np.arange(len(pieces)),
                                                          [len(p.points) for p in pieces]))
    # fixed-precision noding (grid = snap / 8) is robust where floating noding fails
    noded = shapely.union_all(lines, grid_size=snap / 8)
    geom = shapely.union_all(shapely.get_parts(shapely.polygonize(shapely.get_parts(noded))))
    if geom.geom_type not in ("Polygon", "MultiPolygon"):  # empty collection
        geom = shapely.Polygon()
    return pieces, geom


def _pierced(chords, free, margin: float) -> np.ndarray:
    """(c,) bool: which chords a posture crosses farther than ``margin`` from both ends."""
    chords = np.asarray(chords, dtype=np.float64).reshape(-1, 2, 2)
    free = np.asarray(free, dtype=np.float64).reshape(-1, 2, 2)
    free = free[np.isfinite(free).all(axis=(1, 2))]
    out = np.zeros(len(chords), dtype=bool)
    if not len(free) or not len(chords):
        return out
    d = chords[:, 1] - chords[:, 0]
    length = np.hypot(*d.T)
    keep = length > 2 * margin  # the middle of the chord, margin from each end
    if not keep.any():
        return out
    u = d[keep] / length[keep, None]
    mid = shapely.linestrings(np.stack([chords[keep, 0] + margin * u,
                                        chords[keep, 1] - margin * u], axis=1))
    hit, _ = shapely.STRtree(shapely.linestrings(free)).query(mid, predicate="intersects")
    out[np.flatnonzero(keep)[np.unique(hit)]] = True
    return out


def probe_postures(motions) -> np.ndarray:
    """(p, 2, 2) float: the probe, joint to tip, after every motion of a slice's
    :class:`core2d.motionlog.MotionLog` as its joint sensors reported it (``seen``; none
    without a log)."""
    if motions is None or not len(motions):
        return np.zeros((0, 2, 2))
    seen, after = (np.asarray(x, dtype=np.float64) for x in (motions.seen, motions.after))

    # the logged tip moved by the reading's errors: a perfect sensor's tips are the logged
    # ones to the bit (the joint plus L t would differ in the last digits)
    tip = (np.asarray(motions.tip, dtype=np.float64) + (seen[:, :2] - after[:, :2])
           + probe_length(motions) * (unit(seen[:, 2]) - unit(after[:, 2])))
    return np.stack([seen[:, :2], tip], axis=1)


class ClosureLengths(NamedTuple):
    """The lengths of a run's closure (:func:`closure_lengths`)."""

    snap: float
    """End points closer than this are joined (``2 tol``)."""
    noise: float
    """The sensor's standard deviation (0: the paper's perfect sensing)."""
    jitter: float
    """How far two readings of one point may lie apart (:class:`core2d.resolution.Resolution`)."""
    close: float
    """Step 4's closing radius, half the W2 distance ``eps + jitter``: gaps between swept
    areas narrower than the W2 distance are below the method's resolution (§4.3: two
    contacts closer than eps are joined by a segment, W2)."""


def closure_lengths(eps: float, tol: float, noise: float = 0.0,
                    taxel: float = 0.0) -> ClosureLengths:
    """The :class:`ClosureLengths` of a run with ``eps`` and ``tol`` (lengths) and a sensor of
    ``noise`` and ``taxel`` given in eps (0, 0: the paper's perfect sensing).

    >>> closure_lengths(1.0, 0.05)
    ClosureLengths(snap=0.1, noise=0.0, jitter=0.0, close=0.5)
    >>> [round(x, 3) for x in closure_lengths(2.0, 0.1, noise=0.3, taxel=0.25)]
    [0.2, 0.6, 3.046, 2.523]
    """
    res = Resolution.of(eps, tol, noise=noise * eps, taxel=taxel * eps)
    return ClosureLengths(2.0 * tol, noise * eps, res.jitter, (eps + res.jitter) / 2.0)


def result_region(result, snap: float, noise: float = 0.0, jitter: float = 0.0,
                  close: float = 0.0) -> SliceRegion:
    """:func:`slice_region` of a :class:`core2d.SliceResult`: its pieces, less the unknown
    chords its motion log's reported postures went through (margin ``snap + 3 noise`` from
    the ends, ``noise`` the sensor's standard deviation, a length); when ``jitter`` (the
    sensor's, a length) is above 0, less what its motions swept (closing radius
    ``close``)."""
    motions = getattr(result, "motions", None)
    swept = None
    if jitter > 0 and motions is not None and len(motions):
        swept = swept_areas(motions, probe_length(motions), snap)
    return slice_region(result.w1, result.w2, result.w3, result.unknown, snap,
                        probe_postures(motions), snap + 3.0 * noise, jitter, swept, close)


def sample_pieces(pieces, spacing: float) -> tuple[np.ndarray, np.ndarray]:
    """Points along polylines, no farther apart than ``spacing``, ends included.

    Parameters
    ----------
    pieces : list of Piece (or of (k, 2) float arrays)
    spacing : float

    Returns
    -------
    points : (n, 2) float
    owner : (n,) int -- index of the piece of each point.

    >>> pts, owner = sample_pieces([np.array([[0., 0.], [1., 0.]])], 0.5)
    >>> pts[:, 0].tolist(), owner.tolist()
    ([0.0, 0.5, 1.0], [0, 0, 0])
    """
    pts = [np.asarray(getattr(p, "points", p), dtype=np.float64).reshape(-1, 2) for p in pieces]
    if not pts:
        return np.zeros((0, 2)), np.zeros(0, dtype=np.int64)
    a = np.concatenate([p[:-1] for p in pts])
    b = np.concatenate([p[1:] for p in pts])
    seg_owner = np.repeat(np.arange(len(pts)), [len(p) - 1 for p in pts])
    k = np.maximum(np.ceil(np.hypot(*(b - a).T) / spacing), 1).astype(np.int64)
    seg = np.repeat(np.arange(len(a)), k)
    t = (np.arange(len(seg)) - np.repeat(np.cumsum(k) - k, k)) / k[seg]
    inner = a[seg] + t[:, None] * (b - a)[seg]
    last = np.array([p[-1] for p in pts])
    return (np.concatenate([inner, last]),
            np.concatenate([seg_owner[seg], np.arange(len(pts))]))
