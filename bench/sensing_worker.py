"""One side of ``bench_sensing``: sense the z-slices of one scene with one checkout.

Run as a script by :mod:`bench.bench_sensing`, never imported by the project::

    python bench/sensing_worker.py ROOT SCENE SLICES OUT [--raw] [--tol-share F]
                                   [--sensor NOISE,TAXEL,KEYED]

``ROOT`` is the checkout whose ``meshes``, ``slicer`` and ``core2d`` are used
(it goes first on ``sys.path``), so the same script times the commit before
the work and the working tree. It uses only calls both have: ``meshes.load``,
``slicer.slice_mesh``, ``Slice.contact('embree')``, ``core2d.sense_slice``
and the counters of ``SenseStats``.

Compiled code is loaded before timing (a short sensing run on the first
slice, 200 motions); then the process's objects are frozen out of the cyclic
collector (``gc.freeze``), as a run's sensing workers inherit them and as a
run senses in one process. Per slice it writes to ``OUT`` (JSON): CPU seconds of ``sense_slice``
(``time.process_time``: the machine is shared), motions, rays, casts, the
W1 / W2 / W3 / unknown geometry, and the process's peak resident memory
after sensing. With ``--raw`` it senses every slice a second time with the
contact model's ray function wrapped in a ray log (:mod:`bench.ray_log`:
every ray the compiled engine casts, cast by cast) and replays those rays on
the same embreex scene (``scene.run(..., query='INTERSECT')``, the call the
contact model makes, on float32 buffers made beforehand): the time Embree
alone needs for the same rays in the same casts (``raw_seconds``), and in
calls of 65,536 rays (``large_seconds``, Embree's throughput). The log is
replayed every ``_FLUSH`` rays, so its memory is bounded.
"""
from __future__ import annotations

import gc
import json
import logging
import resource
import sys
import time
from pathlib import Path

import numpy as np

_FLUSH = 200_000
_LARGE = 65_536


class _Replay:
    """The rays of one sensing run, replayed on the slice's embreex scene
    (``scene.run(o, d, query='INTERSECT')`` on float32 buffers made
    beforehand): ``as_cast`` -- in the casts as issued, one call per cast;
    ``large`` -- all in calls of ``_LARGE`` rays (Embree's throughput)."""

    def __init__(self, scene):
        self.scene, self.as_cast, self.large, self.rays, self.casts = scene, 0.0, 0.0, 0, 0
        self.tail = np.zeros((0, 2, 3), np.float32)  # rays waiting for a large call

    def add(self, rays, cast_ids) -> None:
        """Replay ``rays`` (n, 4: ox, oy, dx, dy), cast by cast (``cast_ids`` (n,),
        non-decreasing) and in large calls."""
        n = len(rays)
        if n == 0 or self.scene is None:
            return
        od = np.zeros((n, 2, 3), np.float32)
        od[:, 0, :2], od[:, 1, :2] = rays[:, :2], rays[:, 2:]
        cuts = np.flatnonzero(np.diff(cast_ids)) + 1
        batches = [(np.ascontiguousarray(b[:, 0]), np.ascontiguousarray(b[:, 1]))
                   for b in np.split(od, cuts)]
        run = self.scene.run
        t0 = time.process_time()
        for o3, d3 in batches:
            run(o3, d3, query="INTERSECT")
        self.as_cast += time.process_time() - t0
        self.rays, self.casts = self.rays + n, self.casts + len(batches)
        self.tail = np.concatenate((self.tail, od))
        self._large(final=False)

    def _large(self, final) -> None:
        k = len(self.tail) if final else len(self.tail) // _LARGE * _LARGE
        if k == 0:
            return
        chunks = [(np.ascontiguousarray(self.tail[i:i + _LARGE, 0]),
                   np.ascontiguousarray(self.tail[i:i + _LARGE, 1])) for i in range(0, k, _LARGE)]
        run = self.scene.run
        t0 = time.process_time()
        for o3, d3 in chunks:
            run(o3, d3, query="INTERSECT")
        self.large += time.process_time() - t0
        self.tail = self.tail[k:]

    def finish(self) -> None:
        if self.scene is not None:
            self._large(final=True)


class _Logged:
    """The contact model with its ray function wrapped in a ray log
    (:class:`bench.ray_log.RayLog`); batched calls are logged as casts too."""

    def __init__(self, inner, log, replay):
        self.inner, self.log, self.replay = inner, log, replay
        self.ray_kernel = log.ray_kernel

    def __getattr__(self, name):
        return getattr(self.inner, name)

    def cast(self, origins, dirs, max_dist):
        o = np.asarray(origins, dtype=np.float64).reshape(-1, 2)
        d = np.asarray(dirs, dtype=np.float64).reshape(-1, 2)
        self.flush()
        self.replay.add(np.hstack((o, d)), np.zeros(len(o), np.int64))
        return self.inner.cast(origins, dirs, max_dist)

    def fan(self, origin, angles, max_dist):
        angles = np.asarray(angles, dtype=np.float64).reshape(-1)
        dirs = np.stack((np.cos(angles), np.sin(angles)), 1)
        self.flush()
        self.replay.add(np.hstack((np.tile(origin, (len(angles), 1)), dirs)),
                        np.zeros(len(angles), np.int64))
        return self.inner.fan(origin, angles, max_dist)

    def flush(self) -> None:
        """Replay what the ray log holds."""
        rays, ids = self.log.take()
        self.replay.add(rays, ids)


