"""Which contacts of a revisit pass can split A_iB_i.

A revisit pass (:mod:`core2d.planner.revisit`, step 3; it plays Theorem 1's
pass through L_{A0}^{B0} cap G_i cap V_i) is inserted from F across the lid
A_iB_i. A new contact C splits the area into (A_i, C) and (C, B_i): the
paper's flow takes C to lie on C_A^B. But the record has gaps -- walls not yet
explored, and with a noisy sensor the gaps a noisy trace leaves -- and a pass can
stop on another wall the probe reaches from F through such a gap, in front of
the lid. Splitting there lays the children's lids across material. Two tests
keep such contacts out, or hold them back:

* :func:`in_reach`, with a noisy sensor: the contact is behind the lid (the
  probe's segment from the joint to it crosses A_iB_i), or within
  Dist(A_i, B_i) / 2 of the lid.
* :func:`splits_across_record`, with perfect sensing and for a sensor that does not
  resolve eps/2 (:func:`~core2d.planner.grazing.resolves_half_eps` false; sigma 0.3 eps
  with taxels 0.25 eps): a contact in front of the lid does not split it
  when a child's lid A_iC or CB_i would cross recorded contour farther than
  ``near`` (2 tol + jitter) from its ends. A lid spans free space that the
  probe came through, and a recorded wall has material on one side, so such a
  chord does not close any part of C_A^B. C is a wall met in F. The revisit
  *holds* such a contact: the lid's passes go on, at most a spread's worth
  more (:data:`~core2d.planner.pass_plan.MAX_TRIES`), and the first new
  contact they meet that this test lets through splits the lid. When none
  does, the held contact splits it after all, as it did before the test.

Examples
--------
>>> from types import SimpleNamespace
>>> import numpy as np
>>> area = SimpleNamespace(a=np.array([0.0, 0.0]), b=np.array([10.0, 0.0]), dist=10.0)
>>> bool(in_reach(area, np.array([5.0, 20.0]), np.array([5.0, -3.0])))  # behind the lid
True
>>> bool(in_reach(area, np.array([5.0, 20.0]), np.array([5.0, 12.0])))  # in front, far
False
"""
from __future__ import annotations

import numpy as np

from core2d.planner.grazing import crosses_lid, resolves_half_eps
from core2d.planner.known import KnownContour
from core2d.resolution import Resolution

__all__ = ["in_reach", "splits_across_record"]


def in_reach(area, joint, point) -> bool:
    """Can a pass's contact ``point`` lie on C_A^B? Either the probe reached
    it through the lid (its segment from the joint to the contact crosses
    A_iB_i: the contact is behind the lid, where Theorem 1's pass looks), or
    it lies within Dist(A_i, B_i) / 2 of the lid. A contact the probe met in
    front of the lid, farther from it than half its length, is contour the
    probe reached from F without the lid -- a stretch of another wall the
    record has a gap in (a noisy trace leaves such gaps) -- and splitting
    A_iB_i there would lay the children's lids across material (measured
    on the ``star`` outline of ``tests/outlines.py``, seed 0, noise 0.3,
    taxel 0.25 eps: 301 instead of 448 eps of reported lids deeper than eps
    inside material over seeds 0-2). With perfect sensing the record has no
    noise gaps and the contacts in front of a lid mostly graze it (within 0.1
    Dist(A_i, B_i) on the middle slices of 9 built-in scenes; one met on an
    unexplored wall farther in front is held by :func:`splits_across_record`);
    this test is applied with a noisy sensor only.

    area : Area-like with ``a``, ``b`` (2,) float and ``dist``.
    joint, point : (2,) float -- the probe's joint and its contact.
    """
    a, b = np.asarray(area.a, float), np.asarray(area.b, float)
    p, q = np.asarray(joint, float), np.asarray(point, float)
    if crosses_lid(a, b, p, q):
        return True
    ab = b - a
    u = float(np.clip((q - a) @ ab / max(float(ab @ ab), 1e-300), 0.0, 1.0))
    return float(np.hypot(*(q - a - u * ab))) <= area.dist / 2


