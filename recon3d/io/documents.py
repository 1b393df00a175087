"""The JSON documents of a run: ``sensing.json`` (DESIGN.md contract) and ``metrics.json``.

2D metric dicts come from :func:`core2d.truth.metrics.slice_metrics` and are
passed through as they are (their keys may grow); recon3d adds the slice's
family, reference facts, robot time, the 3D ``total.surface`` block and the
``surface_eval`` block that explains it.
"""
from __future__ import annotations

import numpy as np

from recon3d.records import MeshRun, SliceRun

__all__ = ["sensing_document", "slice_document", "metrics_document", "without_timing",
           "ROBOT_RULE"]

ROBOT_RULE = ("robot_time_s = joint_path / probe_speed + motions x motion_overhead_s"
              " + sensor_reads x read_time_s")


def without_timing(doc):
    """``doc`` (a sensing.json / metrics.json document, or any part of one)
    without the keys that depend on the machine (``seconds``, ``jobs``):
    what two runs of the same job must agree on.

    >>> without_timing({"stats": {"motions": 3, "seconds": 0.2}, "jobs": 2})
    {'stats': {'motions': 3}}
    """
    if isinstance(doc, dict):
        return {k: without_timing(v) for k, v in doc.items() if k not in ("seconds", "jobs")}
    if isinstance(doc, list):
        return [without_timing(v) for v in doc]
    return doc


def _world(cut, pts) -> list:
    return np.asarray(cut.to_3d(np.asarray(pts, float).reshape(-1, 2))).round(9).tolist()


def _area_logs(cut, records) -> list:
    """Every A_iB_i record: which rule created it and how it ended (the ends
    of all records mapped to world in one call)."""
    if not records:
        return []
    ends = _world(cut, np.array([(rec.a, rec.b) for rec in records], dtype=float))
    return [{"index": int(rec.index), "a": ends[2 * k], "b": ends[2 * k + 1],
             "parent": int(rec.parent), "rule": rec.rule, "outcome": rec.outcome,
             "note": rec.note} for k, rec in enumerate(records)]


def slice_document(srun: SliceRun, cut=None) -> dict:
    """The ``sensing.json`` entry of one slice (DESIGN.md contract): its plane, its W1 / W2 /
    W3 segments, unknown polylines and A_iB_i records in world coordinates, its counters.

    cut : slicer.Slice, optional -- the slice sensed (default ``srun.slice``): a worker
        makes the entry before the parent fills in ``srun.slice``.
    """
    cut, res = (srun.slice if cut is None else cut), srun.result
    plane = cut.plane
    at = res.known_at  # the motion after which each piece was recorded
    segments = [{"class": cls.upper(), "points": _world(cut, w), "motion": int(k)}
                for cls in ("w1", "w2", "w3") for w, k in zip(getattr(res, cls), at[cls])]
    stats = res.stats.as_dict()
    stats["unknown"] = len(res.unknown)
    return {
        "index": int(plane.index),
        "family": int(srun.family),
        "origin": np.asarray(plane.origin, float).tolist(),
        "normal": np.asarray(plane.normal, float).tolist(),
        "u": np.asarray(plane.u, float).tolist(),
        "v": np.asarray(plane.v, float).tolist(),
        "segments": segments,
        "unknown": [_world(cut, w) for w in res.unknown],
        "areas": _area_logs(cut, res.areas),
        "nudge": float(plane.nudge),
        "stats": stats,
    }


def _families(run: MeshRun) -> list:
    return [{"axis": fam.label, "normal": np.asarray(fam.normal, float).tolist(),
             "slices": len(fam.slices)} for fam in run.families]


def sensing_document(run: MeshRun) -> dict:
    """The ``sensing.json`` object of a :class:`recon3d.records.MeshRun`."""
    return {
        "mesh": run.name,
        "eps": float(run.eps),
        "tol": float(run.tol),
        "probe_length": float(run.probe_length),
        "backend": run.config.backend,
        "method": run.config.method,
        "families": _families(run),
        "slices": [s.document if s.document is not None else slice_document(s)
                   for s in run.slices],
    }


def _slice_metrics(srun: SliceRun, run: MeshRun, position: int) -> dict:
    out = {"index": int(srun.slice.plane.index), "family": int(srun.family),
           "axis": run.families[srun.family].label, "reference": srun.has_reference,
           "outer_loops": srun.outer_loops,
           "holes": int(np.asarray(srun.slice.holes, dtype=bool).sum()),
           "open_chains": len(srun.slice.open_chains)}
    if run.adaptive is not None:  # index: the position among sensed slices, as printed
        out = {"index": position, "candidate": out.pop("index"), **out}
    out.update(srun.metrics)
    return out


def metrics_document(run: MeshRun, surface: dict | None, surface_eval: dict,
                     unknown_chords: list = ()) -> dict:
    """Per-slice 2D metrics, their totals, the 3D ``total.surface`` block and robot time.

    Parameters
    ----------
    run : recon3d.records.MeshRun
    surface : dict or None -- from :func:`recon3d.score.score`.
    surface_eval : dict -- its explanation (domain, tau, samples, the shares of
        the ground truth, each family's own surface).
    unknown_chords : list of dict -- :func:`recon3d.score.unknowns.unknown_chords`;
        ``total.unknown_chords`` counts them, ``total.unknown_chord_length`` sums
        their lengths.

    ``robot.probe_speed`` is in mesh units per second (``robot.units``; the
    ``probe_speed`` parameter is in mm/s). With ``--slices auto`` each slice's
    ``index`` is its position in its family and ``candidate`` its candidate
    plane, and the document ends with ``adaptive`` (``run.adaptive``). A run with a
    sensor model (``noise`` or ``taxel``) records it under ``sensor``, one with
    tip friction its coefficient under ``friction``.
    """
    cfg = run.config
    total = dict(run.totals)
    total["surface"] = surface
    total["unknown_chords"] = len(unknown_chords)
    total["unknown_chord_length"] = float(sum(c["length"] for c in unknown_chords))
    doc = {
        "mesh": run.name,
        "eps": float(run.eps),
        "tol": float(run.tol),
        "method": cfg.method,
        "seconds": float(run.seconds),
        "jobs": int(run.jobs),
        "families": _families(run),
        "robot": {"probe_speed": cfg.speed, "motion_overhead_s": float(cfg.motion_overhead),
                  "read_time_s": float(cfg.read_time),
                  "rule": ROBOT_RULE, "units": cfg.units},
        "total": total,
        "surface_eval": surface_eval,
        "unknown_chords": list(unknown_chords),
        "slices": [_slice_metrics(s, run, k) for fam in run.families
                   for k, s in enumerate(fam.slices)],
    }
    if cfg.noise or cfg.taxel or cfg.torque_threshold or cfg.torque_noise:  # absent: perfect
        doc["sensor"] = {"noise": float(cfg.noise), "taxel": float(cfg.taxel),
                         "seed": int(cfg.seed), "torque_threshold": float(cfg.torque_threshold),
                         "torque_noise": float(cfg.torque_noise),
                         "keyed": bool(cfg.keyed_noise), "reads": int(run.reads), "unit": "eps",
                         "metric_tol": "eps / 2 + 2 noise (the *_sensor metrics)"}
    if cfg.friction:  # absent: no friction, the paper's simulation
        doc["friction"] = float(cfg.friction)
    if run.adaptive is not None:
        doc["adaptive"] = run.adaptive
    return doc
