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

The keys of ``[params]`` are :func:`recon3d.spellings.batch_keys` (the
keywords of :func:`recon3d.run` but ``jobs``, and ``eps_share``;
:func:`recon3d.spellings.manifest_doc` names them). Everything is checked
before the first run: a bad manifest is one clear error.

Each job is :func:`run_job` (``recon3d.run`` with ``jobs=1``); its outputs
go to ``DIR/runs/NNN_<mesh>/`` (``metrics.json``, ``sensing.json``, ``motions.csv``,
``surface.ply``; ``recon3d run`` writes the pictures) and one row per job to
``DIR/batch.csv`` (:func:`write_batch`, staged and moved into place at the end).
"""
from __future__ import annotations

import csv
import itertools
import re
import time
import tomllib
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

import meshes
from recon3d.api import Result, execute, load_input
from recon3d.checks import InputError
from recon3d.config import RunConfig, diagonal, validate
from recon3d.spellings import BATCH_ONLY, batch_keys, make_config
from recon3d.io.motions import motions_text
from recon3d.io.outputs import write_json
from recon3d.io.ply import write_ply
from recon3d.io.staged import Staged


__all__ = ["Job", "read_manifest", "run_job", "write_batch", "COLUMNS"]

COLUMNS = ("job", "mesh", "axis", "slices", "eps", "backend", "noise", "taxel", "sensed_slices",
           "coverage", "coverage_sensor", "fscore_1%", "chamfer_l1_diag", "hd95_diag", "motions",
           "robot_time_s", "budget_hits", "seconds")

_DEFAULT = RunConfig()


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
    allowed = batch_keys()
    bad = set(params) - set(allowed)
    if bad:
        raise InputError(f"manifest: unknown parameters {sorted(bad)} (allowed: {', '.join(allowed)})")
    for key, (target, _) in BATCH_ONLY.items():
        if key in params and target in params:
            raise InputError(f"manifest: give {target} or {key}, not both")
    keys = sorted(params)
    grid = [dict(zip(keys, combo)) for combo in itertools.product(*(_as_list(params[k]) for k in keys))]
    jobs = []
    for name in names:
        source = name if name in meshes.names() else str((path.parent / name).resolve())
        mesh, _, _ = load_input(source)
        diag = diagonal(mesh)
        for p in grid:
            kw = _resolved(p, diag)
            try:
                validate(mesh, make_config(**kw), spelling="params")
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
    documents), ``motions`` (the motions.csv text) and ``surface`` (vertices
    (v, 3), faces (f, 3), labels (f,)).
    """
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mesh, name, notes = load_input(job.mesh)
        diag = diagonal(mesh)
        config = make_config(**_resolved(job.params, diag), jobs=1)
        res = execute(mesh, name, config, notes)
    surf = res.surface
    return {"row": job_row(job, res, diag, time.perf_counter() - t0), "metrics": res.metrics,
            "sensing": res.sensing_document(), "motions": motions_text(res.slices),
            "surface": (np.asarray(surf.vertices), np.asarray(surf.faces),
                        np.asarray(surf.face_attributes["label"]))}


def job_row(job: Job, res: Result, diag: float, seconds: float) -> dict:
    """The batch.csv row of a finished job (lengths over the diagonal, wall seconds; the
    sensor's noise and taxel in eps, 0 for the paper's perfect sensing, and its coverage
    within eps/2 + 2 sigma, empty without a sensor model)."""
    tot = res.metrics["total"]
    sensor = res.metrics.get("sensor") or {}
    s = tot.get("surface") or {}
    axis = job.params.get("axis", "z")
    return {"job": job.index, "mesh": Path(job.mesh).name, "axis": str(axis),
            "slices": job.params.get("slices", _DEFAULT.slices), "eps": res.sensing.eps,
            "backend": job.params.get("backend", _DEFAULT.backend),
            "noise": sensor.get("noise", 0.0), "taxel": sensor.get("taxel", 0.0),
            "sensed_slices": len(res.slices),
            "coverage": tot.get("coverage"), "coverage_sensor": tot.get("coverage_sensor"),
            "fscore_1%": (s.get("fscore") or {}).get("1%"),
            "chamfer_l1_diag": None if s.get("chamfer_l1") is None else s["chamfer_l1"] / diag,
            "hd95_diag": None if s.get("hd95") is None else s["hd95"] / diag,
            "motions": tot.get("motions"), "robot_time_s": tot.get("robot_time_s"),
            "budget_hits": tot.get("budget_hits", 0), "seconds": seconds}


def write_batch(out, jobs: list[Job], results: list[dict]) -> list[Path]:
    """Write batch.csv and the per-job files into ``out``, all or nothing."""
    with Staged(out) as stage:
        runs = stage / "runs"
        runs.mkdir()
        for job, res in zip(jobs, results):
            d = runs / job.name
            d.mkdir()
            for key in ("metrics", "sensing"):
                write_json(d / f"{key}.json", res[key])
            write_ply(d / "surface.ply", *res["surface"])
            (d / "motions.csv").write_text(res["motions"])
        with open(stage / "batch.csv", "w", newline="") as fh:
            w = csv.DictWriter(fh, COLUMNS)
            w.writeheader()
            w.writerows(r["row"] for r in results)
    return [Path(out) / "batch.csv", Path(out) / "runs"]
