"""3D metrics of the reconstructed surface against the ground-truth mesh.

Definitions (all distances are exact point-to-triangle distances, compiled in
:mod:`recon3d.score.closest` and equal to VTK's ``vtkImplicitPolyDataDistance`` up to
rounding, from fixed-count seeded area-uniform samples):

* **domain** -- the slab between the first and last slice of a family (the
  union of the slabs when there are several). Ground truth outside it is
  not scored; the reconstruction's caps (label 5) are where a slab ends, not
  object surface, and are not scored either. ``SAMPLES`` ground-truth points
  are drawn over the whole mesh and those inside the domain are scored.
* ``accuracy`` -- mean distance from reconstruction samples to the ground
  truth; ``completeness`` -- mean distance from ground-truth samples (in the
  domain) to the reconstruction; ``chamfer_l1`` -- their mean;
  ``hausdorff`` -- the larger of the two maxima; ``hd95`` -- the larger of
  the two 95th percentiles.
* ``fscore[s]`` -- 2PR / (P + R) with P the share of reconstruction samples
  and R the share of ground-truth samples within tau = s x the ground truth's
  bounding-box diagonal.
* **reachable part** -- a ground-truth sample inherits the exact 2D
  reachability of the nearest reference-contour sample (3D distance, over
  the slices of the families whose slab holds the sample); a
  reconstruction sample belongs to it when its nearest ground-truth sample
  does. ``reachable`` repeats the metrics on those samples.
* **resolvable part** -- likewise, the reachable samples whose nearest
  reference-contour sample the paper's resolution resolves (not inside an
  opening narrower than eps, which §3.1 closes by a W2 chord and never enters:
  :mod:`core2d.truth.resolvable`); ``resolvable`` repeats the metrics on those.
* **inside a hole** -- a ground-truth sample whose nearest reference-contour
  sample lies on a hole of its section (a loop enclosed in the slice plane:
  no rod in that plane reaches it, §3.2); it is unreachable.
* ``slab_share`` -- scored ground-truth samples / samples drawn over the whole
  mesh; ``reachable_share`` -- reachable scored samples / samples drawn over the
  whole mesh (so ``reachable_share <= slab_share``); ``resolvable_share`` likewise
  (``<= reachable_share``).
* ``touched_share`` -- the 2D coverage carried to 3D: the share of the
  reachable scored samples whose nearest reference-contour sample is within
  eps / 2 of W1 u W2. It says what the probe touched on the slices, nothing
  about the surface between them.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import shapely
import trimesh
from scipy.spatial import cKDTree

from core2d.truth.resolvable import resolvable
from recon3d.config import diagonal
from recon3d.score.closest import MeshTree, mesh_distances
from recon3d.score.subdivide import face_centres, subdivide_to_size
from recon3d.records import Family

__all__ = ["FSCORE_SHARES", "SAMPLES", "Domain", "ContourCloud", "contour_cloud", "on_holes",
           "GroundTruthSamples", "classified_ground_truth", "surface_distances",
           "coverage_mesh", "surface_metrics", "one_after_other", "distances", "mesh_tree",
           "scored_part"]

FSCORE_SHARES = {"0.5%": 0.005, "1%": 0.01, "2%": 0.02}
"""F-score thresholds as shares of the ground truth's bounding-box diagonal."""

SAMPLES = 50_000
"""Surface samples per side (ground truth, reconstruction)."""

@dataclass(frozen=True)
class Domain:
    """Union of slabs ``lo_k <= p . normal_k <= hi_k``.

    normals : (k, 3) float; lo, hi : (k,) float.
    """

    normals: np.ndarray
    lo: np.ndarray
    hi: np.ndarray

    @classmethod
    def of(cls, solids) -> Domain:
        return cls(np.array([s.normal for s in solids]).reshape(-1, 3),
                   np.array([s.slab[0] for s in solids]), np.array([s.slab[1] for s in solids]))

    def contains(self, points, pad: float = 0.0) -> np.ndarray:
        """(n,) bool for (n, 3) points (``pad`` widens every slab)."""
        h = np.asarray(points, dtype=np.float64).reshape(-1, 3) @ self.normals.T
        return np.any((h >= self.lo - pad) & (h <= self.hi + pad), axis=1)

    def as_dict(self) -> list:
        return [{"normal": n.tolist(), "from": float(a), "to": float(b)}
                for n, a, b in zip(self.normals, self.lo, self.hi)]


