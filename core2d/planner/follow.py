"""A pushing contour follower: the strategy the paper argues against (§1, Fig. 2(a)).

The paper starts every trace from a local concave point so that both
tracing directions are pulls (Fig. 2(b)); a trace started "from an
arbitrary point on the surface" pulls one way and pushes the other
(Fig. 2(a)). This module is that arbitrary-start follower, to measure the
difference under tip friction (:mod:`core2d.sim.friction`):

* **insert from F** -- the first contacts are the bootstrap's radial
  insertions from the workspace circle (:func:`core2d.planner.bootstrap.bootstrap`,
  as the pulling planner starts); no local concave point search (§4.2.2);
* **trace both directions** from each first contact D with the compliant
  tracing motion of §4.3 (no Case 3 guard: pushing is the point), in
  motions of ``CHUNK`` eps of joint travel. The first direction starts as
  Theorem 4 plans it at D -- v in K1 cap K2 (or, when the tip makes no
  progress that way, K1 cap not-K2), tau = tau0 sgn(v, t*) (eq. 2,
  :func:`core2d.planner.regions.trace_direction`): a pull. After each
  motion v is re-aimed along the last eps / 2 of traced contour (a
  follower follows the surface) and the torque is held (constant torque).
  The second direction starts at D again with v = minus the contour's
  direction at D and the same torque, which still turns the rod towards
  the contact normal and so keeps the tip pressed: the tip leads, the rod
  is driven into the surface wherever it leans back, v.t > 0 -- the
  pushing side of Fig. 2(a);
* **the paper's events where they apply** end a direction: Case 2 with the
  new contact on the probe's side (a dead end: the body rests on a convex
  corner), Case 2-3 (contact lost), Case 4 (the joint cannot move along v --
  a friction jam reads the same), no progress of the tip over a motion, a
  loop (the tip reaches contour the follower recorded before), the motion
  budget. A Case 2 jump to a new *tip* contact is followed on (the contour
  between is not traced: a hop shorter than eps is W2, §3.1).

Outputs, in the classes of :class:`core2d.result.SliceResult`: W1 the traced
polylines, W2 the hops shorter than eps; no W3 and no unknown areas (the
follower registers no areas A_iB_i and proves nothing about what it did not
trace, like finger probing). It sees sensor readings only.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from core2d.planner.bootstrap import bootstrap
from core2d.planner.regions import trace_direction
from core2d.planner.robot import Robot, final_stats
from core2d.readings import TIP
from core2d.result import SliceResult

__all__ = ["follow_contour", "FollowRecord", "CHUNK"]

CHUNK = 2.0
"""Joint travel of one follower motion, in eps (v is re-aimed between motions)."""


@dataclass
class FollowRecord:
    """What the follower recorded: its polylines, hops and the motion of each.

    lines : list of (k, 2) float -- traced tip contacts, one list per piece.
    at : list of int -- the motion after which each piece was last extended.
    hops : list of (2, 2) float -- Case 2 jumps from one tip contact to the next.
    hop_at : list of int -- the motion of each hop.
    """

    lines: list = field(default_factory=list)
    at: list = field(default_factory=list)
    hops: list = field(default_factory=list)
    hop_at: list = field(default_factory=list)

    def points(self) -> np.ndarray:
        """(m, 2) every recorded contact."""
        pts = [np.asarray(p).reshape(-1, 2) for p in self.lines if len(p)]
        return np.concatenate(pts) if pts else np.zeros((0, 2))


def _near(points: np.ndarray, record: np.ndarray, radius: float) -> bool:
    """Is any of ``points`` (k, 2) within ``radius`` of ``record`` (m, 2)?"""
    if not len(points) or not len(record):
        return False
    d = np.linalg.norm(points[:, None, :] - record[None, :, :], axis=2)
    return bool(d.min() <= radius)


def _heading(line: list, span: float) -> np.ndarray | None:
    """(2,) unit direction of the last ``span`` of a traced piece (None: too short)."""
    end = line[-1]
    for p in reversed(line[:-1]):
        d = end - p
        n = float(np.hypot(d[0], d[1]))
        if n >= span:
            return d / n
    return None


def _follow_side(probe: Robot, v: np.ndarray, tau: int, rec: FollowRecord,
                 before: np.ndarray, eps: float, max_motions: int):
    """Follow the contour from the current tip contact, first along ``v`` (2,),
    then along the contour traced last, the torque ``tau`` held throughout.

    ``before`` (m, 2): the contacts recorded before this direction started
    (reaching them is a loop; those within eps of the start D are left out,
    the other direction starts there too); coming back to D after leaving
    it by 2 eps is a loop as well.

    Returns ``(budget hit, the contour's direction at D or None)``.
    """
    res = probe.resolution
    home = probe.tip.copy()
    before = before[np.linalg.norm(before - home, axis=1) > eps] if len(before) else before
    away = False
    line = [home]
    rec.lines.append(line)
    rec.at.append(probe.motions)
    first, pieces = None, len(rec.lines)
    while True:
        if probe.motions >= max_motions:
            return True, first
        r = probe.trace(v, tau, CHUNK * eps, guard_push=False)
        new = np.asarray(r.trace, float).reshape(-1, 2)
        moved = float(np.linalg.norm(new[-1] - line[-1])) if len(new) else 0.0
        line.extend(list(new[1:] if len(new) and np.allclose(new[0], line[-1]) else new))
        rec.at[-1] = probe.motions
        if len(rec.lines) == pieces:  # still the first piece: the direction at D
            first = _heading(line, res.tol) if first is None else first
        if len(new) and (_near(new, before, res.tip_zone)
                         or (away and _near(new, home[None], res.tip_zone))):
            return False, first  # a loop: back on recorded contour
        if len(new):
            away = away or float(np.linalg.norm(new - home, axis=1).max()) > 2 * eps
        if r.event == "jump":
            c = r.contacts[0] if r.contacts else None
            if c is None or c.face != TIP:
                return False, first  # Case 2, the body on a convex corner: a dead end
            rec.hops.append(np.stack([line[-1], c.point]))
            rec.hop_at.append(probe.motions)
            line = [np.asarray(c.point, float)]
            rec.lines.append(line)
            rec.at.append(probe.motions)
            continue
        if r.event not in ("done", "limit") or moved <= res.tol:
            return False, first  # Case 2-3, Case 4 (or a jam), no progress: a dead end
        heading = _heading(line, 0.5 * eps)
        if heading is not None:
            v = heading


def _start(probe: Robot, point, pose) -> bool:
    """Back to the first contact D along its insertion line; did the tip touch?"""
    probe.approach(point, pose.direction)
    return probe.insert(2 * probe.radius).tip_contact is not None


def follow_contour(probe: Robot, eps: float, max_motions: int = 20000,
                   count: int = 12) -> SliceResult:
    """Follow the contour of a closed slice from its first contacts (see module doc).

    Parameters
    ----------
    probe : Robot -- the simulated probe (readings only).
    eps : float -- the paper's eps (hops shorter than eps are W2).
    max_motions : int -- motion budget; reported when hit.
    count : int -- bootstrap insertions (first contacts).

    Returns
    -------
    SliceResult in the slice's 2D frame.
    """
    t0 = time.perf_counter()
    rec = FollowRecord()
    probe.note_phase("bootstrap")
    starts = [(a.a, a.pose_a) for a in bootstrap(probe, count)]
    budget_hit = False
    probe.note_phase("tracing")
    for point, pose in starts:
        if budget_hit or probe.motions + 2 > max_motions:
            budget_hit = True
            break
        if _near(np.asarray(point)[None], rec.points(), 0.5 * eps):
            continue  # traced already
        # the first direction pulls at D (Theorem 4, the side K allows); the
        # second goes back along the contour's direction at D with the same torque
        first = None
        for toward_b in (True, False):
            if not _start(probe, point, pose):
                break
            v, tau = trace_direction(probe.direction, toward_b)
            budget_hit, first = _follow_side(probe, v, tau, rec, rec.points(), eps, max_motions)
            if budget_hit or first is not None:
                break
        if first is None or budget_hit or not _start(probe, point, pose):
            continue
        budget_hit, _ = _follow_side(probe, -first, tau, rec, rec.points(), eps, max_motions)
    result = SliceResult()
    for line, at in zip(rec.lines, rec.at):
        if len(line) >= 2:
            result.w1.append(np.asarray(line))
            result.known_at["w1"].append(int(at))
    for hop, at in zip(rec.hops, rec.hop_at):
        if np.linalg.norm(hop[1] - hop[0]) < eps:
            result.w2.append(hop)
            result.known_at["w2"].append(int(at))
    result.stats = final_stats(probe, budget_hit=budget_hit, seconds=time.perf_counter() - t0)
    return result
