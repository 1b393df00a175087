"""Which flow the planner runs: the paper's Fig. 16 alone, or with the additions.

The paper's steps -- bootstrap from F, Dist(A_i, B_i) < eps -> W2, single
probe detection (Fig. 6), Theorem 1's initial pass, the bisection of §4.2.2,
the tracing of §4.3 with the registration rule of §4.3.3, the infinite loop
escape of §4.4 -- are the same code in both methods. The default
(``pulling``) adds machinery the paper does not have, each behind one switch
of :class:`Flow`:

* ``map`` -- the robot's own map of what it recorded
  (:class:`~core2d.planner.known.KnownContour`): a pass touching recorded
  contour is a dead end;
* ``covers`` -- with the map, an area whose C_A^B was traced through other
  areas is closed as traced (:meth:`KnownContour.covers`);
* ``escape`` -- §4.4's escape asked for over the whole ancestry: a new area
  repeating the A and B of *any* ancestor, or the third generation in a row
  that traced no new contour. Off, the escape is asked for as §4.4 words
  it: the area repeats its parent's A and B (the same contact points found
  again), or the bisection fails;
* ``defer`` -- a dead end (no pass, a pass finding no new contact) is
  deferred instead of becoming W3 on the spot as §4.2.1 says;
* ``w3_proof`` -- Area(G_i) = 0 gives W3 only when the map proves that no
  line from F crosses the lid;
* ``revisit`` -- deferred areas are looked at again
  (:mod:`core2d.planner.revisit`);
* ``audit`` -- contour no area holds any more is registered again
  (:mod:`core2d.planner.audit`).

``paper`` switches all of them off: Fig. 16 only (with §4.4's escape as worded).

Four of the paper's own decisions can be changed too, for the tests and
``bench.ablation`` that ask what each decides (never by a user):
``detection`` -- single probe detection (Fig. 6) generates G_i of an area
whose A_i and B_i lie on one posture; ``pair`` -- Case 2-1 registers
(P_1st, P_2nd) (§4.3.3); ``lifo`` -- areas processed last registered
first instead of breadth first; ``same`` -- the same-contact radius of the
Theorem 1 dead end and of §4.4 in units of eps/2
(:attr:`~core2d.resolution.Resolution.tip_zone`) -- the one of the paper's
resolution is eps/2 (``same = 1``). ``tests/test_paper_decisions.py`` shows
on whole slices which of them decide the paper's flow.

Why a configuration of one planner and not a second driver: the paper's steps are the bulk of the
planner (:class:`core2d.planner.run.Exploration`), and a second copy of them
would drift; the additions are a handful of branches, and naming each
behind a switch keeps the paper's flow readable in ``Exploration.process``
and lets the tests prove each switch unreachable with ``paper``.
"""
from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Flow", "PULLING", "PAPER", "FLOWS"]


@dataclass(frozen=True)
class Flow:
    """The planner's additions to Fig. 16, each on (True) or off; and four
    of the paper's decisions (``detection``, ``pair``, ``lifo``, ``same``)."""

    map: bool = True
    covers: bool = True
    escape: bool = True
    defer: bool = True
    w3_proof: bool = True
    revisit: bool = True
    audit: bool = True
    detection: bool = True
    pair: bool = True
    lifo: bool = False
    same: float = 1.0

    def __post_init__(self):
        if (self.covers or self.w3_proof or self.revisit or self.audit) and not self.map:
            raise ValueError("covers, w3_proof, revisit and audit need the map")


PULLING = Flow()
"""The default: Fig. 16 with every addition."""

PAPER = Flow(map=False, covers=False, escape=False, defer=False, w3_proof=False,
             revisit=False, audit=False)
"""The paper's Fig. 16 alone: dead ends and Area(G_i) = 0 are W3 (§4.2.1)."""

FLOWS = {"pulling": PULLING, "paper": PAPER}
"""Method name -> flow."""