@dataclass(frozen=True)
class ContourCloud:
    """Reference-contour samples of the slices of several families, in world coordinates.

    points : (m, 3) float; reachable, covered : (m,) bool; family : (m,) int.
    slabs : Domain -- slab k is family k's (first to last slice).
    in_hole : (m,) bool or None -- the sample lies on a hole loop of its section
        (None: on none).
    resolvable : (m,) bool or None -- not inside an opening narrower than eps
        (None: every sample).
    """

    points: np.ndarray
    reachable: np.ndarray
    covered: np.ndarray
    family: np.ndarray
    slabs: Domain
    in_hole: np.ndarray | None = field(default=None)
    resolvable: np.ndarray | None = field(default=None)

    def classify(self, points, workers: int = 1) -> np.ndarray:
        """(n,) int8 for (n, 3) points: 0 in no family's slab, else the class of
        the nearest sample among the families whose slab holds the point:
        1 touched, 2 reachable but missed, 3 unreachable, 4 inside a hole
        (unreachable, on a hole loop of the section), 5 reachable, not touched, in an
        opening narrower than eps (:mod:`core2d.truth.resolvable`: §3.1 closes it by W2;
        reachable like 1 and 2). ``workers``: :meth:`nearest`'s threads."""
        return self.classes(self.nearest(points, workers))

    def classes(self, nearest: np.ndarray) -> np.ndarray:
        """(n,) int8: :meth:`classify`'s class of each :meth:`nearest` sample (-1: 0)."""
        j = np.asarray(nearest, dtype=np.int64)
        if not len(self.points):
            return np.zeros(len(j), dtype=np.int8)
        hole = (np.zeros(len(self.points), dtype=bool) if self.in_hole is None
                else np.asarray(self.in_hole, dtype=bool))
        narrow = (np.zeros(len(self.points), dtype=bool) if self.resolvable is None
                  else ~np.asarray(self.resolvable, dtype=bool))
        c = np.where(self.covered, 1, np.where(self.reachable, np.where(narrow, 5, 2),
                                               np.where(hole, 4, 3)))
        return np.where(j >= 0, c[np.maximum(j, 0)], 0).astype(np.int8)

    def resolved(self, nearest: np.ndarray) -> np.ndarray:
        """(n,) bool: the :meth:`nearest` sample is reachable and resolvable (-1: False)."""
        j = np.asarray(nearest, dtype=np.int64)
        if not len(self.points):
            return np.zeros(len(j), dtype=bool)
        ok = self.reachable if self.resolvable is None else self.reachable & self.resolvable
        return (j >= 0) & ok[np.maximum(j, 0)]

    def nearest(self, points, workers: int = 1) -> np.ndarray:
        """(n,) int for (n, 3) points: the nearest sample among the families whose slab
        holds the point (-1 in no family's slab). ``workers``: threads of the k-d tree's
        query (-1: one per core; each point's answer is the same)."""
        points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
        best = np.full(len(points), np.inf)
        out = np.full(len(points), -1, dtype=np.int64)
        pad = 1e-9 * float(np.ptp(self.points, axis=0).max()) if len(self.points) else 0.0
        for k in range(len(self.slabs.lo)):
            sel = np.flatnonzero(self.family == k)
            slab = Domain(self.slabs.normals[k:k + 1], self.slabs.lo[k:k + 1],
                          self.slabs.hi[k:k + 1])
            inside = np.flatnonzero(slab.contains(points, pad))
            if len(sel) == 0 or len(inside) == 0:
                continue
            d, i = cKDTree(self.points[sel]).query(points[inside], workers=workers)
            better = d < best[inside]
            best[inside[better]] = d[better]
            out[inside[better]] = sel[i][better]
        return out


