"""Forked sensing workers inherit every slice's contact model built
(:func:`recon3d.sensing.worker.built_contacts`): nothing in a worker builds an Embree scene, whose
TBB tasks can wait forever on a lock that a fork left held."""
import meshes
from recon3d.sensing import pool, sense_mesh
from recon3d.spellings import make_config


def test_workers_are_forked_with_every_contact_built(monkeypatch):
    seen = []
    start = pool._Workers.start

    def check(self, ctx, jobs, init, args):  # the moment the workers are forked
        cuts = [cut for fam in pool._STATE.families for cut in fam if not cut.is_empty]
        models = [cut._backends.get("embree") for cut in cuts]
        seen.append([m is not None and m._kernel is not None for m in models])
        return start(self, ctx, jobs, init, args)

    monkeypatch.setattr(pool._Workers, "start", check)
    back = []
    mesh = meshes.load("stepped_pyramid")
    run = sense_mesh(mesh, "stepped_pyramid", make_config(slices=3, jobs=2),
                     progress=lambda srun: back.append(srun.index))
    assert sorted(back) == [0, 1, 2] and len(run.slices) == 3
    assert seen == [[True, True, True]]  # each slice's Embree scene and direct scene built
