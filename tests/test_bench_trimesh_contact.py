"""trimesh's generic ray engine as a third contact backend (slicer.contact.trimesh_ray).

Checked against the exact 2D backend (segment intersection against the
reference contour) on random in-plane rays and on a full sensing run.
"""
import numpy as np
import pytest

import meshes
import slicer
from core2d import sense_slice
from slicer import TrimeshContact
from slicer.agreement import random_rays


@pytest.mark.parametrize("scene", ["fig18_overhangs", "bored_block"])
def test_trimesh_backend_agrees_with_exact_on_random_rays(scene):
    mesh = meshes.load(scene)
    for s in slicer.slice_mesh(mesh, "z", count=3):
        o, d, m = random_rays(s, 400, np.random.default_rng(s.index))
        dt, pt, nt = s.contact("trimesh").cast(o, d, m)
        dx, px, nx = s.contact("exact").cast(o, d, m)
        assert isinstance(s.contact("trimesh"), TrimeshContact)
        assert np.array_equal(np.isfinite(dt), np.isfinite(dx))
        hit = np.isfinite(dx)
        assert hit.sum() > 50
        assert np.allclose(dt[hit], dx[hit], atol=1e-9 * s.scale)
        assert np.allclose(pt[hit], px[hit], atol=1e-9 * s.scale)
        assert np.allclose(nt[hit], nx[hit], atol=1e-6)


def test_trimesh_backend_senses_like_exact():
    (s,) = slicer.slice_mesh(meshes.load("fig17_pocket"), "z", count=1)
    center, radius = s.bounding_circle()
    eps = s.scale / 60
    runs = {b: sense_slice(s.contact(b), (center, radius + eps), eps) for b in ("trimesh", "exact")}
    assert runs["trimesh"].stats.motions == runs["exact"].stats.motions
    a, b = (np.concatenate(r.w1) for r in runs.values())
    assert a.shape == b.shape and np.allclose(a, b, atol=1e-6 * s.scale)


def test_empty_plane_and_unknown_backend():
    import trimesh

    box = trimesh.creation.box(extents=[2.0, 2.0, 2.0])
    plane = slicer.make_planes(box, "z", offsets=[0.3])[0]
    far = trimesh.creation.box(extents=[1, 1, 1]).apply_translation([0, 0, 5])
    d, p, n = TrimeshContact(far, plane).cast(np.zeros((2, 2)), np.array([[1, 0], [0, 1.0]]), 9)
    assert np.isinf(d).all() and np.isnan(p).all()
    with pytest.raises(ValueError, match="backend"):
        slicer.slice_mesh(box, "z", count=1)[0].contact("ray")
