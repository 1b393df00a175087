"""Free directions from points among segments, by exact angular intervals.

Shared maths: :mod:`core2d.truth.reachability` asks it about the true
contour (is a contour point reachable?), the planner about the contour it
has itself recorded (can any line from F still cross this lid?). Nothing
here knows where the segments came from.

Seen from a point ``p``, every segment not containing ``p`` blocks the
*closed* arc of directions it subtends (a segment always subtends less than
pi). For an *inner* point only the open half-plane of directions on the
right of its tangent ``t`` counts (for a contour point: the outward side,
material on the left), so the arcs are clipped to it; otherwise the whole
circle is used and arcs crossing the +-pi cut are split in two. The answer
is the widest open gap the union of blocked arcs leaves, and the direction
at its middle.

Angles ``psi`` are measured clockwise from ``t`` (inner points) or from +x
shifted by pi (full circle); :func:`free_gaps` returns world angles.

Inner points (the planner's lid question, hundreds of points against
thousands of recorded segments; the ground truth's contour samples) take a
compiled path (numba): the same culling, arcs and gap rule in the same
float64 operations, numpy's ``arctan2`` in between (once per segment end a
point sees: a polyline's shared ends once), without the (points x segments)
temporaries; its answers are bit-identical (tested).

Examples
--------
>>> seg_a, seg_b = np.array([[-1.0, 1.0]]), np.array([[2.0, 1.0]])  # a roof above
>>> # tangent -x: the upper half-plane; the roof blocks 26.6 .. 135 degrees
>>> w, ang = free_gaps(np.zeros((1, 2)), np.array([[-1.0, 0.0]]), seg_a, seg_b)
>>> round(float(np.degrees(w[0])), 3), round(float(np.degrees(ang[0])), 3)
(45.0, 157.5)
"""
from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["free_gaps", "joined_segments", "segmented_gap"]


def segmented_gap(row, st, en, nrows, width, circular=False):
    """Widest open gap of [0, width] left by closed arcs ``[st, en]`` of rows ``row``.

    Parameters
    ----------
    row : (k,) int -- which point each arc belongs to.
    st, en : (k,) float -- arc ends, within [0, width].
    nrows : int -- number of points.
    width : float -- the range of directions (pi or 2 pi).
    circular : bool -- join the gaps at both ends (full circle).

    Returns
    -------
    gap : (nrows,) float -- widest gap.
    mid : (nrows,) float -- position of its middle in [0, width).
    """
    order = np.argsort(row, kind="stable")
    row, st, en = row[order], st[order], en[order]
    counts = np.bincount(row, minlength=nrows)
    pos = np.arange(len(row)) - (np.cumsum(counts) - counts)[row]
    shape = (nrows, max(int(counts.max(initial=0)), 1))
    s = np.full(shape, np.inf)  # padding: empty arcs, sorted last
    e = np.full(shape, -np.inf)
    s[row, pos], e[row, pos] = st, en
    order = np.argsort(s, axis=1)
    s = np.minimum(np.take_along_axis(s, order, axis=1), width)  # padding opens no gap
    e = np.maximum(np.maximum.accumulate(np.take_along_axis(e, order, axis=1), axis=1), 0.0)
    lead, trail = s[:, 0], width - e[:, -1]
    # candidate gaps: before the first arc, after the last, between arcs, wrapped
    cand = [lead, trail]
    mids = [lead / 2, e[:, -1] + trail / 2]
    if shape[1] > 1:
        inner = s[:, 1:] - e[:, :-1]
        k = np.argmax(inner, axis=1)
        r = np.arange(nrows)
        cand.append(inner[r, k])
        mids.append(e[r, k] + inner[r, k] / 2)
    if circular:
        cand.append(lead + trail)
        mids.append((e[:, -1] + (lead + trail) / 2) % width)
    cand, mids = np.stack(cand), np.stack(mids)
    best = np.argmax(cand, axis=0)
    r = np.arange(nrows)
    return np.clip(cand[best, r], 0.0, width), mids[best, r]


