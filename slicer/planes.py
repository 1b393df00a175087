"""Slice planes, their 2D frames, and plane families.

A :class:`SlicePlane` is the plane ``{p : p . normal == offset}`` with an
orthonormal right-handed frame ``(u, v, normal)`` and a 2D origin on the
plane, so that a 2D point ``(x, y)`` is the 3D point ``origin + x u + y v``.

Frames
------
For the axis normals the frame is cyclic: ``z -> (u, v) = (x, y)``,
``x -> (y, z)``, ``y -> (z, x)``. For any other unit normal ``n`` let ``i``
be the index of its largest absolute component (lowest index on ties);
then ``u`` is the world axis ``e[(i + 1) % 3]`` made orthogonal to ``n``
(Gram-Schmidt, normalised) and ``v = n x u``. This choice is deterministic,
continuous near the axis directions, and reduces to the axis frames above.

Origins
-------
Every plane of a family takes as origin the orthogonal projection of one
reference point (by default the centre of the mesh bounding box) onto the
plane, so origins are near the middle of each cross-section, which keeps
float32 (Embree) coordinates small.

Examples
--------
>>> import numpy as np
>>> bounds = np.array([[0.0, 0.0, 0.0], [1.0, 2.0, 4.0]])
>>> [float(p.offset) for p in make_planes(bounds, axis="z", count=4)]
[0.5, 1.5, 2.5, 3.5]
>>> p = make_planes(bounds, axis="x", count=1)[0]
>>> p.u.tolist(), p.v.tolist(), p.to_3d(np.array([[1.0, 2.0]])).tolist()
([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [[0.5, 2.0, 4.0]])
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = [
    "SlicePlane",
    "parse_axis",
    "frame_for_normal",
    "extent_along",
    "make_planes",
]


@dataclass(frozen=True, eq=False)
class SlicePlane:
    """One cutting plane with its 2D frame.

    Attributes
    ----------
    index : int
        Position of the plane in its family.
    origin : (3,) float
        2D origin, a point of the plane.
    normal : (3,) float
        Unit normal.
    u, v : (3,) float
        In-plane unit axes, ``u x v == normal``.
    offset : float
        Signed distance of the plane along ``normal``: ``origin . normal``.
    nudge : float
        How far the plane was moved along ``normal`` to avoid a degenerate
        cut (0.0 when it was not moved); see :mod:`slicer.degenerate`.
    nudge_reason : str
        Why it was moved ("" when it was not).
    """

    index: int
    origin: np.ndarray
    normal: np.ndarray
    u: np.ndarray
    v: np.ndarray
    offset: float
    nudge: float = 0.0
    nudge_reason: str = ""

    def __post_init__(self):
        for name in ("origin", "normal", "u", "v"):
            arr = np.array(getattr(self, name), dtype=np.float64).reshape(3)
            arr.flags.writeable = False
            object.__setattr__(self, name, arr)
        object.__setattr__(self, "offset", float(self.offset))
        object.__setattr__(self, "nudge", float(self.nudge))

    @property
    def basis(self) -> np.ndarray:
        """(3, 3) float: rows ``u, v, normal`` (world -> frame rotation)."""
        return np.stack([self.u, self.v, self.normal])

    def to_2d(self, points) -> np.ndarray:
        """World points -> 2D frame.

        Parameters
        ----------
        points : (n, 3) float

        Returns
        -------
        (n, 2) float
            ``((p - origin) . u, (p - origin) . v)``; the component along
            the normal is dropped.
        """
        d = np.asarray(points, dtype=np.float64) - self.origin
        return d @ np.stack([self.u, self.v], axis=1)

    def to_3d(self, points) -> np.ndarray:
        """2D frame points -> world.

        Parameters
        ----------
        points : (n, 2) float

        Returns
        -------
        (n, 3) float
            ``origin + x u + y v``.
        """
        p = np.asarray(points, dtype=np.float64)
        return self.origin + p @ np.stack([self.u, self.v])

    def heights(self, points) -> np.ndarray:
        """Signed distances of world points to the plane, (n,) float."""
        return np.asarray(points, dtype=np.float64) @ self.normal - self.offset

    def moved(self, delta: float, reason: str) -> "SlicePlane":
        """The same plane moved by ``delta`` along its normal (frame kept)."""
        return SlicePlane(
            index=self.index,
            origin=self.origin + delta * self.normal,
            normal=self.normal,
            u=self.u,
            v=self.v,
            offset=float(self.offset + delta),
            nudge=float(self.nudge + delta),
            nudge_reason=reason,
        )

    def as_dict(self) -> dict:
        """JSON-ready description (the ``slices[i]`` frame fields)."""
        return {
            "index": int(self.index),
            "origin": self.origin.tolist(),
            "normal": self.normal.tolist(),
            "u": self.u.tolist(),
            "v": self.v.tolist(),
            "offset": float(self.offset),
            "nudge": float(self.nudge),
            "nudge_reason": self.nudge_reason,
        }


_AXES = {"x": (1.0, 0.0, 0.0), "y": (0.0, 1.0, 0.0), "z": (0.0, 0.0, 1.0)}


def parse_axis(axis) -> np.ndarray:
    """Axis name, ``"nx,ny,nz"`` string or (3,) vector -> (3,) unit normal.

    Only the direction counts: a vector whose length would overflow or
    underflow is scaled by its largest component first, so ``"1e300,1e300,0"``
    and ``"1e-200,1e-200,0"`` both give the unit vector of ``"1,1,0"``; only an
    exactly zero vector is refused.

    >>> parse_axis("y").tolist(), parse_axis("0,0,-2").tolist()
    ([0.0, 1.0, 0.0], [0.0, 0.0, -1.0])
    >>> parse_axis("1e-30,0,0").tolist()
    [1.0, 0.0, 0.0]
    """
    if isinstance(axis, str):
        key = axis.strip().lower()
        if key in _AXES:
            return np.array(_AXES[key])
        if key[:1] in "+-" and key[1:] in _AXES:
            return np.array(_AXES[key[1:]]) * (-1.0 if key[0] == "-" else 1.0)
        try:
            vec = np.array([float(s) for s in key.split(",")])
        except ValueError:
            raise ValueError(
                f"axis must be 'x', 'y', 'z' or 'nx,ny,nz', got {axis!r}"
            ) from None
    else:
        vec = np.asarray(axis, dtype=np.float64).reshape(-1)
    if vec.shape != (3,) or not np.all(np.isfinite(vec)):
        raise ValueError(f"axis must have 3 finite components, got {axis!r}")
    big = float(np.max(np.abs(vec)))
    if big == 0.0:
        raise ValueError(f"axis normal is zero: {axis!r}")
    with np.errstate(over="ignore", under="ignore"):
        norm = float(np.linalg.norm(vec))
    if not 1e-150 < norm < 1e150:  # the square of a component over- or underflows
        vec = vec / big
        norm = float(np.linalg.norm(vec))
    return vec / norm


def frame_for_normal(normal) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Deterministic right-handed frame ``(u, v, n)`` for a normal.

    See the module docstring for the rule.

    >>> [a.tolist() for a in frame_for_normal([0, 0, 1])]
    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    """
    n = parse_axis(normal)
    i = int(np.argmax(np.abs(n)))
    e = np.zeros(3)
    e[(i + 1) % 3] = 1.0
    u = e - (e @ n) * n
    u /= np.linalg.norm(u)
    v = np.cross(n, u)
    v /= np.linalg.norm(v)
    return u + 0.0, v + 0.0, n + 0.0


