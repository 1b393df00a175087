"""The free space the probe's motions swept, and the closed region carved by it.

The rod does not penetrate the object (§3.2): every place it occupied during a motion is free
space. A motion's row of :class:`core2d.motionlog.MotionLog` gives its kind and the postures
before and after, and each kind of the probe protocol sweeps a known area between them:

* ``swing`` / ``turn`` -- a rotation about the joint P: the sector of radius L about P
  between the two probe angles;
* ``pivot`` -- a rotation about the tip (Definition 1's single probe detection): the sector
  of radius L about the tip, between the two directions back to the joint;
* ``translate`` -- the joint along v with t kept: the parallelogram of the two postures;
* ``insert`` -- along t: the segment from the joint before to the tip after;
* ``approach`` (a free transfer whose path is not logged) and ``trace`` (a compliant slide
  whose intermediate postures are not logged): the posture after only.

The postures are the ones the joint sensors reported (``MotionLog.seen``), the one before a
motion the one reported after the motion before it: what the robot knows of where it has
been, not the simulator's truth. Arcs are sampled by chords (inside the arc), no farther than
``sag`` from it.

:func:`carve` is the closure's last step for a noisy sensor (:mod:`recon3d.surface.closure`,
step 4): the closed region, less the swept area that lies away from every sensed piece.

Examples
--------
>>> import numpy as np
>>> from core2d.motionlog import MotionLog
>>> pose = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, np.pi / 2]])  # a quarter turn about the joint
>>> log = MotionLog(kind=np.array([3], np.int8), before=pose[:1], after=pose[1:],
...                 seen=pose[1:], tip=np.array([[0.0, 2.0]]))
>>> area = swept_areas(log, length=2.0, sag=1e-4)
>>> round(float(area[0].area), 3)  # pi * 2 ** 2 / 4
3.141
"""
from __future__ import annotations

import numpy as np
import shapely

from core2d.motionlog import KINDS

__all__ = ["swept_areas", "carve", "probe_length", "unit"]

_KIND = {k: i for i, k in enumerate(KINDS)}
_ABOUT_JOINT = (_KIND["swing"], _KIND["turn"])
_ABOUT_TIP = _KIND["pivot"]
_SLIDE = _KIND["translate"]
_INSERT = _KIND["insert"]
_FULL = 2.0 * np.pi - 1e-9
_QUAD = 2
"""Segments per quarter circle of the carve's buffers (their round ends are snap to close
across: a coarser arc moves them by a few percent of that)."""
_REACH = np.cos(np.pi / 4)
"""The zone kept round the sensed pieces is their buffers by snap + jitter: exact along their
segments, but a buffer's round ends and bends are chords of the circle, cos(pi / 8) of the
radius from the end at the chords' middles, and GEOS may span a bend by one chord up to 90
degrees wide, cos(pi / 4) of it from the vertex. A zone that reaches snap + jitter everywhere
(circumscribed discs about the points) was measured and not kept: F@1 % lower on five scenes
at sigma 0.3 + T 0.25 (up to 0.005) and none higher, 4 x the cost (docs/notes/noise.md)."""


def probe_length(motions) -> float:
    """The probe's length L from a motion log (its tips and joints); 0 without motions."""
    if motions is None or not len(motions):
        return 0.0
    return float(np.median(np.hypot(*(motions.tip - motions.after[:, :2]).T)))


def _postures(motions) -> tuple[np.ndarray, np.ndarray]:
    """(n, 3) before and after: the reported postures (the first motion's before is the
    start, which the robot commanded)."""
    after = np.asarray(motions.seen, dtype=np.float64)
    before = np.vstack([motions.before[:1], after[:-1]])
    return before, after


def unit(theta: np.ndarray) -> np.ndarray:
    """(n, 2) float: the unit vectors of angles ``theta`` (n,)."""
    return np.stack([np.cos(theta), np.sin(theta)], axis=-1)


def _sectors(center: np.ndarray, a0: np.ndarray, a1: np.ndarray, length: float,
             sag: float) -> np.ndarray:
    """(r,) Polygons: sectors about ``center`` (r, 2) of radius ``length`` from angle ``a0``
    to ``a1`` (r,), the arc by chords no farther than ``sag`` from it."""
    if not len(center):
        return np.zeros(0, dtype=object)
    step = 2.0 * np.arccos(np.clip(1.0 - sag / length, -1.0, 1.0))
    a1 = a0 + np.clip(a1 - a0, -_FULL, _FULL)  # a full turn or more sweeps the disc
    q = np.ceil(np.abs(a1 - a0) / step).astype(np.int64) + 1  # arc points, ends included
    q = np.maximum(q, 2)
    row = np.repeat(np.arange(len(center)), q + 1)
    at = np.arange(len(row)) - np.repeat(np.cumsum(q + 1) - (q + 1), q + 1)  # 0 .. q
    frac = (at - 1) / np.maximum(q[row] - 1, 1)
    ang = a0[row] + frac * (a1 - a0)[row]
    pts = center[row] + length * unit(ang)
    pts[at == 0] = center  # the centre first, then the arc
    return shapely.polygons(shapely.linearrings(pts, indices=row))


