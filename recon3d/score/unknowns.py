"""Unknown chords: the areas A_iB_i a slice ends with still unknown, located and explained.

An area ends ``unknown`` (core2d's planner, ``core2d/planner/revisit.py`` and
``core2d/planner/audit.py``) in three ways:

* **budget** -- the slice's motion or area budget ran out while the area was
  queued or deferred (``stats.budget_hit``);
* **dead end** -- no budget hit: the second look at a dead end (§4.2.1 extended)
  found nothing new. Its passes through the lid ended on contour already
  recorded, or no line reached the lid, and the lid could not be proven W3
  (it crosses recorded contour, or the probe cannot hold it, or it closes no
  loop). A chord laid along a flat floor at the bottom of a deep cavity is
  one: every pass lands on the floor, i.e. on the lid itself;
* **loose end** -- no budget hit: the robot's recorded contour stops at a
  loose end and no area traced on from it (the planner's audit left it),
  e.g. the far side of an object behind a lid that opens to F between two
  objects. The chord runs from the loose end to the nearest loose start.

Each chord is reported with its slice, its ends in world coordinates, its
length, the planner's note and the share of its length that lies on the
reference contour (within eps / 2, the 2D coverage distance): a chord on the
contour costs the surface nothing, one across a gap is where the surface
is guessed (label 4).
"""
from __future__ import annotations

import numpy as np
import shapely

from recon3d.records import MeshRun, SliceRun

__all__ = ["unknown_chords", "CAUSES"]

CAUSES = {"budget": "the slice hit its motion or area budget",
          "dead end": "no budget hit; no pass through the lid found anything new and "
                      "the lid is no provable W3 lid",
          "loose end": "no budget hit; the recorded contour stops there and nothing "
                       "traced on from it"}
"""Why a chord is unknown -> what that means (the module doc)."""


def _on_contour(srun: SliceRun, a, b, tol: float, samples: int = 33) -> float | None:
    """Share of the chord a-b within ``tol`` of the slice's reference loops (None: no loops)."""
    if not srun.slice.loops:
        return None
    pts = shapely.points(np.linspace(a, b, samples))
    d = np.min([shapely.distance(pts, shapely.LinearRing(np.asarray(lp, dtype=np.float64)))
                for lp in srun.slice.loops], axis=0)
    return float((d <= tol).mean())


def _cause(budget_hit: bool, rule: str) -> str:
    """The key of :data:`CAUSES` of an unknown area (a budget hit first)."""
    return "budget" if budget_hit else ("loose end" if rule == "loose" else "dead end")


def unknown_chords(run: MeshRun) -> list[dict]:
    """Every unknown chord of a run (the ``unknown_chords`` list of metrics.json).

    Returns
    -------
    list of dict -- ``axis``, ``slice`` (position in its family, as the summary
    names it: ``axis#slice``), ``offset`` (plane offset along the normal),
    ``a``, ``b``, ``middle`` ((3,) world), ``length``, ``cause`` (a key of
    :data:`CAUSES`), ``note`` (the planner's) and ``on_contour`` (share of
    the length on the reference contour).
    """
    out = []
    for fam in run.families:
        for k, s in enumerate(fam.slices):
            hit = bool(s.result.stats.budget_hit)
            for rec in s.result.areas:
                if rec.outcome != "unknown":
                    continue
                a2, b2 = np.asarray(rec.a, float), np.asarray(rec.b, float)
                a, b = s.slice.to_3d(np.stack([a2, b2]))
                out.append({"axis": fam.label, "slice": k,
                            "offset": float(s.slice.plane.offset),
                            "a": np.round(a, 9).tolist(), "b": np.round(b, 9).tolist(),
                            "middle": np.round(0.5 * (a + b), 9).tolist(),
                            "length": float(np.linalg.norm(b2 - a2)),
                            "cause": _cause(hit, rec.rule), "note": rec.note,
                            "on_contour": _on_contour(s, a2, b2, 0.5 * run.eps)})
    return out