def on_holes(cut, points) -> np.ndarray:
    """(m,) bool: which (m, 2) reference samples of a slice lie nearest a hole loop.

    cut : slicer.Slice -- its ``loops`` and ``holes``.

    The nearest loop is the one of the nearest loop segment (one STRtree query for all
    samples); between loops at the same distance, the first, as an argmin over loops.
    The sensing worker computes it with the slice's samples (``ContourTruth.in_hole``)."""
    holes = np.asarray(cut.holes, dtype=bool)
    if not holes.any() or not len(points):
        return np.zeros(len(points), dtype=bool)
    segs, owner = [], []
    for k, lp in enumerate(cut.loops):
        ring = np.asarray(lp, dtype=np.float64).reshape(-1, 2)
        ring = np.vstack([ring, ring[:1]])  # closed, as a LinearRing
        segs.append(np.stack([ring[:-1], ring[1:]], axis=1))
        owner.append(np.full(len(ring) - 1, k))
    owner = np.concatenate(owner)
    tree = shapely.STRtree(shapely.linestrings(np.concatenate(segs)))
    at, seg = tree.query_nearest(shapely.points(np.asarray(points, dtype=np.float64)),
                                 all_matches=True)
    nearest = np.full(len(points), len(holes))
    np.minimum.at(nearest, at, owner[seg])
    return holes[nearest]


def contour_cloud(families: list[Family]) -> ContourCloud:
    """Stack the :class:`recon3d.records.ContourTruth` of every slice in 3D.

    families : list of recon3d.records.Family
    """
    pts, reach, cov, fam = [np.zeros((0, 3))], [np.zeros(0, bool)], [np.zeros(0, bool)], []
    hole, resolved = [np.zeros(0, bool)], [np.zeros(0, bool)]
    normals, lo, hi = [], [], []
    for k, f in enumerate(families):
        offsets = [s.slice.plane.offset for s in f.slices]
        normals.append(np.asarray(f.normal, dtype=np.float64))
        lo.append(min(offsets, default=0.0))
        hi.append(max(offsets, default=0.0))
        for s in f.slices:
            if len(s.truth.points):
                pts.append(s.slice.to_3d(s.truth.points))
                reach.append(s.truth.reachable)
                cov.append(s.truth.covered)
                hole.append(s.truth.in_hole if s.truth.in_hole is not None
                            else on_holes(s.slice, s.truth.points))
                resolved.append(s.truth.resolvable if s.truth.resolvable is not None
                                else resolvable(s.slice.loops, s.truth.points, s.metrics["eps"]))
                fam.append(np.full(len(s.truth.points), k))
    fam = np.concatenate(fam) if fam else np.zeros(0, dtype=np.int64)
    slabs = Domain(np.array(normals).reshape(-1, 3), np.array(lo), np.array(hi))
    return ContourCloud(np.concatenate(pts), np.concatenate(reach), np.concatenate(cov),
                        fam, slabs, np.concatenate(hole), np.concatenate(resolved))


def distances(points, mesh: trimesh.Trimesh, tree: MeshTree | None = None) -> np.ndarray:
    """(n,) float: exact distance from (n, 3) points to a triangle mesh (compiled:
    :func:`recon3d.score.closest.mesh_distances`; ``tree``: the mesh's hierarchy, built
    before, :func:`mesh_tree`)."""
    if len(points) == 0:
        return np.zeros(0)
    if len(mesh.faces) == 0:
        return np.full(len(points), np.inf)
    if tree is not None:
        return tree.distances(points)
    return mesh_distances(points, mesh.vertices, mesh.faces)


def mesh_tree(mesh: trimesh.Trimesh | None) -> MeshTree | None:
    """The distance hierarchy of ``mesh`` (None without a face): built once for the two
    halves of :func:`surface_metrics`, which a forked child shares."""
    if mesh is None or len(mesh.faces) == 0:
        return None
    return MeshTree.of(mesh.vertices, mesh.faces)


def _sample(mesh, count: int, seed: int) -> np.ndarray:
    if len(mesh.faces) == 0 or mesh.area <= 0:
        return np.zeros((0, 3))
    pts, _ = trimesh.sample.sample_surface(mesh, count, seed=seed)
    return np.asarray(pts, dtype=np.float64)


