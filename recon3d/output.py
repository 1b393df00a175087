"""Run output: ``sensing.json`` (DESIGN.md contract) and ``metrics.json``.

Files are written atomically (temporary file + rename) so a failed or
interrupted run never leaves a half-written output.
"""
from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

import numpy as np

__all__ = ["sensing_document", "metrics_document", "write_json"]


def _world(cut, pts) -> list:
    return np.asarray(cut.to_3d(np.asarray(pts, float).reshape(-1, 2))).round(9).tolist()


def _area_log(cut, rec) -> dict:
    """One A_iB_i record: which rule created it and how it ended."""
    a, b = _world(cut, np.stack([rec.a, rec.b]))
    return {"index": int(rec.index), "a": a, "b": b, "parent": int(rec.parent),
            "rule": rec.rule, "outcome": rec.outcome, "note": rec.note}


def _slice_document(srun) -> dict:
    cut, res = srun.slice, srun.result
    plane = cut.plane
    segments = [{"class": "W1", "points": _world(cut, w)} for w in res.w1]
    segments += [{"class": "W2", "points": _world(cut, w)} for w in res.w2]
    segments += [{"class": "W3", "points": _world(cut, w)} for w in res.w3]
    stats = res.stats.as_dict()
    stats["unknown"] = len(res.unknown)
    return {
        "index": int(plane.index),
        "origin": np.asarray(plane.origin, float).tolist(),
        "normal": np.asarray(plane.normal, float).tolist(),
        "u": np.asarray(plane.u, float).tolist(),
        "v": np.asarray(plane.v, float).tolist(),
        "segments": segments,
        "unknown": [_world(cut, w) for w in res.unknown],
        "areas": [_area_log(cut, rec) for rec in res.areas],
        "nudge": float(plane.nudge),
        "stats": stats,
    }


def sensing_document(run) -> dict:
    """The ``sensing.json`` object of a :class:`recon3d.pipeline.MeshRun`."""
    return {
        "mesh": run.name,
        "eps": float(run.eps),
        "probe_length": float(run.probe_length),
        "backend": run.config.backend,
        "slices": [_slice_document(s) for s in run.slices],
    }


def metrics_document(run) -> dict:
    """Per-slice metrics and their totals (``metrics.json``)."""
    return {
        "mesh": run.name,
        "eps": float(run.eps),
        "seconds": float(run.seconds),
        "total": run.totals,
        "slices": [dict(index=int(s.slice.plane.index), **s.metrics) for s in run.slices],
    }


def write_json(path, obj) -> Path:
    """Write ``obj`` as JSON to ``path`` atomically."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=path.name + ".", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w") as fh:
            json.dump(obj, fh, indent=1, allow_nan=False)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path
