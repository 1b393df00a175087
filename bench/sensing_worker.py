"""One side of ``bench_sensing``: sense the z-slices of one scene with one checkout.

Run as a script by :mod:`bench.bench_sensing`, never imported by the project::

    python bench/sensing_worker.py ROOT SCENE SLICES OUT [--raw] [--tol-share F]

``ROOT`` is the checkout whose ``meshes``, ``slicer`` and ``core2d`` are used
(it goes first on ``sys.path``), so the same script times the commit before
the work and the working tree. It uses only calls both have: ``meshes.load``,
``slicer.slice_mesh``, ``Slice.contact('embree')``, ``core2d.sense_slice``
and the counters of ``SenseStats``.

Compiled code is loaded before timing (a short sensing run on the first
slice, 200 motions). Per slice it writes to ``OUT`` (JSON): CPU seconds of ``sense_slice``
(``time.process_time``: the machine is shared), motions, rays, casts, the
W1 / W2 / W3 / unknown geometry, and the process's peak resident memory
after sensing. With ``--raw`` it senses every slice a second time through a
recorder that keeps the ray batches of each call as issued and replays them
on the same embreex scene (``scene.run(..., query='INTERSECT')``, the call
the contact model makes, on float32 buffers made beforehand): the time
Embree alone needs for the same rays in the same calls. Batches are kept
up to ``_FLUSH`` rays and replayed then, so the recorder's memory is bounded.
"""
from __future__ import annotations

import json
import logging
import resource
import sys
import time

import numpy as np

_FLUSH = 200_000


class _Recorder:
    """A contact model that passes calls on and times their raw Embree replay."""

    def __init__(self, inner):
        self.inner, self.scene = inner, inner.scene
        self.pending, self.rays, self.raw = [], 0, 0.0

    def cast(self, origins, dirs, max_dist):
        o = np.asarray(origins, dtype=np.float64).reshape(-1, 2)
        d = np.asarray(dirs, dtype=np.float64).reshape(-1, 2)
        o3 = np.zeros((len(o), 3), np.float32)
        d3 = np.zeros((len(d), 3), np.float32)
        o3[:, :2], d3[:, :2] = o, d
        self.pending.append((o3, d3))
        self.rays += len(o)
        if self.rays >= _FLUSH:
            self.flush()
        return self.inner.cast(origins, dirs, max_dist)

    def flush(self) -> None:
        if self.scene is not None and self.pending:
            run, batches = self.scene.run, self.pending
            t0 = time.process_time()
            for o3, d3 in batches:
                run(o3, d3, query="INTERSECT")
            self.raw += time.process_time() - t0
        self.pending, self.rays = [], 0


def _geometry(result) -> dict:
    return {k: [np.asarray(a, float).tolist() for a in getattr(result, k)]
            for k in ("w1", "w2", "w3", "unknown")}


def _peak_mib() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def _warm_visibility() -> None:
    """Load (or compile) the planner's free-gap kernels before timing, where
    the checkout has them: one lid question against one segment."""
    try:
        from core2d.visibility import free_gaps
    except ImportError:
        return
    free_gaps(np.zeros((1, 2)), np.array([[-1.0, 0.0]]), np.array([[-1.0, 1.0]]),
              np.array([[2.0, 1.0]]))


def main(argv) -> int:
    root, scene, count, out = argv[:4]
    raw = "--raw" in argv
    share = float(argv[argv.index("--tol-share") + 1]) if "--tol-share" in argv else None
    sys.path.insert(0, root)
    logging.disable(logging.WARNING)
    import core2d
    import meshes
    import slicer

    mesh = meshes.load(scene)
    eps = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)) / 200)
    tol = None if share is None else eps * share
    cuts = [c for c in slicer.slice_mesh(mesh, axis="z", count=int(count)) if c.loops]
    for cut in cuts:  # build the scenes and load compiled code before timing
        cut.contact("embree").cast(np.zeros((1, 2)), np.array([[1.0, 0.0]]), 1.0)
        cut.contact("embree").cast(np.zeros((40, 2)), np.tile([1.0, 0.0], (40, 1)), 1.0)
        fan = getattr(cut.contact("embree"), "fan", None)
        if fan is not None:
            fan(np.zeros(2), np.zeros(3), 1.0)
    _warm_visibility()
    if cuts:  # load every compiled kernel the planner and the simulator use
        center, radius = cuts[0].bounding_circle()
        core2d.sense_slice(cuts[0].contact("embree"), (center, radius + eps), eps, tol=tol,
                           max_motions=200)
    base = _peak_mib()
    rows = []
    for cut in cuts:
        center, radius = cut.bounding_circle()
        ws = (center, radius + eps)
        t0 = time.process_time()
        res = core2d.sense_slice(cut.contact("embree"), ws, eps, tol=tol)
        sec = time.process_time() - t0
        st = res.stats
        rows.append(dict(index=cut.index, seconds=sec, motions=st.motions, rays=st.rays,
                         casts=st.casts, budget_hit=bool(st.budget_hit), eps=eps,
                         geometry=_geometry(res)))
    doc = dict(scene=scene, slices=rows, peak_mib=_peak_mib(), base_mib=base)
    if raw:
        total = 0.0
        for cut, row in zip(cuts, rows):
            center, radius = cut.bounding_circle()
            rec = _Recorder(cut.contact("embree"))
            res = core2d.sense_slice(rec, (center, radius + eps), eps, tol=tol)
            rec.flush()
            row["raw_seconds"] = rec.raw
            row["replayed_rays"] = res.stats.rays
            total += rec.raw
        doc["raw_seconds"] = total
    with open(out, "w") as fh:
        json.dump(doc, fh)
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
