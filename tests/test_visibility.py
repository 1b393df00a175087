"""core2d.visibility: the compiled half-plane path against the vectorised one
and against brute-force ray sampling."""
from __future__ import annotations

import numpy as np
import pytest

from core2d.visibility import _vectorised, free_gaps


def _case(seed):
    rng = np.random.default_rng(seed)
    n, c = int(rng.integers(0, 50)), int(rng.integers(1, 30))
    if seed % 2:  # grid coordinates: shared ends, collinear and zero-length segments
        ab = rng.integers(-4, 5, size=(n, 4)) / 2.0
        pts = rng.integers(-4, 5, size=(c, 2)) / 2.0
    else:
        ab, pts = rng.normal(size=(n, 4)), rng.normal(size=(c, 2))
    a, b = ab[:, :2].copy(), ab[:, 2:].copy()
    if n > 2:
        b[0] = a[0]
    if n and c > 1:
        pts[0] = (a[-1] + b[-1]) / 2  # a point on a segment
    ang = rng.uniform(-np.pi, np.pi, c) if seed % 3 else rng.integers(-4, 4, c) * np.pi / 2
    return pts, np.stack([np.cos(ang), np.sin(ang)], axis=1), a, b


@pytest.mark.parametrize("atol", [0.0, 0.1])
@pytest.mark.parametrize("seed", range(40))
def test_compiled_half_plane_path_is_the_vectorised_one(seed, atol):
    """Inner points take the compiled path, with or without ``own`` (a
    segment each point ignores): bit-identical to the vectorised one."""
    pts, tg, a, b = _case(seed)
    inner = np.ones(len(pts), dtype=bool)
    own = np.random.default_rng(seed).integers(-1, len(a), len(pts))  # -1 .. n - 1
    if len(a) and len(pts) > 1:
        own[0] = len(a) - 1  # the point on that segment ignores it
    for o in (None, own):
        fast = free_gaps(pts, tg, a, b, own=o, atol=atol)
        slow = _vectorised(pts, tg, a, b, inner, o, atol)
        for x, y in zip(fast, slow):
            np.testing.assert_array_equal(x, y)


def _chains(seed):
    """Random-walk polylines as the planner's map holds them: segment j starts where
    j - 1 ends (the compiled path computes such a shared end once per point), three
    chains end to start, points among them."""
    rng = np.random.default_rng(seed)
    walks = [np.cumsum(rng.normal(size=(int(rng.integers(5, 40)), 2)), axis=0) + 3 * k
             for k in range(3)]
    a = np.concatenate([w[:-1] for w in walks])
    b = np.concatenate([w[1:] for w in walks])
    pts = rng.normal(size=(20, 2)) * 4 + 3
    ang = rng.uniform(-np.pi, np.pi, len(pts))
    return pts, np.stack([np.cos(ang), np.sin(ang)], axis=1), a, b


@pytest.mark.parametrize("atol", [0.0, 0.5])
@pytest.mark.parametrize("seed", range(12))
def test_compiled_path_on_polylines_is_the_vectorised_one(seed, atol):
    """Shared ends with chains broken where a point culls a segment (behind its tangent,
    within ``atol``, its own): bit-identical to the vectorised path."""
    pts, tg, a, b = _chains(seed)
    assert (a[1:] == b[:-1]).all(axis=1).mean() > 0.9
    own = np.random.default_rng(seed).integers(-1, len(a), len(pts))
    for o in (None, own):
        fast = free_gaps(pts, tg, a, b, own=o, atol=atol)
        slow = _vectorised(pts, tg, a, b, np.ones(len(pts), dtype=bool), o, atol)
        for x, y in zip(fast, slow):
            np.testing.assert_array_equal(x, y)


def _hits(p, d, a, b):
    """Does the ray p + s d (s > 0) meet any segment a-b? (n,) per direction row."""
    e = b - a
    w = a - p
    den = d[:, None, 0] * e[None, :, 1] - d[:, None, 1] * e[None, :, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (w[None, :, 0] * e[None, :, 1] - w[None, :, 1] * e[None, :, 0]) / den
        r = (w[None, :, 0] * d[:, None, 1] - w[None, :, 1] * d[:, None, 0]) / den
    return ((s > 0) & (r >= 0) & (r <= 1)).any(axis=1)


@pytest.mark.parametrize("seed", range(6))
def test_widest_gap_matches_ray_sampling(seed):
    rng = np.random.default_rng(100 + seed)
    a = rng.normal(size=(12, 2)) * 2
    b = a + rng.normal(size=(12, 2))
    p = rng.normal(size=(1, 2)) * 0.2
    t = rng.normal(size=2)
    t /= np.linalg.norm(t)
    width, angle = free_gaps(p, t[None], a, b)
    psi = np.linspace(0, np.pi, 20001)[1:-1]  # clockwise from t: the right half-plane
    world = np.arctan2(t[1], t[0]) - psi
    free = ~_hits(p[0], np.stack([np.cos(world), np.sin(world)], axis=1), a, b)
    best, cur = 0, 0
    for f in free:
        cur = cur + 1 if f else 0
        best = max(best, cur)
    step = psi[1] - psi[0]
    assert abs(width[0] - best * step) <= 3 * step
    d = np.array([np.cos(angle[0]), np.sin(angle[0])])
    if width[0] > 10 * step:
        assert not _hits(p[0], d[None], a, b)[0]  # the gap's middle is free


@pytest.mark.parametrize("scale", [1.0, 3.7, 1e-3])
def test_compiled_tolerance_is_exact_at_its_boundary(scale):
    """A segment exactly ``atol`` away is ignored, one ulp nearer too, one ulp
    farther it blocks: the compiled path decides as the vectorised one."""
    p = np.zeros((1, 2))
    t = np.array([[-1.0, 0.0]])  # free half-plane: y > 0
    a, b = np.array([[-1.0, 1.0]]) * scale, np.array([[2.0, 1.0]]) * scale  # a roof at y = scale
    widths = []
    for atol in (scale, np.nextafter(scale, 0.0), np.nextafter(scale, 2 * scale)):
        fast = free_gaps(p, t, a, b, atol=atol)
        slow = _vectorised(p, t, a, b, np.ones(1, dtype=bool), None, atol)
        for x, y in zip(fast, slow):
            np.testing.assert_array_equal(x, y)
        widths.append(float(fast[0][0]))
    assert widths[0] == widths[2] == pytest.approx(np.pi) and widths[1] < np.pi
