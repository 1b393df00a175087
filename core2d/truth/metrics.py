"""Ground-truth metrics of one sensed slice (DESIGN.md "Metrics").

Evaluation code: it reads the true contour, the planner never does.

Definitions (``tol`` defaults to ``eps / 2``, ``spacing`` to ``tol / 2``):

* the true contour is sampled at sub-segment midpoints no farther apart than
  ``spacing`` (:func:`core2d.truth.reachability.sample_contour`); each sample
  stands for its piece of contour length; reachability is exact per sample
  (:func:`core2d.truth.reachability.reachable`);
* **coverage** -- length of reachable samples within ``tol`` of W1 u W2,
  or behind a W2 chord (on the arc ``C_A^B`` of a W2 segment: §3.1 regards
  ``L_A^B`` as the approximate surface of ``C_A^B`` when Dist(A, B) < eps),
  over the reachable length (a W2 "arc" longer than the rest of its loop is
  a reversed chord and credits nothing: ``w2_long_arcs`` counts them; nor does
  an arc that closes round material with its chord, the tip of a wall thinner
  than ``tol`` that a chord crosses: ``w2_material_arcs`` counts those that would
  credit reachable contour farther than ``tol`` from W1 u W2).
  ``eps / 2`` is the natural tolerance: every
  point of a W2 chord with ``Dist(A, B) < eps`` lies within ``eps / 2`` of
  ``A`` or ``B``. ``w2_credit_length`` is the part of the covered length that
  counts only through such an arc (farther than ``tol`` from W1 u W2): the walls
  of a slot closed by its W2 chord, never touched. A noisy sensor's W2 chords
  reach eps + jitter (:attr:`~core2d.resolution.Resolution.w2_dist`), so they
  can close slots wider than eps that a perfect sensor would have entered;
* **coverage_resolvable** -- the same over the reachable contour that the
  paper's resolution resolves (:mod:`core2d.truth.resolvable`: not inside an
  opening narrower than eps, which §3.1 closes by a W2 chord and never enters);
  ``resolvable_length`` is its length;
* **precision** -- length share of the detected geometry (W1 polylines and
  W2 segments, cut into pieces <= ``spacing``) within ``tol`` of the true
  contour; the two directed Hausdorff distances use the same samples
  (plus the detected vertices), so they are exact to ``spacing / 2``;
* **W3 soundness, per lid** -- a lid ``(A, B)`` covers ``C_A^B``: A and B are
  projected to the nearest contour point and the arc runs from A to B with
  the material on the right. Loops keep the material on their left (outer
  CCW, holes CW), so ``C_A^B`` is the arc of *decreasing* loop arc length
  from A to B, on outer loops and holes alike. A lid is **sound** when no
  reachable contour farther than ``eps`` from both A and B lies under it
  (the paper's resolution is eps) and its ends lie on one loop (it is not a
  bridge between two islands). ``w3_soundness`` = sound lids / lids;
  ``w3_hidden_reachable_length`` is the reachable length farther than eps
  from the ends under all lids, ``w3_cross_loop`` counts the bridges.

Ratios whose denominator is 0 are 1.0 (nothing to miss, nothing wrong);
Hausdorff distances with an empty side are ``None``.
"""
from __future__ import annotations

import numpy as np
import shapely

from core2d.resolution import Resolution
from core2d.result import SliceResult

from .nearest import segment_distances
from .reachability import ContourSamples, contour_edges, reachable_samples, subdivide
from .resolvable import resolvable

__all__ = ["slice_metrics", "sensor_metrics", "total_metrics", "lid_arcs", "w2_credit"]

_RATIOS = {"coverage": ("covered_length", "reachable_length"),
           "precision": ("precise_length", "detected_length"),
           "coverage_sensor": ("covered_length_sensor", "reachable_length"),
           "coverage_resolvable": ("covered_resolvable_length", "resolvable_length"),
           "coverage_resolvable_sensor": ("covered_resolvable_length_sensor",
                                          "resolvable_length"),
           "precision_sensor": ("precise_length_sensor", "detected_length")}
_MAX_KEYS = ("hausdorff_detected_to_true", "hausdorff_true_reachable_to_detected", "eps", "tol",
             "spacing", "sensor_tol")
#: the keys of :func:`slice_metrics` that :func:`sensor_metrics` reports at the sensor's tolerance
_SENSOR_KEYS = ("covered_length", "coverage", "precise_length", "precision", "w3_unsound_count",
                "covered_resolvable_length", "coverage_resolvable", "w2_credit_length",
                "w2_material_arcs")


