"""The paper's regions and signs, computed from the planner's own records.

Everything here is built from contact points and probe postures the planner
has sensed -- never from the contour.

* sgn(x, y) -- eq. (1): sign of the 2D vector product x (x) y.
* V_i -- Definition 3: half plane with sgn{(a_i - q), (b_i - q)} > 0, i.e.
  the side on the right when moving from B_i to A_i (the free side).
* G_i -- Definition 1: region bounded by A_i, B_i and the joints of the two
  probe postures that found them (one polygon, or two triangles when the
  postures cross, Fig. 5(c)/(d)).
* T_i -- Definition 4: semi-infinite region between the rays P_iA_i, P_iB_i.
* K1, K2 -- Definition 6: v.t* < 0 and sgn(v, t*) < 0.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from shapely.geometry import Point, Polygon

from core2d.planar import magnitude

__all__ = [
    "cross", "sgn", "in_V", "Posture", "G_region", "T_contains", "left_normal",
    "trace_direction", "common_point", "polygonal", "V_polygon", "contains", "near_probe",
]


def cross(x, y) -> np.ndarray:
    """2D vector product x (x) y (z component), vectorised over leading axes."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    return x[..., 0] * y[..., 1] - x[..., 1] * y[..., 0]


def sgn(x, y) -> float:
    """Eq. (1): sgn(x, y) = (x (x) y) / ||x (x) y|| (0 when parallel)."""
    return float(np.sign(cross(x, y)))


def in_V(q, a, b) -> np.ndarray:
    """Definition 3: q in V_i  <=>  sgn{(a_i - q), (b_i - q)} > 0.

    q : (..., 2) float. Returns bool array.
    """
    q = np.asarray(q, float)
    return cross(np.asarray(a) - q, np.asarray(b) - q) > 0


def left_normal(t) -> np.ndarray:
    """t rotated by +90 degrees (counter-clockwise)."""
    return np.array([-t[1], t[0]])


@dataclass(frozen=True)
class Posture:
    """A probe posture: joint position P and unit direction t."""

    joint: np.ndarray
    direction: np.ndarray


def G_region(a, b, pose_a: Posture, pose_b: Posture):
    """Definition 1: G_i from two postures as a shapely (Multi)Polygon.

    The ring joint_a -> A -> B -> joint_b is made valid, so crossing postures
    give the two triangles of Fig. 5(c)/(d). Area(G_i) = ``G.area``.
    """
    ring = [pose_a.joint, a, b, pose_b.joint]
    return polygonal(shapely.make_valid(Polygon(ring)))


def polygonal(geom):
    """The polygonal part of a shapely result (drops stray lines / points)."""
    parts = [g for g in getattr(geom, "geoms", [geom])
             if g.geom_type in ("Polygon", "MultiPolygon") and not g.is_empty]
    return shapely.union_all(parts) if parts else Polygon()


def common_point(a, b, pose_a: Posture, pose_b: Posture):
    """Common point of the two triangles when postures joint_a-A and
    joint_b-B cross (Fig. 5(c)), else None."""
    p, r = np.asarray(pose_a.joint), np.asarray(a) - pose_a.joint
    q, s = np.asarray(pose_b.joint), np.asarray(b) - pose_b.joint
    den = cross(r, s)
    if abs(den) < 1e-12:
        return None
    u = cross(q - p, s) / den
    w = cross(q - p, r) / den
    if 0 < u < 1 and 0 < w < 1:
        return p + u * r
    return None


def V_polygon(a, b, size):
    """V_i clipped to a square of half-width ``size`` as a shapely Polygon."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    d = (b - a) / max(np.linalg.norm(b - a), 1e-300)
    n = left_normal(d)  # Def. 3: V_i lies on this side of A->B
    far = 4 * size
    return Polygon([a - far * d, b + far * d, b + far * d + far * n, a - far * d + far * n])


def T_contains(joint, a, b, q) -> bool:
    """Definition 4: is q in T_i, the wedge at ``joint`` spanned by A_i, B_i."""
    ja, jb, jq = np.asarray(a) - joint, np.asarray(b) - joint, np.asarray(q) - joint
    s = cross(ja, jb)
    if s == 0:
        return False
    return bool(np.sign(cross(ja, jq)) == np.sign(s) and np.sign(cross(jq, jb)) == np.sign(s))


def trace_direction(t_star, toward_B: bool):
    """Theorem 4: joint direction v and torque sign tau for one tracing side.

    toward_B -> v in K1 cap K2 (sgn(v, t*) < 0, P_fin = B_i, Def. 8);
    otherwise v in K1 cap not-K2 (P_fin = A_i). v bisects the quadrant, and
    tau = tau0 sgn(v, t*) with clockwise positive (eq. 2).

    Returns ``(v (2,), tau)``.
    """
    t = np.asarray(t_star, float)
    n = left_normal(t)
    v = (-t + (n if toward_B else -n)) / np.sqrt(2.0)
    return v, int(sgn(v, t))


def contains(geom, q) -> bool:
    """Point-in-region test tolerant to boundary points."""
    return bool(geom.buffer(1e-9).contains(Point(float(q[0]), float(q[1]))))


def near_probe(point, joint, direction, length, tol) -> bool:
    """Is ``point`` within ``tol`` of the probe segment joint -> joint + L t?"""
    w = np.asarray(point, float) - joint
    s = float(np.clip(w @ direction, 0.0, length))
    return magnitude(w - s * np.asarray(direction)) <= tol