def _scores(d_rec, d_gt, taus) -> dict:
    """The metric block of two distance arrays (None where a side is empty)."""
    if len(d_rec) == 0 or len(d_gt) == 0:
        return {"accuracy": None, "completeness": None, "chamfer_l1": None,
                "hausdorff": None, "hd95": None, "fscore": {k: None for k in taus}}
    acc, comp = float(d_rec.mean()), float(d_gt.mean())
    fs = {}
    for k, tau in taus.items():
        p, r = float((d_rec <= tau).mean()), float((d_gt <= tau).mean())
        fs[k] = 2 * p * r / (p + r) if p + r > 0 else 0.0
    return {"accuracy": acc, "completeness": comp, "chamfer_l1": 0.5 * (acc + comp),
            "hausdorff": float(max(d_rec.max(), d_gt.max())),
            "hd95": float(max(np.percentile(d_rec, 95), np.percentile(d_gt, 95))),
            "fscore": fs}


class GroundTruthSamples:
    """Seeded area-uniform samples of the ground truth, those inside a domain kept.

    points : (n, 3) float; drawn : int -- samples drawn over the whole mesh;
    mesh : the whole ground truth (distances are to it);
    diagonal : float -- its bounding-box diagonal.
    """

    def __init__(self, mesh, domain: Domain, count: int = SAMPLES, seed: int = 0):
        self.diagonal = diagonal(mesh)
        pts = _sample(mesh, count, seed)
        self.points = pts[domain.contains(pts, pad=1e-9 * self.diagonal)]
        self.drawn = len(pts)
        self.mesh = mesh


def scored_part(surface: trimesh.Trimesh) -> trimesh.Trimesh | None:
    """The faces of a labelled surface that are scored: all but the caps (label 5)."""
    label = np.asarray(surface.face_attributes.get("label", np.zeros(0)), dtype=np.int64)
    keep = np.flatnonzero(label != 5)
    return surface.submesh([keep], append=True) if len(keep) else None


def classified_ground_truth(mesh: trimesh.Trimesh, cloud: ContourCloud,
                            max_edge: float) -> trimesh.Trimesh:
    """Ground truth subdivided to ``max_edge`` with a class per face
    (``face_attributes['coverage']`` (f,) int8, :meth:`ContourCloud.classify` on every core:
    10^5 - 10^6 faces): the part of :func:`coverage_mesh` that needs the sensing only."""
    v, f = subdivide_to_size(mesh.vertices, mesh.faces, max_edge, max_iter=12)
    out = trimesh.Trimesh(v, f, process=False)
    out.face_attributes["coverage"] = cloud.classify(face_centres(v, f), workers=-1)
    return out


def surface_distances(points, surface: trimesh.Trimesh, diag: float) -> np.ndarray:
    """(n,) float: distance of (n, 3) points to the scored part of a labelled surface
    (:func:`scored_part`) in % of ``diag`` (the unit of ``FSCORE_SHARES``; inf without a
    scored part), by the compiled :func:`recon3d.score.closest.mesh_distances` (a picture's
    colours: VTK's distances up to rounding, ~10x faster on 10^5 - 10^6 points)."""
    part = scored_part(surface)
    if part is None:
        return np.full(len(points), np.inf)
    return 100.0 * mesh_distances(points, part.vertices, part.faces) / diag


def coverage_mesh(mesh: trimesh.Trimesh, cloud: ContourCloud, max_edge: float,
                  surface: trimesh.Trimesh | None = None) -> trimesh.Trimesh:
    """Ground truth subdivided to ``max_edge`` with a class per face and a distance per vertex.

    Classes (:data:`recon3d.records.COVERAGE_CLASSES`): 0 outside every slab,
    1 touched, 2 reachable but missed, 3 unreachable, 4 inside a hole, 5 in an opening
    narrower than eps (module doc). Returns a trimesh with ``face_attributes['coverage']`` (f,) int8
    (:func:`classified_ground_truth`) and, given the labelled ``surface``,
    ``vertex_attributes['distance']`` (v,) float (:func:`surface_distances`).
    """
    out = classified_ground_truth(mesh, cloud, max_edge)
    if surface is not None:
        out.vertex_attributes["distance"] = surface_distances(out.vertices, surface,
                                                              diagonal(mesh))
    return out