def _points_of(mesh_or_bounds) -> np.ndarray:
    """Vertices of a mesh, or the 8 corners of a (2, 3) bounds array."""
    verts = getattr(mesh_or_bounds, "vertices", None)
    if verts is not None:
        pts = np.asarray(verts, dtype=np.float64)
    else:
        b = np.asarray(mesh_or_bounds, dtype=np.float64)
        if b.shape != (2, 3):
            raise ValueError(f"expected a mesh or (2, 3) bounds, got shape {b.shape}")
        idx = np.array(np.meshgrid([0, 1], [0, 1], [0, 1], indexing="ij")).reshape(3, -1).T
        pts = b[idx, np.arange(3)]
    if len(pts) == 0 or not np.all(np.isfinite(pts)):
        raise ValueError("mesh has no vertices or non-finite vertices")
    return pts


def extent_along(mesh_or_bounds, normal) -> tuple[float, float]:
    """(lo, hi): range of ``p . normal`` over a mesh's vertices or a box."""
    h = _points_of(mesh_or_bounds) @ parse_axis(normal)
    return float(h.min()), float(h.max())


def _offsets(lo, hi, count, spacing, offsets) -> np.ndarray:
    given = [name for name, val in
             (("count", count), ("spacing", spacing), ("offsets", offsets))
             if val is not None]
    if len(given) != 1:
        raise ValueError(
            f"give exactly one of count, spacing, offsets (got {given or 'none'})"
        )
    if not hi > lo:
        raise ValueError(f"mesh is flat along the normal (extent {lo}..{hi})")
    if count is not None:
        if isinstance(count, bool) or int(count) != count or count < 1:
            raise ValueError(f"count must be a positive integer, got {count!r}")
        count = int(count)
        return lo + (np.arange(count) + 0.5) * ((hi - lo) / count)
    if spacing is not None:
        spacing = float(spacing)
        if not (np.isfinite(spacing) and spacing > 0):
            raise ValueError(f"spacing must be a positive number, got {spacing!r}")
        n = int(np.ceil((hi - lo) / spacing - 0.5))
        out = lo + spacing / 2 + np.arange(max(n, 0) + 1) * spacing
        out = out[out < hi]
        if len(out) == 0:
            raise ValueError(
                f"spacing {spacing:g} leaves no plane inside the extent {lo:g}..{hi:g}"
            )
        return out
    out = np.asarray(offsets, dtype=np.float64).reshape(-1)
    if len(out) == 0:
        raise ValueError("offsets is empty")
    bad = ~((out > lo) & (out < hi))
    if bad.any():
        raise ValueError(
            f"offsets must lie strictly inside the extent ({lo:g}, {hi:g}); "
            f"bad: {out[bad][:5].tolist()}"
        )
    return out


