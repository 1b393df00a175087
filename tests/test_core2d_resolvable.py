"""The contour the paper's resolution resolves (core2d.truth.resolvable), checked against
the geometry of a disc of diameter eps worked out by hand: slots (the disc fits in a slot
iff it is at least eps wide), V-grooves (the disc stops where it touches both walls) and
holes (enclosed: never). Then the 2D and 3D scores over it."""
from __future__ import annotations

import numpy as np
import pytest

from core2d.result import SliceResult
from core2d.truth.metrics import slice_metrics
from core2d.truth.reachability import reachable_samples, sample_contour
from core2d.truth.resolvable import resolvable

EPS = 1.0
R = EPS / 2


def _slotted(widths, depth=6.0, tooth=3.0, base=2.0):
    """A block (one CCW loop) with slots of the given widths opening upwards, and the slots'
    x ranges."""
    slots, x = [], tooth
    for w in widths:
        slots.append((x, x + w))
        x += w + tooth
    top = base + depth
    pts = [(0.0, 0.0), (x, 0.0), (x, top)]
    for x0, x1 in slots[::-1]:  # along the top, right to left, down into each slot
        pts += [(x1, top), (x1, base), (x0, base), (x0, top)]
    pts.append((0.0, top))
    return [np.array(pts)], slots


def _ccw(loop):
    a = 0.5 * np.sum(loop[:, 0] * np.roll(loop[:, 1], -1) - np.roll(loop[:, 0], -1) * loop[:, 1])
    return loop if a > 0 else loop[::-1]


@pytest.mark.parametrize("width", [0.2, 0.5, 0.8, 0.9, 1.1, 1.3, 2.0, 3.5])
def test_a_slot_is_resolved_iff_the_disc_fits_in_it(width):
    """Walls and floor deeper than eps below the mouth: resolvable iff width >= eps (the disc
    then sweeps the whole slot; a floor corner is (sqrt 2 - 1) r < r from it)."""
    loops, slots = _slotted([width])
    loops = [_ccw(lp) for lp in loops]
    s = sample_contour(loops, 0.05)
    ok = resolvable(loops, s.points, EPS)
    (x0, x1), = slots
    mouth = 8.0
    inside = ((s.points[:, 0] >= x0 - 1e-9) & (s.points[:, 0] <= x1 + 1e-9)
              & (s.points[:, 1] > 1.0) & (s.points[:, 1] < mouth - EPS))  # not the block's foot
    assert inside.sum() > 20
    assert ok[inside].all() == (width >= EPS) and ok[inside].any() == (width >= EPS)
    assert ok[s.points[:, 1] <= 0.0 + 1e-9].all()  # the outside of the block, always
    assert ok[(s.points[:, 1] > mouth - 1e-9)].all()  # its top, between the slots


@pytest.mark.parametrize("angle", [10.0, 20.0, 35.0, 60.0, 90.0])
def test_a_v_groove_is_resolved_down_to_where_the_disc_stops(angle):
    """The disc (radius r) wedged in a groove of opening angle theta touches each wall
    r / tan(theta/2) from the apex; a wall point t from the apex nearer than that lies
    sqrt((r / tan(theta/2) - t)^2 + r^2) - r from the disc: resolvable iff that is <= r,
    i.e. t >= r (1 / tan(theta/2) - sqrt 3)."""
    half = np.radians(angle) / 2
    depth = 12.0
    top = depth * np.tan(half)
    loop = _ccw(np.array([[-20.0, -5.0], [20.0, -5.0], [20.0, depth], [top, depth],
                          [0.0, 0.0], [-top, depth], [-20.0, depth]]))
    s = sample_contour([loop], 0.02)
    ok = resolvable([loop], s.points, EPS)
    on_wall = (s.points[:, 1] > 1e-9) & (s.points[:, 1] < depth - 1e-9) \
        & (np.abs(s.points[:, 0]) <= top)
    t = np.hypot(*s.points[on_wall].T)  # distance from the apex along the wall
    bound = R * (1.0 / np.tan(half) - np.sqrt(3.0))
    margin = 0.02 * EPS + 0.02  # the circles are polygons; the samples 0.02 apart
    assert ok[on_wall][t > bound + margin].all()
    assert not ok[on_wall][t < bound - margin].any()
    assert (bound > margin) == (not ok[on_wall].all())


