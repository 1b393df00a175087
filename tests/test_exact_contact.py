"""The exact backend's compiled cast gives numpy's answers to the bit, and its ray function
gives the simulator's compiled engine the runs of the Python engine.

``slicer.contact.exact.ExactContact.cast`` runs one numba kernel per call. The reference
here is the numpy computation it replaced, every ray against every segment at once (no
culling): ``w = p - o``, ``denom = d x e``, ``s = (w x e) / denom``, ``r = (w x d) / denom``,
the least admissible s by ``argmin``, the hit point ``o + s d`` and the segment's normal
turned against the ray. The planner's decisions hang on the last bits of these numbers, so
distances, points and normals must be equal, not close: on random outlines with islands and
open chains, rays aimed exactly at vertices, along edges, from the contour itself, with
scalar, per-ray and infinite ``max_dist``. The ray function (``ray_kernel``) answers
each ray as ``cast`` does, so a slice sensed through the compiled engine (the ray function)
and through the Python engine (``cast`` only) is the same run: geometry, counters and motion
log, noiseless and with a noisy sensor.
"""
from __future__ import annotations

import ctypes

import numpy as np
import pytest

import figure_scenes as F
import outlines
from core2d import SensorModel, sense_slice
from core2d.sim.compiled import CompiledEngine
from core2d.sim.probe import Probe
from core2d.sim.search import PythonEngine
from slicer.contact.exact import _SLACK, ExactContact