def _segments(polylines) -> tuple[np.ndarray, np.ndarray]:
    """Consecutive vertex pairs of open polylines; a lone vertex gives a zero-length segment."""
    a, b = [np.zeros((0, 2))], [np.zeros((0, 2))]
    for pl in polylines:
        pl = np.asarray(pl, dtype=np.float64).reshape(-1, 2)
        if len(pl) == 1:
            pl = np.vstack([pl, pl])
        a.append(pl[:-1])
        b.append(pl[1:])
    return np.concatenate(a), np.concatenate(b)


def _nearest(tree, points) -> tuple[np.ndarray, np.ndarray]:
    """(m,) nearest tree item and distance for every point (-1 and inf for an empty tree)."""
    idx, dist = tree.query_nearest(shapely.points(points), all_matches=False, return_distance=True)
    item = np.full(len(points), -1, dtype=np.int64)
    d = np.full(len(points), np.inf)
    item[idx[0]], d[idx[0]] = idx[1], dist
    return item, d


def lid_arcs(loops, lids, samples: ContourSamples, resolution: float = 0.0) -> dict:
    """Contour arcs ``C_A^B`` under segments ``(A, B)`` (W3 lids or unknown areas).

    Parameters
    ----------
    loops : list of (k, 2) float -- the true contour.
    lids : list of (2, 2) float -- segments A -> B.
    samples : ContourSamples -- samples of ``loops``.
    resolution : float -- ends closer than this along the loop, in the
        reverse order, are one point (empty arc), not a walk round the loop.

    Returns
    -------
    dict with ``mask`` (m,) bool (samples under some same-loop lid),
    ``cross_loop`` (n,) bool, ``offset`` (n,) float (largest distance of A or
    B to the contour), ``arc_length`` (n,) float (0 for cross-loop lids) and
    ``member`` (n, m) bool (samples under each lid), ``loop`` (n,) int (loop
    of A, -1 without contour) and ``area`` (n,) float (signed area of the arc
    closed by its chord, A and B at their nearest contour points: positive round
    free space, the opening the chord spans; negative round material). Without any contour
    every lid counts as cross-loop, with an infinite offset.

    Examples
    --------
    >>> sq = [np.array([[0., 0.], [4., 0.], [4., 4.], [0., 4.]])]
    >>> from core2d.truth.reachability import sample_contour
    >>> arcs = lid_arcs(sq, [np.array([[4., 2.], [2., 4.]])], sample_contour(sq, 0.5))
    >>> float(arcs["arc_length"][0])  # down, along the bottom, up, to the middle of the top
    12.0
    >>> round(float(arcs["area"][0]), 1)  # round material: the square but the corner cut off
    -13.9
    """
    lids = np.asarray(lids, dtype=np.float64).reshape(-1, 2, 2)
    n, m = len(lids), len(samples.points)
    out = dict(mask=np.zeros(m, dtype=bool), cross_loop=np.zeros(n, dtype=bool),
               loop=np.full(n, -1, dtype=np.int64),
               offset=np.zeros(n), arc_length=np.zeros(n), area=np.zeros(n),
               member=np.zeros((n, m), dtype=bool))
    if n == 0:
        return out
    a, b, loop = contour_edges(loops)
    e = b - a
    elen = np.hypot(*e.T)
    start = np.cumsum(elen) - elen
    edge_s = start - (np.cumsum(samples.loop_lengths) - samples.loop_lengths)[loop]
    if len(a) == 0:  # no contour: nothing to put a lid on
        out.update(cross_loop=np.ones(n, dtype=bool), offset=np.full(n, np.inf))
        return out
    tree = shapely.STRtree(shapely.linestrings(np.stack([a, b], axis=1)))
    ends = lids.reshape(-1, 2)  # A0, B0, A1, B1, ...
    edge, dist = _nearest(tree, ends)
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.nan_to_num(np.clip(np.einsum("ij,ij->i", ends - a[edge], e[edge]) / elen[edge] ** 2, 0, 1))
    s = (edge_s[edge] + t * elen[edge]).reshape(n, 2)
    lp = loop[edge].reshape(n, 2)
    on_contour = a[edge] + t[:, None] * e[edge]  # A0, B0, A1, ... at their nearest contour points
    out["offset"] = dist.reshape(n, 2).max(axis=1)
    out["cross_loop"] = lp[:, 0] != lp[:, 1]
    out["loop"] = lp[:, 0]
    for i in np.flatnonzero(~out["cross_loop"]):
        length = samples.loop_lengths[lp[i, 0]]
        arc = (s[i, 0] - s[i, 1]) % length  # walk from A with decreasing s
        if length - arc <= resolution:  # A, B one point at this resolution: no arc,
            arc = 0.0  # not the whole loop the other way round
        under = (samples.loop == lp[i, 0]) & ((s[i, 0] - samples.s) % length <= arc)
        out["member"][i] = under
        out["arc_length"][i] = arc
        out["area"][i] = _closed_area(samples, under, s[i, 0], length, on_contour[2 * i:2 * i + 2])
    out["mask"] = out["member"].any(axis=0)
    return out


