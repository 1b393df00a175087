"""A lid the revisit's passes touched along its length (noisy sensor): W2 piece by piece.

With a perfect sensor a revisit pass that meets C_{A_i}^{B_i} farther than eps/2 from
A_i and B_i splits the area at that contact C (§4.4), and the halves go on until
Dist < eps makes them W2 (§3.1). With a noisy sensor that split is refused where the
contact lies on recorded contour (:func:`~core2d.planner.short_lids.on_map`), near a
contact an ancestor was split at, or near an end (the widened same-contact radius):
re-reading a wall the robot has recorded must not split a lid again and again. Along a
wall whose noisy trace left a gap, the lid A_iB_i then lies on the wall within the
sensor's scatter, every pass touches the wall at the lid, and each contact is refused:
the area ended ``unknown`` although the passes had touched its contour all along
(``cup_handle`` z5 at sigma 0.3 eps with taxels 0.25 eps, sensor seed 5: a lid 4.9 eps
down the cup's wall, 20 passes that touched the wall within 0.7 eps of the lid, all
refused; the walls of ``deep_slot``'s slot held such lids 3 - 12 eps long).

:class:`Touches` keeps those contacts -- the pass's contact on C_A^B's side (its
segment from the joint crosses the lid, or the contact lies within the sensor's
tolerance eps/2 + 2 sigma of it), not beyond an end on the lid's line
(:func:`~core2d.planner.grazing.beyond_ends`) -- and says when they sample the lid
finely enough: ordered along A_i -> B_i, with A_i and B_i at the ends, no two
neighbours are as far apart as the W2 distance (eps + jitter,
:attr:`~core2d.resolution.Resolution.w2_dist`). That is what the refused splits would
have made: children between neighbouring contacts, each W2. The area is closed as W2
along those contacts (their block means along the lid, :meth:`Touches.chain`), one W2
segment per pair of neighbours. The chain is not added to the robot's map (an unknown
lid was not either): laid a few sigma inside a slit 1.26 eps wide it narrowed the slit
for the lid question of the areas after it (``trimesh_octagonal_pocket`` z1 at sigma
0.1 eps: coverage within eps/2 + 2 sigma 0.988 -> 0.951 with the chain on the map,
0.991 without). The rule reads the passes the revisit makes anyway, and then those of
:class:`Fill`: passes aimed into the gaps the touches leave.

A lid whose touches leave gaps as wide as the W2 distance (the passes land where a grazing
line meets the wall, and some stretches get none) stays ``unknown`` and is reported as any
unknown lid, but the chain's segments shorter than the W2 distance are W2
(:meth:`Touches.pieces`) -- again the refused splits' children, W2 where the passes touched
densely. Over the 8-slice study with three seeds this lifted coverage on 134
of 570 slice runs at sigma 0.3 + T 0.25 and 63 at sigma 0.1, lowered it on none, with the
same motions.

It needs at least one contact farther than the lid's end radius from both ends (the
lid's middle was touched, not only its ends: ends alone are the revisit's W3 by
probing, a slit narrower than eps). Perfect sensing (jitter 0) leaves the paper's flow
as it was: :func:`applies` is False.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from core2d.planner.grazing import crosses_lid
from core2d.planner.pass_plan import MAX_TRIES
from core2d.resolution import Resolution

__all__ = ["Touches", "Fill", "applies", "gap_key", "TRIED"]

#: times the :class:`Fill` aims at one gap (a gap out of reach counts as tried out)
TRIED = 2


def gap_key(lo: float, hi: float) -> tuple[float, float]:
    """A gap's ends along the lid, rounded: the key of how often it was aimed at."""
    return round(lo, 9), round(hi, 9)


def applies(res: Resolution) -> bool:
    """The rule acts with a noisy sensor only (two readings of one point differ)."""
    return res.jitter > 0