def _logged_engine(base):
    """``base`` (the compiled engine class) marking a new cast in the ray log
    before every call into compiled code, and replaying the log now and then."""

    class Logged(base):
        def _mark(self, counter):
            log = self.contact.log
            log.new_cast(counter)
            if log.head[3] >= _FLUSH:
                self.contact.flush()
                log.new_cast(counter)

        def _run(self, kernel, *args):
            self._mark(self._count)
            return super()._run(kernel, *args)

        def cast(self, origins, dirs, max_dist):
            self._mark(None)
            return super().cast(origins, dirs, max_dist)

        def sense_rays(self, *args):
            self._mark(None)
            return super().sense_rays(*args)

    return Logged


def _raw(core2d, cut, eps, tol, sensor=None) -> dict:
    """Sense ``cut`` again through a ray log and replay its rays on raw embreex."""
    import importlib.util

    import core2d.sim.engine as engine_module

    # this worker's ray log (the checkout under test may have none, or an older one)
    spec = importlib.util.spec_from_file_location("_ray_log", Path(__file__).with_name(
        "ray_log.py"))
    ray_log = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(ray_log)
    RayLog = ray_log.RayLog

    contact = cut.contact("embree")
    replay = _Replay(contact.scene)
    logged = _Logged(contact, RayLog(contact.ray_kernel), replay)
    compiled = engine_module.CompiledEngine
    engine_module.CompiledEngine = _logged_engine(compiled)
    try:
        center, radius = cut.bounding_circle()
        res = core2d.sense_slice(logged, (center, radius + eps), eps, tol=tol, sensor=sensor)
    finally:
        engine_module.CompiledEngine = compiled
    logged.flush()
    replay.finish()
    if (replay.rays, replay.casts) != (res.stats.rays, res.stats.casts):
        raise RuntimeError(f"replayed {replay.rays} rays in {replay.casts} casts, sensing "
                           f"cast {res.stats.rays} in {res.stats.casts}")
    return dict(raw_seconds=replay.as_cast, large_seconds=replay.large,
                replayed_rays=replay.rays, replayed_casts=replay.casts)


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
    stated = argv[argv.index("--sensor") + 1].split(",") if "--sensor" in argv else None
    sys.path.insert(0, root)
    logging.disable(logging.WARNING)
    import core2d
    import meshes
    import slicer

    mesh = meshes.load(scene)
    eps = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)) / 200)
    tol = None if share is None else eps * share

    def sensor(index):
        """The sensor of slice ``index`` (None: the paper's perfect one)."""
        if stated is None:
            return None
        from core2d.resolution import repeated_reads

        noise, taxel, keyed = float(stated[0]), float(stated[1]), stated[2] == "1"
        return core2d.SensorModel.of_eps(eps, noise, taxel, int(index), keyed=keyed,
                                         reads=repeated_reads(1.0, noise, taxel))
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
                           max_motions=200, sensor=sensor(cuts[0].index))
    # as the product senses (recon3d.sensing.pool): what exists before the sensing frozen
    # out of the cyclic collector, so that its full collections walk only what sensing made
    gc.freeze()
    base = _peak_mib()
    rows = []
    for cut in cuts:
        center, radius = cut.bounding_circle()
        ws = (center, radius + eps)
        t0 = time.process_time()
        res = core2d.sense_slice(cut.contact("embree"), ws, eps, tol=tol,
                                 sensor=sensor(cut.index))
        sec = time.process_time() - t0
        st = res.stats
        rows.append(dict(index=cut.index, seconds=sec, motions=st.motions, rays=st.rays,
                         casts=st.casts, budget_hit=bool(st.budget_hit), eps=eps,
                         geometry=_geometry(res)))
    doc = dict(scene=scene, slices=rows, peak_mib=_peak_mib(), base_mib=base)
    if raw:
        for cut, row in zip(cuts, rows):
            row.update(_raw(core2d, cut, eps, tol, sensor(cut.index)))
        doc["raw_seconds"] = sum(r["raw_seconds"] for r in rows)
        doc["large_seconds"] = sum(r["large_seconds"] for r in rows)
    with open(out, "w") as fh:
        json.dump(doc, fh)
    gc.unfreeze()  # the exit's collection then frees what the bindings hold (no leak report)
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