def swept_areas(motions, length: float, sag: float) -> np.ndarray:
    """(n,) shapely geometries: what each motion of ``motions`` swept (module doc).

    Parameters
    ----------
    motions : core2d.motionlog.MotionLog
    length : float -- the probe's length L (:func:`probe_length`).
    sag : float -- largest distance of an arc's chords from the arc.

    Returns
    -------
    (n,) object array of Polygons (rotations, translations) and LineStrings (the rest).
    """
    n = 0 if motions is None else len(motions)
    if not n or length <= 0:
        return np.zeros(0, dtype=object)
    kind = np.asarray(motions.kind)
    before, after = _postures(motions)
    out = shapely.linestrings(np.stack([after[:, :2], after[:, :2] + length * unit(after[:, 2])],
                                       axis=1))
    ins = np.flatnonzero(kind == _INSERT)
    out[ins] = shapely.linestrings(np.stack(
        [before[ins, :2], after[ins, :2] + length * unit(after[ins, 2])], axis=1))
    rot = np.flatnonzero(np.isin(kind, _ABOUT_JOINT) & (before[:, 2] != after[:, 2]))
    out[rot] = _sectors(after[rot, :2], before[rot, 2], after[rot, 2], length, sag)
    piv = np.flatnonzero((kind == _ABOUT_TIP) & (before[:, 2] != after[:, 2]))
    tip = before[piv, :2] + length * unit(before[piv, 2])
    out[piv] = _sectors(tip, before[piv, 2] + np.pi, after[piv, 2] + np.pi, length, sag)
    slide = np.flatnonzero(kind == _SLIDE)
    if len(slide):
        t = length * unit(before[slide, 2])
        p0, p1 = before[slide, :2], after[slide, :2]
        quad = shapely.polygons(np.stack([p0, p0 + t, p1 + t, p1, p0], axis=1))
        d = p1 - p0
        moved = d[:, 0] * t[:, 1] != d[:, 1] * t[:, 0]  # a parallelogram with an area
        out[slide[moved]] = quad[moved]
    return out


def carve(geometry, sensed, swept, snap: float, jitter: float, close: float):
    """The closed region ``geometry`` less what the probe swept away from the sensed pieces.

    A noisy sensor's loose ends are bridged closest first, and a bridge can close free space
    the probe went through (a slot's mouth bridged, the slot filled; a chamber behind a neck
    filled from the neck's lid). The swept areas, each widened by ``snap`` (a posture's line
    has none), closed by ``close`` (gaps between them narrower than ``2 close`` are below the
    method's resolution and taken as swept), are free: they are cut from the region, except
    within ``snap + jitter`` of a sensed piece, as far as a reading can lie from the surface
    the probe touched (at a piece's ends and bends the zone reaches ``_REACH`` of that at
    least: its buffer's arcs are chords). Swept areas that do not come within ``snap + close`` of what is cut
    are left out of the closing (a gap they would fill lies at its edge).

    Parameters
    ----------
    geometry : shapely (Multi)Polygon -- the closed region.
    sensed : list of (k, 2) float -- W1 polylines, W2 segments, W3 lids.
    swept : (s,) shapely geometries -- :func:`swept_areas`.
    snap, jitter, close : float -- lengths.

    Returns
    -------
    shapely (Multi)Polygon
    """
    if geometry.is_empty or not len(swept):
        return geometry
    inner = geometry
    if len(sensed):
        lines = shapely.linestrings(np.concatenate(sensed),
                                    indices=np.repeat(np.arange(len(sensed)),
                                                      [len(p) for p in sensed]))
        # the union of the pieces' own buffers: a tenth of the cost of buffering their union
        near_wall = shapely.union_all(shapely.buffer(lines, snap + jitter, quad_segs=_QUAD))
        inner = geometry.difference(near_wall)
    if inner.is_empty:
        return geometry
    # closing = dilation, union, erosion; a dilation of a union is the union of the
    # dilations, so each area is widened by snap + close on its own (cheap), and only the
    # ones that then reach the region are united and eroded
    wide = shapely.buffer(swept, snap + close, quad_segs=_QUAD)
    shapely.prepare(inner)
    wide = wide[shapely.intersects(inner, wide)]
    if not len(wide):
        return geometry
    free = shapely.union_all(wide)
    if close > 0:
        free = shapely.buffer(free, -close, quad_segs=_QUAD)
    cut = geometry.difference(free.intersection(inner))
    if cut.geom_type == "GeometryCollection":  # a difference can leave lines beside the faces
        cut = shapely.union_all([g for g in shapely.get_parts(cut)
                                 if g.geom_type in ("Polygon", "MultiPolygon")])
    return cut if cut.geom_type in ("Polygon", "MultiPolygon") else shapely.Polygon()