@dataclass
class Touches:
    """Contacts the revisit's passes read on one lid's contour.

    res : Resolution -- the sensor's stated resolution.
    a, b : (2,) float -- A_i and B_i.
    end_radius : float -- a contact this close to A_i or B_i is an end again.
    points : list of (2,) float -- the contacts kept (:meth:`add`).
    along : list of float -- their positions along A_i -> B_i (0 at A_i, 1 at B_i).

    Examples
    --------
    A lid 4 eps long on y = 0, the wall a hair behind it (y < 0), a sensor of
    sigma 0.3 eps and taxels 0.25 eps (W2 distance 2.52 eps); the probe comes from y > 0.

    >>> res = Resolution.of(1.0, noise=0.3, taxel=0.25)
    >>> t = Touches(res, np.zeros(2), np.array([4.0, 0.0]), end_radius=0.5)
    >>> t.add((1.0, 3.0), (5.0, -0.1)), t.add((1.0, 3.0), (1.0, 2.5))  # past B; in front
    (False, False)
    >>> t.add((1.5, 3.0), (1.5, -0.2)), t.closes()  # gaps 1.51 and 2.51 eps
    (True, True)
    >>> t.chain().round(2).tolist()
    [[0.0, 0.0], [1.5, -0.2], [4.0, 0.0]]
    """

    res: Resolution
    a: np.ndarray
    b: np.ndarray
    end_radius: float
    points: list = field(default_factory=list)
    along: list = field(default_factory=list)

    def add(self, joint, point) -> bool:
        """Keep ``point`` (a pass's contact, the probe's ``joint`` when read) if it
        lies on C_A^B's side of the lid and projects inside it; whether it was kept."""
        a, b, p = self.a, self.b, np.asarray(point, dtype=np.float64)
        ab = b - a
        u = float((p - a) @ ab / max(float(ab @ ab), 1e-300))
        if not 0.0 < u < 1.0:  # beyond an end: the wall the lid lies along
            return False
        off = float(np.hypot(*(p - a - u * ab)))
        if off > self.res.sensor_tol and not crosses_lid(a, b, joint, p):
            return False  # in front of the lid: contour reached from F without it
        self.points.append(p)
        self.along.append(u)
        return True

    def _raw(self) -> np.ndarray:
        """(k + 2, 2) float: A_i, the kept contacts in order along the lid, B_i."""
        order = np.argsort(self.along, kind="stable")
        return np.vstack([self.a, *[self.points[i] for i in order], self.b])

    def chain(self) -> np.ndarray:
        """(m + 2, 2) float: A_i, the means of the kept contacts in blocks of
        :attr:`~core2d.resolution.Resolution.hop` (eps/4 + jitter) along the lid, B_i --
        the block means of :mod:`core2d.planner.denoise` taken along the lid: readings
        scattered across a straight wall average onto it."""
        if not self.points:
            return np.vstack([self.a, self.b])
        length = float(np.hypot(*(self.b - self.a)))
        block = np.floor(np.asarray(self.along) * length / self.res.hop).astype(np.int64)
        pts = np.asarray(self.points, dtype=np.float64)
        means = [pts[block == k].mean(axis=0) for k in np.unique(block)]
        return np.vstack([self.a, *means, self.b])

    def _gaps(self) -> np.ndarray:
        return np.hypot(*np.diff(self._raw(), axis=0).T)

    def open_gaps(self) -> list[tuple[float, float, float]]:
        """``(width, from, to)`` of every gap between neighbours (A_i and B_i included)
        as wide as the W2 distance, widest first; ``from`` and ``to`` along A_i -> B_i."""
        along = np.concatenate([[0.0], np.sort(self.along), [1.0]])
        gaps = self._gaps()
        wide = np.flatnonzero(gaps >= self.res.w2_dist)
        return sorted(((float(gaps[i]), float(along[i]), float(along[i + 1])) for i in wide),
                      reverse=True)

    def widest_untried(self, tried: dict, most: int = TRIED) -> tuple[float, float] | None:
        """``(from, to)`` of the widest open gap (:meth:`open_gaps`) that ``tried`` (a gap's
        :func:`gap_key` -> times aimed at) holds fewer than ``most`` times; None if none."""
        return next(((lo, hi) for _, lo, hi in self.open_gaps()
                     if tried.get(gap_key(lo, hi), 0) < most), None)

    def middle_touched(self) -> bool:
        """Is some kept contact farther than the end radius from both ends?"""
        return any(min(np.hypot(*(p - self.a)), np.hypot(*(p - self.b))) > self.end_radius
                   for p in self.points)

    def closes(self) -> bool:
        """Do the kept contacts sample the lid finely enough for W2 piece by piece
        (every neighbour within the W2 distance, the middle touched)?"""
        return (applies(self.res) and self.middle_touched()
                and float(self._gaps().max()) < self.res.w2_dist)

    def pieces(self) -> dict | None:
        """The W2 and unknown segments of the lid (for ``Exploration.close``): all of
        :meth:`chain` W2 when :meth:`closes`; else, once the middle was touched, the chain's
        segments shorter than the W2 distance W2 (the refused splits' children where the
        passes touched densely) and the lid itself unknown, as any unknown area reports
        it; None when nothing is W2."""
        chain = self.chain()
        segments = [chain[i:i + 2] for i in range(len(chain) - 1)]
        if self.closes():
            return {"W2": segments}
        if not (applies(self.res) and self.middle_touched()):
            return None
        short = [float(np.hypot(*(s[1] - s[0]))) < self.res.w2_dist for s in segments]
        if not any(short):
            return None
        return {"W2": [s for s, k in zip(segments, short) if k],
                "unknown": [np.vstack([self.a, self.b])]}


