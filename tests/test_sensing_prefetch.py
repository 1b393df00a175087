"""Each sensing worker holds a second task while more are left than there are workers;
the last ones go one at a time to an idle worker. The results do not move."""
import trimesh

from recon3d.config import RunConfig
from recon3d.sensing import pool
from recon3d.sensing.mesh import sense_mesh


def _sent(monkeypatch, jobs: int, slices: int):
    """(worker, task, tasks the worker held before this one) of every send of a run."""
    sent = []
    real = pool._Workers.send

    def recording(self, w, k, task):
        sent.append((w, k, len(self.busy[w])))
        return real(self, w, k, task)

    monkeypatch.setattr(pool._Workers, "send", recording)
    monkeypatch.setattr(pool, "cold_kernels", lambda: False)  # no slice sensed in the parent
    mesh = trimesh.creation.annulus(r_min=1.0, r_max=2.0, height=1.0, sections=32)
    run = sense_mesh(mesh, "ring", RunConfig(slices=slices, jobs=jobs, eps=0.2))
    return sent, run


def test_two_tasks_in_flight_until_the_last_ones(monkeypatch):
    jobs, slices = 2, 8
    sent, run = _sent(monkeypatch, jobs, slices)
    assert sorted(k for _, k, _ in sent) == list(range(slices))  # each task sent once
    held = [h for _, _, h in sent]
    # the first round gives every worker one task, the second a queued one
    assert held[:2 * jobs] == [0] * jobs + [1] * jobs
    assert [w for w, _, _ in sent[:2 * jobs]] == list(range(jobs)) * 2
    # while more than `jobs` tasks were left, a refill queued behind the running one
    assert all(h == 1 for h in held[2 * jobs:slices - jobs])
    # the last `jobs` tasks went to workers holding none
    assert held[-jobs:] == [0] * jobs
    assert max(held) == 1
    # the same slices as sensed in one process
    alone = sense_mesh(trimesh.creation.annulus(r_min=1.0, r_max=2.0, height=1.0, sections=32),
                       "ring", RunConfig(slices=slices, jobs=1, eps=0.2))
    for a, b in zip(run.families[0].slices, alone.families[0].slices):
        assert [p.tolist() for p in a.result.w1] == [p.tolist() for p in b.result.w1]
        assert a.result.stats.motions == b.result.stats.motions


def test_few_tasks_go_one_at_a_time(monkeypatch):
    sent, _ = _sent(monkeypatch, 2, 3)  # 3 tasks, 2 workers: the third is one of the last
    assert [h for _, _, h in sent] == [0, 0, 0]
