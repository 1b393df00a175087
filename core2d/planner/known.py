"""What the robot has itself recorded of the contour: its own map.

Everything here is built from the planner's results -- W1 polylines traced
by the tip, W2 chords, W3 lids -- never from the true contour. Every piece
is stored oriented the way the paper orients an area A_iB_i: the contour
runs with the material on its right (V_i on its left, Definition 3).

Two questions the map answers:

* :meth:`KnownContour.covers` -- is the contour from A to B already known
  (a chain of recorded pieces leads from A to B)? Then an unknown area
  A_iB_i has been traced through other areas and needs nothing more.
* :meth:`KnownContour.free_lines` -- can a straight line from the free area
  F still cross the open lid L_{A}^{B} from its V side without meeting
  recorded contour? Every piece of the map is real contour (W1 was touched
  by the tip; a line crossing a W2 chord or a proven W3 lid crosses the
  contour behind it), so a line that meets the map is blocked by the real
  contour. The contour C_A^B behind the lid is reachable only through the
  lid (the lid and the arc bound the region behind it, and a straight line
  cannot cross the lid twice), so **when no line from F reaches the open
  lid past the map, no point of C_A^B can be touched: the robot has proven
  W3 from its own records** (the extension of Area(G_i) = 0, §4.2.1, to
  lids whose surroundings are known). When lines remain, each is a pass
  the robot can try. A W2 chord longer than eps (a noisy sensor's W2 band)
  that the probe itself went through is an opening, not contour: it blocks
  no free line (:meth:`KnownContour.soften`, :mod:`core2d.planner.openings`).
"""
from __future__ import annotations

import numpy as np

from core2d.planner.lid_lines import FreeLine, FreeLines
from core2d.planner.segments import (continued_ends, continuing, cross2, cull_margin,
                                     near_segments, nearest_distance, point_segment_distances,
                                     segment_params, segments_within)

__all__ = ["KnownContour", "FreeLine"]