def w2_credit(loops, w2, samples: ContourSamples, spacing: float):
    """The contour §3.1 approximates by W2 chords: ``(behind, arcs, long, material)``.

    ``behind`` (m,) bool -- samples under the arc of some W2 chord that spans an
    opening; ``arcs`` -- :func:`lid_arcs` of ``w2``; ``long`` (n,) bool -- chords whose
    arc is longer than the rest of its loop (a reversed chord, not a W2 area);
    ``material`` (n,) bool -- chords whose arc runs round material (a chord across a
    thin wall's tip). Neither of the last two spans an opening, so neither credits
    its samples.
    """
    arcs = lid_arcs(loops, w2, samples, resolution=spacing)
    long_ = arcs["arc_length"] > 0.5 * np.append(samples.loop_lengths, 0.0)[arcs["loop"]]
    material = ~long_ & (arcs["area"] < 0)
    return arcs["member"][~long_ & ~material].any(axis=0), arcs, long_, material


def _closed_area(samples: ContourSamples, under, s_a: float, length: float, ends) -> float:
    """Signed area of the polygon A, the samples ``under`` a lid from A on, B (shoelace).

    The arc runs with the material on its right, so it closes round free space
    (an opening) counter-clockwise, positive, and round material clockwise. The
    samples, sub-segment midpoints, cut each corner by ``spacing / 2``; A is the origin, so
    coordinates of 1e6 lose no digits that matter."""
    idx = np.flatnonzero(under)
    order = idx[np.argsort((s_a - samples.s[idx]) % length, kind="stable")]
    x, y = (np.concatenate([ends[:1], samples.points[order], ends[1:]]) - ends[0]).T  # A at 0
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def slice_metrics(loops, result: SliceResult, eps: float, tol: float | None = None,
                  spacing: float | None = None, samples=None, lid_tol: float = 0.0,
                  resolved=None) -> dict:
    """Metrics of one :class:`core2d.result.SliceResult` against the true contour.

    Parameters
    ----------
    loops : list of (k, 2) float -- true contour of the slice (outer CCW, holes CW).
    result : SliceResult
    eps : float -- the planner's eps.
    tol : float, optional -- distance tolerance, default ``eps / 2``
        (:attr:`Resolution.metric_tol <core2d.resolution.Resolution.metric_tol>`).
    spacing : float, optional -- sampling step, default ``tol / 2``.
    samples : (ContourSamples, (m,) bool), optional -- a cached
        :func:`core2d.truth.reachability.reachable_samples` of ``loops`` at ``spacing``.
    lid_tol : float -- reachable contour behind a W3 lid within this of the
        lid itself is not hidden (0: any; :func:`sensor_metrics` passes the
        sensor's tolerance).
    resolved : (m,) bool, optional -- :func:`core2d.truth.resolvable.resolvable` of the
        samples (computed here when not given).

    Returns
    -------
    dict of JSON-serialisable numbers (see module doc), plus the counters of
    ``result.stats.as_dict()`` under their own names.
    """
    tol = Resolution.of(eps).metric_tol if tol is None else float(tol)
    spacing = 0.5 * tol if spacing is None else float(spacing)
    samp, reach = reachable_samples(loops, spacing) if samples is None else samples
    w = samp.lengths
    a, b, _ = contour_edges(loops)

    # detected geometry: W1 polylines and W2 segments
    w1a, w1b = _segments(result.w1)
    w2a, w2b = _segments(result.w2)
    da, db = np.concatenate([w1a, w2a]), np.concatenate([w1b, w2b])
    if len(da):
        d_true = segment_distances(samp.points, da, db)
        seg, frac, dl = subdivide(da, db, spacing)
        pts = np.concatenate([da[seg] + frac[:, None] * (db - da)[seg], da, db])
        d_det = segment_distances(pts, a, b)
        d_det_pieces = d_det[: len(seg)]
    else:
        d_true = np.full(len(w), np.inf)
        dl = d_det = d_det_pieces = np.zeros(0)
    behind_w2, w2_arcs, w2_long, w2_material = w2_credit(loops, result.w2, samp, spacing)
    covered = reach & ((d_true <= tol) | behind_w2)
    # the arcs round material that would credit reachable contour farther than tol
    w2_material &= (w2_arcs["member"] & (reach & (d_true > tol))).any(axis=1)
    reachable_length = float(w[reach].sum())
    resolved = (resolvable(loops, samp.points, eps) if resolved is None
                else np.asarray(resolved, dtype=bool))
    resolvable_length = float(w[reach & resolved].sum())
    covered_resolvable = float(w[covered & resolved].sum())
    detected_length = float(dl.sum())

    # W3 lids (per-lid soundness) and unknown areas
    lids = lid_arcs(loops, result.w3, samp, resolution=spacing)
    unk = lid_arcs(loops, result.unknown, samp, resolution=spacing)
    ends = np.asarray(result.w3, dtype=np.float64).reshape(-1, 2, 2)
    far = np.ones((len(ends), len(w)), dtype=bool)
    for k in range(2):  # farther than eps from both ends of each lid
        far &= np.hypot(*(samp.points[None] - ends[:, k, None]).transpose(2, 0, 1)) > eps
    hidden = lids["member"] & far & reach  # (n, m): reachable, behind a lid, not at its ends
    if lid_tol > 0 and len(ends):
        for k, (p, q) in enumerate(ends):  # farther than lid_tol from the lid's chord
            hidden[k] &= _point_chord(samp.points, p, q) > lid_tol
    hidden_length = hidden.astype(float) @ w
    unsound = lids["cross_loop"] | (hidden_length > 0)
    chords = np.hypot(*(ends[:, 1] - ends[:, 0]).T)
    lidded = float(w[lids["mask"]].sum())
    lid_unreachable = float(w[lids["mask"] & ~reach].sum())

    out = {
        "eps": float(eps),
        "tol": tol,
        "spacing": spacing,
        "contour_length": float(w.sum()),
        "hole_length": float(w[samp.is_hole].sum()),
        "reachable_length": reachable_length,
        "covered_length": float(w[covered].sum()),
        "coverage": float(w[covered].sum() / reachable_length) if reachable_length > 0 else 1.0,
        "resolvable_length": resolvable_length,
        "covered_resolvable_length": covered_resolvable,
        "coverage_resolvable": (covered_resolvable / resolvable_length
                                if resolvable_length > 0 else 1.0),
        "w1_count": len(result.w1),
        "w1_length": float(np.hypot(*(w1b - w1a).T).sum()),
        "w2_count": len(result.w2),
        "detected_length": detected_length,
        "precise_length": float(dl[d_det_pieces <= tol].sum()),
        "precision": float(dl[d_det_pieces <= tol].sum() / detected_length) if detected_length > 0 else 1.0,
        "hausdorff_detected_to_true": float(d_det.max()) if len(d_det) and len(a) else None,
        "hausdorff_true_reachable_to_detected": (float(d_true[reach].max())
                                                 if len(da) and reach.any() else None),
        "w2_arc_length": float(w[behind_w2].sum()),
        "w2_credit_length": float(w[covered & (d_true > tol)].sum()),
        "w2_long_arcs": int(w2_long.sum()),
        "w2_material_arcs": int(w2_material.sum()),
        "w3_count": len(result.w3),
        "w3_lidded_length": lidded,
        "w3_unreachable_length": lid_unreachable,
        "w3_reachable_length": lidded - lid_unreachable,
        "w3_hidden_reachable_length": float(w[hidden.any(axis=0)].sum()),
        "w3_cross_loop": int(lids["cross_loop"].sum()),
        "w3_cross_loop_length": float(chords[lids["cross_loop"]].sum()),
        "w3_off_contour": int((lids["offset"] > tol).sum()),
        "w3_unsound_count": int(unsound.sum()),
        "w3_soundness": float(1.0 - unsound.mean()) if len(unsound) else 1.0,
        "unknown_count": len(result.unknown),
        "unknown_length": float(w[unk["mask"]].sum()),
        "unknown_reachable_length": float(w[unk["mask"] & reach].sum()),
    }
    out.update(result.stats.as_dict())
    return out


