"""A forked child (a sensing worker, a side process) inherits its parent's objects frozen
out of the cyclic collector (``gc.freeze``), sensing in this process runs with them frozen,
and the parent's own collector gets them back once the fork, the pool or the sensing is
done."""
import gc

import pytest
import trimesh

from recon3d.config import RunConfig
from recon3d.io.side import Side, can_fork, frozen_heap
from recon3d.sensing import pool
from recon3d.sensing import worker as worker_mod
from recon3d.sensing.mesh import sense_mesh

needs_fork = pytest.mark.skipif(not can_fork(), reason="this platform cannot fork")


def test_frozen_heap_freezes_then_gives_back():
    assert gc.get_freeze_count() == 0
    with frozen_heap() as froze:
        assert froze and gc.get_freeze_count() > 0
    assert gc.get_freeze_count() == 0


def test_frozen_heap_leaves_a_freeze_it_did_not_make():
    gc.freeze()
    try:
        count = gc.get_freeze_count()
        with frozen_heap() as froze:
            assert not froze
        assert gc.get_freeze_count() == count  # not undone by the block
    finally:
        gc.unfreeze()


@needs_fork
def test_a_side_child_inherits_the_heap_frozen():
    assert Side(gc.get_freeze_count).result() > 0
    assert gc.get_freeze_count() == 0


@pytest.mark.parametrize("jobs", [pytest.param(2, marks=needs_fork), 1],
                         ids=["workers", "this-process"])
def test_sensing_runs_with_the_heap_frozen(monkeypatch, jobs):
    """Forked workers inherit the parent's objects frozen; with ``jobs=1`` (and for the
    first slice sensed here while the kernels compile) the objects made before the
    sensing are frozen while it runs, as in a worker. Both give them back after."""
    real = worker_mod.WorkerState.sense

    def sense(self, *args, **kwargs):
        srun = real(self, *args, **kwargs)
        srun.metrics["frozen_objects"] = gc.get_freeze_count()
        return srun

    monkeypatch.setattr(worker_mod.WorkerState, "sense", sense)
    monkeypatch.setattr(pool, "cold_kernels", lambda *backend: False)  # every slice in a worker
    ring = trimesh.creation.annulus(r_min=1.0, r_max=2.0, height=1.0, sections=32)
    run = sense_mesh(ring, "ring", RunConfig(slices=4, jobs=jobs, eps=0.2))
    counts = [s.metrics["frozen_objects"] for s in run.families[0].slices]
    assert len(counts) == 4 and all(c > 1000 for c in counts)  # the parent's objects
    assert gc.get_freeze_count() == 0
