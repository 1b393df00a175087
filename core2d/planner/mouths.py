"""Mouths whose width a fine noisy sensor cannot tell from eps.

§3.1 makes an area W2 when Dist(A_i, B_i) < eps: the chord A_iB_i then stays
within eps/2 of C_{A_i}^{B_i}, and the flow does not enter it. A_i and B_i
are readings; with a noisy sensor two readings of a point lie up to the
jitter apart (:attr:`~core2d.resolution.Resolution.jitter`), so the planner
closes every area that *reads* shorter than eps + jitter as W2
(:attr:`~core2d.resolution.Resolution.w2_dist`), and its map joins recorded
pieces across gaps that short: a gap narrower than eps may read that much
wider.

That closed real openings too. A slit 1.26 eps wide between the thin outer
wall of ``trimesh_octagonal_pocket`` and its body, ~117 eps long and open at
both ends, reads 0.96 - 1.40 eps across its mouths at sigma 0.1 eps
(w2_dist 1.42 eps): each mouth was W2 at once or "traced through other
areas" -- the map's chain from A_i to B_i hopped the mouth itself -- and the
slit's walls were never touched (reachable coverage within eps/2 + 2 sigma
0.68 on z1, noiseless 1.00). Two rules, only where two readings of a point
resolve eps/2 (:func:`~core2d.planner.grazing.resolves_half_eps`: sigma
<= 0.106 eps, or taxels alone; perfect sensing has no jitter and is
unchanged):

* **A mouth is processed** (:func:`is_mouth`): an area that the contact
  point's jump across an opening made -- Case 2-1 / 2-2 (§4.3.2) or a hop of
  the tip over a gap (``core2d.planner.tracing``) -- and that reads at least
  eps (the paper's own test, applied to the reading) but less than eps +
  jitter. The flow processes it like any area (Theorem 1's pass, the local
  search, the trace); at a dead end (``Exploration.defer``) it is closed
  W2 as before, never left to the revisit, since its reading does not show
  it wider than eps. Areas split off a lid along recorded contour (escape,
  revisit, one-sided, ...) stay W2 at once: processing those too lost
  coverage in the slots ~1 eps wide of the ``comb`` outlines (0.98 -> 0.91).
* **A chain that hops a mouth covers nothing** (:func:`covered`).
* **A mouth whose inside stays unknown is W2** (:func:`close_unresolved`):
  when the flow behind a processed mouth leaves an area unknown, the
  mouth is closed W2 at the end of the run, as at a dead end. A slit a
  little narrower than eps reads wider than eps often enough (the two ends
  are readings: at sigma 0.1 eps a mouth 0.87 eps wide read 1.06 on the
  ``comb`` outline seed 0) to be entered; the rod fits, but with a wall
  the jitter cannot tell from the other, the children close W2 along one
  wall and leave the rest unknown, and the contour behind the mouth --
  which the noiseless flow approximates by the mouth's W2 -- was covered
  by nothing.
"""
from __future__ import annotations

import numpy as np

from core2d.planner.grazing import resolves_half_eps
from core2d.resolution import Resolution

__all__ = ["JUMPS", "is_mouth", "covered", "traced_gaps", "end_chords", "close_unresolved"]

JUMPS = ("case2-1", "case2-2", "hop")
"""Rules (:class:`~core2d.result.AreaRecord`) whose A_i and B_i are the two
sides of an opening that the contact point jumped or the tip hopped across."""


def is_mouth(res: Resolution, dist: float, rule: str) -> bool:
    """Whether an area of ``rule`` reading ``dist`` = Dist(A_i, B_i) is a
    mouth: made by a jump (:data:`JUMPS`), eps <= dist < eps + jitter, under a
    sensor whose readings resolve eps/2.

    Examples
    --------
    >>> from core2d.resolution import Resolution
    >>> fine = Resolution.of(1.0, noise=0.1)  # jitter 0.424
    >>> [is_mouth(fine, d, "case2-1") for d in (0.9, 1.2, 1.5)]
    [False, True, False]
    >>> is_mouth(fine, 1.2, "escape"), is_mouth(Resolution.of(1.0), 1.0, "hop")
    (False, False)
    """
    return (rule in JUMPS and resolves_half_eps(res)
            and res.eps <= dist < res.w2_dist)


def covered(known, a, b, tol: float, res: Resolution) -> bool:
    """C_{A_i}^{B_i} traced through other areas: a chain of recorded pieces
    leads from A_i to B_i (:meth:`~core2d.planner.known.KnownContour.covers`)
    and, under a sensor whose readings resolve eps/2, every hop between two
    of its pieces is narrower than eps (:func:`traced_gaps`).

    known : KnownContour
    a, b : (2,) float -- A_i and B_i.
    tol : float -- how near A_i and B_i the chain must start and end.
    res : Resolution -- the sensor's stated resolution.
    """
    return traced_gaps(known, a, b, tol, res) is not None