def _point_chord(points, p, q) -> np.ndarray:
    """(m,) distances of (m, 2) ``points`` from the segment p -> q."""
    d = q - p
    t = np.clip(((points - p) @ d) / max(float(d @ d), 1e-300), 0.0, 1.0)
    return np.hypot(*(points - p - t[:, None] * d).T)


def sensor_metrics(loops, result: SliceResult, eps: float, noise: float,
                   spacing: float | None = None, samples=None, resolved=None) -> dict:
    """Coverage and precision at the tolerance a noisy sensor allows.

    A reading is off by the sensor's noise (standard deviation ``noise``),
    so a point within eps / 2 + 2 noise of the contour
    (:attr:`Resolution.sensor_tol <core2d.resolution.Resolution.sensor_tol>`)
    is as good as the sensor can tell. Returns ``sensor_tol`` and the keys
    ``covered_length``, ``coverage``, ``precise_length``, ``precision``,
    ``w3_unsound_count``, ``covered_resolvable_length``, ``coverage_resolvable``,
    ``w2_credit_length`` of :func:`slice_metrics` at that tolerance (a lid is
    unsound when it hides reachable contour farther than eps from its ends
    and farther than the tolerance from the lid), each with the suffix
    ``_sensor`` (reported beside the noiseless ones), and ``w3_soundness_sensor``. ``spacing``,
    ``samples`` and ``resolved`` as in :func:`slice_metrics` (default spacing eps / 4, the
    noiseless metrics' sampling).
    """
    tol = Resolution.of(eps, noise=noise).sensor_tol
    spacing = 0.25 * eps if spacing is None else spacing
    m = slice_metrics(loops, result, eps, tol=tol, spacing=spacing, samples=samples, lid_tol=tol,
                      resolved=resolved)
    out = {"sensor_tol": tol, **{f"{k}_sensor": m[k] for k in _SENSOR_KEYS}}
    n = m["w3_count"]
    out["w3_soundness_sensor"] = 1.0 - m["w3_unsound_count"] / n if n else 1.0
    return out


