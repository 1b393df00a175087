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

__all__ = ["ALONG_RECORD", "JUMPS", "is_mouth", "covered", "traced_gaps", "end_chords",
           "record_gaps", "close_unresolved"]

ALONG_RECORD = ("the lid lies on recorded contour (sensor jitter)",
                "the lid lies on contour recorded from B to A")
"""Notes of the areas the revisit closes as traced because their lid lies along
recorded contour (:func:`~core2d.planner.along.on_recorded`,
:func:`~core2d.planner.along.reversed_lid`): within
:attr:`~core2d.resolution.Resolution.near` of a wall, where the sensor cannot
tell that wall from another as near (:func:`close_unresolved`)."""

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

    For the same reason, with a noisy sensor, each hop of the chain longer than
    the fan spacing (eps/4) is a W2 chord too: the map joined the two pieces
    across a gap narrower than eps + jitter, which §3.1 approximates by the
    chord (below eps only, for a sensor whose readings do not resolve eps/2:
    :func:`_chord_limit`). Reported as traced, a slot 0.89 eps wide and 84 eps
    deep whose mouth the chain hopped was covered by nothing (``comb`` scene z7
    of 8, keyed sensor seed 7 at sigma 0.1 eps: 0.835 -> 0.914). A hop is the
    record's own gap (:meth:`~core2d.planner.known.KnownContour.hops`: to where the
    next piece passes); measured to that piece's first point, a piece that began
    back along the wall read as a hop of eps or more over a gap of a tenth of that,
    and a lid over a slot traced that way ended unknown after its revisit passes.
    Perfect sensing keeps the paper's output as it was.

    With a noisy sensor the chain need not start on A_i's own piece: it starts on
    any piece passing within ``tol`` of A_i, which may lie across an opening. The
    gap from A_i to the chain's nearest point, and from the chain's nearest point
    to B_i, is then a hop like the others
    (:meth:`~core2d.planner.known.KnownContour.hops` with ``ends``): wider than the
    fan spacing and the jitter (a narrower one is the scatter of the end's own
    reading) and narrower than :func:`_chord_limit`, it is a W2 chord. "No farther
    than eps from the recorded contour" measured A_i against its own piece: on the
    ``star`` outline seed 21 (sensor seed 2021, sigma 0.3 eps + taxels 0.25 eps, 16
    reads) A_i ended the piece on one side of a slot mouth 0.89 eps wide, the chain
    started on the piece across it, 0.93 eps away, and the slot's 30 eps of contour
    were covered by nothing (coverage within eps/2 + 2 sigma 0.910 -> 1.000).

    An end's gap counts only within ``tol``, the same-contact radius, below eps
    under a sensor whose readings resolve eps/2: the rule only writes chords, and
    the motions are those of the planner without it. The map's walk can begin a
    chain on a piece reached from another (a cycle of continuations), which does
    not start at A_i: measured to that chain's first point the gap read 1.3 - 1.9
    eps on the ``star`` outline seed 1 at sigma 0.1 and turned closed areas into
    processed ones; such a chain passed 2.7 - 14 eps from A_i on the ``comb`` and
    ``undercut`` outlines seed 4. That is the walk's gap, not the record's.

    Returns
    -------
    list of (2, 2) float (the ends' chords, then the hops'), or None.

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
    >>> fine = Resolution.of(1.0, noise=0.0775, taxel=0.25)  # 15 reads at sigma 0.3 eps
    >>> known = KnownContour(join=fine.w2_dist)
    >>> known.add(np.array([[0.0, 0.0], [3.0, 0.0]])); known.add(np.array([[3.6, 0.0], [8.0, 0.0]]))
    >>> [g.tolist() for g in traced_gaps(known, (0.0, 0.0), (8.0, 0.0), 0.5, fine)]
    [[[3.0, 0.0], [3.6, 0.0]]]
    """
    noisy = res.jitter > 0
    hops = known.hops(a, b, tol, ends=noisy)
    if hops is None:
        return None
    widths = [float(np.hypot(*(h[1] - h[0]))) for h in hops]
    least = [res.fan_spacing] * len(hops)
    if noisy:  # the ends' gaps: past the scatter of the end's own reading, within tol
        least[0] = least[-1] = max(res.fan_spacing, res.jitter)
        inner = range(1, len(hops) - 1)
        keep = [k for k in range(len(hops)) if k in inner or widths[k] <= tol]
        hops, widths, least = ([x[k] for k in keep] for x in (hops, widths, least))
    if resolves_half_eps(res) and max(widths, default=0.0) >= res.eps:
        return None
    ends = end_chords(known, a, b, res)
    if not noisy:
        return ends
    return ends + [h for h, w, low in zip(hops, widths, least) if low < w < _chord_limit(res)]


def _chord_limit(res: Resolution) -> float:
    """The widest break or hop of the record written as a W2 chord
    (:func:`traced_gaps`, :func:`record_gaps`): the W2 distance eps + jitter
    where two readings resolve eps/2, else eps, the paper's own bound. A coarse
    sensor (sigma 0.3 eps read once: jitter 1.52 eps) reads the mouth of a slot
    1.5 - 2.5 eps wide as a gap narrower than its W2 distance; its chord would
    credit contour the readings cannot place (one read of the ``star`` outline,
    seed 1, keyed seeds 1001 / 2001 / 5001: coverage 0.95 / 0.96 / 0.91 -> 1.0,
    all of it through such chords)."""
    return res.w2_dist if resolves_half_eps(res) else res.eps


def end_chords(known, a, b, res: Resolution) -> list[np.ndarray]:
    """W2 chords from A_i, and to B_i, from the nearest recorded point, for each end
    farther than eps from the recorded contour (:func:`traced_gaps`); an area closed
    as traced because its lid lies along recorded contour
    (:func:`~core2d.planner.along.on_recorded`,
    :func:`~core2d.planner.along.reversed_lid`) has the same ends.

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


