"""Sense one closed slice: the simulator and the planner put together.

This is the only module that sees both rooms of core2d: it builds the
simulated probe (:mod:`core2d.sim`, which owns the geometry) and hands it to
the planner (:mod:`core2d.planner.run`, which sees sensor readings only) -- with the
default flow or the paper's Fig. 16 alone (:mod:`core2d.planner.flow`) --
or, with ``method="finger"``, to the dense finger-probing baseline
(:mod:`core2d.planner.finger`), or, with ``method="follow"``, to the pushing
contour follower the paper argues against (:mod:`core2d.planner.follow`). A :class:`~core2d.sim.recorder.Recorder`
between the two logs every motion (``result.motions``).
"""
from __future__ import annotations

from core2d.planner.finger import finger_probe
from core2d.planner.flow import FLOWS, Flow
from core2d.planner.follow import follow_contour
from core2d.planner.run import explore
from core2d.result import SliceResult
from core2d.sim.contact import ContactModel
from core2d.sim.probe import Probe
from core2d.sim.recorder import Recorder
from core2d.sim.sensor import SensorModel

__all__ = ["sense_slice", "METHODS"]

METHODS = ("pulling", "paper", "follow", "finger")


def sense_slice(contact: ContactModel, workspace, eps: float, probe_length: float | None = None,
                tol: float | None = None, max_motions: int = 20000, max_areas: int = 4000,
                bootstrap_count: int = 12, method: str = "pulling", directions: int = 32,
                spacing: float | None = None, sensor: SensorModel | None = None,
                friction: float = 0.0, flow: Flow | None = None) -> SliceResult:
    """Run the pulling-motion algorithm (or finger probing) on one closed slice.

    Parameters
    ----------
    contact : ContactModel -- the slice's ray-cast backend.
    workspace : ((2,) float, float) -- centre and radius of a circle that
        contains the slice (all the robot knows beforehand).
    eps : float -- the paper's epsilon (W2 threshold, smoothness scale).
    probe_length : float, optional -- default 2 x workspace diameter.
    tol : float, optional -- contact resolution, default eps / 20
        (:class:`core2d.resolution.Resolution` derives every tolerance from both).
    max_motions, max_areas : int -- budgets; when hit, the areas still
        unknown are reported in ``result.unknown`` and ``stats.budget_hit``.
    method : {'pulling', 'paper', 'follow', 'finger'} -- the paper's algorithm
        with the planner's additions, the paper's Fig. 16 flow alone
        (:data:`core2d.planner.flow.PAPER`), a contour follower from the
        first contact (:func:`core2d.planner.follow.follow_contour`), or
        straight insertions on a grid (:func:`core2d.planner.finger.finger_probe`).
    directions, spacing : finger probing only -- insertion directions and
        line spacing (default eps / 2).
    sensor : SensorModel, optional -- noise and taxels of the readings
        (:mod:`core2d.sim.sensor`); default the paper's perfect sensing.
    friction : float -- Coulomb mu at the tip (:mod:`core2d.sim.friction`;
        default 0, frictionless). The planner is not told it.
    flow : Flow, optional -- the planner's additions switched one by one
        (:mod:`core2d.planner.flow`, ``bench.ablation``); overrides the flow
        that ``method`` names.

    Returns
    -------
    SliceResult in the slice's 2D frame.
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    probe = Recorder(Probe(contact, workspace, eps, probe_length, tol, sensor, friction))
    if method == "finger":
        result = finger_probe(probe, eps, directions, spacing, max_motions)
    elif method == "follow":
        result = follow_contour(probe, eps, max_motions)
    else:
        result = explore(probe, eps, max_motions, max_areas, bootstrap_count,
                         flow or FLOWS[method])
    result.motions = probe.log()
    return result
