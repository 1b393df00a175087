"""Worker processes are handed the costliest slices first; the results do not move."""
import numpy as np
import shapely
import trimesh

from recon3d.config import RunConfig
from recon3d.sensing import pool
from recon3d.sensing.mesh import sense_mesh
from recon3d.sensing.order import LOOP_WEIGHT, dispatch_order, slice_cost
from recon3d.sensing.worker import family_slices


def _funnel():
    """A cone standing on its apex: its z-sections grow with z (plane order is cheapest first)."""
    cone = trimesh.creation.cone(radius=2.0, height=4.0, sections=48)
    cone.apply_transform(trimesh.transformations.rotation_matrix(np.pi, [1.0, 0.0, 0.0]))
    return cone


def test_slice_cost_is_contour_length_over_eps_plus_loops():
    box = trimesh.creation.box(extents=[4.0, 2.0, 1.0])
    ring = trimesh.creation.annulus(r_min=1.0, r_max=2.0, height=1.0, sections=64)
    for mesh, loops in ((box, 1), (ring, 2)):
        (cut,) = family_slices(mesh, np.array([0.0, 0.0, 1.0]), 1)
        length = sum(shapely.LinearRing(lp).length for lp in cut.loops)
        assert len(cut.loops) == loops
        assert np.isclose(slice_cost(cut, 0.25), length / 0.25 + LOOP_WEIGHT * loops)


def test_dispatch_order_is_costliest_first_with_each_tasks_eps():
    cuts = [family_slices(_funnel(), np.array([0.0, 0.0, 1.0]), 6)]
    tasks = [(0, i) for i in range(6)]
    order = dispatch_order(cuts, tasks, 0.1)
    assert order == [5, 4, 3, 2, 1, 0]  # the widest section last in plane order, first here
    # a task's own eps counts: slice 5 at 100 x eps costs least
    order = dispatch_order(cuts, [*tasks[:5], (0, 5, 10.0)], 0.1)
    assert order == [4, 3, 2, 1, 0, 5]


def test_the_pool_hands_out_tasks_in_that_order(monkeypatch):
    sent = []
    real = pool._Workers.send

    def recording(self, w, k, task):
        sent.append(k)
        return real(self, w, k, task)

    monkeypatch.setattr(pool._Workers, "send", recording)
    monkeypatch.setattr(pool, "cold_kernels", lambda *backend: False)  # no slice sensed in the parent
    config = RunConfig(slices=6, jobs=2, eps=0.2)
    run = sense_mesh(_funnel(), "funnel", config)
    cuts = [[s.slice for s in run.families[0].slices]]
    expected = dispatch_order(cuts, [(0, i) for i in range(6)], run.eps)
    assert expected != list(range(6))
    assert sent == expected
    # results in plane order whatever the order they were sensed in
    assert [s.index for s in run.families[0].slices] == list(range(6))
    alone = sense_mesh(_funnel(), "funnel", RunConfig(slices=6, jobs=1, eps=0.2))
    for a, b in zip(run.families[0].slices, alone.families[0].slices):
        assert [p.tolist() for p in a.result.w1] == [p.tolist() for p in b.result.w1]