def record_gaps(known, a, b, res: Resolution) -> list[np.ndarray]:
    """W2 chords over the breaks of the recorded contour along the lid A_iB_i
    of an area closed as traced because its lid lies along recorded contour
    (:func:`~core2d.planner.along.on_recorded`,
    :func:`~core2d.planner.along.reversed_lid`).

    Such a lid passes within :attr:`~core2d.resolution.Resolution.near` (2 tol
    + the jitter) of the record at every point it is sampled at, so a break
    between two recorded pieces along it is about as narrow as eps + jitter, the
    W2 distance: §3.1 approximates the contour behind it by the chord
    (Dist < eps at the sensor's resolution; a break as wide as
    :func:`_chord_limit` or wider is left as it was). Closing the area as traced
    without the chord claimed that contour recorded: a slot 0.8 eps wide whose
    mouth lay under such a lid was covered by nothing (``comb`` outline seed 0,
    keyed sensor seed 2000 at sigma 0.3 eps + taxels 0.25 eps, 15 reads).

    Each recorded segment is clipped to the band of half-width ``near`` about
    the lid; the stretches of the lid that no clipped segment projects onto,
    between two that do, and longer than the fan spacing (eps/4, the step at
    which ``on_recorded`` samples the lid), are the breaks. A chord joins the
    recorded points either side of a break. A_i and B_i count as recorded points
    where :func:`end_chords` leaves them (within eps of the record): a break between
    an end and the nearest piece along the lid is a break like any other (the
    ``comb`` scene z2 of 8 at sigma 0.1 eps, keyed sensor seed 2: the last piece
    along a lid ended 0.92 eps before B_i, and the slot behind that break was
    covered by nothing, coverage 0.825; with the chord 0.906). :func:`end_chords`
    chords the ends farther away (both together give every contour the area
    claims).

    known : KnownContour ; a, b : (2,) float -- A_i and B_i ; res : Resolution.

    Returns
    -------
    list of (2, 2) float, ordered from A_i to B_i.

    Examples
    --------
    >>> from core2d.planner.known import KnownContour
    >>> fine = Resolution.of(1.0, noise=0.0775, taxel=0.25)  # near 0.55 eps
    >>> known = KnownContour(join=fine.w2_dist)
    >>> known.add(np.array([[0.0, 0.0], [3.0, 0.0]]))
    >>> known.add(np.array([[4.2, 0.1], [8.0, 0.0]]))
    >>> [g.round(2).tolist() for g in record_gaps(known, (0.0, 0.0), (8.0, 0.0), fine)]
    [[[3.0, 0.0], [4.2, 0.1]]]
    """
    a, b = np.asarray(a, float), np.asarray(b, float)
    seg_a, seg_b = known.segments()
    length = float(np.hypot(*(b - a)))
    if length == 0 or not len(seg_a):
        return []
    u = (b - a) / length
    n = np.array([-u[1], u[0]])
    half = res.near
    # each segment in the lid's frame: s along it, h across (Liang-Barsky clip)
    s0, s1 = (seg_a - a) @ u, (seg_b - a) @ u
    h0, h1 = (seg_a - a) @ n, (seg_b - a) @ n
    lo, hi = np.zeros(len(s0)), np.ones(len(s0))
    for p0, p1, low, high in ((s0, s1, 0.0, length), (h0, h1, -half, half)):
        d = p1 - p0
        with np.errstate(divide="ignore", invalid="ignore"):
            ta, tb = (low - p0) / d, (high - p0) / d
        flat = d == 0
        inside = (p0 >= low) & (p0 <= high)
        lo = np.where(flat, np.where(inside, lo, 2.0), np.maximum(lo, np.minimum(ta, tb)))
        hi = np.where(flat, np.where(inside, hi, -1.0), np.minimum(hi, np.maximum(ta, tb)))
    keep = lo <= hi
    lo, hi = lo[keep], hi[keep]
    pa, pb = seg_a[keep], seg_b[keep]
    p_lo = pa + lo[:, None] * (pb - pa)
    p_hi = pa + hi[:, None] * (pb - pa)
    # A_i and B_i are readings too, where end_chords leaves them (within eps of the record)
    ends = [e for e in (a, b) if known.distance(e) <= res.eps]
    if ends:
        p_lo, p_hi = np.concatenate([p_lo, ends]), np.concatenate([p_hi, ends])
    if not len(p_lo):
        return []
    t_lo, t_hi = (p_lo - a) @ u, (p_hi - a) @ u
    swap = t_lo > t_hi  # a segment read against the lid's direction
    start = np.where(swap, t_hi, t_lo)
    stop = np.where(swap, t_lo, t_hi)
    start_pt = np.where(swap[:, None], p_hi, p_lo)
    stop_pt = np.where(swap[:, None], p_lo, p_hi)
    order = np.argsort(start, kind="stable")
    gaps, reach, reach_pt, limit = [], stop[order[0]], stop_pt[order[0]], _chord_limit(res)
    for k in order[1:].tolist():
        if start[k] - reach > res.fan_spacing and np.hypot(*(start_pt[k] - reach_pt)) < limit:
            gaps.append(np.array([reach_pt, start_pt[k]], dtype=float))
        if stop[k] > reach:
            reach, reach_pt = stop[k], stop_pt[k]
    return gaps