def test_a_hole_is_never_resolved_and_an_island_in_it_neither():
    outer = _ccw(np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]]))
    hole = _ccw(np.array([[2.0, 2.0], [8.0, 2.0], [8.0, 8.0], [2.0, 8.0]]))[::-1]
    island = _ccw(np.array([[4.0, 4.0], [6.0, 4.0], [6.0, 6.0], [4.0, 6.0]]))
    loops = [outer, hole, island]
    s = sample_contour(loops, 0.1)
    ok = resolvable(loops, s.points, EPS)
    assert ok[s.loop == 0].all() and not ok[s.loop > 0].any()


def test_coverage_over_the_part_eps_resolves():
    """A comb traced everywhere but inside its slots: the slots narrower than eps lower the
    reachable coverage, not the coverage of the part eps resolves; missing a wide slot's
    floor lowers both."""
    loops, slots = _slotted([0.3, 2.0, 0.6])
    loops = [_ccw(lp) for lp in loops]
    samples = reachable_samples(loops, 0.05)
    pts = samples[0].points

    def traced(skip):
        keep = ~skip(pts)
        return SliceResult(w1=[p[None] for p in pts[keep]])

    def in_slot(k, below=8.0 - EPS):
        (x0, x1) = slots[k]
        return lambda p: ((p[:, 0] > x0 - 1e-9) & (p[:, 0] < x1 + 1e-9) & (p[:, 1] > 1.0)
                          & (p[:, 1] < below))

    narrow = traced(lambda p: in_slot(0)(p) | in_slot(2)(p))
    m = slice_metrics(loops, narrow, EPS, samples=samples)
    assert m["coverage"] < 0.9 and m["coverage_resolvable"] == 1.0
    assert m["resolvable_length"] < m["reachable_length"]
    wide = traced(lambda p: in_slot(0)(p) | in_slot(2)(p) | (in_slot(1, 2.0 + 1e-9)(p)))
    m = slice_metrics(loops, wide, EPS, samples=samples)
    assert m["coverage_resolvable"] < 1.0 - 1.0 / m["resolvable_length"]


def test_the_3d_scores_leave_out_the_walls_of_a_slot_narrower_than_eps():
    """A block with a slot 0.4 eps wide and one 3 eps wide, z-slices: the ground-truth
    samples the 3D scores leave out of the part eps resolves are those inside the narrow
    slot (counted here from the slot's box), and the surface, which closes that slot at its
    mouth, scores higher there than over the reachable part."""
    import trimesh

    import recon3d
    from recon3d.score.evaluate import SAMPLES, Domain, GroundTruthSamples

    eps = 1.0
    block = trimesh.creation.box(extents=(30.0, 20.0, 10.0))
    narrow = trimesh.creation.box(extents=(0.4, 16.0, 20.0))
    narrow.apply_translation((-6.0, 4.0, 0.0))  # from y = -4 up through the top (y = 10)
    wide = trimesh.creation.box(extents=(3.0, 16.0, 20.0))
    wide.apply_translation((6.0, 4.0, 0.0))
    mesh = block.difference(trimesh.util.concatenate([narrow, wide]), engine="manifold")
    res = recon3d.run(mesh, slices=3, eps=eps, jobs=1)
    ev, surf = res.metrics["surface_eval"], res.metrics["total"]["surface"]
    dom = ev["domain"][0]
    gt = GroundTruthSamples(res.mesh, Domain(np.array([dom["normal"]]), np.array([dom["from"]]),
                                             np.array([dom["to"]])), SAMPLES)
    p = gt.points
    in_narrow = (np.abs(p[:, 0] + 6.0) <= 0.2 + 1e-6) & (p[:, 1] > -4.0 - 1e-6)
    deep = in_narrow & (p[:, 1] < 10.0 - eps)  # farther than eps below the mouth
    left_out = ev["reachable_share"] - ev["resolvable_share"]
    assert deep.sum() > 500
    assert deep.sum() / gt.drawn <= left_out <= in_narrow.sum() / gt.drawn
    assert surf["resolvable"]["fscore"]["1%"] > surf["reachable"]["fscore"]["1%"] + 0.02
    # the coloured ground truth (scene.vtm, coverage.png) marks the same part: class 5 faces
    # lie in the narrow slot, and the faces deep in it are class 5
    from recon3d.api import _coverage

    cov = _coverage(res.mesh, res.sensing, res.recon)
    c, centre = cov.face_attributes["coverage"], cov.triangles_center
    in_slot = (np.abs(centre[:, 0] + 6.0) <= 0.2 + 1e-6) & (centre[:, 1] > -4.0 - 1e-6)
    deep_faces = in_slot & (centre[:, 1] < 10.0 - eps) & (c != 0)
    assert (c == 5).any() and in_slot[c == 5].all()
    assert (c[deep_faces] == 5).mean() > 0.9