def free_gaps(points, tangents, seg_a, seg_b, inner=None, own=None, atol=0.0,
              chunk: int = 500_000, joined=None):
    """Widest open gap of free directions at each point, and its middle.

    Parameters
    ----------
    points : (c, 2) float
    tangents : (c, 2) float -- unit tangent per point; for inner points the
        free half-plane is on its right (clockwise side).
    seg_a, seg_b : (n, 2) float -- blocking segments.
    inner : (c,) bool, optional -- half-plane (True, default) or whole
        circle (False) of directions.
    own : (c,) int, optional -- a segment each point lies on (ignored for
        that point), -1 for none.
    atol : float -- segments within ``atol`` of the point block nothing.
    chunk : int -- points x segments pairs handled at once (memory bound).
    joined : (n,) bool, optional -- :func:`joined_segments` of the segments, when the
        caller asks about the same segments many times (computed here otherwise).

    Returns
    -------
    width : (c,) float -- in [0, pi] for inner points, [0, 2 pi] otherwise.
    angle : (c,) float -- world direction angle of the gap's middle.
    """
    p = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    c = len(p)
    a = np.asarray(seg_a, dtype=np.float64).reshape(-1, 2)
    b = np.asarray(seg_b, dtype=np.float64).reshape(-1, 2)
    inner = np.ones(c, dtype=bool) if inner is None else np.asarray(inner, dtype=bool)
    tg = np.broadcast_to(np.asarray(tangents, dtype=np.float64).reshape(-1, 2), (c, 2))
    own = None if own is None else np.asarray(own, dtype=np.int64)
    step = max(1, chunk // max(len(a), 1))
    if c > step:
        parts = [free_gaps(p[i:i + step], tg[i:i + step], a, b, inner[i:i + step],
                           None if own is None else own[i:i + step], atol, chunk, joined)
                 for i in range(0, c, step)]
        return np.concatenate([w for w, _ in parts]), np.concatenate([g for _, g in parts])
    if inner.all() and len(a):
        tx, ty = np.array(tg[:, 0]), np.array(tg[:, 1])  # writable copies: one signature
        atol = float(atol)
        own = np.full(c, -1, np.int64) if own is None else np.ascontiguousarray(own)
        k = c * len(a)  # at most ``chunk`` pairs: room for all, one pass
        row, ends = np.empty(k, np.int64), np.empty((k, 2), np.int64)
        y, x = np.empty(2 * k), np.empty(2 * k)
        joined = joined_segments(a, b) if joined is None else joined
        k, v = _kept_pairs(p, tx, ty, a, b, atol, own, joined, row, ends, y, x)
        width, psi = np.empty(c), np.empty(c)
        ps = np.arctan2(y[:v], x[:v], out=y[:v])  # numpy's, as below; in place
        _row_gaps(row[:k], ends[:k], np.negative(ps, out=ps), width, psi)
        angle = np.arctan2(ty, tx) - psi
        return width, (angle + np.pi) % (2 * np.pi) - np.pi
    return _vectorised(p, tg, a, b, inner, own, atol)


def joined_segments(seg_a, seg_b) -> np.ndarray:
    """(n,) bool: segment j starts where segment j - 1 ends (``seg_a[j] == seg_b[j - 1]``).

    >>> joined_segments(np.array([[0., 0.], [1., 0.], [5., 5.]]),
    ...                 np.array([[1., 0.], [2., 0.], [6., 5.]])).tolist()
    [False, True, False]
    """
    a = np.asarray(seg_a, dtype=np.float64).reshape(-1, 2)
    b = np.asarray(seg_b, dtype=np.float64).reshape(-1, 2)
    joined = np.zeros(len(a), dtype=np.bool_)
    joined[1:] = (a[1:] == b[:-1]).all(axis=1)
    return joined


def _vectorised(p, tg, a, b, inner, own, atol):
    """:func:`free_gaps` on (points x segments) arrays, for any points (the
    compiled path takes inner points only)."""
    c = len(p)
    tx = np.where(inner, tg[:, 0], 1.0)
    ty = np.where(inner, tg[:, 1], 0.0)
    # cross(t, v) >= 0 at both ends (v = end - p): the segment lies in the
    # closed left half-plane and cannot block a ray to the right. Culled
    # densely, the rest is done on the kept pairs only.
    k = (tx * p[:, 1] - ty * p[:, 0])[:, None]
    ca = np.outer(tx, a[:, 1]) - np.outer(ty, a[:, 0]) - k
    cb = np.outer(tx, b[:, 1]) - np.outer(ty, b[:, 0]) - k
    keep = (ca < 0) | (cb < 0)
    keep[~inner] = True
    if own is not None:
        has = own >= 0
        keep[np.flatnonzero(has), own[has]] = False
    row, col = np.nonzero(keep)
    del keep, k, ca, cb
    pr = p[row]
    va, vb = a[col] - pr, b[col] - pr
    e = vb - va
    l2 = np.einsum("ij,ij->i", e, e)
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.nan_to_num(np.clip(-np.einsum("ij,ij->i", va, e) / l2, 0.0, 1.0))
    far = np.hypot(*(va + t[:, None] * e).T) > atol
    row, va, vb = row[far], va[far], vb[far]
    txr, tyr = tx[row], ty[row]
    # psi: angle measured clockwise from t; the right side is psi in (0, pi)
    psa = -np.arctan2(txr * va[:, 1] - tyr * va[:, 0], txr * va[:, 0] + tyr * va[:, 1])
    psb = -np.arctan2(txr * vb[:, 1] - tyr * vb[:, 0], txr * vb[:, 0] + tyr * vb[:, 1])
    lo = np.minimum(psa, psb)
    hi = np.maximum(psa, psb)
    wrap = hi - lo > np.pi  # the short arc crosses the +-pi cut
    width = np.empty(c)
    psi = np.empty(c)
    rin = inner[row]
    # inner points: clip arcs to the right half-plane [0, pi]
    st = np.where(wrap, np.maximum(hi, 0.0), np.maximum(lo, 0.0))
    en = np.where(wrap, np.pi, hi)
    m = rin & (en > st)
    width[inner], psi[inner] = segmented_gap(np.cumsum(inner)[row[m]] - 1, st[m], en[m],
                                             int(inner.sum()), np.pi)
    if (~inner).any():  # whole circle, arcs split at the cut, shifted to [0, 2 pi]
        vidx = np.cumsum(~inner) - 1
        m = ~rin
        r1 = vidx[row[m]]
        st1 = np.where(wrap[m], hi[m], lo[m]) + np.pi
        en1 = np.where(wrap[m], np.pi, hi[m]) + np.pi
        w = m.copy()
        w[m] = wrap[m]
        r2 = vidx[row[w]]
        st2 = np.zeros(int(w.sum()))
        en2 = lo[w] + np.pi
        nv = int((~inner).sum())
        rr, ss, ee = np.r_[r1, r2], np.r_[st1, st2], np.r_[en1, en2]
        width[~inner], shifted = segmented_gap(rr, ss, ee, nv, 2 * np.pi, circular=True)
        psi[~inner] = shifted - np.pi
    angle = np.arctan2(ty, tx) - psi
    return width, (angle + np.pi) % (2 * np.pi) - np.pi



@numba.njit(cache=True, nogil=True, error_model="numpy")
def _kept_pairs(p, tx, ty, a, b, atol, own, joined, out_row, out_ends, out_y,
                out_x):  # pragma: no cover
    """(point, segment) pairs of :func:`free_gaps` for inner points, culled
    as the vectorised path does (same float64 operations), in its order;
    segment ``own[r]`` of point r (-1: none) is ignored.

    It writes the row of each pair, the ``arctan2`` arguments of the segment
    ends it sees (``out_y``, ``out_x`` : (2 k,), room for every end) and which
    of them are each pair's two ends (``out_ends`` : (k, 2)). A segment that
    starts where the one before it ends (``joined``: the map's polylines, ~92 %
    of its segments) shares that end's entry when both are kept for the same
    point: the same floats give the same arguments, so up to half the
    ``arctan2`` calls are saved and every angle is the one computed per end.
    Returns the number of pairs and of ends.
    """
    m = 0
    v = 0
    far2, near2 = (atol * (1 + 1e-9)) ** 2, (atol * (1 - 1e-9)) ** 2
    for r in range(p.shape[0]):
        px, py, txr, tyr = p[r, 0], p[r, 1], tx[r], ty[r]
        k = txr * py - tyr * px
        skip = own[r]
        last = -2  # the last segment kept for this point
        for j in range(a.shape[0]):
            if j == skip:
                continue
            ax, ay, bx, by = a[j, 0], a[j, 1], b[j, 0], b[j, 1]
            if not (txr * ay - tyr * ax - k < 0 or txr * by - tyr * bx - k < 0):
                continue
            vax, vay, vbx, vby = ax - px, ay - py, bx - px, by - py
            ex, ey = vbx - vax, vby - vay
            t = -(vax * ex + vay * ey) / (ex * ex + ey * ey)
            t = 0.0 if t < 0.0 else (1.0 if t > 1.0 else t)
            if t != t:  # nan (zero-length segment)
                t = 0.0
            qx, qy = vax + t * ex, vay + t * ey
            if atol == 0.0:  # hypot(q) > 0 without the hypot (finite q)
                if not ((qx != 0.0 or qy != 0.0) and qx == qx and qy == qy):
                    continue
            else:  # hypot(q) > atol; the hypot only within 1e-9 of atol
                q2 = qx * qx + qy * qy
                if not q2 > far2 and (q2 < near2 or not math.hypot(qx, qy) > atol):
                    continue
            out_row[m] = r
            if last == j - 1 and joined[j]:  # A_j is B_{j-1}, seen from this point
                out_ends[m, 0] = v - 1
            else:
                out_y[v] = txr * vay - tyr * vax
                out_x[v] = txr * vax + tyr * vay
                out_ends[m, 0] = v
                v += 1
            out_y[v] = txr * vby - tyr * vbx
            out_x[v] = txr * vbx + tyr * vby
            out_ends[m, 1] = v
            v += 1
            last = j
            m += 1
    return m, v


@numba.njit(cache=True, nogil=True)
def _row_gaps(row, ends, ps, width, psi):  # pragma: no cover - compiled
    """Widest gap in [0, pi] per point from the arcs ``ps[ends]`` (k, 2) of the
    pairs ``row`` (ascending): :func:`segmented_gap`'s rule, row by row."""
    st = np.empty(row.shape[0])
    en = np.empty(row.shape[0])
    head = np.empty(row.shape[0] + 1, np.int64)
    link = np.empty(row.shape[0], np.int64)
    q0 = 0
    for r in range(width.shape[0]):
        m = 0
        while q0 < row.shape[0] and row[q0] == r:
            pa, pb = ps[ends[q0, 0]], ps[ends[q0, 1]]
            lo, hi = min(pa, pb), max(pa, pb)
            if hi - lo > np.pi:  # the short arc crosses the +-pi cut
                s0, e0 = max(hi, 0.0), np.pi
            else:
                s0, e0 = max(lo, 0.0), hi
            if e0 > s0:
                st[m] = s0
                en[m] = e0
                m += 1
            q0 += 1
        if m == 0:
            width[r], psi[r] = np.pi, np.pi / 2
            continue
        order = _order(st, m, head, link)
        lead = min(st[order[0]], np.pi)
        acc = -np.inf
        best, mid = lead, lead / 2
        gap_in, mid_in = -np.inf, 0.0
        for q in range(m):
            i = order[q]
            if q > 0:
                g = min(st[i], np.pi) - max(acc, 0.0)
                if g > gap_in:
                    gap_in, mid_in = g, max(acc, 0.0) + g / 2
            acc = max(acc, en[i])
        last = max(acc, 0.0)
        trail = np.pi - last
        if trail > best:
            best, mid = trail, last + trail / 2
        if gap_in > best:
            best, mid = gap_in, mid_in
        width[r] = min(max(best, 0.0), np.pi)
        psi[r] = mid


@numba.njit(cache=True, nogil=True)
def _order(st, m, head, link):  # pragma: no cover - compiled
    """Indices sorting ``st[:m]`` (values in [0, pi]) ascending: bucket sort
    into m buckets, each bucket sorted by insertion (ties in any order)."""
    for q in range(m + 1):
        head[q] = -1
    scale = m / np.pi
    for i in range(m - 1, -1, -1):  # lists keep the original order
        q = min(int(st[i] * scale), m)
        link[i] = head[q]
        head[q] = i
    out = np.empty(m, np.int64)
    n = 0
    for q in range(m + 1):
        first = n
        i = head[q]
        while i >= 0:
            v = st[i]
            k = n
            while k > first and st[out[k - 1]] > v:
                out[k] = out[k - 1]
                k -= 1
            out[k] = i
            n += 1
            i = link[i]
    return out
