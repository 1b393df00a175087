"""Two families round a cavity that one of them cannot see (the Ravens cup's mechanism).

The constructed case: a 20 mm cube with a 12 mm pocket open at the top (+z). Family z slices
across the pocket's axis: each plane through the pocket cuts a ring whose inner loop no probe
in the plane can reach, so z traces the outer loop only and the closure fills the pocket --
solid z only filled in. Family x slices along it: its planes cut a U and see the pocket
empty, except the middle plane, whose probe never entered: its W1 stops at the pocket's
mouth and an unknown chord A_iB_i closes it (§3.3). The caps rule (:mod:`recon3d.surface.caps`)
drops that chord's fill on the middle plane, as both neighbouring x planes show the pocket
empty. Checked against the truth solid with trimesh (``contains``), not recon3d code.
"""
import numpy as np
import pytest
import trimesh

import slicer
from recon3d.surface.caps import CapSettings
from recon3d.surface.closure import slice_region
from recon3d.surface.fusion import FusionSettings
from recon3d.surface.solid import family_solid, fuse

STEP = 0.5


def _uv(plane, pts3):
    rel = np.asarray(pts3, dtype=float) - plane.origin
    return np.column_stack([rel @ plane.u, rel @ plane.v])


def _cup(caps=CapSettings()):
    """The truth, family z (outer loops only) and family x (middle plane closed by a chord)."""
    pocket = trimesh.creation.box((12.0, 12.0, 12.0)).apply_translation([0, 0, 4.01])
    mesh = trimesh.creation.box((20.0, 20.0, 20.0)).difference(pocket)
    zc = slicer.slice_mesh(mesh, axis="z", count=5)
    zreg = []
    for c in zc:  # the outer loop only: the pocket's wall is enclosed in the plane
        outer = max(c.loops, key=lambda lp: trimesh.path.polygons.Polygon(lp).area)
        zreg.append(slice_region([np.vstack([outer, outer[:1]])], [], [], [], 1e-9))
    xc = slicer.slice_mesh(mesh, axis="x", count=5)
    xreg = [slice_region([np.vstack([lp, lp[:1]]) for lp in c.loops], [], [], [], 1e-9)
            for c in xc]
    mid = xc[2].plane  # x = 0: W1 round the outside from one mouth corner to the other
    w1 = _uv(mid, [[0, 6, 10], [0, 10, 10], [0, 10, -10], [0, -10, -10], [0, -10, 10],
                   [0, -6, 10]])
    chord = np.array([w1[-1], w1[0]])
    xreg[2] = slice_region([w1], [], [], [chord], 1e-9)
    assert xreg[2].area == pytest.approx(400.0)  # the pocket filled on the middle plane
    z = family_solid(zreg, [c.plane for c in zc], STEP, keep_field=True)
    x = family_solid(xreg, [c.plane for c in xc], STEP, keep_field=True, caps=caps)
    return mesh, z, x


@pytest.fixture(scope="module")
def cup():
    return _cup()


def _pocket_on_middle_plane():
    """(n, 3) points in the pocket on the x = 0 plane, 1 mm and more from its walls, inside both slabs."""
    y, z = np.meshgrid(np.linspace(-5, 5, 11), np.linspace(-1, 7, 9))
    return np.column_stack([np.zeros(y.size), y.ravel(), z.ravel()])


def test_the_pocket_stays_open_on_the_plane_that_closed_it_with_a_chord(cup):
    """On x's middle plane its own field is dropped to the neighbours' empty; their sensing
    says so, so that empty carries their trust against z's solid, which z only filled in.
    With the slice's own 'unseen' trust there (the closure's chord fill), z's filled solid
    wins on the plane and leaves a plate across the pocket."""
    mesh, z, x = cup
    pts = _pocket_on_middle_plane()
    assert not mesh.contains(pts).any()  # the truth: empty
    assert not fuse([x], mesh.bounds).contains(pts).any()  # x alone: the rule drops the fill
    assert fuse([z], mesh.bounds).contains(pts).all()  # z alone fills the pocket
    fused = fuse([z, x], mesh.bounds)
    assert not fused.contains(pts).any()
    _, z, x = _cup(CapSettings(own_trust=False))  # the dropped fill keeps its 'unseen' trust
    assert fuse([z, x], mesh.bounds).contains(pts).mean() > 0.5  # a plate across the pocket


def test_without_the_rule_for_filled_solid_the_fused_pocket_wall_is_the_same(cup):
    """The pocket's walls lie 4 mm (8 steps) behind z's traced outer wall: z's solid there is
    filled in; on the planes x saw it empty. The fused surface keeps the true wall within a
    step with and without ``FusionSettings.filled``."""
    mesh, z, x = cup
    for settings in (FusionSettings(), FusionSettings(filled=False)):
        fused = fuse([z, x], mesh.bounds, "weighted", settings)
        pts, _ = trimesh.sample.sample_surface(fused, 4000, seed=2)
        lo = -8.0  # inside both slabs
        pts = pts[(np.abs(pts) <= 8.0 + 1e-9).all(axis=1) & (pts[:, 2] >= lo)]
        far = np.abs(trimesh.proximity.signed_distance(mesh, pts))
        assert np.percentile(far, 99) < 2 * STEP
