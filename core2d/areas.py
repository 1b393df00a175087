"""Unknown areas A_iB_i (§3.3) and the registration rule of §4.3.3."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from core2d.regions import Posture

__all__ = ["Area", "register"]


@dataclass
class Area:
    """An unknown area A_iB_i with the postures that detected A_i and B_i.

    a, b : (2,) float -- A_i, B_i; C_{A_i}^{B_i} runs from A_i to B_i.
    pose_a, pose_b : Posture -- probe postures that touched A_i and B_i.
        ``pose_a is pose_b`` marks a single probe detection (Fig. 6).
    parent : int -- index of the area whose processing registered it.
    rule : str -- which rule created it (see AreaRecord).
    depth : int -- recursion depth.
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
    notes: list = field(default_factory=list)

    @property
    def dist(self) -> float:
        """Dist(A_i, B_i)."""
        return float(np.linalg.norm(self.b - self.a))

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