@dataclass
class Fill:
    """Passes aimed into the gaps a lid's touches leave, after the planned passes.

    The revisit's planned passes through a lid laid along a wall land where their
    grazing lines meet it, and stretches of the wall get no touch: the lid ends
    ``unknown`` with W2 only where neighbouring touches lie within the W2 distance
    (:meth:`Touches.pieces`). Where a grazing pass lands moves linearly with a sideways
    shift of its line (:class:`~core2d.planner.reaim.Aim`), so once the planned passes
    are spent the robot aims one at the middle of the widest gap between neighbouring
    touches (A_i and B_i included), from its own landings (:meth:`Aim.toward
    <core2d.planner.reaim.Aim.toward>`), until every neighbour lies within the W2
    distance (:meth:`Touches.closes`: W2 along them), every gap was aimed at twice or is
    out of reach (below), or ``cap`` passes are made. Where it was
    read: the ``comb`` outline seed 1 at sigma 0.1 eps, a lid 5.7 eps down the wall of
    a slot 1.45 eps wide, 9 planned passes touching it at 0.23, 0.48 - 0.50 and 0.98 of
    its length; three passes aimed at 0.74, 0.86 and 0.36 landed at 0.73, 0.86 and
    0.37, and the lid closed W2 along its touches. Over the keyed sensor study at sigma
    0.1 eps (6 seeds, 8 slices of every case) it raises 56 slice runs' reachable
    coverage and lowers 8 (p = 6e-10), most on the ``comb`` scene's slot walls, for
    0.3 % more motions. Every contact is judged as a planned pass's is (a new
    one splits the area, §4.4); the landings only steer where the robot looks. Nothing
    acts before a pass touched the lid's middle (:meth:`Touches.middle_touched`) and
    landed on its line (the Aim's series): a lid no pass reached, or one whose passes
    ended at its ends (the revisit's W3 by probing), is left as it was.

    A gap the landings cannot reach (no series on the lid's line, or a shift farther than a
    reading's reach: the passes crossed the lid steeply, not grazing a wall) gets the pass
    the spread would make there (:func:`~core2d.planner.pass_plan.spread`, steer 0): through
    the free lid sample nearest the gap's middle, along the middle of its free gap, a sample
    not taken before and lying inside the gap (``shift`` None: its landing starts no
    series), at most a spread's worth of them per lid
    (:data:`~core2d.planner.pass_plan.MAX_TRIES`): a lid across a cavity, whose passes
    land far behind it, leaves its gaps open whatever the passes do (``textured_pocket``
    z2, keyed sensor seed 2002: 85 such passes on a few lids, 1,310 -> 1,554 motions, for
    nothing, without the cap). Where it was read: the ``comb`` scene z1 at sigma 0.3 eps +
    taxels 0.25 eps averaged over 16 reads, keyed sensor seed 2001, a lid 12 eps long
    across a tooth's top and the mouth of a slot 2.5 eps wide and 84 eps deep beside it;
    the spread's passes at 0.3, 0.5 and 0.7 of the lid fell on the tooth's top, the one
    at 0.9 entered the mouth 22 degrees off the horizontal and met the slot's wall at the
    lid, and the widest gap (0.71 - 1.0) lay 1.8 tip zones from the only series'
    line: the slot was never entered (coverage within eps/2 + 2 sigma over the part eps
    resolves 0.896; 0.984 with the pass, docs/notes/noise.md).

    A gap neither way reaches (no series, no free sample inside it) counts as tried out
    (:data:`TRIED`), and the next widest gap is aimed at instead: the Fill goes on down
    the gaps rather than ending at the first. Where it was read: the ``comb`` scene's
    z-plane 2 of 5 at sigma 0.1 eps over 16 reads, sensor seed 1002: a lid from the far
    corner of a tooth's top to the wall of the slot 2.5 eps wide beside it lay a few
    hundredths of a millimetre under the tooth's recorded top, so its free samples lay
    only over the slot's mouth and two unrecorded stretches of the top; the widest gap
    between the passes' touches was the top, which no line reaches past the record, and
    the Fill stopped there. The slot (84 eps deep) was never entered: 0.899 over the part
    eps resolves, 1.000 with the pass into the mouth, the next widest gap. The same lid
    over the same slot held z-plane 0 at sigma 0.3 eps + taxels 0.25 eps (seed 0: 0.905
    -> 0.990) and z-plane 3 at sigma 0.1 eps (seed 2003: 0.907 -> 0.999).

    touches : Touches; aim : Aim -- the lid's touches and its passes' landings.
    cap : int -- most passes (the revisit gives 2 ceil(Dist(A_i, B_i) / W2 distance),
        at most :data:`~core2d.planner.pass_plan.MAX_SWEEP`).
    lines : FreeLines or None -- the lid's free lines, for the gaps the landings cannot reach.
    spent : int -- passes made; tried : dict -- (from, to) of a gap -> passes aimed at it.
    taken : list of float -- ``along`` of the free lid samples a pass went through.
    """

    touches: Touches
    aim: object
    cap: int
    lines: object = None
    spent: int = 0
    tried: dict = field(default_factory=dict)
    taken: list = field(default_factory=list)

    def _aimed(self, gap):
        """A pass into ``gap`` from the landings, else the spread's pass through a free
        sample inside it; None if neither can be aimed."""
        again = self.aim.toward(0.5 * (gap[0] + gap[1]))
        if again is None and self.lines is not None and len(self.taken) < MAX_TRIES:
            # out of the landings' reach: the spread's pass through the gap
            ln = self.lines.nearest(0.5 * (gap[0] + gap[1]), self.taken)
            if ln is not None and gap[0] < ln.along < gap[1]:
                self.taken.append(ln.along)
                again = ln.point, ln.direction, None
        return again

    def next(self):
        """The next pass ``(point, direction, shift)``, or None when the touches close
        the lid, the middle is untouched, the passes are spent or none can be aimed."""
        t = self.touches
        if self.spent >= self.cap or not t.middle_touched() or t.closes():
            return None
        while (gap := t.widest_untried(self.tried)) is not None:
            again = self._aimed(gap)
            if again is not None:
                break
            self.tried[gap_key(*gap)] = TRIED  # out of reach: the next widest gap
        else:
            return None
        key = gap_key(*gap)
        self.tried[key] = self.tried.get(key, 0) + 1
        self.spent += 1
        return again