class KnownContour:
    """The recorded contour: oriented pieces (polylines) with material on the right.

    Parameters
    ----------
    join : float
        A piece passing within ``join`` of another piece's last point, and
        turning there by less than 120 degrees, continues it. (Gaps shorter
        than eps are W2 at the paper's resolution; the facing walls of two
        objects across a gap run antiparallel, so a chain does not hop
        between them.)

    Examples
    --------
    >>> k = KnownContour(join=0.5)
    >>> k.add([[0.0, 0.0], [4.0, 0.0]]); k.add([[4.2, 0.1], [8.0, 0.0]])
    >>> k.covers([1.0, 0.0], [7.0, 0.0], tol=0.1), k.covers([7.0, 0.0], [1.0, 0.0], tol=0.1)
    (True, False)
    >>> k.covers([3.0, 0.0], [1.0, 0.0], tol=0.1)  # one segment, the wrong way
    False
    """

    def __init__(self, join: float):
        self.join = float(join)
        self.pieces: list[np.ndarray] = []
        self.poses: list[tuple] = []  # (posture at the first point, at the last) or (None, None)
        self._a = np.zeros((0, 2))
        self._b = np.zeros((0, 2))
        self._piece = np.zeros(0, dtype=np.int64)  # piece of every segment
        self._first = []  # index of each piece's first segment
        self._next = []  # piece i -> [(j, k)]: piece j passes piece i's end at its segment k
        self._ends = np.zeros((0, 2))  # last point of every piece
        self._starts = np.zeros((0, 2))  # first point of every piece
        self._lo = np.zeros((0, 2))  # bounding box of every piece: cheap culling
        self._hi = np.zeros((0, 2))
        self._end_dirs = np.zeros((0, 2))  # _end_direction of every piece (once)
        self._buf = (np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0, dtype=np.int64))
        self._soft = np.zeros(0, dtype=bool)  # segments that block no line (free_lines)
        self.memo: dict = {}  # name -> (len(pieces), answer): see :meth:`remembered`

    def add(self, polyline, pose_first=None, pose_last=None) -> None:
        """Record a piece, (k, 2) float with k >= 2, material on its right,
        with the postures that touched its first and last points."""
        pl = np.ascontiguousarray(np.asarray(polyline, dtype=np.float64).reshape(-1, 2))
        if len(pl) < 2:
            return
        i = len(self.pieces)
        ends = self._ends
        end_dir = _end_direction(pl, self.join)
        self.pieces.append(pl)
        self.poses.append((pose_first, pose_last))
        self._first.append(len(self._a))
        # pieces that continue the new one, and old pieces the new one continues
        # (compiled: the distances and the turn test per segment, first per piece)
        nxt = []
        if len(self._lo):
            p, join = pl[-1], self.join
            out = np.empty(len(self._piece), dtype=np.int64)
            m = continuing(float(p[0]), float(p[1]), join + cull_margin(join, p, p), join,
                           float(end_dir[0]), float(end_dir[1]), self._lo, self._hi,
                           self._piece, self._a, self._b, out)
            nxt = [(int(self._piece[g]), int(g) - self._first[int(self._piece[g])])
                   for g in out[:m].tolist()]
        self._next.append(nxt)
        # only ends within ``join`` of the new piece's bounding box can pass it
        lo, hi = pl.min(axis=0), pl.max(axis=0)
        reach = self.join + cull_margin(self.join, lo, hi)
        if len(ends):
            js = np.empty(len(ends), dtype=np.int64)
            ks = np.empty(len(ends), dtype=np.int64)
            m = continued_ends(ends, self._end_dirs, lo, hi, reach, pl, self.join, js, ks)
            for j, k in zip(js[:m].tolist(), ks[:m].tolist()):
                self._next[j].append((i, k))
        self._append(pl, i)
        self._soft = np.concatenate([self._soft, np.zeros(len(pl) - 1, dtype=bool)])
        self._ends = np.concatenate([ends, pl[-1:]])
        self._starts = np.concatenate([self._starts, pl[:1]])
        self._end_dirs = np.concatenate([self._end_dirs, end_dir[None]])
        self._lo = np.concatenate([self._lo, lo[None]])
        self._hi = np.concatenate([self._hi, hi[None]])

    def _near(self, p, r) -> np.ndarray:
        """Indices (ascending) of the segments of every piece whose bounding
        box lies within ``r`` of point ``p``: no other segment is within ``r``
        (the margin is far above the rounding of the exact distances)."""
        if not len(self._lo):
            return np.zeros(0, dtype=np.int64)
        r = r + cull_margin(r, p, p)
        out = np.empty(len(self._piece), dtype=np.int64)
        return out[:near_segments(float(p[0]), float(p[1]), r, self._lo, self._hi,
                                   self._piece, out)]

    def _within(self, p, r, first_only: bool = False) -> np.ndarray:
        """Indices (ascending) of the segments within ``r`` of point ``p`` (2,) float:
        ``g = self._near(p, r)`` then ``g[point_segment_distances(p, a[g], b[g]) <= r]``,
        the same to the bit, in one compiled pass; ``first_only``: each piece's first."""
        if not len(self._lo):
            return np.zeros(0, dtype=np.int64)
        out = np.empty(len(self._piece), dtype=np.int64)
        return out[:segments_within(float(p[0]), float(p[1]), r + cull_margin(r, p, p),
                                    float(r), self._lo, self._hi, self._piece, self._a,
                                    self._b, first_only, out)]

    def _append(self, pl, i) -> None:
        """Append the segments of piece ``i`` (amortised: buffers grow 2x)."""
        n, k = len(self._a), len(pl) - 1
        a, b, piece = self._buf
        if n + k > len(a):
            cap = max(2 * len(a), n + k, 64)
            grown = tuple(np.empty((cap,) + x.shape[1:], x.dtype) for x in (a, b, piece))
            for old, new in zip((a, b, piece), grown):
                new[:n] = old[:n]
            a, b, piece = self._buf = grown
        a[n:n + k], b[n:n + k], piece[n:n + k] = pl[:-1], pl[1:], i
        self._a, self._b, self._piece = a[:n + k], b[:n + k], piece[:n + k]

    def soften(self, i: int) -> None:
        """Let lines of :meth:`free_lines` pass through piece ``i``: a W2 chord the
        probe went through (:mod:`core2d.planner.openings`); it stays on the map."""
        self._soft[self._first[i]:self._first[i] + len(self.pieces[i]) - 1] = True

    def with_pieces(self, pieces) -> "KnownContour":
        """A copy of the map with ``pieces`` (each (k, 2) float) recorded too."""
        out = KnownContour(self.join)
        out.pieces, out.poses, out._first = list(self.pieces), list(self.poses), list(self._first)
        out._next = [list(nxt) for nxt in self._next]  # the same as adding them again
        for name in ("_ends", "_starts", "_end_dirs", "_lo", "_hi"):
            setattr(out, name, getattr(self, name).copy())
        n = len(self._a)
        out._buf = tuple(x[:n].copy() for x in (self._a, self._b, self._piece))
        out._a, out._b, out._piece = out._buf
        out._soft = self._soft.copy()
        for pl in pieces:
            out.add(pl)
        return out

    def loose_ends(self):
        """Where the recorded contour stops. Every piece runs with the
        material on its right, so unknown contour begins where a piece ends
        and no other piece passes within ``join`` (a loose end), and arrives
        where a piece starts and none passes (a loose start). A finer test
        of where it stops: :func:`core2d.planner.loose_ends.recorded_stops`.

        Returns ``(ends, starts)``: lists of (point (2,) float, Posture or
        None, piece index)."""
        ends, starts = [], []
        for i, pl in enumerate(self.pieces):
            if not self._next[i]:
                ends.append((pl[-1], self.poses[i][1], i))
            if not (self._piece[self._within(pl[0], self.join)] != i).any():
                starts.append((pl[0], self.poses[i][0], i))
        return ends, starts

    def remembered(self, name: str, compute):
        """``compute(self)``, remembered under ``name`` while the map stays as it is.

        The map only grows, one piece per :meth:`add` (a copy, :meth:`with_pieces`,
        starts with nothing remembered), so its number of pieces is its version: an
        answer computed from the map at that version is the answer again. The answer
        is shared: callers must not change it."""
        hit = self.memo.get(name)
        if hit is None or hit[0] != len(self.pieces):
            hit = self.memo[name] = (len(self.pieces), compute(self))
        return hit[1]

    def successors(self, i) -> list:
        """[(j, k)]: piece j passes the last point of piece ``i`` (within
        ``join``, turning less than 120 degrees) at its segment k."""
        return self._next[i]

    def passing(self, point, r) -> list:
        """[(j, k)]: piece j passes within ``r`` of ``point`` (2,), first at its segment k."""
        g = self._within(np.asarray(point, float), float(r), first_only=True)
        first = self._first
        return [(j, k - first[j]) for j, k in zip(self._piece[g].tolist(), g.tolist())]

    def segments(self) -> tuple[np.ndarray, np.ndarray]:
        """(n, 2), (n, 2) float: start and end of every recorded segment."""
        return self._a, self._b

    def distance(self, point) -> float:
        """Distance from ``point`` (2,) to the recorded contour (inf if none)."""
        if len(self._a) == 0:
            return float("inf")
        p = np.asarray(point, float)
        # the nearest piece start bounds the answer; only boxes within it count
        return float(nearest_distance(float(p[0]), float(p[1]), self._starts, self._lo,
                                      self._hi, self._piece, self._a, self._b))

    def nearest_point(self, point) -> np.ndarray | None:
        """(2,) float: the point of the recorded contour nearest ``point`` (None if none)."""
        if len(self._a) == 0:
            return None
        return _nearest_on(self._a, self._b, np.asarray(point, float))

    def runs_along(self, point, r: float, direction) -> bool:
        """Does a recorded segment within ``r`` of ``point`` (2,) run along
        ``direction`` (2,): a positive component on it? (False if none is within ``r``.)"""
        g = self._within(np.asarray(point, float), float(r))
        return bool(len(g)) and bool(((self._b[g] - self._a[g]) @ direction > 0).any())

    def crosses(self, p, q, margin: float) -> bool:
        """Does segment pq cross recorded contour farther than ``margin`` from p and q?"""
        a, b = self._a, self._b
        if len(a) == 0:
            return False
        p, q = np.asarray(p, float), np.asarray(q, float)
        pq = q - p
        n = float(np.hypot(*pq))
        if n <= 2 * margin:
            return False
        u = pq / n
        p2, q2 = p + margin * u, q - margin * u
        d1 = cross2(q2 - p2, a - p2)
        d2 = cross2(q2 - p2, b - p2)
        d3 = cross2(b - a, p2 - a)
        d4 = cross2(b - a, q2 - a)
        return bool(np.any((d1 * d2 <= 0) & (d3 * d4 <= 0) & ((d1 != 0) | (d2 != 0))))

    def covers(self, a, b, tol: float) -> bool:
        """Is C_A^B known: a chain of pieces, each continuing the last within
        ``join``, leading from (within ``tol`` of) A to (within ``tol`` of) B
        in the pieces' direction (B after A along the pieces)?"""
        return self.chain(a, b, tol) is not None

    def hops(self, a, b, tol: float, ends: bool = False) -> list[np.ndarray] | None:
        """The gaps that the chain of :meth:`covers` from A to B hops between two
        pieces, as (2, 2) float segments from the last point of one piece to the
        point where the next passes it (the gap itself, not the distance to that
        piece's first point), in order; None when no chain leads there.
        ``ends``: also the gap from A to the nearest point of the chain (first) and
        from the chain's nearest point to B (last): the chain may start on a piece
        other than A's own, up to ``tol`` away."""
        found = self._chain(a, b, tol, ())
        if found is None:
            return None
        points, gaps = found
        if not ends:
            return gaps
        pa, pb = np.asarray(a, float), np.asarray(b, float)
        a_seg, b_seg = points[:-1], points[1:]
        return [np.stack([pa, _nearest_on(a_seg, b_seg, pa)]), *gaps,
                np.stack([_nearest_on(a_seg, b_seg, pb), pb])]

    def chain(self, a, b, tol: float, exclude=()):
        """The recorded contour from A to B (see :meth:`covers`) as a (k, 2)
        polyline, or None when no chain of pieces leads there; pieces whose
        index is in ``exclude`` are not used."""
        found = self._chain(a, b, tol, exclude)
        return None if found is None else found[0]

    def _chain(self, a, b, tol: float, exclude):
        """:meth:`chain` and :meth:`hops` together, or None."""
        if len(self._a) == 0:
            return None
        pa, pb = np.asarray(a, float), np.asarray(b, float)
        near_a, near_b = self._within(pa, float(tol)), self._within(pb, float(tol))
        if not len(near_a) or not len(near_b):
            return None
        first = np.asarray(self._first)
        pos_b = near_b + segment_params(pb, self._a[near_b], self._b[near_b])  # position along pieces
        best_b = np.full(len(self.pieces), -np.inf)  # farthest position near B, per piece
        np.maximum.at(best_b, self._piece[near_b], pos_b)
        reached, came = {}, {}  # piece -> earliest position reached, and from which piece
        todo = [(int(self._piece[g]), g + float(segment_params(pa, self._a[g:g + 1], self._b[g:g + 1])[0]),
                 None) for g in near_a]
        skip = set(exclude)
        while todo:
            i, pos, prev = todo.pop()
            if i in skip or reached.get(i, np.inf) <= pos:
                continue
            reached[i], came[i] = pos, prev
            if best_b[i] >= pos:
                return self._walk(i, best_b[i], reached, came)
            todo.extend((j, float(first[j] + k), i) for j, k in self._next[i])
        return None

    def _walk(self, last, end_pos, reached, came) -> tuple[np.ndarray, list]:
        """Points of the chain that ends in piece ``last`` at ``end_pos``:
        each piece from where it was reached to its end (or to B); and its
        hops between two pieces ((2, 2) float each)."""
        parts, i, stop, seen = [], last, end_pos, set()
        while i is not None and i not in seen:  # a re-reached piece can close a cycle
            seen.add(i)
            parts.append(self._span(i, reached[i], stop))
            i = came[i]
            if i is not None:
                stop = self._first[i] + len(self.pieces[i]) - 1.0  # that piece's last point
        parts = parts[::-1]
        hops = [np.stack([p[-1], q[0] + segment_params(p[-1], q[:1], q[1:2])[0] * (q[1] - q[0])])
                for p, q in zip(parts, parts[1:])]  # to where q passes p's end
        return np.concatenate(parts), hops

    def _span(self, i, start, stop) -> np.ndarray:
        """Points of piece ``i`` between global segment positions ``start`` and ``stop``."""
        pl, g0 = self.pieces[i], self._first[i]
        s0, s1 = start - g0, max(stop - g0, start - g0)

        def at(x):
            k = int(min(max(np.floor(x), 0), len(pl) - 2))
            return pl[k] + (x - k) * (pl[k + 1] - pl[k])

        inner = pl[int(np.floor(s0)) + 1:int(np.ceil(s1))]
        return np.vstack([at(s0), inner, at(s1)])

    def free_lines(self, a, b, spacing: float, margin: float, min_gap: float,
                   along: float = 0.0) -> FreeLines:
        """Lines from F crossing the open lid A->B from its V side (Def. 3)
        past the recorded contour, one per lid sample with a free gap wider
        than ``min_gap``; empty when none is left (the W3 proof above).

        The lid is sampled every ``spacing`` (at most 512 samples), leaving
        ``margin`` at each touched end. The samples are solved as asked
        (:class:`~core2d.planner.lid_lines.FreeLines`: ``bool``, ``nearest``,
        or the whole list). With ``along`` > 0, segments whose two ends lie
        within ``along`` of the lid's line block nothing.
        """
        a, b = np.asarray(a, float), np.asarray(b, float)
        ab = b - a
        n = float(np.hypot(*ab))
        keep = ~self._soft
        if along > 0 and n > 0:  # |cross(ab, p - a)| / |ab|: the distance to the line
            keep &= ~((np.abs(cross2(ab, self._a - a)) <= along * n)
                      & (np.abs(cross2(ab, self._b - a)) <= along * n))
        seg_a, seg_b = (self._a, self._b) if keep.all() else (self._a[keep], self._b[keep])
        if n <= 2 * margin:
            none = np.zeros((0, 2))
            return FreeLines(none, none, np.zeros(0), seg_a, seg_b, min_gap)
        k = int(min(512, max(2, np.ceil((n - 2 * margin) / spacing) + 1)))
        s = np.linspace(margin, n - margin, k)
        pts = a + (s / n)[:, None] * ab
        tangent = np.broadcast_to(-ab / n, pts.shape)  # B -> A: V_i on its right
        return FreeLines(pts, tangent, s / n, seg_a, seg_b, min_gap)


def _end_direction(pl, span) -> np.ndarray:
    """Direction of a piece's last ``span`` (its first point if shorter): the
    final point may be a touched end a hair behind the last contact."""
    back = np.hypot(*(pl - pl[-1]).T)
    far = np.flatnonzero(back >= span)
    return pl[-1] - pl[far[-1] if len(far) else 0]


def _nearest_on(a: np.ndarray, b: np.ndarray, p: np.ndarray) -> np.ndarray:
    """(2,) float: the point of the segments a -> b ((n, 2) each, n >= 1) nearest ``p``."""
    q = a + segment_params(p, a, b)[:, None] * (b - a)
    return q[int(np.argmin(np.hypot(*(q - p).T)))]
