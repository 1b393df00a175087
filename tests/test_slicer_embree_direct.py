"""The compiled one-ray function (slicer.contact.embree_direct) against EmbreeContact.cast."""
import ctypes

import numpy as np
import pytest

import meshes
from slicer import slice_mesh
from slicer.contact.embree_direct import DirectScene, available

pytestmark = pytest.mark.skipif(not available(), reason="no Embree 4 library to call directly")

_PROTO = ctypes.CFUNCTYPE(None, ctypes.c_void_p, *[ctypes.c_double] * 5, ctypes.c_void_p)


@pytest.mark.parametrize("name", ["fig18_overhangs", "gear", "twin_posts"])
def test_ray_function_answers_as_cast(name):
    cut = slice_mesh(meshes.load(name), axis="z", count=3)[1]
    contact = cut.contact("embree")
    address, context = contact.ray_kernel
    ray = _PROTO(address)
    center, radius = cut.bounding_circle()
    rng = np.random.default_rng(3)
    n = 2000
    o = center + rng.uniform(-1.2 * radius, 1.2 * radius, (n, 2))
    a = rng.uniform(0, 2 * np.pi, n)
    d = np.stack([np.cos(a), np.sin(a)], axis=1)
    limit = rng.uniform(0.05, 2.0, n) * radius
    d[: n // 10] = [1.0, 0.0]  # axis-aligned rays, through vertices of the box-like parts
    want_d, want_p, _ = contact.cast(o, d, limit)
    out = np.empty(3)
    got = np.empty((n, 3))
    for i in range(n):
        ray(context.ctypes.data, *o[i], *d[i], limit[i], out.ctypes.data)
        got[i] = out
    assert np.array_equal(got[:, 0], want_d)
    assert np.array_equal(got[:, 1:], want_p, equal_nan=True)
    assert 0.2 < np.isfinite(want_d).mean() < 0.95  # hits and misses both tested


def test_direct_scene_of_nothing_misses():
    from slicer.contact.embree_direct import ray_function

    scene = DirectScene(np.zeros((0, 3, 3), np.float32), np.zeros((0, 6)))
    out = np.zeros(3)
    _PROTO(ray_function())(scene.context.ctypes.data, 0.0, 0.0, 1.0, 0.0, 1e9, out.ctypes.data)
    assert np.isinf(out[0]) and np.isnan(out[1:]).all()


def test_without_a_direct_library_the_contact_has_no_ray_function(monkeypatch):
    """No Embree 4 library to call: ``ray_kernel`` is None and the probe keeps
    to ``cast`` (the same answers, the Python search)."""
    import slicer.contact.embree as ec
    from core2d import sense_slice

    monkeypatch.setattr(ec, "ray_function", lambda: 0)
    cut = slice_mesh(meshes.load("fig17_pocket"), axis="z", count=1)[0]
    contact = cut.contact("embree")
    assert contact.ray_kernel is None
    center, radius = cut.bounding_circle()
    res = sense_slice(contact, (center, radius + 1.0), 1.0, max_motions=300)
    assert res.stats.motions > 50 and res.w1
