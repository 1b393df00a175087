"""The run's budget: a run always ends.

Every motion loop of the planner asks the budget before it moves; the budget
counts the robot's motions (:attr:`~core2d.planner.robot.Robot.motions`) and
the areas A_iB_i registered, and remembers whether either ran out (reported
as ``budget_hit`` in :class:`~core2d.result.SenseStats`).
"""
from __future__ import annotations

from core2d.planner.robot import Robot

__all__ = ["Budget"]


class Budget:
    """Motion / area budget: a run always ends.

    >>> from types import SimpleNamespace
    >>> probe = SimpleNamespace(motions=0)
    >>> budget = Budget(probe, max_motions=2)
    >>> budget(), budget.hit
    (True, False)
    >>> probe.motions = 2
    >>> budget(), budget.hit
    (False, True)
    """

    def __init__(self, probe: Robot, max_motions: int = 20000, max_areas: int = 4000):
        self.probe, self.max_motions, self.max_areas = probe, max_motions, max_areas
        self.areas = 0
        self.hit = False

    def __call__(self) -> bool:
        ok = self.probe.motions < self.max_motions and self.areas < self.max_areas
        self.hit |= not ok
        return ok
