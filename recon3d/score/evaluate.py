"""3D metrics of the reconstructed surface against the ground-truth mesh.

Definitions (all distances are exact point-to-triangle distances, VTK's
``vtkImplicitPolyDataDistance``, from fixed-count seeded area-uniform samples):

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
* **touched** -- a ground-truth sample whose nearest reference-contour
  sample is reachable and lies within eps / 2 of W1 u W2 (the distance of the 2D coverage);
  ``coverage`` = touched / reachable ground-truth samples.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import trimesh
from scipy.spatial import cKDTree

from recon3d.config import diagonal
from recon3d.records import Family
from recon3d.viz import libs

__all__ = ["FSCORE_SHARES", "SAMPLES", "Domain", "ContourCloud", "contour_cloud",
           "GroundTruthSamples", "coverage_mesh", "surface_metrics", "distances"]

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
    """

    points: np.ndarray
    reachable: np.ndarray
    covered: np.ndarray
    family: np.ndarray
    slabs: Domain

    def classify(self, points) -> np.ndarray:
        """(n,) int8 for (n, 3) points: 0 in no family's slab, else the class of
        the nearest sample among the families whose slab holds the point:
        1 touched, 2 reachable but missed, 3 unreachable."""
        points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
        best = np.full(len(points), np.inf)
        cls = np.zeros(len(points), dtype=np.int8)
        pad = 1e-9 * float(np.ptp(self.points, axis=0).max()) if len(self.points) else 0.0
        for k in range(len(self.slabs.lo)):
            sel = np.flatnonzero(self.family == k)
            slab = Domain(self.slabs.normals[k:k + 1], self.slabs.lo[k:k + 1],
                          self.slabs.hi[k:k + 1])
            inside = np.flatnonzero(slab.contains(points, pad))
            if len(sel) == 0 or len(inside) == 0:
                continue
            d, i = cKDTree(self.points[sel]).query(points[inside])
            j = sel[i]
            c = np.where(self.covered[j], 1, np.where(self.reachable[j], 2, 3))
            better = d < best[inside]
            best[inside[better]] = d[better]
            cls[inside[better]] = c[better]
        return cls


def contour_cloud(families: list[Family]) -> ContourCloud:
    """Stack the :class:`recon3d.records.ContourTruth` of every slice in 3D.

    families : list of recon3d.records.Family
    """
    pts, reach, cov, fam = [np.zeros((0, 3))], [np.zeros(0, bool)], [np.zeros(0, bool)], []
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
                fam.append(np.full(len(s.truth.points), k))
    fam = np.concatenate(fam) if fam else np.zeros(0, dtype=np.int64)
    slabs = Domain(np.array(normals).reshape(-1, 3), np.array(lo), np.array(hi))
    return ContourCloud(np.concatenate(pts), np.concatenate(reach), np.concatenate(cov),
                        fam, slabs)


def distances(points, mesh: trimesh.Trimesh) -> np.ndarray:
    """(n,) float: exact distance from (n, 3) points to a triangle mesh (VTK)."""
    if len(points) == 0:
        return np.zeros(0)
    pv = libs.pyvista()  # vtkImplicitPolyDataDistance
    cloud = pv.PolyData(np.asarray(points, dtype=np.float64))
    res = cloud.compute_implicit_distance(libs.polydata(mesh))
    return np.abs(np.asarray(res["implicit_distance"], dtype=np.float64))


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


def coverage_mesh(mesh: trimesh.Trimesh, cloud: ContourCloud, max_edge: float) -> trimesh.Trimesh:
    """Ground truth subdivided to ``max_edge`` with a per-face ``coverage`` class.

    Classes (:data:`recon3d.records.COVERAGE_CLASSES`): 0 outside every slab,
    1 touched, 2 reachable but missed, 3 unreachable (see module doc). Returns
    a trimesh with ``face_attributes['coverage']`` (f,) int8.
    """
    v, f = trimesh.remesh.subdivide_to_size(mesh.vertices, mesh.faces, max_edge, max_iter=12)
    out = trimesh.Trimesh(v, f, process=False)
    out.face_attributes["coverage"] = cloud.classify(out.triangles_center)
    return out


def surface_metrics(surface: trimesh.Trimesh, gt: GroundTruthSamples, cloud: ContourCloud,
                    count: int = SAMPLES, seed: int = 1) -> tuple[dict, dict]:
    """Metrics of a labelled surface (module doc).

    Parameters
    ----------
    surface : trimesh.Trimesh with ``face_attributes['label']``.
    gt : GroundTruthSamples -- in the evaluation domain.
    cloud : ContourCloud -- reference samples of the slices used.

    Returns
    -------
    metrics : dict -- the ``total.surface`` block (with ``reachable``).
    extra : dict -- ``coverage``, sample counts and tau values.
    """
    taus = {k: s * gt.diagonal for k, s in FSCORE_SHARES.items()}
    label = np.asarray(surface.face_attributes.get("label", np.zeros(0)), dtype=np.int64)
    scored = surface.submesh([np.flatnonzero(label != 5)], append=True) \
        if (label != 5).any() else None
    rec = _sample(scored, count, seed) if scored is not None else np.zeros((0, 3))
    d_rec = distances(rec, gt.mesh)
    d_gt = distances(gt.points, scored) if scored is not None else np.full(len(gt.points), np.inf)
    cls = cloud.classify(gt.points)
    reach = (cls == 1) | (cls == 2)
    if len(gt.points) and len(rec):
        _, j = cKDTree(gt.points).query(rec)
        rec_reach = reach[j]
    else:
        rec_reach = np.zeros(len(rec), dtype=bool)
    out = _scores(d_rec, d_gt, taus)
    out["reachable"] = _scores(d_rec[rec_reach], d_gt[reach], taus)
    extra = {
        "coverage": float((cls == 1).sum() / reach.sum()) if reach.any() else None,
        "reachable_share": float(reach.mean()) if len(reach) else None,
        "samples": {"ground_truth_drawn": int(gt.drawn), "ground_truth": int(len(gt.points)),
                    "reconstruction": int(len(rec)), "seeds": [0, seed]},
        "tau": taus,
    }
    return out, extra
