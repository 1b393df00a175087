"""A lid between two slices that neither neighbouring gap continues is a step (recon3d.surface.steps).

Constructed cases, z-slices traced all round (W1 squares), checked against the truth solid
with trimesh (volume, distance of the surface to the truth), not recon3d code:

* two stacked square blocks (20 x 20 below, 6 x 6 above), the tread half-way between two
  slices: the walls stand still in the neighbouring gaps, so the tread is a step at mid-gap
  and the surface is the truth; the aligned blend alone makes a ramp (a frustum in the gap);
* a frustum (the square shrinks in every gap): its walls move in the neighbouring gaps, so the
  blend keeps the slope; calling every disagreement a step makes stairs.
"""
import manifold3d
import numpy as np
import pytest
import trimesh

import slicer
from recon3d.surface.caps import CapSettings
from recon3d.surface.closure import slice_region
from recon3d.surface.solid import family_solid, fuse
from recon3d.surface import steps

STEP = 0.5
GAP = 3.0


def _square(half):
    return np.array([[-half, -half], [half, -half], [half, half], [-half, half],
                     [-half, -half]], dtype=float)


def _stairs(z0, z1, tread=12.0):
    """The two stacked blocks between z0 and z1 (a manifold union, then trimesh)."""
    lo = manifold3d.Manifold.cube([20, 20, tread - z0]).translate([-10, -10, z0])
    hi = manifold3d.Manifold.cube([6, 6, z1 - tread]).translate([-3, -3, tread])
    m = (lo + hi).to_mesh()
    return trimesh.Trimesh(np.asarray(m.vert_properties)[:, :3], np.asarray(m.tri_verts))


def _surface(mesh, half_of, caps=CapSettings()):
    """The single-family surface from 7 z-slices whose regions are the true squares."""
    planes = [c.plane for c in slicer.slice_mesh(mesh, axis="z", count=7)]
    assert np.allclose(np.diff([p.offset for p in planes]), GAP)
    regions = [slice_region([_square(half_of(p.offset))], [], [], [], 1e-9) for p in planes]
    return fuse([family_solid(regions, planes, STEP, caps=caps)], mesh.bounds), planes


def _far(surface, truth):
    pts, _ = trimesh.sample.sample_surface(surface, 5000, seed=3)
    return np.abs(trimesh.proximity.signed_distance(truth, pts)).max()


@pytest.fixture(scope="module")
def stairs():
    mesh = _stairs(0.0, 21.0)  # planes at 1.5, 4.5, ..., 19.5; the tread at 12 (mid-gap)
    surface, planes = _surface(mesh, lambda z: 10.0 if z < 12.0 else 3.0)
    truth = _stairs(planes[0].offset, planes[-1].offset)
    return mesh, surface, truth


def test_a_tread_between_slices_is_a_step(stairs):
    _, surface, truth = stairs
    assert surface.is_watertight
    assert surface.volume == pytest.approx(truth.volume, rel=0.01)
    assert _far(surface, truth) < STEP


def test_without_the_rule_the_tread_is_a_ramp(stairs):
    """The failing side: the aligned blend alone matches the two walls and makes a ramp."""
    mesh, _, truth = stairs
    surface, _ = _surface(mesh, lambda z: 10.0 if z < 12.0 else 3.0, CapSettings(steps=False))
    assert abs(surface.volume / truth.volume - 1) > 0.01
    assert _far(surface, truth) > STEP


def _frustum(z0, z1):
    half = lambda z: 14.0 - 0.6 * z  # noqa: E731 - the wall moves 1.8 per gap
    pts = [(sx * half(z), sy * half(z), z) for z in (z0, z1) for sx in (-1, 1) for sy in (-1, 1)]
    return trimesh.convex.convex_hull(np.array(pts)), half


@pytest.mark.parametrize("all_steps", [False, True])
def test_a_slanted_wall_stays_a_slope(all_steps, monkeypatch):
    """A frustum's walls move in every gap: no step. With the test of the neighbouring gaps
    removed (every disagreement a step) the frustum turns into stairs."""
    if all_steps:
        monkeypatch.setattr(steps, "_still", lambda comp, n, *a: (np.ones(n, bool),) * 2)
    mesh, half = _frustum(0.0, 21.0)
    surface, planes = _surface(mesh, half)
    truth, _ = _frustum(planes[0].offset, planes[-1].offset)
    far = _far(surface, truth)
    assert (far > STEP) if all_steps else (far < STEP)
