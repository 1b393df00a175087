"""Where the robot's recorded contour stops: loose ends and loose starts.

Every piece of the map (:class:`~core2d.planner.known.KnownContour`) runs
with the material on its right, so on a closed contour the stretches not
yet recorded run from a *loose end* (the recorded contour stops) to a
*loose start* (it begins again). This is the finer test
:mod:`core2d.planner.audit` applies at the ends of a lid that opened to F
(:meth:`KnownContour.loose_ends <core2d.planner.known.KnownContour.loose_ends>`
is the coarse one it applies everywhere).

An end is continued only by recorded contour that goes on *beyond* it: a
chain of pieces, each passing the end of the one before within ``join``
and turning there by less than 120 degrees (a piece shorter than ``join``
has no direction to turn from: any piece passing its end may continue it),
that moves away from the end to farther than ``join``. A piece that merely
passes within ``join`` and stops there too -- a W2 chord a hair long laid
at the end of a trace, the same stretch recorded twice, a chord ending just
behind the end -- continues nothing: where the recorded pieces all stop
within ``join`` of one point, the contour beyond is unrecorded. A start is
led into likewise by contour recorded farther than ``join`` before it.
Where the recorded contour stops, the last point of the chain that lies
farthest from the end is the loose end (the first point farthest before a
start is the loose start); loose points within ``join`` of one another are
one.
"""
from __future__ import annotations

import numpy as np

__all__ = ["recorded_stops"]


def _onward(points, p, e, r) -> bool:
    """Do ``points`` (k, 2) -- a piece's points past the point ``p`` where it
    meets the chain -- move away from ``e``: farther than ``r`` from it and
    farther than ``p`` is? A piece that meets the chain behind ``e`` and
    runs towards it (a stretch recorded again, a chord behind the end) does not."""
    if not len(points):
        return False
    return bool((np.hypot(*(points - e).T) > max(r, float(np.hypot(*(p - e))))).any())


def _meets(known, j, k, q):
    """The point of segment ``k`` of piece ``j`` nearest to ``q`` (2,): the
    projection clipped to the segment, in float arithmetic that rounds as
    numpy's ``(q - a) @ ab / (ab @ ab)`` does on (2,) vectors."""
    a, b = known.pieces[j][k], known.pieces[j][k + 1]
    ax, ay = float(a[0]), float(a[1])
    abx, aby = float(b[0]) - ax, float(b[1]) - ay
    t = ((float(q[0]) - ax) * abx + (float(q[1]) - ay) * aby) / max(abx * abx + aby * aby, 1e-300)
    t = 0.0 if t < 0.0 else (1.0 if t > 1.0 else t)  # np.clip's order; nan stays nan
    return np.array((ax + t * abx, ay + t * aby))


def _end_chain(known, i):
    """Follow the recorded contour on from the last point e of piece ``i``,
    through pieces passing the end of the one before within ``join`` and
    turning there by less than 120 degrees, within 2 ``join`` of e.

    Returns None when it moves on beyond ``join`` from e, else the piece of
    the chain that ends farthest on from e (``i`` itself when nothing
    continues it): where the recorded contour stops."""
    pl, r = known.pieces[i], known.join
    e = pl[-1]
    todo = [(j, k, e) for j, k in known.successors(i)]
    if not (np.hypot(*(pl - e).T) > r).any():  # shorter than join: its direction is no reading
        todo += [(j, k, e) for j, k in known.passing(e, r)]
    seen, last, far = {i}, i, 0.0
    while todo:
        j, k, q = todo.pop()
        if j in seen:  # (no need to place it)
            continue
        p = _meets(known, j, k, q)
        if np.hypot(*(p - e)) > 2 * r:
            continue
        seen.add(j)
        if _onward(known.pieces[j][k + 1:], p, e, r):
            return None
        d = float(np.hypot(*(known.pieces[j][-1] - e)))
        if d > max(far, float(np.hypot(*(p - e)))):  # ends farther on
            last, far = j, d
        q = known.pieces[j][-1]  # j stops there too: what continues j?
        todo += [(m, n, q) for m, n in known.successors(j)]
    return last


def _start_chain(known, i, passing):
    """Follow the recorded contour back from the first point s of piece
    ``i`` likewise: None when it leads in from beyond ``join``, else the
    piece of the chain whose first point lies farthest from s (where the
    recorded contour begins). ``passing(m)`` is ``known.passing`` at the
    first point of piece m within ``join`` (the same for every i)."""
    s, r = known.pieces[i][0], known.join
    seen, todo, first, far = {i}, [i], i, 0.0
    while todo:
        m = todo.pop()
        q = known.pieces[m][0]
        for j, k in passing(m):
            if j in seen:  # (no need to place it)
                continue
            p = _meets(known, j, k, q)
            if np.hypot(*(p - s)) > 2 * r:
                continue
            seen.add(j)
            if _onward(known.pieces[j][:k + 1], p, s, r):
                return None
            d = float(np.hypot(*(known.pieces[j][0] - s)))
            if d > max(far, float(np.hypot(*(p - s)))):  # begins farther back
                first, far = j, d
            todo.append(j)  # j starts there too: what leads into j?
    return first


def _one_each(found, r):
    """Keep the first of loose points lying within ``r`` of one kept."""
    kept = []
    for item in found:
        if all(np.hypot(*(item[0] - k[0])) > r for k in kept):
            kept.append(item)
    return kept


def recorded_stops(known):
    """Loose ends and loose starts of ``known`` (see the module doc).

    The audit asks again about a map that has not changed (its last round, then
    :func:`~core2d.planner.audit.report_leftovers`): the answer is remembered per
    version of the map (:meth:`KnownContour.remembered
    <core2d.planner.known.KnownContour.remembered>`) and shared, not to be changed.

    Returns
    -------
    (ends, starts) : tuples of (point (2,) float, Posture or None, piece index)
        -- the last point of the piece where the recorded contour stops
        (the first of the one where it begins) and its posture.
    """
    return known.remembered("recorded_stops", _walk_stops)


def _walk_stops(known):
    """:func:`recorded_stops` walked from scratch."""
    ends, starts, found = [], [], {}

    def passing(m):  # who passes the first point of piece m: asked again by later chains
        if m not in found:
            found[m] = known.passing(known.pieces[m][0], known.join)
        return found[m]

    for i in range(len(known.pieces)):
        j = _end_chain(known, i)
        if j is not None:
            ends.append((known.pieces[j][-1], known.poses[j][1], j))
        j = _start_chain(known, i, passing)
        if j is not None:
            starts.append((known.pieces[j][0], known.poses[j][0], j))
    return tuple(_one_each(ends, known.join)), tuple(_one_each(starts, known.join))
