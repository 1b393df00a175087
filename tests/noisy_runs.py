"""Seeded noisy runs of one constructed outline, checked per seed (tests helper).

:func:`coverages` senses the outline once with the paper's perfect sensor
and once per sensor seed, asserts on every noisy run what the issue's
targets ask of each slice -- no budget hit, precision within eps/2 + 2 sigma
>= 0.98, no W3 lid unsound at that tolerance, at most twice the noiseless
motions -- and returns the reachable coverages within eps/2 + 2 sigma, whose
mean the caller tests (one seed's coverage is a lottery at +-0.01).
"""
from __future__ import annotations

import numpy as np

from core2d import SensorModel, sense_slice
from core2d.resolution import repeated_reads
from core2d.truth.metrics import sensor_metrics
from outlines import outline
from slicer.contact.exact import ExactContact

__all__ = ["coverages", "scene_slice", "mesh_slice", "outline_run", "slot_covered"]


def coverages(loops, ws, noise: float, seeds, eps: float = 1.0,
              taxel: float = 0.0, keyed: bool = False, reads: int = 1) -> np.ndarray:
    """(len(seeds),) reachable coverage within eps/2 + 2 ``noise`` (``noise``
    and the taxel spacing ``taxel`` in eps) of ``loops`` sensed in the
    workspace ``ws`` (exact backend), one run per sensor seed; asserts the
    per-seed targets (module doc) and a noiseless coverage >= 0.99; ``keyed``:
    the sensor's draws keyed by reading (``SensorModel(keyed=True)``); ``reads``: reads
    averaged per reading point (``SensorModel(reads=...)``)."""
    contact = ExactContact(loops)
    base = sense_slice(contact, ws, eps)
    assert sensor_metrics(loops, base, eps, 0.0)["coverage_sensor"] >= 0.99
    covs = []
    for seed in seeds:
        res = sense_slice(contact, ws, eps,
                          sensor=SensorModel.of_eps(eps, noise, taxel, seed, keyed=keyed,
                                                    reads=reads))
        m = sensor_metrics(loops, res, eps, noise * eps)
        assert not res.stats.budget_hit, f"seed {seed}"
        assert m["precision_sensor"] >= 0.98, f"seed {seed}: {m['precision_sensor']:.4f}"
        assert m["w3_unsound_count_sensor"] == 0, f"seed {seed}"
        assert res.stats.motions <= 2 * base.stats.motions, (seed, res.stats.motions)
        covs.append(m["coverage_sensor"])
    return np.array(covs)


def mesh_slice(source, index: int, count: int = 8):
    """z-slice ``index`` of ``count`` of the mesh ``source`` (a built-in scene's name or a
    path), cut as the sensor study cuts it: ``(cut, eps, workspace, loops)``, eps =
    diagonal / 200, the workspace the cut's bounding circle grown by eps."""
    import meshes
    import slicer

    mesh = meshes.load(source)
    eps = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)) / 200)
    cut = slicer.slice_mesh(mesh, axis="z", count=count)[index]
    center, radius = cut.bounding_circle()
    return cut, eps, (center, radius + eps), [np.asarray(lp) for lp in cut.loops]


def scene_slice(name: str, index: int, noise: float, taxel: float, seed: int,
                keyed: bool = False, reads: int = 1):
    """Sense z-slice ``index`` of 8 of the built-in scene ``name`` (Embree,
    eps = diagonal / 200) with the sensor (``noise`` and ``taxel`` in eps,
    ``seed``; ``keyed`` draws; ``reads`` averaged per reading point), as the sensor study
    does; returns the result and
    :func:`~core2d.truth.metrics.sensor_metrics` of it."""
    cut, eps, ws, loops = mesh_slice(name, index)
    res = sense_slice(cut.contact("embree"), ws, eps,
                      sensor=SensorModel.of_eps(eps, noise, taxel, seed, keyed=keyed,
                                                reads=reads))
    return res, sensor_metrics(loops, res, eps, noise * eps)


def outline_run(kind: str, seed: int, sensor_seed: int, noise: float = 0.3,
                taxel: float = 0.25):
    """Sense the seeded outline ``kind``-``seed`` of ``tests/outlines.py`` (exact backend,
    eps 1) with the sensor (``noise`` and ``taxel`` in eps, ``sensor_seed``, the reads
    ``recon3d run`` takes), as the sensor study does; returns the result and
    :func:`~core2d.truth.metrics.sensor_metrics` of it."""
    loops = outline(kind, np.random.default_rng(seed), 1.0)
    pts = np.concatenate(loops)
    ws = ((pts.min(0) + pts.max(0)) / 2, float(np.linalg.norm(np.ptp(pts, axis=0)) / 2 + 1.0))
    sensor = SensorModel.of_eps(1.0, noise, taxel, sensor_seed,
                                reads=repeated_reads(1.0, noise, taxel))
    res = sense_slice(ExactContact(loops), ws, 1.0, sensor=sensor)
    return res, sensor_metrics(loops, res, 1.0, noise)


def slot_covered(res, loops, x, eps, tol) -> float:
    """Share of the reachable contour samples of the slot at ``x`` below the top face
    (within 0.3 units of x) that the metrics count covered: within ``tol`` of W1 or W2,
    or under a W2 chord that spans an opening (:func:`~core2d.truth.metrics.w2_credit`)."""
    from core2d.truth.metrics import w2_credit
    from core2d.truth.nearest import segment_distances
    from core2d.truth.reachability import reachable_samples

    samples, reach = reachable_samples(loops, eps / 4)
    pts = samples.points
    top = max(lp[:, 1].max() for lp in loops)
    slot = reach & (np.abs(pts[:, 0] - x) < 0.3) & (pts[:, 1] < top - 0.25 * eps)
    pieces = [np.asarray(p) for p in list(res.w1) + list(res.w2)]
    a = np.concatenate([p[:-1] for p in pieces])
    b = np.concatenate([p[1:] for p in pieces])
    near = segment_distances(pts, a, b) <= tol
    behind = w2_credit(loops, res.w2, samples, eps / 4)[0]
    return float((slot & (near | behind)).sum() / slot.sum())
