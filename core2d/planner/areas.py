"""Unknown areas A_iB_i (§3.3) and the registration rule of §4.3.3."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from shapely.geometry.base import BaseGeometry

from core2d.planar import magnitude
from core2d.planner.regions import Posture
from core2d.planner.robot import Robot

__all__ = ["Area", "register", "pivot_G"]


@dataclass
class Area:
    """An unknown area A_iB_i with the postures that detected A_i and B_i.

    a, b : (2,) float -- A_i, B_i; C_{A_i}^{B_i} runs from A_i to B_i.
    pose_a, pose_b : Posture -- probe postures that touched A_i and B_i.
        ``pose_a is pose_b`` marks a single probe detection (Fig. 6).
    parent : int -- index of the area whose processing registered it.
    rule : str -- which rule created it (see AreaRecord).
    depth : int -- recursion depth.
    G, zero_G -- for a single probe detection, G_i is generated when the
        area is found by rotating the probe about its tip (Definition 1);
        ``zero_G`` records Area(G_i) = 0.
    escape : bool -- infinite loop escape requested (§4.4).
    lineage : tuple of ((2,) float, (2,) float) -- (A, B) of every ancestor,
        for the §4.4 test over the whole ancestry.
    stale : int -- generations in a row whose processing traced no new contour.
    tries : int -- passes through the lid that found nothing new (revisits).
    seen : tuple of (2,) float -- contacts at which revisit passes split
        this area's ancestors (never new twice).
    mouth : bool -- a jump's area reading between eps and eps + the sensor's
        jitter: processed, and W2 at a dead end (:mod:`core2d.planner.mouths`).
    """

    a: np.ndarray
    b: np.ndarray
    pose_a: Posture
    pose_b: Posture
    parent: int = -1
    rule: str = "bootstrap"
    depth: int = 0
    index: int = -1
    escape: bool = False
    G: BaseGeometry | None = None  # G_i made at detection time (single probe detection)
    zero_G: bool = False  # Area(G_i) = 0 verified at detection time
    lineage: tuple = ()
    stale: int = 0
    tries: int = 0
    seen: tuple = ()
    mouth: bool = False

    @property
    def dist(self) -> float:
        """Dist(A_i, B_i)."""
        return magnitude(self.b - self.a)

    @property
    def single(self) -> bool:
        return self.pose_a is self.pose_b


def register(p_first, pose_first, p_end, pose_end, fin_is_A: bool, parent, rule, depth):
    """Registration rule (§4.3.3, Fig. 14).

    (i) P_fin = A_i: (A_j, B_j) = (P_2nd or P_fin, P_1st);
    (ii) P_fin = B_i: (A_j, B_j) = (P_1st, P_2nd or P_fin).
    ``p_end`` is P_2nd or P_fin. The rule keeps the orientation of V_i.
    """
    if fin_is_A:
        return Area(np.asarray(p_end, float), np.asarray(p_first, float), pose_end,
                    pose_first, parent, rule, depth)
    return Area(np.asarray(p_first, float), np.asarray(p_end, float), pose_first,
                pose_end, parent, rule, depth)


def pivot_G(probe: Robot, body_face, max_angle=np.pi / 4):
    """Definition 1 / Fig. 6(a): rotate the probe about its tip, away from
    the body contact on ``body_face``, until it touches; return G_i (the
    swept triangle, shapely Polygon) or None when Area(G_i) = 0 (Fig. 6(b)).
    The probe is rotated back afterwards, so its posture is unchanged."""
    from shapely.geometry import Polygon

    tip, joint = probe.tip.copy(), probe.joint.copy()
    rot = -1 if body_face == "left" else 1
    r = probe.pivot(rot, max_angle)
    angle = r.angle
    if abs(angle) > 0:
        probe.pivot(-rot, abs(angle))  # back along the swept, free path
    if abs(angle) <= 4 * probe.resolution.angle_tol(probe.length):
        return None
    return Polygon([tip, joint, r.joint])
