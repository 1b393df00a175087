"""``recon3d batch MANIFEST``: many meshes x parameters, one job each, on Dask.

The manifest is TOML. Every mesh runs with every combination of the listed
parameter values (a grid)::

    meshes = ["fig17_pocket", "parts/bracket.stl"]  # scene names or paths (relative
                                                    # to the manifest's folder)
    [params]                                        # each key: one value or a list
    slices = [4, 8, "auto"]
    eps_share = [0.01, 0.005]   # eps as a share of the diagonal (or eps = mesh units)
    axis = "z"                  # or ["z", "x"] as one value: [["z", "x"]]
    backend = "embree"

Keys of ``[params]``: ``axis``, ``slices``, ``eps``, ``eps_share``, ``tol``,
``backend``, ``max_motions``, ``max_slices``, ``slice_tol``, ``probe_speed``,
``motion_overhead`` (the keywords of :func:`recon3d.run`). Everything is
checked before the first run: a bad manifest is one clear error.

Each job is :func:`run_job` (``recon3d.run`` with ``jobs=1``); its outputs
go to ``DIR/runs/NNN_<mesh>/`` (``metrics.json``, ``sensing.json``,
``surface.ply``; ``recon3d run`` writes the pictures) and one row per job to
``DIR/batch.csv``. Outputs are staged and moved into place at the end.
"""
from __future__ import annotations

import itertools
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from recon3d.checks import InputError

__all__ = ["Job", "read_manifest", "run_job", "job_row", "COLUMNS", "PARAMS"]

PARAMS = ("axis", "slices", "eps", "eps_share", "tol", "backend", "max_motions", "max_slices",
          "slice_tol", "probe_speed", "motion_overhead")

COLUMNS = ("job", "mesh", "axis", "slices", "eps", "backend", "sensed_slices", "coverage",
           "fscore_1%", "chamfer_l1_diag", "hd95_diag", "motions", "robot_time_s",
           "budget_hits", "seconds")


@dataclass(frozen=True)
class Job:
    """One mesh with one parameter set.

    index : int -- position in the batch.
    mesh : str -- scene name or absolute mesh path.
    params : dict -- keywords of :func:`recon3d.run` (``eps_share`` resolved later).
    """

    index: int
    mesh: str
    params: dict

    @property
    def name(self) -> str:
        """Directory name: ``NNN_<mesh file stem>``."""
        stem = re.sub(r"[^A-Za-z0-9_.-]+", "_", Path(self.mesh).stem)
        return f"{self.index:03d}_{stem}"


def _as_list(value):
    return list(value) if isinstance(value, list) else [value]


def read_manifest(path) -> list[Job]:
    """Parse and check a manifest (see the module doc); the jobs in grid order.

    Raises
    ------
    InputError -- unreadable TOML, no meshes, an unknown key, a mesh that does
        not load, or a parameter set that ``recon3d run`` would reject.
    """
    import meshes

    from recon3d.api import load_input, make_config, validate

    path = Path(path)
    try:
        doc = tomllib.loads(path.read_text())
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"cannot read manifest {path}: {exc.__class__.__name__}") from None
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"manifest {path} is not valid TOML: {exc}") from None
    extra = set(doc) - {"meshes", "params"}
    if extra:
        raise InputError(f"manifest: unknown top-level keys {sorted(extra)} (meshes, params)")
    names = doc.get("meshes")
    if not names or not isinstance(names, list) or not all(isinstance(n, str) for n in names):
        raise InputError("manifest: 'meshes' must be a non-empty list of scene names or paths")
    params = doc.get("params", {})
    if not isinstance(params, dict):
        raise InputError("manifest: [params] must be a table")
    bad = set(params) - set(PARAMS)
    if bad:
        raise InputError(f"manifest: unknown parameters {sorted(bad)} (allowed: {', '.join(PARAMS)})")
    if "eps" in params and "eps_share" in params:
        raise InputError("manifest: give eps or eps_share, not both")
    keys = sorted(params)
    grid = [dict(zip(keys, combo)) for combo in itertools.product(*(_as_list(params[k]) for k in keys))]
    jobs = []
    for name in names:
        source = name if name in meshes.names() else str((path.parent / name).resolve())
        mesh, _, _ = load_input(source)
        diag = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)))
        for p in grid:
            kw = _resolved(p, diag)
            try:
                validate(mesh, make_config(**kw), {k: f"params.{k}" for k in PARAMS})
            except (TypeError, ValueError) as exc:
                raise InputError(f"manifest: {name} with {p}: {exc}") from None
            jobs.append(Job(len(jobs), source, dict(p)))
    return jobs


def _resolved(params: dict, diag: float) -> dict:
    """``eps_share`` -> ``eps`` (mesh units)."""
    kw = dict(params)
    share = kw.pop("eps_share", None)
    if share is not None:
        if isinstance(share, bool) or not isinstance(share, (int, float)):
            raise InputError(f"manifest: eps_share must be a number (got {share!r})")
        kw["eps"] = float(share) * diag
    return kw


def run_job(job: Job) -> dict:
    """Run one job (in a Dask worker or in this process).

    Returns
    -------
    dict with ``row`` (the batch.csv row), ``metrics`` and ``sensing`` (the JSON
    documents) and ``surface`` (vertices (v, 3), faces (f, 3), labels (f,)).
    """
    import time
    import warnings

    from recon3d.api import execute, load_input, make_config

    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mesh, name, notes = load_input(job.mesh)
        diag = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)))
        config = make_config(**_resolved(job.params, diag), jobs=1)
        res = execute(mesh, name, config, notes)
    surf = res.surface
    return {"row": job_row(job, res, diag, time.perf_counter() - t0), "metrics": res.metrics,
            "sensing": res.sensing_document(),
            "surface": (np.asarray(surf.vertices), np.asarray(surf.faces),
                        np.asarray(surf.face_attributes["label"]))}


def job_row(job: Job, res, diag: float, seconds: float) -> dict:
    """The batch.csv row of a finished job (lengths over the diagonal, wall seconds)."""
    tot = res.metrics["total"]
    s = tot.get("surface") or {}
    axis = job.params.get("axis", "z")
    return {"job": job.index, "mesh": Path(job.mesh).name, "axis": str(axis),
            "slices": job.params.get("slices", 8), "eps": res.sensing.eps,
            "backend": job.params.get("backend", "embree"), "sensed_slices": len(res.slices),
            "coverage": tot.get("coverage"), "fscore_1%": (s.get("fscore") or {}).get("1%"),
            "chamfer_l1_diag": None if s.get("chamfer_l1") is None else s["chamfer_l1"] / diag,
            "hd95_diag": None if s.get("hd95") is None else s["hd95"] / diag,
            "motions": tot.get("motions"), "robot_time_s": tot.get("robot_time_s"),
            "budget_hits": tot.get("budget_hits", 0), "seconds": seconds}
