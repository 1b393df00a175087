"""The ground truth subdivided until every edge is short (the coloured ground truth).

:func:`subdivide_to_size` gives ``trimesh.remesh.subdivide_to_size``'s vertices and
faces, the same arrays in the same order, while looking at fewer faces per round: a face
whose three edges are short is final (its edges never change), and every round of trimesh
looks again at all of them (its edge sort and unique over every face: most of its time on
a ground truth of 10^5 - 10^6 faces). Here a round looks only at the faces made in the
round before.

Why the arrays are the same: a round's faces are, in order, those already final and those
just made, so keeping the final ones aside and appending each round's final ones keeps
trimesh's order; a long edge lies only on faces with a long edge (the ones looked at), and
the midpoint of each long edge gets the next vertex number in the order of
``trimesh.grouping.unique_rows`` (a fixed key per edge: the order of the long edges among
themselves does not depend on the short edges present), computed with the same numpy
expressions (tested ``==`` against trimesh).
"""
from __future__ import annotations

import numpy as np
from trimesh import grouping
from trimesh.geometry import faces_to_edges

__all__ = ["subdivide_to_size"]


def _split(faces: np.ndarray, face_mid: np.ndarray, vertices: np.ndarray) -> np.ndarray:
    """(k, 3) int64: the faces made from ``faces`` (n, 3) with 1, 2 or 3 long edges, their
    midpoints ``face_mid`` (n, 3) (-1: a short edge) -- trimesh's three templates, in its
    order (one long edge, two, three)."""
    split = face_mid >= 0
    count = split.sum(axis=1)
    one = count == 1
    j = np.argmax(split[one], axis=1)
    r = np.arange(len(j))
    f1, mid1 = faces[one], face_mid[one]
    a, b, c = f1[r, j], f1[r, (j + 1) % 3], f1[r, (j + 2) % 3]
    p = mid1[r, j]
    faces_one = np.column_stack((a, p, c, p, b, c)).reshape((-1, 3))
    two = count == 2
    j = (np.argmin(split[two], axis=1) + 1) % 3
    r = np.arange(len(j))
    f2, mid2 = faces[two], face_mid[two]
    a, b, c = f2[r, j], f2[r, (j + 1) % 3], f2[r, (j + 2) % 3]
    p, q = mid2[r, j], mid2[r, (j + 1) % 3]
    use_aq = (((vertices[a, :3] - vertices[q, :3]) ** 2).sum(axis=1)
              <= ((vertices[p, :3] - vertices[c, :3]) ** 2).sum(axis=1))[:, None]
    corner = np.column_stack((p, b, q))
    quad_a = np.where(use_aq, np.column_stack((a, p, q)), np.column_stack((a, p, c)))
    quad_b = np.where(use_aq, np.column_stack((a, q, c)), np.column_stack((p, q, c)))
    faces_two = np.vstack((corner, quad_a, quad_b))
    three = count == 3
    f3, mid3 = faces[three], face_mid[three]
    v0, v1, v2 = f3.T
    m0, m1, m2 = mid3.T
    faces_three = np.column_stack((v0, m0, m2, m0, v1, m1, m2, m1, v2, m0, m1, m2)
                                  ).reshape((-1, 3))
    return np.vstack((faces_one, faces_two, faces_three)).astype(np.int64)


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
    """
    vertices = np.array(vertices, dtype=np.float64, copy=True)
    active = np.array(faces, dtype=np.int64, copy=True).reshape(-1, 3)
    final = []
    for i in range(max_iter + 1):
        edges = np.sort(faces_to_edges(active), axis=1)
        lengths = ((vertices[edges[:, 0], :3] - vertices[edges[:, 1], :3]) ** 2
                   ).sum(axis=1) ** 0.5
        long_edge = lengths > max_edge
        count = long_edge.reshape(-1, 3).sum(axis=1)
        final.append(active[count == 0])
        if not long_edge.any():
            break
        if i >= max_iter:
            raise ValueError("max_iter exceeded!")
        unique, inverse = grouping.unique_rows(edges[long_edge])
        ends = edges[long_edge][unique]
        face_mid = np.full(len(edges), -1, dtype=np.int64)
        face_mid[long_edge] = np.asarray(inverse).reshape(-1) + len(vertices)
        vertices = np.vstack((vertices, vertices[ends].mean(axis=1)))
        active = _split(active, face_mid.reshape((-1, 3)), vertices)
    return vertices, np.vstack(final).astype(np.int64)
