"""A forked child (a sensing worker, a side process) inherits its parent's objects frozen
out of the cyclic collector (``gc.freeze``), sensing in this process runs with them frozen,
and the parent's own collector gets them back once the fork, the pool or the sensing is
done. The collector is paused (``paused_collector``) where a process only makes objects
that live on: the run's imports, the parent waiting for its workers."""
import gc
import pathlib
import subprocess
import sys
import textwrap

import pytest
import trimesh

from recon3d.config import RunConfig
from recon3d.io.side import Side, can_fork, frozen_heap, paused_collector
from recon3d.sensing import pool
from recon3d.sensing import worker as worker_mod
from recon3d.sensing.mesh import sense_mesh

ROOT = pathlib.Path(__file__).resolve().parents[1]
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


@pytest.mark.parametrize("enabled", [True, False], ids=["was-on", "was-off"])
def test_paused_collector_pauses_then_leaves_it_as_it_was(enabled):
    (gc.enable if enabled else gc.disable)()
    try:
        with pytest.raises(KeyError):
            with paused_collector():
                assert not gc.isenabled()
                raise KeyError("an error inside the block")
        assert gc.isenabled() == enabled
    finally:
        gc.enable()


@needs_fork
def test_the_parent_waits_for_its_workers_with_its_collector_paused(monkeypatch):
    """The workers collect (their heap inherited frozen) while the parent, which only takes
    their slices back, has its collector paused; the contact models the workers inherit are
    built after the freeze (a full collection while they were built walked the whole heap);
    the parent's collector is back on after the sensing."""
    real = worker_mod.WorkerState.sense
    built = []
    real_built = pool.built_contacts

    def sense(self, *args, **kwargs):
        srun = real(self, *args, **kwargs)
        srun.metrics["collector_on"] = gc.isenabled()
        return srun

    def built_contacts(*args):
        built.append(gc.get_freeze_count())
        return real_built(*args)

    monkeypatch.setattr(worker_mod.WorkerState, "sense", sense)
    monkeypatch.setattr(pool, "built_contacts", built_contacts)
    monkeypatch.setattr(pool, "cold_kernels", lambda *backend: False)  # every slice in a worker
    parent = []
    ring = trimesh.creation.annulus(r_min=1.0, r_max=2.0, height=1.0, sections=32)
    run = sense_mesh(ring, "ring", RunConfig(slices=4, jobs=2, eps=0.2),
                     progress=lambda srun: parent.append(gc.isenabled()))
    assert [s.metrics["collector_on"] for s in run.families[0].slices] == [True] * 4
    assert parent == [False] * 4
    assert len(built) == 1 and built[0] > 1000  # the heap frozen before the models are built
    assert gc.isenabled() and gc.get_freeze_count() == 0


def test_the_runs_libraries_load_with_the_collector_paused():
    """``recon3d run`` imports its libraries (trimesh, the sensing, VTK) with the collector
    paused: one collection as the pause ends (the young objects), where about 280 ran
    (0.1 s) and found nothing (a fresh interpreter: the libraries not loaded yet)."""
    code = textwrap.dedent("""
        import gc, sys
        from recon3d.cli import run
        assert "recon3d.api" not in sys.modules and "trimesh" not in sys.modules
        seen = []
        gc.callbacks.append(lambda phase, info: seen.append(phase) if phase == "start" else None)
        run.libraries()
        assert "recon3d.api" in sys.modules and "trimesh" in sys.modules
        print(len(seen), gc.isenabled())
    """)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=str(ROOT))
    collections, enabled = out.stdout.split()
    assert int(collections) <= 1 and enabled == "True"