def make_planes(
    mesh_or_bounds,
    axis="z",
    count=None,
    spacing=None,
    offsets=None,
    center=None,
) -> list[SlicePlane]:
    """A family of parallel planes strictly inside a mesh's extent.

    Planes are not checked for degeneracy here; see
    :func:`slicer.degenerate.nudge_planes` (``slice_mesh`` does both).

    Parameters
    ----------
    mesh_or_bounds : trimesh.Trimesh or (2, 3) float
        Anything with ``vertices``, or an axis-aligned box.
    axis : {'x', 'y', 'z'}, str 'nx,ny,nz' or (3,) float
        Plane normal.
    count : int, optional
        ``count`` planes at ``lo + (k + 0.5) (hi - lo) / count``.
    spacing : float, optional
        Planes at ``lo + spacing / 2 + k spacing`` while ``< hi``.
    offsets : (m,) float, optional
        Explicit signed offsets along the normal, each strictly in (lo, hi).
    center : (3,) float, optional
        Reference point whose projections are the 2D origins (default: the
        bounding box centre).

    Returns
    -------
    list of SlicePlane
        Exactly one of ``count``, ``spacing``, ``offsets`` must be given,
        otherwise ``ValueError``.
    """
    normal = parse_axis(axis)
    u, v, n = frame_for_normal(normal)
    pts = _points_of(mesh_or_bounds)
    h = pts @ n
    lo, hi = float(h.min()), float(h.max())
    offs = _offsets(lo, hi, count, spacing, offsets)
    if center is None:
        center = 0.5 * (pts.min(axis=0) + pts.max(axis=0))
    center = np.asarray(center, dtype=np.float64).reshape(3)
    c_h = float(center @ n)
    planes = []
    for k, off in enumerate(offs):
        origin = center + (off - c_h) * n
        planes.append(
            SlicePlane(index=k, origin=origin, normal=n, u=u, v=v, offset=float(off))
        )
    return planes