def numpy_cast(contact: ExactContact, o, d, max_dist):
    """Every ray (n, 2) against every segment with numpy: (dist, points, normals)."""
    o, d = np.atleast_2d(o).astype(float), np.atleast_2d(d).astype(float)
    n = len(o)
    md = np.broadcast_to(np.asarray(max_dist, dtype=float), (n,))
    p, e = contact.starts[None], contact.edges[None]
    w = p - o[:, None, :]
    denom = d[:, None, 0] * e[..., 1] - d[:, None, 1] * e[..., 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (w[..., 0] * e[..., 1] - w[..., 1] * e[..., 0]) / denom
        r = (w[..., 0] * d[:, None, 1] - w[..., 1] * d[:, None, 0]) / denom
    ok = (denom != 0) & (s >= 0) & (r >= -_SLACK) & (r <= 1 + _SLACK) & (s <= md[:, None])
    s = np.where(ok, s, np.inf)
    seg = np.argmin(s, axis=1)
    dist = s[np.arange(n), seg]
    hit = np.isfinite(dist)
    points = np.full((n, 2), np.nan)
    normals = np.full((n, 2), np.nan)
    points[hit] = o[hit] + dist[hit, None] * d[hit]
    edge = contact.edges[seg[hit]]
    nrm = np.stack([-edge[:, 1], edge[:, 0]], axis=1)
    nrm /= np.linalg.norm(nrm, axis=1, keepdims=True)
    nrm[np.einsum("ij,ij->i", nrm, d[hit]) > 0] *= -1
    normals[hit] = nrm + 0.0
    return dist, points, normals


def _outline(rng):
    """A star-shaped loop (k vertices), a square island, an open chain."""
    k = int(rng.integers(5, 40))
    angles = np.sort(rng.uniform(0, 2 * np.pi, k))
    radii = rng.uniform(2.0, 10.0, k)
    star = np.c_[radii * np.cos(angles), radii * np.sin(angles)]
    island = np.array([[12.0, 12.0], [14.0, 12.0], [14.0, 14.0], [12.0, 14.0]])
    chain = rng.uniform(-12, 12, (4, 2))
    return [star, island], [chain]


def _rays(rng, contact, n):
    """Random rays, rays aimed at vertices, rays along edges and rays from the contour."""
    o = rng.uniform(-15, 15, (n, 2))
    d = rng.normal(size=(n, 2))
    at = contact.starts[rng.integers(0, len(contact.starts), n // 3)]
    d[: n // 3] = at - o[: n // 3]  # exactly through a vertex
    pick = rng.integers(0, len(contact.starts), n // 6)
    o[n // 3: n // 3 + n // 6] = contact.starts[pick]  # from a vertex along its edge
    d[n // 3: n // 3 + n // 6] = contact.edges[pick]
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    return o, d


@pytest.mark.parametrize("seed", range(12))
def test_the_compiled_cast_is_numpys_to_the_bit(seed):
    rng = np.random.default_rng(seed)
    loops, chains = _outline(rng)
    contact = ExactContact(loops, chains)
    o, d = _rays(rng, contact, 60)
    per_ray = rng.uniform(0.5, 30.0, len(o))
    with_inf = per_ray.copy()
    with_inf[::7] = np.inf
    for max_dist in (25.0, per_ray, with_inf, np.inf):
        got = contact.cast(o, d, max_dist)
        want = numpy_cast(contact, o, d, max_dist)
        for g, w, what in zip(got, want, ("distances", "points", "normals")):
            assert g.shape == w.shape and g.dtype == w.dtype
            # the bits: a negative zero differs from a zero, a NaN equals the NaN it is
            assert np.array_equal(g.view(np.int64), w.view(np.int64)), f"seed {seed}: {what}"
        assert not (np.signbit(got[2]) & (got[2] == 0)).any(), "a normal's negative zero"
    hits = np.isfinite(contact.cast(o, d, np.inf)[0])
    assert 0.2 < hits.mean() < 1.0  # the rays both hit and miss


def test_a_short_batch_and_one_ray():
    square = [np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)]
    contact = ExactContact(square)
    d, p, n = contact.cast(np.array([-1.0, 0.5]), np.array([1.0, 0.0]), np.array([0.5]))
    assert np.isinf(d[0]) and np.isnan(p).all() and np.isnan(n).all()  # too short
    d, p, n = contact.cast(np.zeros((0, 2)), np.zeros((0, 2)), 1.0)
    assert d.shape == (0,) and p.shape == n.shape == (0, 2)
    with pytest.raises(ValueError, match="max_dist holds 2 values for 3 rays"):
        contact.cast(np.zeros((3, 2)), np.ones((3, 2)), np.ones(2))


def test_the_ray_function_answers_as_cast():
    rng = np.random.default_rng(3)
    loops, chains = _outline(rng)
    contact = ExactContact(loops, chains)
    o, d = _rays(rng, contact, 200)
    md = rng.uniform(0.5, 30.0, len(o))
    md[::5] = np.inf
    address, context = contact.ray_kernel
    ray = ctypes.CFUNCTYPE(None, ctypes.c_void_p, *[ctypes.c_double] * 5,
                           ctypes.c_void_p)(address)
    got, out = np.empty((len(o), 3)), np.empty(3)
    for i in range(len(o)):
        ray(context.ctypes.data, *o[i], *d[i], md[i], out.ctypes.data)
        got[i] = out
    dist, points, _ = contact.cast(o, d, md)
    assert np.array_equal(got.view(np.int64), np.c_[dist, points].view(np.int64))
    assert ExactContact([]).ray_kernel is None  # nothing to hit: the Python engine


class _CastOnly:
    """The exact contact model without its ray function: the Python engine."""

    def __init__(self, inner):
        self.inner = inner

    def cast(self, origins, dirs, max_dist):
        return self.inner.cast(origins, dirs, max_dist)


def _run(contact, ws, eps, noise):
    sensor = SensorModel.of_eps(eps, noise, 0.25 if noise else 0.0, 5) if noise else None
    return sense_slice(contact, ws, eps, sensor=sensor)


@pytest.mark.parametrize("scene,noise", [("OVERHANG_LEFT", 0.0), ("HILL", 0.3),
                                         ("comb", 0.0), ("undercut", 0.1)])
def test_the_compiled_engine_senses_as_the_python_engine(scene, noise):
    if scene.isupper():
        loops, ws, eps = F.block(getattr(F, scene)), F.WORKSPACE, F.EPS
    else:
        loops, eps = outlines.outline(scene, np.random.default_rng(4), eps=1.0), 1.0
        pts = np.concatenate(loops)
        ws = ((pts.min(0) + pts.max(0)) / 2, float(np.linalg.norm(np.ptp(pts, 0)) / 2 + 1.0))
    contact = ExactContact(loops)
    assert type(Probe(contact, ws, eps).engine) is CompiledEngine
    assert type(Probe(_CastOnly(contact), ws, eps).engine) is PythonEngine
    fast, slow = _run(contact, ws, eps, noise), _run(_CastOnly(contact), ws, eps, noise)
    for key in ("w1", "w2", "w3", "unknown"):
        a, b = getattr(fast, key), getattr(slow, key)
        assert len(a) == len(b) and all(np.array_equal(x, y) for x, y in zip(a, b)), key
    for key in ("motions", "casts", "pushes", "push_attempts", "joint_path", "areas"):
        assert getattr(fast.stats, key) == getattr(slow.stats, key), key
    assert fast.stats.motions > 100
    assert fast.stats.rays < slow.stats.rays  # the compiled windows stop at their first hit
    for key in ("kind", "event", "contacts", "before", "after", "tip"):
        assert np.array_equal(getattr(fast.motions, key), getattr(slow.motions, key)), key


def test_a_rays_answer_does_not_depend_on_its_batch():
    """A ray straight down, 1e-13 left of a peak V, meets both segments at V: the one
    rising to V (s = 4 + 1e-13) and, within the parameter's slack, the one falling from V
    to the right (s = 4 - 1e-13, r = -2e-13), whose bounding box lies wholly right of the
    ray. The nearer one is the answer whether the ray comes alone or beside a ray to the
    right (a cull by the batch's bounding box dropped it for the lone ray only)."""
    loop = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 0.5], [1.5, 0.5], [1.0, 1.0], [0.5, 0.5],
                     [0.0, 0.5]])
    contact = ExactContact([loop])
    ray = (np.array([[1.0 - 1e-13, 5.0]]), np.array([[0.0, -1.0]]))
    far = (np.array([[1.4, 5.0]]), np.array([[0.0, -1.0]]))
    alone = contact.cast(*ray, 10.0)
    beside = contact.cast(np.r_[ray[0], far[0]], np.r_[ray[1], far[1]], 10.0)
    for a, b in zip(alone, beside):
        assert np.array_equal(a[0].view(np.int64), b[0].view(np.int64))
    assert alone[0][0] < 4.0  # the segment falling from V, met within its slack
    numpy_answer = numpy_cast(contact, *ray, 10.0)
    assert np.array_equal(alone[0].view(np.int64), numpy_answer[0].view(np.int64))
