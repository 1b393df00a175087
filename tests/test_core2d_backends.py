"""Embree and exact backends give the same W-classes on the same slice.

Each contour sample is labelled by the class of the nearest detection within
tol (W1, W2, W3 lid arc, or none); the labels of the two runs are compared.
Disagreements are reported, and must stay rare.
"""
import numpy as np
import pytest
import shapely

import meshes
import slicer
from core2d import sense_slice
from core2d.truth.metrics import lid_arcs
from core2d.truth.reachability import sample_contour

SCENES = ["fig17_pocket", "fig18_overhangs", "deep_slot", "gear"]


def _labels(loops, res, samples, tol):
    label = np.zeros(len(samples.points), dtype=int)  # 0 none, 1 W1, 2 W2, 3 W3
    pts = shapely.points(samples.points)
    for cls, geoms in ((1, res.w1), (2, res.w2)):
        if geoms:
            near = shapely.distance(pts, shapely.MultiLineString(list(geoms))) <= tol
            label[(label == 0) & near] = cls
    if res.w3:
        under = lid_arcs(loops, res.w3, samples)["mask"]
        label[(label == 0) & under] = 3
    return label


@pytest.mark.parametrize("name", SCENES)
def test_embree_and_exact_agree_on_w_classes(name, record_property):
    mesh = meshes.load(name)
    eps = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)) / 200)
    (cut,) = slicer.slice_mesh(mesh, axis="z", count=1)
    loops = [np.asarray(l) for l in cut.loops]
    center, radius = cut.bounding_circle()
    runs = {b: sense_slice(cut.contact(b), (center, radius + eps), eps)
            for b in ("embree", "exact")}
    samples = sample_contour(loops, eps / 4)
    tol = eps / 2
    la, lb = (_labels(loops, runs[b], samples, tol) for b in ("embree", "exact"))
    differ = la != lb
    rate = float(samples.lengths[differ].sum() / samples.lengths.sum())
    record_property("w_class_disagreement", rate)
    print(f"{name}: W-class disagreement {rate:.4%} of contour length")
    assert (la > 0).mean() > 0.95 and (lb > 0).mean() > 0.95
    assert rate <= 0.01, f"{name}: backends disagree on {rate:.2%} of the contour"
