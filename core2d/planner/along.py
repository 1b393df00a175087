"""A lid that lies along contour the robot has recorded (noisy sensor): closed as traced.

Step 1 of the revisit (:mod:`core2d.planner.revisit`) closes an area whose C_A^B the map
already holds. With a noisy sensor two more shapes mean the same, and both are closed as
traced before any pass is made (notes :data:`~core2d.planner.mouths.ALONG_RECORD`):

* :func:`on_recorded` -- the whole lid lies on recorded contour that runs from A_i towards
  B_i: two readings of one wall made a lid along it.
* :func:`reversed_lid` -- the lid lies along a chain of pieces recorded from B_i to A_i: a
  traced wall read backwards (a split at a contact on the far wall of a slit).

The map's pieces run in the contour's direction (Definition 3: material on their right;
:mod:`core2d.planner.tracing` reverses a trace made towards A_i), so C_A^B runs from A_i
to B_i. Contour recorded the other way along the lid belongs to C_B^A: in a slit narrower
than the radius, a wall beside a lid laid inside it, with C_A^B, the rest of the slit, behind
the lid (``comb-20`` at sigma 0.3 + T 0.25, sensor seeds 20 and 1020: lids from one wall of a
slot 0.72 eps wide, 2.3 eps deep, to the far corner of its mouth, and from a corner of one
0.51 eps wide to its far wall 2.8 - 4.6 eps deep; the slots are 16 - 21 eps deep). That is
:func:`reversed_lid`'s case when the chain from B_i to A_i lies along the lid, and the
passes' when it does not; :func:`on_recorded` counts only the record that runs along the lid.
"""
from __future__ import annotations

import numpy as np
import shapely

from core2d.planner.grazing import resolves_half_eps
from core2d.planner.short_lids import on_map
from core2d.planner.thin_walls import behind_recorded

__all__ = ["on_recorded", "reversed_lid"]

# ``run`` below: the planner's state (core2d.planner.run.Exploration; its ``res`` and ``known``)


def on_recorded(run, area) -> bool:
    """With a noisy sensor: does the whole lid lie within
    :attr:`~core2d.resolution.Resolution.near` (2 tol + the jitter) of
    recorded contour running from A_i towards B_i? Its ends are readings
    that scatter by the jitter, so two readings of one wall can make a lid
    along that wall (or a hair inside it) whose C_A^B the robot has recorded
    but whose pieces do not chain
    (:meth:`~core2d.planner.known.KnownContour.covers`): nothing hides
    behind it, and the W3 proof (no free line crosses it past the noisy
    record) would make W3 of a traced wall. A lid sample counts when a
    recorded segment within that distance has a positive component along
    B_i - A_i (:meth:`~core2d.planner.known.KnownContour.runs_along`):
    contour recorded only the other way belongs to C_B^A (module doc).
    Only while the sensor resolves eps/2
    (:func:`~core2d.planner.grazing.resolves_half_eps`): a coarser one keeps
    the distance alone, the test its path was measured with (at sigma 1 eps,
    one read, the direction moved ``comb`` z4 0.997 -> 0.821 and
    ``twin_posts`` z4 from 1.12 to 2.15 x its noiseless motions, one run
    each). A short lid's middle band must lie on the map too
    (:func:`~core2d.planner.short_lids.on_map`). Perfect sensing (jitter 0)
    leaves the paper's flow as it is.

    Examples
    --------
    A lid 0.3 eps beside a wall traced from A's end towards B's (sigma 0.3 eps read 16
    times, taxel 0.25 eps) lies on it; the same lid from B to A runs against the record:

    >>> from types import SimpleNamespace
    >>> from core2d.planner.known import KnownContour
    >>> from core2d.resolution import Resolution
    >>> known = KnownContour(0.1)
    >>> known.add(np.array([[x, 0.0] for x in np.arange(0.0, 4.1, 0.25)]))
    >>> run = SimpleNamespace(res=Resolution.of(1.0, noise=0.075, taxel=0.25), known=known)
    >>> lid = lambda a, b: SimpleNamespace(a=np.array(a), b=np.array(b), dist=3.0)
    >>> on_recorded(run, lid([0.5, 0.3], [3.5, 0.3])), on_recorded(run, lid([3.5, 0.3], [0.5, 0.3]))
    (True, False)
    """
    if run.res.jitter == 0:
        return False
    k = int(np.ceil(area.dist / run.res.fan_spacing)) + 1
    pts = area.a + np.linspace(0.0, 1.0, k)[:, None] * (area.b - area.a)
    near = on_map(run.res, area.dist)  # a short lid: its middle band is off the map
    if not resolves_half_eps(run.res):  # a coarse sensor: the test it was measured with
        return all(run.known.distance(p) <= near for p in pts)
    along = area.b - area.a
    return all(run.known.runs_along(p, near, along) for p in pts)


def reversed_lid(run, area) -> bool:
    """Does the lid A_iB_i lie on contour the robot recorded from B_i to A_i?

    A split at a contact on the far wall of a slit (Case 2-2, P_1st on the
    wall facing the one traced) can make a child whose lid runs along a
    traced wall, read backwards: the chain of pieces leads from B_i to A_i
    within eps/2 of the lid (Hausdorff distance), and none from A_i to B_i.
    Its C_A^B (from A_i along the pieces) is then the rest of the loop, which
    the other areas hold; nothing lies behind the lid itself (G_i between the
    lid and the wall is narrower than eps/2, §3.1), so no pass can find
    anything and the area would only report an unknown chord over traced
    contour. It is closed as traced -- unless, with a noisy sensor, the lid's
    middle lies on the chain's material side deeper than the jitter: the lid
    then runs along the back of a wall thinner than the radius, contour of its
    own (:mod:`core2d.planner.thin_walls`)."""
    chain = run.known.chain(area.b, area.a, run.res.tip_zone)
    if chain is None or len(chain) < 2 or behind_recorded(
            run.known, run.res, (area.a + area.b) / 2, run.res.tip_zone):
        return False  # (the lid along the back of a thin wall: core2d.planner.thin_walls)
    lid = shapely.linestrings(np.stack([area.a, area.b]))
    return bool(shapely.hausdorff_distance(lid, shapely.linestrings(chain)) <= run.res.tip_zone)
