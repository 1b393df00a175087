"""The back of a thin wall under a noisy sensor: a lid behind recorded contour.

A split at a contact on the far wall of a slit can make a child whose lid runs along contour
the robot recorded from B_i to A_i; :func:`core2d.planner.along.reversed_lid` closes such an
area as traced when the chain of pieces from B_i to A_i lies within the same-contact radius
eps/2 + the sensor's jitter of the lid (Hausdorff distance). By distance alone the two faces
of a wall thinner than that radius are one: ``trimesh_octagonal_pocket`` z0 and z7 hold an
outer wall 0.7 eps thick beside a slit 2.67 eps wide, its outer face traced from bottom to top
(material on its right), and at sigma 0.1 eps (radius 0.92 eps) the areas laid along the
slit's side of the wall, lids from top to bottom, were closed as "the lid lies on contour
recorded from B to A" one after another and the face was never recorded (0.958 - 0.992
coverage on those slices over three sensor seeds, 1.0 noiseless; docs/notes/noise.md).

The map's pieces run with the material on their right (Definition 3). A reading of a recorded
surface lies on its line within the sensor's jitter; a point deeper than that on the material
side of the recorded piece's local line is on another surface -- the back of the wall, which
the probe reached from the other side. :func:`behind_recorded` asks that of every piece
within the radius: the local line is the piece's chord over its points within ``WINDOW`` eps
of the point (its mean point, its direction first to last: the trace's scatter averages out),
and the point must project inside that chord (past a piece's end the surface may turn round a
convex corner). A lid whose middle lies behind the chain so is not closed as traced: it goes
on through the revisit. Perfect sensing (jitter 0) is unchanged.

The rod tells the faces apart too: it cannot lie inside material, so a contact whose probe
lies behind a recorded piece's line (:func:`touched_from_behind`: the rod's point eps back
from the contact deeper than the jitter on the piece's material side) was made on another
surface, however close to the record it reads. ``numerics`` seed 2 at sigma 0.1 eps: the
Theorem 1 pass of an area laid along a needle's upper face, where the needle is thinner
than ``near`` (0.2 eps), touched the upper face within ``near`` of the lower face's record
and was deferred as "touched recorded contour"; the needle's tip was never touched
(0.970 - 0.9715 of the reachable contour, 1.000 noiselessly).
"""
from __future__ import annotations

import numpy as np

from core2d.planner.known import KnownContour
from core2d.resolution import Resolution

__all__ = ["behind_recorded", "far_face", "far_face_means", "touched_from_behind", "WINDOW"]

#: the local line of a recorded piece: its points within this many eps of the contact
WINDOW = 1.5
#: cos 45 degrees: two faces turned from each other by more than 135 degrees run against
_COS_WALL = 2.0 ** -0.5


def _local_chord(pl, p, window):
    """The local line of recorded piece ``pl`` (k, 2) at ``p``: (its points from the first to
    the last within ``window`` of ``p``, the unit direction and the length of their chord);
    None with fewer than two such points."""
    idx = np.flatnonzero(np.hypot(*(pl - p).T) <= window)
    if len(idx) < 2:
        return None
    run = pl[idx.min():idx.max() + 1]
    chord = run[-1] - run[0]
    length = float(np.hypot(*chord))
    return (run, chord / length if length > 0 else chord, length)


def far_face(known: KnownContour, res: Resolution, point, face, radius: float) -> bool:
    """Was ``point`` (2,) recorded on a surface facing away from ``face``: does every
    recorded piece within ``radius`` of it whose local line is readable run against
    ``face`` (a unit (2,) direction with the material on its right, as the map's pieces
    run), turned from it by more than 135 degrees, and is there at least one?

    The two faces of a wall run antiparallel (material between them); one face, or two
    faces across a concave corner, turn by less. Unlike a depth, the turn does not need
    the wall thicker than the sensor's jitter (:func:`~core2d.planner.hops.across_wall`):
    a local line (the chord of a piece's points within ``WINDOW`` eps) as long as the
    jitter or longer has its direction within 45 degrees (its two ends each within half
    the jitter of the contour), the margin between 135 degrees and a wall's 180; shorter
    ones are skipped (and with perfect sensing, those shorter than the trace's sampling
    eps/4). At the stop on ``numerics`` seed 0's needle at sigma 0.3 eps, taxels 0.25 eps
    the recorded faces ran at cos -0.91 .. -1.00 to the face slid along, over 0.47 - 0.90
    eps; with eps/2 asked, ``numerics`` seed 2's needle tip, recorded over 0.29 and 0.38
    eps, was missed noiselessly (0.972 of its reachable contour covered, against 1.000).

    >>> res = Resolution.of(1.0, noise=0.075, taxel=0.25)  # sigma 0.3 eps over 16 reads
    >>> k = KnownContour(join=0.5)
    >>> k.add([[x, -0.3] for x in np.arange(6.0, -0.1, -0.5)])  # a wall's lower face
    >>> far_face(k, res, [3.0, -0.3], np.array([1.0, 0.0]), res.tip_zone)  # its upper face
    True
    >>> far_face(k, res, [3.0, -0.3], np.array([-1.0, 0.0]), res.tip_zone)  # the same face
    False
    >>> far_face(k, res, [9.0, -0.3], np.array([1.0, 0.0]), res.tip_zone)  # nothing recorded
    False
    """
    return len(far_face_means(known, res, point, face, radius)) > 0


