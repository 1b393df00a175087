"""Embree vs exact agreement: how often the two contact backends disagree.

For each slice, random in-plane rays are cast with both backends:

* rays from points on a circle around the section (1.2 x its bounding
  circle) aimed at random points of the section's bounding box (the probe
  coming in from free space), and
* rays from random free points inside the bounding box (in pockets,
  concavities and holes) in random directions, with random ``max_dist``.

Separately, *vertex rays* go from the outer circle exactly through contour
vertices: the degenerate case. There a ray tangent to a convex vertex is a
touch for the exact backend (closed segments) and, depending on float32
rounding, a touch or a near miss for Embree.

A ray *disagrees* when one backend hits and the other does not, or when both
hit and the distances differ by more than ``tol * scale``. The rates are
reported per slice and in total; they are findings, not something to hide.

Examples
--------
>>> import trimesh
>>> mesh = trimesh.creation.annulus(r_min=1.0, r_max=2.0, height=1.0)
>>> rep = agreement_report(mesh, name="annulus", count=2, degenerate=1, rays=200)
>>> rep.rays, rep.disagreements
(400, 0)
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from slicer.degenerate import mesh_scale
from slicer.planes import extent_along, make_planes, parse_axis
from slicer.slices import Slice, slice_mesh

__all__ = [
    "SliceAgreement",
    "AgreementReport",
    "random_rays",
    "vertex_rays",
    "degenerate_offsets",
    "compare_backends",
    "agreement_report",
]


@dataclass(frozen=True)
class SliceAgreement:
    """Agreement on one slice (distances in units of ``scale``)."""

    index: int
    offset: float
    nudge: float
    nudge_reason: str
    rays: int
    hits: int
    hit_miss: int
    distance: int
    max_distance_error: float
    max_normal_error: float

    @property
    def disagreements(self) -> int:
        return self.hit_miss + self.distance


@dataclass(frozen=True)
class AgreementReport:
    """Per-slice and total agreement of the Embree and exact backends."""

    name: str
    scale: float
    tol: float
    rows: tuple
    vertex_rows: tuple = ()

    @property
    def rays(self) -> int:
        return sum(r.rays for r in self.rows)

    @property
    def disagreements(self) -> int:
        return sum(r.disagreements for r in self.rows)

    @property
    def rate(self) -> float:
        """Disagreeing random rays / random rays."""
        return self.disagreements / max(self.rays, 1)

    @property
    def vertex_rays(self) -> int:
        return sum(r.rays for r in self.vertex_rows)

    @property
    def vertex_disagreements(self) -> int:
        return sum(r.disagreements for r in self.vertex_rows)

    @property
    def vertex_rate(self) -> float:
        """Disagreeing vertex rays / vertex rays."""
        return self.vertex_disagreements / max(self.vertex_rays, 1)

    @property
    def nudged(self) -> int:
        return sum(r.nudge != 0.0 for r in self.rows)

    def summary(self) -> str:
        hm = sum(r.hit_miss for r in self.rows)
        de = max((r.max_distance_error for r in self.rows), default=0.0)
        ne = max((r.max_normal_error for r in self.rows), default=0.0)
        return (
            f"{self.name}: {len(self.rows)} slices ({self.nudged} nudged), "
            f"{self.rays} rays, {self.disagreements} disagree "
            f"(rate {self.rate:.2e}; hit/miss {hm}), "
            f"max |d_embree - d_exact| {de:.1e}*scale, max normal error {ne:.1e}; "
            f"vertex rays: {self.vertex_rays}, {self.vertex_disagreements} disagree "
            f"(rate {self.vertex_rate:.2e})"
        )

    def format(self) -> str:
        """Summary line plus one line per slice."""
        lines = [self.summary()]
        for r in self.rows:
            lines.append(
                f"  slice {r.index:3d} offset {r.offset:+.6g} nudge {r.nudge:+.1e}: "
                f"{r.rays} rays, {r.hits} hits, {r.hit_miss} hit/miss, {r.distance} dist "
                f"(max err {r.max_distance_error:.1e}*scale)"
            )
        return "\n".join(lines)


def _material(slc: Slice, pts) -> np.ndarray:
    """Even-odd inside test of points against the slice's closed loops."""
    import shapely

    inside = np.zeros(len(pts), dtype=bool)
    for loop in slc.loops:
        inside ^= shapely.contains_xy(shapely.Polygon(loop), pts[:, 0], pts[:, 1])
    return inside


def vertex_rays(slc: Slice, n: int, rng):
    """Rays from a circle around the slice exactly through contour vertices.

    Returns
    -------
    origins (n, 2), dirs (n, 2) unit, max_dist (n,)
    """
    center, radius = slc.bounding_circle()
    pts = slc.points()
    target = pts[rng.integers(0, len(pts), n)]
    ang = rng.uniform(0.0, 2.0 * np.pi, n)
    o = center + 1.2 * radius * np.stack([np.cos(ang), np.sin(ang)], axis=1)
    d = target - o
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    return o, d, np.full(n, 2.6 * radius)


