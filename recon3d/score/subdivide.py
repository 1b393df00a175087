"""The ground truth subdivided until every edge is short (the coloured ground truth).

:func:`subdivide_to_size` gives ``trimesh.remesh.subdivide_to_size``'s vertices and
faces, the same arrays in the same order, with two savings: a face whose three edges are
short is final (its edges never change), so a round looks only at the faces made in the
round before (trimesh looks again at all of them, its edge sort and unique over every face);
and a round is two compiled kernels around numpy's ``unique`` of the long edges
(:func:`_round`) instead of numpy expressions over every edge (a ground truth of 10^5 - 10^6
faces: ~6x faster). :func:`face_centres` gives trimesh's ``triangles_center`` of the result,
where the faces are classified, without trimesh's copy of the triangles.

Why the arrays are the same: a round's faces are, in order, those already final and those
just made, so keeping the final ones aside and appending each round's final ones keeps
trimesh's order; a long edge lies only on faces with a long edge (the ones looked at); the
midpoints of a round are numbered in the order of ``trimesh.grouping.unique_rows`` of the
long edges (its key sorts an edge (lo, hi) by hi, then lo); and each number is computed with
the same floating-point operations in the same order as trimesh's numpy expressions (an
edge's length: the squares of x, y, z added left to right, then the square root; a midpoint:
the two ends added, then halved). Tested ``==`` against trimesh.
"""
from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["subdivide_to_size", "face_centres", "compile_kernels"]


@numba.njit(cache=True)
def _dist2(vertices, fresh, nv, i, j):
    """Squared distance of vertices i and j (numbers from ``nv`` on are rows of ``fresh``),
    the squares of x, y, z added left to right (numpy's ``((a - b) ** 2).sum(axis=1)``)."""
    s = 0.0
    for k in range(3):
        a = vertices[i, k] if i < nv else fresh[i - nv, k]
        b = vertices[j, k] if j < nv else fresh[j - nv, k]
        d = a - b
        s += d * d
    return s


@numba.njit(cache=True)
def _long_edges(vertices, faces, max_edge):
    """(n, 3) bool: which edges of ``faces`` (n, 3) are longer than ``max_edge`` (edge k
    joins corners k and k + 1), and (j,) int64: the key of each long edge, face by face
    (``unique_rows``' order: hi << 32 | lo)."""
    n = faces.shape[0]
    long_edge = np.zeros((n, 3), dtype=np.bool_)
    keys = np.empty(3 * n, dtype=np.int64)
    nk = 0
    for i in range(n):
        for k in range(3):
            a, b = faces[i, k], faces[i, (k + 1) % 3]
            lo, hi = min(a, b), max(a, b)
            if math.sqrt(_dist2(vertices, vertices, len(vertices), lo, hi)) > max_edge:
                long_edge[i, k] = True
                keys[nk] = (hi << 32) | lo
                nk += 1
    return long_edge, keys[:nk]


@numba.njit(cache=True)
def _put(out, row, a, b, c):
    out[row, 0], out[row, 1], out[row, 2] = a, b, c


@numba.njit(cache=True)
def _made(vertices, fresh, faces, long_edge, number):
    """The faces of a round (:func:`_round`) from its long edges and their midpoints'
    vertex numbers ``number`` (j,), in the order of the long edges face by face."""
    n, nv = faces.shape[0], vertices.shape[0]
    mid = np.full((n, 3), -1, dtype=np.int64)
    count = np.zeros(n, dtype=np.int64)
    sizes = np.zeros(4, dtype=np.int64)
    r = 0
    for i in range(n):
        for k in range(3):
            if long_edge[i, k]:
                mid[i, k] = number[r]
                r += 1
                count[i] += 1
        sizes[count[i]] += 1
    n1, n2 = sizes[1], sizes[2]
    final = np.empty((sizes[0], 3), dtype=np.int64)
    made = np.empty((2 * n1 + 3 * n2 + 4 * sizes[3], 3), dtype=np.int64)
    s2 = 2 * n1  # the two-edge faces' corners, then first quads, then second quads
    s3 = 2 * n1 + 3 * n2
    r0 = r1 = r2 = r3 = 0
    for i in range(n):
        c = count[i]
        if c == 0:
            _put(final, r0, faces[i, 0], faces[i, 1], faces[i, 2])
            r0 += 1
        elif c == 1:
            j = 0
            while not long_edge[i, j]:
                j += 1
            a, b, cc, p = faces[i, j], faces[i, (j + 1) % 3], faces[i, (j + 2) % 3], mid[i, j]
            _put(made, r1, a, p, cc)
            _put(made, r1 + 1, p, b, cc)
            r1 += 2
        elif c == 2:
            short = 0
            while long_edge[i, short]:
                short += 1
            j = (short + 1) % 3
            a, b, cc = faces[i, j], faces[i, (j + 1) % 3], faces[i, (j + 2) % 3]
            p, q = mid[i, j], mid[i, (j + 1) % 3]
            use_aq = _dist2(vertices, fresh, nv, a, q) <= _dist2(vertices, fresh, nv, p, cc)
            _put(made, s2 + r2, p, b, q)
            qa, qb = s2 + n2 + r2, s2 + 2 * n2 + r2
            if use_aq:
                _put(made, qa, a, p, q)
                _put(made, qb, a, q, cc)
            else:
                _put(made, qa, a, p, cc)
                _put(made, qb, p, q, cc)
            r2 += 1
        else:
            m0, m1, m2 = mid[i, 0], mid[i, 1], mid[i, 2]
            o = s3 + 4 * r3
            _put(made, o, faces[i, 0], m0, m2)
            _put(made, o + 1, m0, faces[i, 1], m1)
            _put(made, o + 2, m2, m1, faces[i, 2])
            _put(made, o + 3, m0, m1, m2)
            r3 += 1
    return final, made


