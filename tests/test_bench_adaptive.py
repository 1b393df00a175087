"""Adaptive slicing (``recon3d run --slices auto``, recon3d.sensing.adaptive).

Checked on solids whose sections are known: a post on a plate (the section
changes at one height only), a plain box (never changes), and a plate with a
narrow slot (a feature of a few eps, which asks for a finer eps).
"""
import numpy as np
import pytest
from manifold3d import Manifold
from shapely.geometry import Polygon, box

import meshes
import recon3d
from recon3d.sensing.adaptive import feature_width, refine_pairs, region_difference


def _mesh(solid):
    return meshes.to_trimesh(solid)


def _post_on_plate():
    plate = Manifold.cube([40, 40, 10])
    post = Manifold.cube([10, 10, 30]).translate([15, 15, 10])
    return _mesh(plate + post)


def _heights(res):
    return np.array([s.slice.plane.offset for s in res.slices])


def test_region_difference_and_refine_pairs():
    a, b = box(0, 0, 4, 4), box(0, 0, 4, 6)
    assert region_difference(a, b) == pytest.approx(2.0)
    assert region_difference(a, a) == 0.0
    assert region_difference(a, Polygon()) == float("inf")
    regs = {0: a, 2: a, 4: b}
    assert refine_pairs([0, 2, 4], regs, 1.0) == [3]
    assert refine_pairs([0, 2, 4], regs, 3.0) == []


@pytest.mark.parametrize("slot, shows", [(1.0, 2.0), (3.0, 4.0), (12.0, None)])
def test_feature_width_finds_the_slot(slot, shows):
    plate = box(0, 0, 40, 40).difference(box(14, 20, 14 + slot, 41))  # slot 20 deep
    assert feature_width(plate, [2.0, 4.0, 8.0]) == shows


def test_slices_gather_where_the_section_changes():
    mesh = _post_on_plate()  # z in [0, 40]; the section changes at z = 10
    res = recon3d.run(mesh, slices="auto", max_slices=16, eps=0.5, jobs=1)
    z = _heights(res)
    cand = (np.arange(16) + 0.5) * 40 / 16
    below, above = cand[cand < 10].max(), cand[cand > 10].min()
    assert np.isclose(z, below).any() and np.isclose(z, above).any()  # the step is bracketed
    assert len(z) <= 8
    gaps = np.diff(np.sort(z))
    assert gaps.max() > 3 * gaps.min()  # uneven: dense at the step, sparse elsewhere
    ada = res.metrics["adaptive"]
    assert ada["slices"] == [len(z)] and ada["rounds"] >= 2
    uni = recon3d.run(mesh, slices=16, eps=0.5, jobs=1)
    f_a = res.metrics["total"]["surface"]["fscore"]["1%"]
    f_u = uni.metrics["total"]["surface"]["fscore"]["1%"]
    assert f_a >= f_u - 0.01


def test_a_section_that_never_changes_stays_coarse():
    res = recon3d.run(_mesh(Manifold.cube([30, 20, 40])), slices="auto", max_slices=32,
                      eps=0.5, jobs=1)
    assert len(res.slices) == 5 and res.metrics["adaptive"]["rounds"] == 1
    assert res.sensing.eps == pytest.approx(1.0)  # every slice at the coarse eps (2 x eps)


def test_a_narrow_slot_is_sensed_again_at_a_finer_eps():
    plate = Manifold.cube([40, 30, 10]) - Manifold.cube([2.5, 25, 12]).translate([18, 6, -1])
    res = recon3d.run(_mesh(plate), slices="auto", max_slices=8, eps=0.5, jobs=1)
    ada = res.metrics["adaptive"]
    # the middle slice shows the slot at the coarse eps and is sensed again; the
    # others are sensed at the eps it asked for at once (no second pass)
    assert ada["resensed"]["slices"] == 1 and ada["resensed"]["motions"] > 0
    assert len(res.slices) == 3
    assert ada["eps"]["per_slice"] == pytest.approx([0.5] * 3)  # eps, never below it
    assert res.metrics["total"]["coverage"] > 0.99


def test_a_slot_the_probe_slice_did_not_show_is_sensed_again_where_it_shows():
    # the slot only cuts the top 3 of 10 mm: the middle slice (z = 5.625) shows none
    plate = Manifold.cube([40, 30, 10]) - Manifold.cube([2.5, 25, 4]).translate([18, 6, 7])
    res = recon3d.run(_mesh(plate), slices="auto", max_slices=8, eps=0.5, jobs=1)
    ada = res.metrics["adaptive"]
    z, e = _heights(res), np.array(ada["eps"]["per_slice"])
    assert ada["resensed"]["slices"] >= 1
    # fine where the slot is (and between it and the coarse slices: the finer neighbour)
    assert np.all(e[z > 7] == 0.5) and np.all(e[z < 6] == 1.0)
    assert res.metrics["total"]["coverage"] > 0.99