def traced_gaps(known, a, b, tol: float, res: Resolution) -> list[np.ndarray] | None:
    """The W2 chords that join A_i and B_i to the chain of recorded pieces over
    C_{A_i}^{B_i}, traced through other areas; None when it is not (:func:`covered`).

    The map joins recorded pieces across gaps narrower than the W2 distance eps +
    jitter, so a chain may hop an opening that reads between eps and eps +
    jitter -- the mouth of the very area asked about. Such a chain is no
    evidence that C_A^B was traced (§3.1 approximates only gaps narrower
    than eps). With perfect sensing the map joins only gaps narrower than
    eps and this is ``covers``; a coarse sensor (sigma 0.3 eps) keeps
    ``covers``, whose readings cannot tell eps from 2.5 eps.

    The chain starts and ends within ``tol`` of A_i and B_i: the same-contact
    radius, eps/2 with perfect sensing, 2 eps at sigma 0.3 eps with taxels 0.25 eps.
    A_i and B_i are readings of their own, often in no recorded piece, so the
    contour between them and the recorded contour is in no piece either. An end
    no farther than eps from the recorded contour needs nothing (each point of
    the gap lies within eps/2 of A_i or of the contour, §3.1's bound); a farther
    one is joined to the nearest recorded point by a W2 chord (Dist < eps +
    jitter, §3.1 at the sensor's resolution), so that the result shows all of
    the contour the planner closes as known. With perfect sensing there is none.

    Returns
    -------
    list of (2, 2) float (at most two: from A_i, to B_i), or None.

    Examples
    --------
    >>> from core2d.planner.known import KnownContour
    >>> coarse = Resolution.of(1.0, noise=0.3, taxel=0.25)  # tip zone 2.02 eps
    >>> known = KnownContour(join=coarse.w2_dist)
    >>> known.add(np.array([[0.0, 0.0], [6.0, 0.0]]))
    >>> [g.tolist() for g in traced_gaps(known, (0.0, 0.4), (7.5, 0.0), 2.0, coarse)]
    [[[6.0, 0.0], [7.5, 0.0]]]
    >>> traced_gaps(known, (0.0, 0.4), (9.0, 0.0), 2.0, coarse) is None
    True
    """
    if resolves_half_eps(res):
        hop = known.widest_hop(a, b, tol)
        if hop is None or hop >= res.eps:
            return None
    elif not known.covers(a, b, tol):
        return None
    return end_chords(known, a, b, res)


def end_chords(known, a, b, res: Resolution) -> list[np.ndarray]:
    """W2 chords from A_i, and to B_i, from the nearest recorded point, for each end
    farther than eps from the recorded contour (:func:`traced_gaps`); an area closed
    as traced because its lid lies along recorded contour
    (:func:`~core2d.planner.revisit.on_recorded`,
    :func:`~core2d.planner.revisit.reversed_lid`) has the same ends.

    Returns
    -------
    list of (2, 2) float (at most two).
    """
    gaps = []
    for end, first in ((a, True), (b, False)):
        if known.distance(end) > res.eps:
            q = known.nearest_point(end)
            gaps.append(np.array([end, q] if first else [q, end], dtype=float))
    return gaps


def close_unresolved(run) -> int:
    """Close W2 every processed mouth of ``run`` (an
    :class:`~core2d.planner.run.Exploration`) that was split and has a
    descendant area that ended unknown; returns how many.

    The mouth read shorter than eps + jitter, the width the sensor cannot
    tell from eps (§3.1 at the sensor's resolution); the flow behind it
    resolved part of C_A^B and left the rest unknown. As at a dead end
    (``Exploration.defer``) the mouth's chord is written W2; the unknown
    areas behind it stay reported as they are."""
    records = run.result.areas
    kids: dict[int, list[int]] = {}
    for rec in records:
        kids.setdefault(rec.parent, []).append(rec.index)

    def unresolved(i) -> bool:
        todo = list(kids.get(i, ()))
        while todo:
            j = todo.pop()
            if records[j].outcome == "unknown":
                return True
            todo.extend(kids.get(j, ()))
        return False

    closed = 0
    for area in run.mouths:
        rec = records[area.index]
        if rec.outcome == "split" and unresolved(area.index):
            run.close(area, "W2", "split, but an area behind it stayed unknown; "
                                  "Dist(A,B) < eps + the sensor's jitter")
            closed += 1
    return closed
