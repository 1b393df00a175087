"""Stability study: where each method breaks (``stability.csv``).

Methods: the pulling planner with each contact backend (Embree, exact,
trimesh) and finger probing (Embree); the reconstruction has one method.
Factors (one task each value, :func:`run_factor`):

* ``plane offset`` -- a plane 1e-3 ... 1e-9 x diagonal above a step top of
  ``stepped_pyramid`` (a horizontal face and its vertices), no nudge;
* ``noise`` -- the sensor of :class:`core2d.SensorModel` with Gaussian noise
  sigma = 0 ... eps on contact positions and joint readings (the project's one
  noise model), ``fig18_overhangs``, every method (:data:`SENSOR_METHODS`:
  the three backends, finger probing, the paper's flow, the contour follower),
  each reading point averaged over the reads ``recon3d run`` takes by default
  (:func:`core2d.resolution.repeated_reads`: 2 at sigma 0.03 eps, 16 at 0.1 and
  0.3 eps, else 1);
* ``taxel`` -- its taxel spacing 0 ... eps, ``fig18_overhangs``, every method;
* ``resolution`` -- ``bowl`` at 4 tessellations (3D F@1% for pulling);
* ``rotation x|y|z`` -- ``fig18_overhangs`` rotated about each axis (3D F@1%);
* ``eps / edge`` -- eps from twice to 1/16 of the mesh's median edge length
  (``bowl``, 32 segments);
* ``islands/holes`` -- every slice of ``twin_posts``, ``cup_handle``,
  ``bored_block`` (W3 soundness too);
* ``mesh defects`` -- a non-watertight ``fig18_overhangs`` (2 % of faces
  dropped) and two overlapping boxes (self-intersecting), whole runs.

Every run uses eps = diagonal / 50 (``eps / edge`` aside) and a budget of
5000 motions per slice for the planners (finger probing's grid is finite);
the full study takes more values of each factor than ``--quick``, and 4
slices instead of 3 in its 3D runs.

A row per (factor, value, method, slice): crashed (and the error), budget
hit, reachable coverage (and, for the sensor factors, within the sensor's
tolerance eps/2 + 2 sigma: ``coverage_sensor``), motions, F@1% (3D runs),
seconds. :func:`breaking_points`
says where each method first breaks: a crash, a budget hit, or coverage
(F@1%) more than 0.05 below the method's value at the first setting.
"""
from __future__ import annotations

import time
import warnings

import numpy as np
import trimesh

import meshes
import recon3d
import slicer
from core2d import SensorModel, sense_slice
from core2d.resolution import repeated_reads
from core2d.truth.metrics import sensor_metrics, slice_metrics
from recon3d.benchmark.cases import workspace
from recon3d.config import diagonal

__all__ = ["stability_tasks", "run_factor", "breaking_points", "score_key", "METHODS", "SENSOR_METHODS",
           "SENSOR_FACTORS"]

METHODS = (("pulling", "embree"), ("pulling", "exact"), ("pulling", "trimesh"),
           ("finger", "embree"))
"""The methods every factor of geometry compares: the pulling planner on each
contact backend and finger probing."""

SENSOR_METHODS = METHODS + (("paper", "embree"), ("follow", "embree"))
"""The sensor factors add the other planners of :func:`core2d.sense_slice`: the
paper's Fig. 16 flow alone (§4.2) and the pushing contour follower (Fig. 2(a)),
so noise and taxels are measured on every method."""


#: factors whose value is a sensor figure in eps (:class:`core2d.SensorModel`)
SENSOR_FACTORS = ("noise", "taxel")


def stability_tasks(quick: bool) -> list[dict]:
    """One task per (factor, value)."""
    t = []
    for delta in (1e-3, 1e-5, 1e-7, 1e-9) if quick else (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9):
        t.append({"factor": "plane offset", "value": delta})
    for s in (0.0, 0.1, 0.3, 1.0) if quick else (0.0, 0.01, 0.03, 0.1, 0.3, 1.0):
        t.append({"factor": "noise", "value": s})
    for s in (0.0, 0.25, 1.0) if quick else (0.0, 0.1, 0.25, 0.5, 1.0):
        t.append({"factor": "taxel", "value": s})
    for r in (8, 16, 32, 64):
        t.append({"factor": "resolution", "value": r})
    for ax in "xyz":
        for a in (0, 30, 90) if quick else (0, 15, 30, 45, 90):
            t.append({"factor": f"rotation {ax}", "value": a})
    for ratio in (2.0, 0.5, 0.125) if quick else (2.0, 1.0, 0.5, 0.25, 0.125, 0.0625):
        t.append({"factor": "eps / edge", "value": ratio})
    for scene in ("twin_posts", "cup_handle", "bored_block"):
        t.append({"factor": "islands/holes", "value": scene})
    for kind in ("open", "self-intersecting"):
        t.append({"factor": "mesh defects", "value": kind})
    for task in t:
        task["quick"] = quick
    return t