def total_metrics(metrics: list[dict]) -> dict:
    """Aggregate :func:`slice_metrics` dicts over slices.

    Lengths and counters are summed, ``coverage`` and ``precision``
    recomputed from the summed lengths (so they are length weighted), Hausdorff distances (and eps, tol, spacing) are maxima over
    the slices that have one, ``budget_hit`` is any and ``budget_hits`` the
    number of slices that hit the budget; ``w3_soundness`` is the share of
    sound lids over all slices.

    Examples
    --------
    >>> m = [{"covered_length": 1.0, "reachable_length": 4.0, "coverage": 0.25},
    ...      {"covered_length": 3.0, "reachable_length": 4.0, "coverage": 0.75}]
    >>> total_metrics(m)["coverage"]
    0.5
    """
    out: dict = {"slices": len(metrics)}
    keys = list(dict.fromkeys(k for m in metrics for k in m))
    for k in keys:
        vals = [m[k] for m in metrics if m.get(k) is not None]
        if k in _MAX_KEYS:
            out[k] = float(max(vals)) if vals else None
        elif k == "budget_hit":
            out["budget_hit"] = bool(any(vals))
            out["budget_hits"] = int(sum(bool(v) for v in vals))
        elif k in _RATIOS or k in ("w3_soundness", "w3_soundness_sensor"):
            continue
        elif all(isinstance(v, (int, np.integer)) and not isinstance(v, bool) for v in vals):
            out[k] = int(sum(vals))
        elif all(isinstance(v, (int, float, np.number)) and not isinstance(v, bool) for v in vals):
            out[k] = float(sum(vals))
    for k, (num, den) in _RATIOS.items():
        if num in out or (den in out and not k.endswith("_sensor")):  # _sensor: noisy runs only
            n, d = out.get(num, 0.0), out.get(den, 0.0)
            out[k] = float(n / d) if d > 0 else 1.0
    if "w3_count" in out:
        n = out["w3_count"]
        out["w3_soundness"] = float(1.0 - out.get("w3_unsound_count", 0) / n) if n else 1.0
        if "w3_unsound_count_sensor" in out:
            out["w3_soundness_sensor"] = float(1.0 - out["w3_unsound_count_sensor"] / n) if n else 1.0
    return out