def far_face_means(known: KnownContour, res: Resolution, point, face,
                   radius: float) -> np.ndarray:
    """(k, 2) float: the mean points of the local lines :func:`far_face` read at ``point``
    (the recorded far face, one row per piece), or (0, 2) when ``point`` was not recorded
    on a face running against ``face``.

    A local line's mean point averages its readings (``WINDOW`` eps of them): where the
    single reading ``point`` lies within the jitter of the face slid along, on either side,
    the mean tells the side the far face lies on -- behind the face (a wall's far face) or
    in front of it (a slit's far wall) -- to the jitter over the square root of its
    readings (:func:`~core2d.planner.hops.across_wall`). With perfect sensing (jitter 0)
    ``point`` is exact and tells the side itself: it is returned, one row, where
    :func:`far_face` holds (perfect sensing is left as it was).

    >>> res = Resolution.of(1.0, noise=0.075, taxel=0.25)
    >>> k = KnownContour(join=0.5)
    >>> k.add([[x, -0.1] for x in np.arange(6.0, -0.1, -0.5)])  # a wall's lower face
    >>> far_face_means(k, res, [3.0, 0.1], np.array([1.0, 0.0]), res.tip_zone).round(2)
    array([[ 3. , -0.1]])
    """
    p = np.asarray(point, dtype=np.float64)
    means = []
    for j, _ in known.passing(p, radius):
        line = _local_chord(known.pieces[j], p, WINDOW * res.eps)
        if line is None or line[2] < max(res.fan_spacing, res.jitter):
            continue  # too short to read its direction to 45 degrees
        if float(line[1] @ face) > -_COS_WALL:
            return np.zeros((0, 2))
        means.append(line[0].mean(axis=0))
    if means and res.jitter == 0:
        return p[None]
    return np.array(means).reshape(-1, 2)


def behind_recorded(known: KnownContour, res: Resolution, point, radius: float) -> bool:
    """With a noisy sensor: does ``point`` (2,) lie on the material side of every recorded
    piece within ``radius`` of it, deeper than the sensor's jitter behind its local line?

    >>> res = Resolution.of(1.0, noise=0.1)
    >>> k = KnownContour(join=0.5)
    >>> k.add([[x, 0.0] for x in np.arange(0.0, 6.1, 0.5)])  # material below y = 0
    >>> behind_recorded(k, res, [3.0, -0.5], res.near)  # 0.5 deep: the wall's other face
    True
    >>> behind_recorded(k, res, [3.0, 0.3], res.near)  # the free side
    False
    >>> behind_recorded(k, res, [3.0, -0.3], res.near)  # within the jitter: a reading of it
    False
    """
    return _behind_every(known, res, point, point, radius)


def touched_from_behind(known: KnownContour, res: Resolution, point, joint) -> bool:
    """With a noisy sensor: was the contact ``point`` (2,) reached by a probe whose body
    lies behind every recorded piece within ``near`` of it -- the rod's point eps back
    from the contact (towards ``joint``) on the piece's material side, deeper than the
    jitter behind its local line? Then the contact is not a reading of that piece (the
    rod cannot lie inside its material) but of another surface: the far face of a wall
    thinner than ``near``.

    >>> res = Resolution.of(1.0, noise=0.1)
    >>> k = KnownContour(join=0.5)
    >>> k.add([[x, 0.0] for x in np.arange(6.0, -0.1, -0.5)])  # material above y = 0
    >>> touched_from_behind(k, res, [3.0, 0.05], [3.0, 40.0])  # from above: the far face
    True
    >>> touched_from_behind(k, res, [3.0, -0.05], [3.0, -40.0])  # from below: the face
    False
    """
    p = np.asarray(point, dtype=np.float64)
    back = np.asarray(joint, dtype=np.float64) - p
    return _behind_every(known, res, p, p + back / np.hypot(*back) * res.eps, res.near)


def _behind_every(known: KnownContour, res: Resolution, at, point, radius: float) -> bool:
    """With a noisy sensor: is ``point`` (2,) deeper than the jitter on the material side of
    the local line at ``at`` (2,) of every recorded piece within ``radius`` of ``at`` (at
    least one; each line at least eps long, ``at`` projecting inside it)?"""
    if res.jitter == 0:
        return False
    at = np.asarray(at, dtype=np.float64)
    hits = known.passing(at, radius)
    if not hits:
        return False
    for j, _ in hits:
        line = _local_chord(known.pieces[j], at, WINDOW * res.eps)
        if line is None or line[2] < res.eps:
            return False
        run, u, length = line
        if not 0.0 <= float((at - run[0]) @ u) <= length:
            return False  # past the chord's ends
        depth = float((run.mean(axis=0) - point) @ np.array([-u[1], u[0]]))
        if depth <= res.jitter:
            return False
    return True
