"""The reach of 'space beside an unknown chord is not shown empty' (ConfidenceSettings.unswept_reach).

A 20 mm cube. Family x: its exact sections (solid everywhere inside). Family z: each plane
traced all round but for a wide stretch (14 mm) of one side, from whose ends two unknown
chords A_iB_i meet at the centre -- the lids of an area the planner never explored (§3.3).
The closure leaves the wedge between them outside the regions (no piece closes its mouth).
The unknown contour between a chord's ends lies anywhere in G_i (Def. 1), so nothing in the
wedge was shown empty, however far from the chord: a point near the wedge's mouth lies 5 mm
(20 grid steps) from both chords, and its nearest piece is a chord. With the unbounded reach
(the default) x's solid stays there; with a reach of 8 steps the point counts as swept by z,
and z's empty carves x's solid. Checked against the truth (the cube contains the point).
"""
import numpy as np
import pytest
import shapely
import trimesh

import slicer
from recon3d.surface.closure import slice_region
from recon3d.surface.confidence import ConfidenceSettings
from recon3d.surface.solid import family_solid, fuse

STEP = 0.25


def _family(mesh, axis, count, chords_mouth=None, trust=ConfidenceSettings()):
    """A family of ``count`` planes: exact sections, or (``chords_mouth`` mm) a side left open
    between two unknown chords meeting at the centre."""
    cuts = slicer.slice_mesh(mesh, axis=axis, count=count)
    regions = []
    for c in cuts:
        loop = np.vstack([c.loops[0], c.loops[0][:1]])
        if chords_mouth is None:
            regions.append(slice_region([loop], [], [], [], 1e-6))
            continue
        (x0, y0), (x1, y1) = c.loops[0].min(axis=0), c.loops[0].max(axis=0)
        xm, mid = (x0 + x1) / 2, np.array([(x0 + x1) / 2, (y0 + y1) / 2])
        a, b = xm - chords_mouth / 2, xm + chords_mouth / 2
        w1 = [np.array([[b, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0], [a, y0]])]
        chords = [np.array([[a, y0], mid]), np.array([mid, [b, y0]])]
        regions.append(slice_region(w1, [], [], chords, 1e-6))
    return family_solid(regions, [c.plane for c in cuts], STEP, "warp", True, trust), cuts


@pytest.fixture(scope="module")
def cube():
    mesh = trimesh.creation.box((20.0, 20.0, 20.0))
    x, _ = _family(mesh, "x", 8)
    _, cuts = _family(mesh, "z", 6, 14.0)
    plane = cuts[2].plane  # near the wedge's mouth, half-way between z planes 2 and 3
    (x0, y0), (x1, y1) = cuts[2].loops[0].min(axis=0), cuts[2].loops[0].max(axis=0)
    u, v = (x0 + x1) / 2, y0 + 1.0
    height = (cuts[3].plane.offset - plane.offset) / 2
    point = plane.origin + u * plane.u + v * plane.v + height * np.asarray(plane.normal)
    # farther than 8 steps from both chords, and the chords are its nearest pieces
    xm, mid = (x0 + x1) / 2, shapely.Point((x0 + x1) / 2, (y0 + y1) / 2)
    chords = [shapely.LineString([(xm + s * 7.0, y0), mid]) for s in (-1, 1)]
    traced = shapely.LineString([(xm + 7.0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0),
                                 (xm - 7.0, y0)])
    d_chord = min(c.distance(shapely.Point(u, v)) for c in chords)
    assert 8 * STEP < d_chord < traced.distance(shapely.Point(u, v))
    return mesh, x, point[None]


@pytest.mark.parametrize("reach", [float("inf"), 8.0])
def test_a_wide_unexplored_wedge_does_not_carve_the_other_family(cube, reach):
    mesh, x, point = cube
    assert mesh.contains(point)[0] and fuse([x], mesh.bounds).contains(point)[0]
    z, _ = _family(mesh, "z", 6, 14.0, ConfidenceSettings(unswept_reach=reach))
    assert not fuse([z], mesh.bounds).contains(point)[0]  # z's closure leaves the wedge out
    kept = fuse([z, x], mesh.bounds).contains(point)[0]
    assert kept if np.isinf(reach) else not kept
