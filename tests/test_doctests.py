"""Docstring examples run (they are the documentation)."""
from __future__ import annotations

import doctest
import importlib

import pytest

MODULES = [
    "slicer",
    "slicer.planes",
    "slicer.degenerate",
    "slicer.section",
    "slicer.contact",
    "slicer.contact.crossing",
    "slicer.contact.embree",
    "slicer.contact.refine",
    "slicer.contact.embree_direct",
    "slicer.contact.embree_device",
    "slicer.contact.exact",
    "slicer.contact.trimesh_ray",
    "slicer.slices",
    "slicer.agreement",
    "core2d.planar",
    "core2d.resolution",
    "core2d.sim.codes",
    "core2d.visibility",
    "core2d.planner.known",
    "core2d.planner.segments",
    "core2d.planner.local_search",
    "core2d.planner.touched",
    "core2d.planner.mouths",
    "core2d.planner.along",
    "core2d.planner.tip_bound",
    "core2d.planner.thin_walls",
    "core2d.planner.hops",
    "core2d.planner.openings",
    "core2d.planner.pass_contacts",
    "core2d.planner.pass_plan",
    "core2d.planner.budget",
    "core2d.truth.reachability",
    "core2d.truth.metrics",
    "core2d.truth.resolvable",
    "recon3d.surface.warp",
    "recon3d.surface.sweep",
    "recon3d.surface.per_label",
    "recon3d.numerics",
    "recon3d.io.documents",
    "recon3d.records",
    "recon3d.viz.plot",
    "recon3d.viz.figure2d",
    "recon3d.viz.animate",
    "recon3d.viz.multiples",
    "recon3d.io.lock",
    "recon3d.io.side",
    "recon3d.sensing.pool",
    "recon3d.cli.printing",
    "recon3d.score.report",
    "recon3d.cli.signals",
    "bench.paired",
    "bench.sensor_surface",
]


@pytest.mark.parametrize("name", MODULES)
def test_doctests(name):
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS)
    assert result.failed == 0


def test_public_api():
    import slicer

    assert sorted(slicer.__all__) == sorted(set(slicer.__all__))
    for name in slicer.__all__:
        assert getattr(slicer, name).__doc__