def _sense(slc, eps, method, backend, sensor=None, max_motions=20000):
    """Sense one slice with ``sensor`` (a :class:`core2d.SensorModel`, None:
    perfect); a row fragment (crash caught and reported)."""
    t0 = time.perf_counter()
    try:
        budget = max_motions if method != "finger" else 10 ** 7  # a finger grid is finite
        res = sense_slice(slc.contact(backend), workspace(slc, eps), eps, method=method,
                          max_motions=budget, sensor=sensor)
        loops = [np.asarray(lp) for lp in slc.loops]
        m = slice_metrics(loops, res, eps) if loops and not slc.open_chains else {}
        if m:
            m.update(sensor_metrics(loops, res, eps, sensor.noise if sensor else 0.0))
        return {"crashed": False, "error": "", "budget_hit": bool(res.stats.budget_hit),
                "coverage": m.get("coverage", np.nan),
                "coverage_sensor": m.get("coverage_sensor", np.nan),
                "w3_soundness": m.get("w3_soundness", np.nan),
                "motions": res.stats.motions, "seconds": time.perf_counter() - t0}
    except Exception as exc:  # the study records crashes; the tests forbid them
        return {"crashed": True, "error": f"{type(exc).__name__}: {exc}"[:160], "budget_hit": False,
                "coverage": np.nan, "coverage_sensor": np.nan, "w3_soundness": np.nan,
                "motions": 0, "seconds": time.perf_counter() - t0}


