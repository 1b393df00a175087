"""Internal: quasi-static Coulomb friction at the probe tip -- the jam condition.

The paper's argument (§1, Figs. 1-2): a finger or a probe *pushed* along a
frictional surface sticks, slips or is blocked by a small irregularity,
while a *pulled* one slides "even under significant friction"; hence the
pulling strategy, and the local concave point as the start of every trace
(Fig. 2(b)), where both tracing directions are pulls, against Fig. 2(a),
where a trace from an arbitrary point pushes on its inner side.

The model, opt-in (``friction`` = mu, default 0: no friction, today's
simulator bit for bit):

* a **pushing** micro-step of a compliant trace (§4.3) is one whose joint
  direction v has v.t > 0 (the quantity of Case 3): the joint drives the
  rigid rod *into* the surface, so the force the rod puts on the surface is
  axial, along t (the compliant torque tau0 adds a lateral part of order
  tau0 / L, small against the drive: the torque only keeps the tip on the
  surface, eq. 2). The tip can slide only if the tangential part of that
  force exceeds mu times its normal part. With the step's slide direction
  d (from the tip contact before the step to the one after it: the
  surface's local tangent, at the simulator's resolution) the rod axis lies
  within the friction cone -- within atan(mu) of the contact normal -- when

      |t . d| < mu |t x d|,

  and then **no** drive force makes it slide: the rod is self-locked (a
  wedge). The step jams: the tip sticks, the joint does not move, and the
  sensors read what a joint stalled by its own drive reads -- the joint
  cannot advance along v, the torque sensor feels the contact, the tip
  contact is where it was. That is the paper's Case 4 (§4.3.2: "the joint
  loses the moving degree of freedom in the direction given by v_i ...
  confirmed by the torque sensor"), so the reading's event is ``"blocked"``;
  the simulator alone counts it as a jam (``SenseStats.jams``).
* a **pulling** step (v.t <= 0) slides: the rod drags the tip; the normal
  force is only the compliant torque's tau0 / L, the friction it causes is
  bounded and the stiff joint overcomes it. The step is executed as without
  friction.

Nothing more is modelled: no stick-slip, no dynamics, no friction on the
probe's side faces or during a swing, an insertion (the tip moves along
the normal of nothing: it stops at the first touch; finger probing, made of
insertions only, never slides) or a free transfer. A stick-slip would
shift the recorded contacts by less than the contact resolution between
jams, which changes no W1/W2/W3 class; the jam is the event that changes
what a planner can trace, and it is the one counted.
"""
from __future__ import annotations

__all__ = ["self_locked"]


def self_locked(mu: float, tx: float, ty: float, dx: float, dy: float) -> bool:
    """Is a pushing step inside the friction cone (self-locking: it jams)?

    Parameters
    ----------
    mu : float -- Coulomb friction coefficient at the tip (>= 0).
    tx, ty : float -- unit probe direction t (the rod axis, the push force).
    dx, dy : float -- the tip's slide over the step (the surface tangent, any
        length; zero: no slide, no jam).

    Returns
    -------
    bool -- ``|t . d| < mu |t x d|``: the rod axis within atan(mu) of the
    contact normal. Always False for mu = 0. Scalar math, compiled as is
    by :mod:`core2d.sim.kernels` (both engines decide alike).
    """
    along = tx * dx + ty * dy
    across = tx * dy - ty * dx
    return abs(along) < mu * abs(across)
