"""A sensing worker whose reply is arriving is sent its next slice before the reply is read
(and unpickled, and the progress updated); still one slice at a time per worker. The
results do not move."""
import trimesh

from recon3d.config import RunConfig
from recon3d.sensing import pool
from recon3d.sensing.mesh import sense_mesh


def _ring():
    return trimesh.creation.annulus(r_min=1.0, r_max=2.0, height=1.0, sections=32)


def test_the_next_slice_is_sent_before_the_reply_is_read(monkeypatch):
    jobs, slices = 2, 8
    sent = []
    real_send = pool._Workers.send

    def recording(self, w, k, task):
        sent.append((w, k, list(self.busy[w])))
        return real_send(self, w, k, task)

    monkeypatch.setattr(pool._Workers, "send", recording)
    monkeypatch.setattr(pool, "cold_kernels", lambda *backend: False)  # no slice sensed in the parent
    run = sense_mesh(_ring(), "ring", RunConfig(slices=slices, jobs=jobs, eps=0.2))
    assert sorted(k for _, k, _ in sent) == list(range(slices))  # each slice sent once
    first, refills = sent[:jobs], sent[jobs:]
    assert [w for w, _, _ in first] == list(range(jobs))
    assert all(held == [] for _, _, held in first)
    # every later slice went to a worker while its finished slice was still booked, i.e.
    # before its reply was read (the booking ends when it is): one finishing, one starting
    assert len(refills) == slices - jobs
    assert all(len(held) == 1 for _, _, held in refills)
    # the same slices as sensed in one process
    alone = sense_mesh(_ring(), "ring", RunConfig(slices=slices, jobs=1, eps=0.2))
    for a, b in zip(run.families[0].slices, alone.families[0].slices):
        assert [p.tolist() for p in a.result.w1] == [p.tolist() for p in b.result.w1]
        assert a.result.stats.motions == b.result.stats.motions