def random_rays(slc: Slice, n: int, rng, inside_share: float = 0.4):
    """Random in-plane rays around and inside one slice.

    Parameters
    ----------
    slc : Slice
    n : int
        Number of rays.
    rng : numpy.random.Generator
    inside_share : float
        Share of rays starting at free points inside the bounding box.

    Returns
    -------
    origins : (n, 2) float
    dirs : (n, 2) float
        Unit.
    max_dist : (n,) float
    """
    center, radius = slc.bounding_circle()
    pts = slc.points()
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    n_in = int(round(n * inside_share))
    n_out = n - n_in
    ang = rng.uniform(0.0, 2.0 * np.pi, n_out)
    o_out = center + 1.2 * radius * np.stack([np.cos(ang), np.sin(ang)], axis=1)
    target = rng.uniform(lo, hi, (n_out, 2))
    d_out = target - o_out
    m_out = np.full(n_out, 2.6 * radius)
    free = np.zeros((0, 2))
    for _ in range(20):
        if len(free) >= n_in:
            break
        cand = rng.uniform(lo, hi, (max(4 * n_in, 16), 2))
        free = np.concatenate([free, cand[~_material(slc, cand)]])
    o_in = free[:n_in]
    n_in = len(o_in)
    a = rng.uniform(0.0, 2.0 * np.pi, n_in)
    d_in = np.stack([np.cos(a), np.sin(a)], axis=1)
    m_in = rng.uniform(0.05, 2.5, n_in) * radius
    o = np.concatenate([o_out, o_in])
    d = np.concatenate([d_out, d_in])
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    return o, d, np.concatenate([m_out, m_in])


def compare_backends(slc: Slice, origins, dirs, max_dist, tol: float = 1e-6) -> SliceAgreement:
    """Cast the same rays with both backends of one slice and compare."""
    de, pe, ne = slc.contact("embree").cast(origins, dirs, max_dist)
    dx, px, nx = slc.contact("exact").cast(origins, dirs, max_dist)
    he, hx = np.isfinite(de), np.isfinite(dx)
    both = he & hx
    err = np.abs(de[both] - dx[both]) / slc.scale
    nerr = np.linalg.norm(ne[both] - nx[both], axis=1)
    return SliceAgreement(
        index=slc.index,
        offset=slc.plane.offset,
        nudge=slc.plane.nudge,
        nudge_reason=slc.plane.nudge_reason,
        rays=len(origins),
        hits=int(hx.sum()),
        hit_miss=int(np.count_nonzero(he != hx)),
        distance=int(np.count_nonzero(err > tol)),
        max_distance_error=float(err.max()) if len(err) else 0.0,
        max_normal_error=float(nerr.max()) if len(nerr) else 0.0,
    )


def degenerate_offsets(mesh, axis, k: int, rng) -> np.ndarray:
    """Up to ``k`` offsets exactly at vertex heights strictly inside the
    extent, preferring heights where faces lie in the plane."""
    n = parse_axis(axis)
    lo, hi = extent_along(mesh, n)
    h = np.asarray(mesh.vertices, dtype=np.float64) @ n
    fh = h[np.asarray(mesh.faces)]
    flat = fh[np.ptp(fh, axis=1) == 0, 0]
    flat = np.unique(flat[(flat > lo) & (flat < hi)])
    inner = np.unique(h[(h > lo) & (h < hi)])
    picks = list(rng.permutation(flat)[: (k + 1) // 2])
    rest = np.setdiff1d(inner, picks)
    picks += list(rng.permutation(rest)[: k - len(picks)])
    return np.sort(np.array(picks, dtype=np.float64))


def agreement_report(
    mesh,
    name: str = "",
    axis="z",
    count: int = 8,
    degenerate: int = 4,
    rays: int = 1000,
    vertex_rays_per_slice: int = 0,
    seed: int = 0,
    tol: float = 1e-6,
) -> AgreementReport:
    """Agreement of Embree and exact contact over a family of slices.

    Parameters
    ----------
    mesh : trimesh.Trimesh
    name : str
        Label for the report.
    axis : str or (3,) float
        Plane normal.
    count : int
        Evenly spaced planes.
    degenerate : int
        Extra planes placed exactly at vertex heights (half of them on
        heights where faces lie in the plane, when there are such); they are
        nudged by :func:`slice_mesh` and the nudge is in the report.
    rays : int
        Random rays per slice.
    vertex_rays_per_slice : int
        Rays through contour vertices per slice (reported apart).
    seed : int
    tol : float
        Distance tolerance, times ``scale``.

    Returns
    -------
    AgreementReport
    """
    rng = np.random.default_rng(seed)
    offs = [p.offset for p in make_planes(mesh, axis=axis, count=count)]
    offs += degenerate_offsets(mesh, axis, degenerate, rng).tolist()
    rows, vrows = [], []
    for slc in slice_mesh(mesh, axis=axis, offsets=np.array(offs)):
        if slc.is_empty:
            continue
        o, d, m = random_rays(slc, rays, rng)
        rows.append(compare_backends(slc, o, d, m, tol=tol))
        if vertex_rays_per_slice:
            o, d, m = vertex_rays(slc, vertex_rays_per_slice, rng)
            vrows.append(compare_backends(slc, o, d, m, tol=tol))
    return AgreementReport(
        name=name, scale=mesh_scale(mesh), tol=tol, rows=tuple(rows), vertex_rows=tuple(vrows)
    )
