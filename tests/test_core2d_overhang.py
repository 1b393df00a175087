"""The probe's end hanging in a slot the trace stepped over
(:func:`core2d.sim.compliance.overhangs`).

A contact within the tip zone (eps / 2 of the probe's end) is the tip's, so a
probe stepping over a slot narrower than that can rest on the slot's far corner
with its end inside the slot. The compliant trace then reports a contact point
jump (Case 2 of §4.3.2) instead of a continuous slide, and the slot's mouth is
registered by the rule of §4.3.3 (W2 at once: Dist < eps).
"""
import numpy as np
import pytest

from core2d.sim.compliance import overhangs
from slicer.contact.embree_direct import available


@pytest.mark.parametrize("end,want", [
    ((0.5, -0.1), True),     # in the gap between o and q, behind the chord
    ((0.5, -0.01), False),   # within the settle's resolution of the chord
    ((0.5, 0.2), False),     # on the joint's (free) side
    ((1.0, 0.0), False),     # the contact at the very end: the end is q
    ((1.2, -0.5), False),    # beyond q: the overhang of a convex corner
    ((-0.2, -0.5), False),   # before o
])
def test_overhangs_reads_the_end_against_the_step(end, want):
    o, q, joint = (0.0, 0.0), (1.0, 0.0), (3.0, 5.0)
    assert overhangs(*o, *q, *end, *joint, 0.02) is want
    # mirrored (the joint below): the material side flips with it
    assert overhangs(*o, *q, end[0], -end[1], joint[0], -joint[1], 0.02) is want


@pytest.mark.skipif(not available(), reason="no Embree 4 library to call directly")
@pytest.mark.parametrize("lean", [20, 38, 60, 80])
def test_a_slot_under_the_tip_zone_is_a_case_2_jump(lean):
    """A slot 0.3 eps wide and 20 eps deep in a flat top (eps = 1), traced left
    to right by a probe leaning back at ``lean`` degrees (its end trailing, as
    the ``comb`` scene's trace): the end drops into the slot and the body
    meets its far corner within the tip zone. The trace reports Case 2-1 with
    the slot's mouth (its two corners, read on the true top) as the new area;
    the Python path and the compiled kernels agree. Before the rule the trace
    slid on over the slot as one polyline (Case 1 only), the slot recorded as
    traced contour."""
    from figure_scenes import block
    from test_core2d_kernels import _extruded_contact, _PythonPath, trace_constructed

    near, far = (50.0, 60.0), (50.3, 60.0)
    top = [(0, 60), near, (50, 40), (50.3, 40), far, (100, 60)]
    contact = _extruded_contact(block(top))
    lean = np.radians(lean)
    got = []
    for model in (contact, _PythonPath(contact)):
        probe, lines, new, cases = trace_constructed(
            model, (45.0, 60.0), (-np.cos(lean), -np.sin(lean)), (5.0, 60.0), (95.0, 60.0))
        got.append((cases, [np.asarray(pl).tolist() for pl in lines],
                    [(k.rule, k.a.tolist(), k.b.tolist()) for k in new],
                    probe.stats.casts, probe.stats.joint_path))
    assert got[0] == got[1]
    cases, lines, new, _, _ = got[0]
    assert "case2-1" in cases
    (rule, p1st, p2nd), = [k for k in new if k[0] == "case2-1"]
    tol = probe.tol
    assert np.hypot(*np.subtract(p1st, near)) <= 2 * tol
    assert np.hypot(*np.subtract(p2nd, far)) <= 2 * tol
    steps = [(p, q) for pl in lines for p, q in zip(pl[:-1], pl[1:])]
    assert not any(p[0] < near[0] and q[0] > far[0] for p, q in steps)  # none over it


def test_the_comb_slot_stepped_over_is_w2():
    """The ``comb`` scene, z-slice 4 of 8, perfect sensing: the slot 0.32 eps
    wide at x 25.83 (corners read from the true section) lay under one trace
    step of 0.43 eps, its 70 mm of walls recorded as the traced top (the slot's
    samples 0.0 covered, the slice 0.915). With the end's overhang read as a
    jump its mouth is a W2 chord between its corners and the walls behind it
    count covered."""
    from noisy_runs import mesh_slice, scene_slice, slot_covered

    _, eps, _, loops = mesh_slice("comb", 4)
    res, m = scene_slice("comb", 4, 0.0, 0.0, 0)
    top = max(lp[:, 1].max() for lp in loops)
    pts = np.concatenate(loops)
    mouth = pts[(np.abs(pts[:, 0] - 25.83) < 0.3) & (pts[:, 1] == top)]
    near, far = mouth[np.argsort(mouth[:, 0])]
    assert 0.2 * eps < far[0] - near[0] < 0.5 * eps  # narrower than the tip zone
    chords = [np.asarray(c) for c in res.w2 if len(c) == 2]
    assert any(np.hypot(*(c[0] - near)) < eps / 8 and np.hypot(*(c[1] - far)) < eps / 8
               or np.hypot(*(c[1] - near)) < eps / 8 and np.hypot(*(c[0] - far)) < eps / 8
               for c in chords)
    steps = np.concatenate([np.stack([pl[:-1], pl[1:]], 1) for pl in map(np.asarray, res.w1)])
    lo, hi = steps[:, :, 0].min(1), steps[:, :, 0].max(1)
    assert not np.any((lo < near[0]) & (hi > far[0]) & (steps[:, :, 1].min(1) > top - eps / 8))
    assert slot_covered(res, loops, 25.83, eps, eps / 2) >= 0.95
    assert m["coverage_sensor"] >= 0.99 and m["precision_sensor"] >= 0.99