def _round(vertices, faces, max_edge):
    """One round of trimesh's ``subdivide_to_size`` over ``faces`` (n, 3).

    Returns
    -------
    final : (k, 3) int64 -- the faces whose three edges are short, in order.
    fresh : (u, 3) float64 -- the midpoints of the long edges, numbered from len(vertices)
        on in the order of ``unique_rows`` (by hi, then lo).
    made : (q, 3) int64 -- the faces made from those with 1, 2 or 3 long edges (trimesh's
        templates: the one-edge faces' pairs, then the two-edge faces' corners, first
        quads, second quads, then the three-edge faces' fours).
    """
    long_edge, keys = _long_edges(vertices, faces, max_edge)
    unique, inverse = np.unique(keys, return_inverse=True)
    ends = np.column_stack((unique & 0xFFFFFFFF, unique >> 32))
    fresh = vertices[ends].mean(axis=1)
    final, made = _made(vertices, fresh, faces, long_edge, inverse + len(vertices))
    return final, fresh, made


def subdivide_to_size(vertices, faces, max_edge: float, max_iter: int = 10
                      ) -> tuple[np.ndarray, np.ndarray]:
    """Bisect every edge longer than ``max_edge`` until none is (module doc).

    Parameters
    ----------
    vertices : (n, 3) float; faces : (m, 3) int
    max_edge : float
    max_iter : int -- rounds allowed; ValueError when edges are still long after them.

    Returns
    -------
    vertices : (j, 3) float64 -- the input's first, then the midpoints round by round.
    faces : (q, 3) int64

    >>> v = np.array([[0.0, 0, 0], [4, 0, 0], [0, 1, 0]])
    >>> nv, nf = subdivide_to_size(v, np.array([[0, 1, 2]]), 1.5)
    >>> edges = nv[nf[:, [1, 2, 0]]] - nv[nf]
    >>> len(nf), float(np.linalg.norm(edges, axis=2).max()) <= 1.5
    (9, True)
    """
    points = [np.array(vertices, dtype=np.float64, copy=True).reshape(-1, 3)]
    active = np.array(faces, dtype=np.int64, copy=True).reshape(-1, 3)
    stack = np.ascontiguousarray(points[0])
    final = []
    for i in range(max_iter + 1):
        done, fresh, made = _round(stack, active, float(max_edge))
        final.append(done)
        if not len(made):
            break
        if i >= max_iter:
            raise ValueError("max_iter exceeded!")
        points.append(fresh)
        stack = np.vstack(points)
        active = made
    return np.vstack(points), np.vstack(final).astype(np.int64)


def face_centres(vertices, faces) -> np.ndarray:
    """(m, 3) float: the centre of each face, the numbers of trimesh's ``triangles_center``
    (``triangles.mean(axis=1)``: the corners added in order, then divided by 3) without
    its (m, 3, 3) copy of the triangles and its cache's hashing (half a second at 10^6 faces).

    >>> face_centres(np.array([[0.0, 0, 0], [3, 0, 0], [0, 3, 0]]), np.array([[0, 1, 2]]))
    array([[1., 1., 0.]])
    """
    v, f = np.asarray(vertices, dtype=np.float64), np.asarray(faces)
    return (v[f[:, 0]] + v[f[:, 1]] + v[f[:, 2]]) / 3.0


def compile_kernels() -> None:
    """Compile (or load from numba's cache) the kernels of a round (:func:`_long_edges`,
    :func:`_made`) with the one signature :func:`subdivide_to_size` calls them with, on a
    triangle: the first run of a machine does
    this beside the sensing (:mod:`recon3d.sensing.pool`), so the coloured ground truth after
    the sensing finds it in the cache.

    >>> compile_kernels()
    """
    subdivide_to_size(np.array([[0.0, 0, 0], [2, 0, 0], [0, 2, 0]]), np.array([[0, 1, 2]]), 1.0)