def one_after_other(first: Callable[[], Any], second: Callable[[], Any]) -> tuple[Any, Any]:
    """Run two calls in this process, one after the other: ``(first(), second())``."""
    return first(), second()


def surface_metrics(surface: trimesh.Trimesh, gt: GroundTruthSamples, cloud: ContourCloud,
                    count: int = SAMPLES, seed: int = 1,
                    pair: Callable = one_after_other) -> tuple[dict, dict]:
    """Metrics of a labelled surface (module doc).

    Parameters
    ----------
    surface : trimesh.Trimesh with ``face_attributes['label']``.
    gt : GroundTruthSamples -- in the evaluation domain.
    cloud : ContourCloud -- reference samples of the slices used.
    pair : callable(first, second) -> (first(), second()) -- how the two halves of the
        distances run (each half: half the reconstruction's samples -> ground truth, half
        the ground truth's -> reconstruction): one after the other here, or side by side
        on two cores (:func:`recon3d.api.execute` passes a forked one); the numbers are
        the same.

    Returns
    -------
    metrics : dict -- the ``total.surface`` block (with ``reachable`` and ``resolvable``).
    extra : dict -- ``slab_share``, ``reachable_share``, ``resolvable_share``,
        ``touched_share`` (module
        doc), sample counts and tau values.
    """
    taus = {k: s * gt.diagonal for k, s in FSCORE_SHARES.items()}
    scored = scored_part(surface)
    rec = _sample(scored, count, seed) if scored is not None else np.zeros((0, 3))
    # both directions split in halves between the two calls (a point's distance does not
    # depend on the others): which one costs more depends on the meshes (the ground truth
    # to a finely meshed reconstruction, or samples to a large ground-truth mesh)
    half_rec = len(rec) // 2
    half = len(gt.points) // 2 if scored is not None else 0

    # each mesh's hierarchy built once, here: both halves query it (a forked one inherits it)
    gt_tree = mesh_tree(gt.mesh) if len(rec) else None
    rec_tree = mesh_tree(scored) if len(gt.points) else None

    def to_rec(pts):
        return (distances(pts, scored, rec_tree) if scored is not None
                else np.full(len(pts), np.inf))

    (d_rec0, d_gt0), (d_rec1, d_gt1) = pair(
        lambda: (distances(rec[:half_rec], gt.mesh, gt_tree), to_rec(gt.points[:half])),
        lambda: (distances(rec[half_rec:], gt.mesh, gt_tree), to_rec(gt.points[half:])))
    d_rec = np.concatenate([d_rec0, d_rec1])
    d_gt = np.concatenate([d_gt0, d_gt1])
    near = cloud.nearest(gt.points)
    cls = cloud.classes(near)
    reach = np.isin(cls, (1, 2, 5))
    resolved = cloud.resolved(near)
    if len(gt.points) and len(rec):
        _, j = cKDTree(gt.points).query(rec)
        rec_reach, rec_resolved = reach[j], resolved[j]
    else:
        rec_reach = rec_resolved = np.zeros(len(rec), dtype=bool)
    out = _scores(d_rec, d_gt, taus)
    out["reachable"] = _scores(d_rec[rec_reach], d_gt[reach], taus)
    out["resolvable"] = _scores(d_rec[rec_resolved], d_gt[resolved], taus)
    drawn = max(int(gt.drawn), 1)
    extra = {
        "slab_share": len(gt.points) / drawn,
        "reachable_share": float(reach.sum()) / drawn,
        "resolvable_share": float(resolved.sum()) / drawn,
        "touched_share": float((cls == 1).sum() / reach.sum()) if reach.any() else None,
        "samples": {"ground_truth_drawn": int(gt.drawn), "ground_truth": int(len(gt.points)),
                    "reconstruction": int(len(rec)), "seeds": [0, seed]},
        "tau": taus,
    }
    return out, extra