def _run3d(mesh, slices, eps=None):
    """Whole pulling run (Embree); (F@1%, coverage, crashed, error)."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = recon3d.run(mesh, slices=slices, eps=eps, jobs=1)
        s = res.metrics["total"].get("surface") or {}
        return (s.get("fscore") or {}).get("1%", np.nan), res.metrics["total"].get("coverage"), \
            False, "", res.metrics["total"].get("budget_hits", 0) > 0
    except Exception as exc:
        return np.nan, np.nan, True, f"{type(exc).__name__}: {exc}"[:160], False


def _methods(task, quick):
    """The methods a factor compares (trimesh only where the geometry of contact
    matters; every planner for the sensor factors)."""
    if task["factor"] in SENSOR_FACTORS:
        return tuple(m for m in SENSOR_METHODS if not quick or m[1] != "trimesh")
    if task["factor"] in ("plane offset", "eps / edge"):
        return METHODS if not quick or task["factor"] == "plane offset" else METHODS[:2] + METHODS[3:]
    return (("pulling", "embree"), ("finger", "embree"))


def _mesh_for(task):
    f, v = task["factor"], task["value"]
    if f == "resolution":
        return meshes.load("bowl", resolution=int(v))
    if f.startswith("rotation"):
        mesh = meshes.load("fig18_overhangs")
        axis = np.eye(3)["xyz".index(f[-1])]
        mesh.apply_transform(trimesh.transformations.rotation_matrix(np.radians(v), axis,
                                                                     mesh.bounds.mean(axis=0)))
        return mesh
    if f == "eps / edge":
        return meshes.load("bowl", resolution=32)
    if f == "islands/holes":
        return meshes.load(v)
    if f in SENSOR_FACTORS:
        return meshes.load("fig18_overhangs")
    if f == "mesh defects":
        if v == "open":
            mesh = meshes.load("fig18_overhangs")
            keep = np.random.default_rng(0).random(len(mesh.faces)) > 0.02
            return trimesh.Trimesh(mesh.vertices, mesh.faces[keep], process=False)
        a = trimesh.creation.box(extents=[40, 40, 40])
        b = trimesh.creation.box(extents=[40, 40, 40]).apply_translation([20, 10, 5])
        return trimesh.util.concatenate([a, b])
    return meshes.load("stepped_pyramid")


def _slices(task, mesh, diag):
    f, v = task["factor"], task["value"]
    if f == "plane offset":
        z = np.unique(np.round(mesh.vertices[:, 2], 9))
        h = z[len(z) // 2]  # a step top: a horizontal face and its vertices
        return slicer.slice_mesh(mesh, "z", offsets=[h + v * diag], nudge=False)
    if f == "islands/holes":
        return slicer.slice_mesh(mesh, "z", count=4)
    return [slicer.slice_mesh(mesh, "z", count=3)[1]]


def run_factor(task: dict) -> list[dict]:
    """All methods at one (factor, value); one row per (method, slice)."""
    quick, f, v = task["quick"], task["factor"], task["value"]
    mesh = _mesh_for(task)
    diag = diagonal(mesh)
    edge = float(np.median(mesh.edges_unique_length))
    eps = v * edge if f == "eps / edge" else diag / 50  # full: more values, same runs
    rows = []
    base = {"factor": f, "value": v, "eps": eps, "edge": edge, "fscore_1": np.nan}
    if f == "mesh defects":
        for backend in ("embree", "exact"):
            t0 = time.perf_counter()
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    res = recon3d.run(mesh, slices=3 if quick else 4, eps=eps, backend=backend,
                                      jobs=1)
                s = res.metrics["total"].get("surface") or {}
                out = {"crashed": False, "error": "",
                       "coverage": res.metrics["total"].get("coverage", np.nan),
                       "fscore_1": (s.get("fscore") or {}).get("1%", np.nan),
                       "budget_hit": res.metrics["total"].get("budget_hits", 0) > 0}
            except Exception as exc:
                out = {"crashed": True, "error": f"{type(exc).__name__}: {exc}"[:160],
                       "coverage": np.nan, "fscore_1": np.nan, "budget_hit": False}
            rows.append({**base, "method": f"pulling/{backend}", "slice": -1, "motions": 0,
                         "w3_soundness": np.nan, **out, "seconds": time.perf_counter() - t0})
        return rows
    for slc in _slices(task, mesh, diag):
        sensor = None
        if f in SENSOR_FACTORS and v:
            fig = {"noise": 0.0, "taxel": 0.0, f: v}  # the reads recon3d run averages
            sensor = SensorModel.of_eps(eps, **fig, seed=slc.index,
                                        reads=repeated_reads(1.0, fig["noise"], fig["taxel"]))
        for method, backend in _methods(task, quick):
            r = _sense(slc, eps, method, backend, sensor, 5000)
            rows.append({**base, "method": f"{method}/{backend}", "slice": slc.index, **r})
    if f in ("resolution",) or f.startswith("rotation"):
        f1, cov, crashed, err, hit = _run3d(mesh, 3 if quick else 4, eps)
        rows.append({**base, "method": "pulling/embree 3D", "slice": -1, "crashed": crashed,
                     "error": err, "budget_hit": hit, "coverage": cov, "fscore_1": f1,
                     "w3_soundness": np.nan, "motions": 0, "seconds": np.nan})
    return rows


def score_key(factor: str, method: str) -> str:
    """The score a row of ``factor`` is judged by: F@1% for whole 3D runs,
    coverage within the sensor's tolerance eps/2 + 2 sigma
    (``coverage_sensor``) for the sensor factors -- a contact reported 2 sigma
    off is what the sensor allows, not a miss of the method --, the reachable
    coverage within eps/2 otherwise."""
    if method.endswith("3D"):
        return "fscore_1"
    return "coverage_sensor" if factor in SENSOR_FACTORS else "coverage"


def breaking_points(rows, drop: float = 0.05) -> list[dict]:
    """Per (factor, method): the first value where the method breaks (or None).

    Values are taken in task order (coarse -> hard). A run breaks when it
    crashes, hits its budget, or its score falls more than ``drop`` below
    the first value's: :func:`score_key` names the score.
    """
    out = []
    keys = list(dict.fromkeys((r["factor"], r["method"]) for r in rows))
    for factor, method in keys:
        sel = [r for r in rows if r["factor"] == factor and r["method"] == method]
        values = list(dict.fromkeys(r["value"] for r in sel))
        metric = score_key(factor, method)

        def score(v):
            xs = [r.get(metric, np.nan) for r in sel if r["value"] == v]
            return float(np.nanmean(xs)) if np.isfinite(xs).any() else np.nan

        ref = score(values[0])
        broke, why = None, ""
        for v in values:
            rs = [r for r in sel if r["value"] == v]
            if any(r["crashed"] for r in rs):
                broke, why = v, "crash: " + next(r["error"] for r in rs if r["crashed"])
            elif any(r["budget_hit"] for r in rs):
                broke, why = v, "budget hit"
            elif np.isfinite(ref) and np.isfinite(score(v)) and score(v) < ref - drop:
                broke, why = v, f"{metric} {score(v):.3f} (from {ref:.3f})"
            if broke is not None:
                break
        out.append({"factor": factor, "method": method, "breaks_at": broke, "why": why})
    return out
