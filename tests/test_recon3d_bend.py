"""Between slices a boundary follows a curve through four slices (recon3d.surface.warp.bend_shift).

Constructed families whose regions are the true sections (z-slices traced all round), the
surface checked against the analytic solid, not recon3d code:

* a sphere: its section radius sqrt(R^2 - z^2) bends between the planes; the straight blend
  runs as a chord inside the sphere, the bent one follows it: less error, most of all in the
  end gaps (the parabola through three slices);
* a cone: its radius is linear in z, the moves of all gaps agree and the bend changes nothing.
"""
import numpy as np
import pytest
import trimesh

import slicer
from recon3d.surface.closure import slice_region
from recon3d.surface.solid import family_solid, fuse
from recon3d.surface.warp import WarpSettings

STEP = 0.25
R = 10.0


def _circle(r, n=256):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    c = np.column_stack([r * np.cos(t), r * np.sin(t)])
    return np.vstack([c, c[:1]])


def _surface(mesh, radius_of, count, warp):
    planes = [c.plane for c in slicer.slice_mesh(mesh, axis="z", count=count)]
    regions = [slice_region([_circle(radius_of(p.offset))], [], [], [], 1e-9) for p in planes]
    surf = fuse([family_solid(regions, planes, STEP, warp=warp)], mesh.bounds)
    label = surf.face_attributes["label"]
    return surf.submesh([np.flatnonzero(label != 5)], append=True), planes  # no caps


def _errors(surface, radial):
    """Analytic distance of surface samples to the truth (radial(p) -> signed error)."""
    pts, _ = trimesh.sample.sample_surface(surface, 20000, seed=5)
    return np.abs(radial(pts))


def test_a_sphere_between_its_slices_is_closer_bent_than_straight():
    mesh = trimesh.creation.icosphere(subdivisions=5, radius=R)
    def on_sphere(z):
        return float(np.sqrt(max(R * R - z * z, 1e-6)))
    bent, planes = _surface(mesh, on_sphere, 7, WarpSettings())
    straight, _ = _surface(mesh, on_sphere, 7, WarpSettings(bend=False))
    def err(pts):
        return np.linalg.norm(pts, axis=1) - R
    e_bent, e_straight = _errors(bent, err), _errors(straight, err)
    gap = planes[1].offset - planes[0].offset
    assert np.mean(e_bent) < 0.7 * np.mean(e_straight)
    assert np.percentile(e_bent, 95) < 0.8 * np.percentile(e_straight, 95)
    assert np.percentile(e_straight, 95) > 0.05 * gap  # the chord is measurably off


def test_a_cone_is_not_bent():
    h, r0, r1 = 20.0, 10.0, 3.0
    mesh = trimesh.creation.cone(radius=r0, height=h, sections=256)
    def radius(z):
        return r0 - (r0 - 0.0) * z / h
    def err(pts):  # distance to the cone's side, measured radially, scaled to the normal
        rad = np.hypot(pts[:, 0], pts[:, 1])
        return (rad - radius(pts[:, 2])) * h / np.hypot(h, r0)
    mesh = mesh.slice_plane([0, 0, h * (1 - r1 / r0)], [0, 0, -1], cap=True)
    bent, _ = _surface(mesh, radius, 6, WarpSettings())
    straight, _ = _surface(mesh, radius, 6, WarpSettings(bend=False))
    e_bent, e_straight = _errors(bent, err), _errors(straight, err)
    assert np.mean(e_bent) == pytest.approx(np.mean(e_straight), abs=0.02 * STEP)
    assert np.percentile(e_bent, 99) < STEP


def test_an_end_gap_aligns_a_part_the_end_slice_barely_cuts():
    """A block whose foot is a shallow ramp (slope 1 : 10 along x): the first plane cuts the
    ramp far out, the second near its toe, 10 gaps apart. The first and last gaps align
    over ``end_reach`` (12) gaps, so the boundaries are matched and most of the ramp between
    the two planes is a ramp; with the middle gaps' reach (4 gaps) they go unmatched and the
    blend puts a flat step half-way (measured: the surface's distance to the true solid in
    that gap, median; the move spreads only about half a gap around its midpoint, so the
    ramp's far ends stay off either way)."""
    import manifold3d

    from recon3d.surface.solid import family_solid, fuse

    xz = np.array([[24.0, 0.0], [40.0, 0.0], [40.0, 20.0], [0.0, 20.0], [0.0, 2.4]])
    prism = manifold3d.Manifold.extrude(manifold3d.CrossSection([xz]), 10.0)  # along z
    m = prism.rotate([90.0, 0.0, 0.0]).to_mesh()  # the profile's y up -> z up, extruded along y
    mesh = trimesh.Trimesh(np.asarray(m.vert_properties)[:, :3], np.asarray(m.tri_verts))
    cuts = slicer.slice_mesh(mesh, axis="z", count=16)
    regions = [slice_region([np.vstack([lp, lp[:1]]) for lp in c.loops], [], [], [], 1e-9)
               for c in cuts]
    planes = [c.plane for c in cuts]
    z0, z1 = planes[0].offset, planes[1].offset
    assert z1 < 2.4 < planes[2].offset  # the ramp's toe lies in the second gap

    def far_in_first_gap(warp):
        surf = fuse([family_solid(regions, planes, STEP, warp=warp)], mesh.bounds)
        keep = surf.face_attributes["label"] != 5
        pts, _ = trimesh.sample.sample_surface(surf.submesh([np.flatnonzero(keep)],
                                                            append=True), 20000, seed=2)
        gap = pts[(pts[:, 2] > z0 + 0.05) & (pts[:, 2] < z1 - 0.05)]
        return np.abs(trimesh.proximity.signed_distance(mesh, gap)), z1 - z0

    near, g = far_in_first_gap(WarpSettings())
    short, _ = far_in_first_gap(WarpSettings(end_reach=4.0))
    assert np.median(near) < 0.6 * np.median(short) and np.median(short) > 0.08 * g
