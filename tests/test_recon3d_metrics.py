"""3D metrics (recon3d.score.evaluate) against analytic answers, and recon3d's doctests."""
import doctest
import importlib

import numpy as np
import pytest
import trimesh

from recon3d.score.evaluate import (ContourCloud, Domain, GroundTruthSamples, _scores,
                              surface_metrics)

R = 10.0


def _sphere(radius=R):
    return trimesh.creation.icosphere(subdivisions=5, radius=radius)


def _labelled(mesh, label=1):
    mesh = mesh.copy()
    mesh.face_attributes["label"] = np.full(len(mesh.faces), label, dtype=np.int32)
    return mesh


def _cloud(reachable_where=lambda p: np.ones(len(p), bool), covered_where=None):
    """Contour samples on the sphere's equator band, one family (z slab -R..R)."""
    t = np.linspace(0, 2 * np.pi, 400, endpoint=False)
    pts = np.concatenate([np.column_stack([R * np.cos(a) * np.cos(t), R * np.cos(a) * np.sin(t),
                                           np.full_like(t, R * np.sin(a))])
                          for a in np.linspace(-1.4, 1.4, 15)])
    reach = reachable_where(pts)
    cov = reach if covered_where is None else reach & covered_where(pts)
    slabs = Domain(np.array([[0.0, 0.0, 1.0]]), np.array([-R]), np.array([R]))
    return ContourCloud(pts, reach, cov, np.zeros(len(pts), int), slabs)


def _gt(domain_lo=-2 * R):
    dom = Domain(np.array([[0.0, 0.0, 1.0]]), np.array([domain_lo]), np.array([2 * R]))
    return GroundTruthSamples(_sphere(), dom, count=20000)


def test_scores_formula():
    out = _scores(np.array([0.0, 0.0, 1.0, 1.0]), np.array([0.0, 1.0, 1.0, 1.0]),
                  {"t": 0.5})
    assert out["fscore"]["t"] == pytest.approx(2 * 0.5 * 0.25 / 0.75)
    assert out["accuracy"] == 0.5 and out["completeness"] == 0.75
    assert out["chamfer_l1"] == 0.625 and out["hausdorff"] == 1.0
    assert _scores(np.zeros(0), np.ones(3), {"t": 1.0})["accuracy"] is None


def test_offset_sphere_distances_are_the_offset():
    """A sphere of radius R + d is d away everywhere: every distance metric is d."""
    d = 0.3
    surf, extra = surface_metrics(_labelled(_sphere(R + d)), _gt(), _cloud(), count=20000)
    for key in ("accuracy", "completeness", "chamfer_l1", "hausdorff", "hd95"):
        assert surf[key] == pytest.approx(d, abs=0.01), key
    tau = {k: s * float(np.linalg.norm(np.ptp(_sphere().bounds, axis=0)))
           for k, s in {"0.5%": 0.005, "1%": 0.01, "2%": 0.02}.items()}
    assert tau["0.5%"] < d < tau["1%"]
    assert surf["fscore"] == {"0.5%": 0.0, "1%": 1.0, "2%": 1.0}
    assert extra["touched_share"] == 1.0 and extra["tau"] == pytest.approx(tau)


def test_caps_are_not_scored():
    surf = _labelled(_sphere(R + 0.3))
    cap = trimesh.Trimesh([[50, 50, 0], [60, 50, 0], [50, 60, 0]], [[0, 1, 2]], process=False)
    cap.face_attributes["label"] = np.array([5], dtype=np.int32)
    both = trimesh.util.concatenate([surf, cap])
    both.face_attributes["label"] = np.r_[surf.face_attributes["label"], 5].astype(np.int32)
    a, _ = surface_metrics(surf, _gt(), _cloud(), count=5000)
    b, _ = surface_metrics(both, _gt(), _cloud(), count=5000)
    assert b["hausdorff"] == pytest.approx(a["hausdorff"], abs=0.02)


def test_ground_truth_outside_the_domain_is_not_scored():
    gt = _gt(domain_lo=0.0)
    assert gt.points[:, 2].min() >= -1e-6 and 0.4 < len(gt.points) / gt.drawn < 0.6
    upper = _labelled(_sphere(R + 0.3).slice_plane([0, 0, 0], [0, 0, 1]))
    surf, _ = surface_metrics(upper, gt, _cloud(), count=5000)
    assert surf["completeness"] == pytest.approx(0.3, abs=0.02)


def test_reachable_part_and_coverage_follow_the_contour_samples():
    """West half unreachable and pushed 0.6 out; east half 0.2 out."""
    sphere = _sphere(R)
    v = sphere.vertices.copy()
    v *= np.where(v[:, :1] < 0, (R + 0.6) / R, (R + 0.2) / R)
    rec = _labelled(trimesh.Trimesh(v, sphere.faces, process=False))
    cloud = _cloud(lambda p: p[:, 0] >= 0, covered_where=lambda p: p[:, 1] >= 0)
    surf, extra = surface_metrics(rec, _gt(), cloud, count=20000)
    assert surf["reachable"]["completeness"] < 0.25 < 0.35 < surf["completeness"]
    assert surf["reachable"]["accuracy"] < 0.25 < 0.35 < surf["accuracy"]
    assert extra["touched_share"] == pytest.approx(0.5, abs=0.05)
    assert extra["reachable_share"] == pytest.approx(0.5, abs=0.05)


def test_classify_uses_only_families_whose_slab_holds_the_point():
    pts = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, 5.0]])
    slabs = Domain(np.array([[0, 0, 1.0], [1.0, 0, 0]]), np.array([-1.0, -1.0]),
                   np.array([1.0, 1.0]))
    cloud = ContourCloud(pts, np.array([True, False]), np.array([True, False]),
                         np.array([0, 1]), slabs)
    # (0, 0, 4) is nearer the family-1 sample but only family 1's slab (x) holds it
    got = cloud.classify(np.array([[0.0, 0.0, 4.0], [0.0, 0.0, 0.5], [5.0, 0.0, 5.0]]))
    assert got.tolist() == [3, 1, 0]


@pytest.mark.parametrize("name", ["recon3d.surface.closure", "recon3d.surface.field",
                                  "recon3d.records", "recon3d.config", "recon3d.io.staged",
                                  "recon3d.cli.printing", "recon3d.sensing.adaptive",
                                  "recon3d.api", "recon3d"])
def test_doctests(name):
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0


def test_public_api():
    import recon3d

    assert set(recon3d.__all__) >= {"run", "Result"}
    for name in recon3d.__all__:
        assert getattr(recon3d, name) is not None


def test_nearest_on_every_core_is_the_same(monkeypatch):
    """The coloured ground truth classifies its 10^5 - 10^6 faces with the k-d tree's query
    on every core (``workers=-1``): each point's nearest sample is the one-thread answer, and
    :func:`classified_ground_truth` asks for it."""
    from recon3d.score import evaluate

    cloud = _cloud(reachable_where=lambda p: p[:, 0] > 0, covered_where=lambda p: p[:, 1] > 0)
    pts = np.random.default_rng(4).normal(size=(20000, 3)) * R
    assert np.array_equal(cloud.nearest(pts, workers=-1), cloud.nearest(pts))
    asked = []
    real = evaluate.ContourCloud.classify

    def spy(self, points, workers=1):
        asked.append(workers)
        return real(self, points, workers)

    monkeypatch.setattr(evaluate.ContourCloud, "classify", spy)
    evaluate.classified_ground_truth(trimesh.creation.icosphere(2, radius=R), cloud, R / 4)
    assert asked == [-1]