def splits_across_record(res: Resolution, known: KnownContour, area, joint, point) -> bool:
    """Would splitting A_iB_i at a pass's contact ``point``, met in front of
    the lid, lay a child's lid across recorded contour?

    True when the sensor is perfect or does not resolve eps/2, the probe's segment
    from ``joint`` to ``point`` does not cross the lid, and the chord A_iC or CB_i
    crosses a recorded segment farther than ``near`` (2 tol + jitter) from both
    of its ends. Within ``near`` of an end the crossing is that end's own
    wall: A_i and B_i are readings scattered by the jitter about the pieces
    recorded at them.

    Why: in :func:`in_reach` a contact up to Dist(A_i, B_i) / 2 in front of
    the lid counts, and on a long lid that is far. In ``undercut-1`` of
    ``tests/outlines.py`` (sigma 0.3 eps, taxels 0.25 eps) a lid 45 eps long
    ran from a chamber's floor up a 3-eps neck. A pass stopped on the wall of
    the *other* neck, 17 eps in front of it. Split there, the children's lids
    crossed both traced neck walls, the revisit spent its passes on them, and
    the neck's far wall (22 eps) was never touched. Held, the next passes
    reach it: over six keyed sensor seeds the case's coverage within
    eps/2 + 2 sigma went 0.969 -> 0.981.

    Why the held contact still splits when nothing else is found: refusing
    it outright (measured before the hold) left long lids between separate
    objects (``twin_posts``' posts) unsplit and unknown, and an unknown chord
    closes a slice's region across free space (F@1 % 0.997 -> 0.937 on
    ``twin_posts``); the children of such a split cross a post, which costs
    the surface nothing. Why a spread's worth of passes: 58 % of the splits
    found after a hold came within 4 passes, 82 % within 8, and the sensor
    study's coverage was the same with 4, 6 or 8; every pass more cost motions
    (``numerics-1``, keyed seed 2001: 944 against 982 motions, its noiseless
    run 481).

    Why with perfect sensing too: the record has no noise gaps then, but walls not
    yet explored are gaps all the same. On the ``comb`` scene (every z-slice of 8) a
    deferred lid ran down a slot 0.89 eps wide and 84 eps deep, from its floor to the
    far corner of its mouth, the slot's unexplored right wall behind it; its first
    pass came in steeply through the mouth of another slot, 21 eps to the left, and
    stopped on that slot's unexplored wall. Split there, both children's lids crossed
    the teeth between, their passes went elsewhere, and the right wall (84 eps) was
    covered by nothing: 0.875 - 0.876 of the reachable contour noiselessly. Held, the
    next passes come down the slot and reach it: 0.915 - 0.916 on all eight slices
    (motions -3 to +15 %; the slot narrower than eps/2 that the trace stepped over kept
    the rest, since closed by a W2 chord: :func:`core2d.sim.compliance.overhangs`).
    Elsewhere, noiselessly: 110 of the 120 slices of the 15 built-in scenes and 58 of 64
    of the eight real meshes in ``../shared/meshes`` the same (the others the same
    coverage, motions -2.3 to +1.1 %); 132 of 144 outlines of ``tests/outlines.py``
    (seeds 0 - 23) the same, coverage up on three (``undercut-20``
    0.9954 -> 0.9992, ``undercut-15`` 0.9982 -> 1.0, ``comb-10`` 0.9964 -> 0.9974),
    down on one (``islands-8`` 0.9995 -> 0.9990, 8 % more motions).

    For a fine sensor the rule cost more than it gained (sigma 0.1: 97 -> 96
    of 105 case runs at coverage >= 0.99, three sensor seeds, refusing
    outright), so it does not act there.

    res : the sensor's :class:`~core2d.resolution.Resolution`.
    known : the robot's map.
    area : Area-like with ``a``, ``b`` (2,) float.
    joint, point : (2,) float -- the probe's joint and its contact C.
    """
    if resolves_half_eps(res):  # a fine sensor: the hold cost more than it gained
        return False
    a, b = np.asarray(area.a, float), np.asarray(area.b, float)
    q = np.asarray(point, float)
    if crosses_lid(a, b, joint, q):
        return False
    return known.crosses(a, q, res.near) or known.crosses(q, b, res.near)
