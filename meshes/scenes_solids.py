"""Scenes that are genuinely 3D: revolved, unioned or stacked solids.

Same conventions as :mod:`meshes.scenes_profiles`: millimetres, "up" = +y
(openings face +y, so z-slices cut through them), bounding-box minimum at
the origin, everything inside a 100 mm cube. Unlike the extruded profiles,
the z-slices of these scenes change from slice to slice.
"""
from __future__ import annotations

from manifold3d import CrossSection, Manifold, OpType

from .geometry import check_resolution, circle, place, rect, share
from .registry import scene

__all__ = ["bowl", "cup_handle", "stepped_pyramid", "twin_posts"]


def _axis_z_to_y(solid: Manifold) -> Manifold:
    """Rotate so the +z axis becomes +y (rotation of -90 deg about x)."""
    return solid.rotate((-90.0, 0.0, 0.0))


@scene()
def bowl(*, resolution: int = 32) -> Manifold:
    """Hemispherical bowl opening toward +y, with a flat foot and an outer rim flange.

    Outer radius 45 mm, wall 5 mm, flange out to r = 48 mm, disc foot of
    radius 20 mm. z-slices with |z - 48| < 40 cut a U-shaped cavity whose
    width changes with z (curved concave pocket, fully reachable); slices
    beyond the inner sphere are solid caps. The concave corner under the
    flange is a small local pocket on the outside. ``resolution``: segments
    per full turn, both for the profile arcs and around the axis.
    """
    res = check_resolution(resolution)
    shell = (circle((0, 0), 45.0, res) - circle((0, 0), 40.0, res)) \
        ^ rect(0.0, -50.0, 50.0, 0.0)
    profile = shell + rect(40.5, -3.0, 48.0, 0.0) + rect(0.0, -48.0, 20.0, -40.0)
    solid = Manifold.revolve(profile, res)
    return place(_axis_z_to_y(solid))


@scene()
def cup_handle(*, resolution: int = 32) -> Manifold:
    """Cylindrical cup opening toward +y with a ring handle on its +z side.

    Cup radius 30 mm (wall 3, floor 4), 70 mm tall; the handle is a torus
    (ring radius 16, tube radius 4) in the y-z plane whose ends merge into
    the wall. One body, but z-slices just outside the wall (z > 60 after
    placement) cut only the handle, into two separate islands (two outer
    loops, the single-object assumption of section 3.2 broken), and slices
    through the cup show the U-shaped cavity. ``resolution``: segments
    around the cup and the ring; the tube gets half as many.
    """
    res = check_resolution(resolution)
    outer = Manifold.cylinder(70.0, 30.0, circular_segments=res)
    cavity = Manifold.cylinder(70.0, 27.0, circular_segments=res).translate((0, 0, 4))
    tube = CrossSection.circle(4.0, share(res, 0.5, minimum=6)).translate((16.0, 0.0))
    ring = Manifold.revolve(tube, res).rotate((0.0, 90.0, 0.0))
    handle = ring.translate((0.0, -36.0, 35.0))
    return place(_axis_z_to_y((outer + handle) - cavity))


@scene()
def stepped_pyramid(*, resolution: int = 8, tiers: int = 4) -> Manifold:
    """Ziggurat of square tiers stacked along +y (80, 60, 40, 20 mm wide, 10 mm each).

    Sharp 90 deg convex and concave corners only: z-slices are staircases
    whose number of steps depends on z (1 near the sides, ``tiers`` through
    the middle), which probes corner handling and the slice-to-slice
    stacking of a changing profile. Straight-sided: ``resolution`` has no
    effect.
    """
    check_resolution(resolution)
    n = int(tiers)
    if n != tiers or not 1 <= n <= 8:
        raise ValueError(f"tiers must be an integer in [1, 8], got {tiers!r}")
    width, step = 80.0, 10.0
    boxes = []
    for i in range(n):
        s = width * (n - i) / n
        inset = 0.5 * (width - s)
        boxes.append(Manifold.cube((s, step, s)).translate((inset, step * i, inset)))
    return place(Manifold.batch_boolean(boxes, OpType.Add))


@scene(bodies=2)
def twin_posts(*, resolution: int = 32) -> Manifold:
    """Two separate upright posts 6 mm apart: a round one (r = 12 mm) and a square one.

    Two bodies on purpose. Every z-slice through both has two outer loops,
    and the 6 mm gap between them looks like a pocket from outside although
    it belongs to neither object: the single-object assumption fails.
    ``resolution``: segments around the round post.
    """
    res = check_resolution(resolution)
    round_post = Manifold.cylinder(60.0, 12.0, circular_segments=res).translate((12, 12, 0))
    square_post = Manifold.cube((24.0, 24.0, 45.0)).translate((30.0, 0.0, 0.0))
    return place(_axis_z_to_y(round_post + square_post))