def close_unresolved(run) -> int:
    """Close W2 every processed mouth of ``run`` (an
    :class:`~core2d.planner.run.Exploration`) that was split and has a
    descendant area that ended unknown, or that was closed as traced because
    its lid lies along recorded contour (:data:`ALONG_RECORD`); returns how many.

    The mouth read shorter than eps + jitter, the width the sensor cannot
    tell from eps (§3.1 at the sensor's resolution); the flow behind it
    resolved part of C_A^B and left the rest unknown. As at a dead end
    (``Exploration.defer``) the mouth's chord is written W2; the unknown
    areas behind it stay reported as they are.

    A lid closed along recorded contour behind the mouth is the same event:
    the lid lies within ``near`` (2 tol + the jitter) of one wall, and the
    other wall of a slot narrower than that lies within it too, unread; the
    area's C_A^B runs down that wall and back, but the record of the first
    wall answers for it. On the ``comb`` outline seed 20 (sensor seed 1020,
    sigma 0.3 eps + taxels 0.25 eps, 16 reads) a slot 0.84 eps wide and 30 eps
    deep read 1.08 eps across its mouth and was entered; one wall was traced
    part way and a lid from it to the far corner was closed that way, and the
    other wall, the bottom and the rest of the first wall were covered by
    nothing."""
    records = run.result.areas
    kids: dict[int, list[int]] = {}
    for rec in records:
        kids.setdefault(rec.parent, []).append(rec.index)

    def unresolved(i) -> str | None:
        todo, found = list(kids.get(i, ())), None
        while todo:
            rec = records[todo.pop()]
            if rec.outcome == "unknown":
                return "stayed unknown"
            if rec.outcome == "traced" and rec.note in ALONG_RECORD:
                found = "was closed along a wall the sensor cannot tell from another"
            todo.extend(kids.get(rec.index, ()))
        return found

    closed = 0
    for area in run.mouths:
        rec = records[area.index]
        why = unresolved(area.index) if rec.outcome == "split" else None
        if why is not None:
            run.close(area, "W2", f"split, but an area behind it {why}; "
                                  "Dist(A,B) < eps + the sensor's jitter")
            closed += 1
    return closed
