"""One sensed slice as the 2D figures draw it: plain data in the slice's own frame.

A :class:`SliceView` is built from the documents of a run (``sensing.json``,
``metrics.json``) -- world points are brought back into the slice frame
``(u, v)`` about the plane's origin -- plus, when known, the true section
(the reference loops) and the slice's motion log (:class:`MotionLog`, read
from ``motions.csv`` by :mod:`recon3d.viz.rundata`).

The classes follow §3.1 of the paper: W1 traced by the tip, W2 the straight
approximation of an area with Dist(A, B) < eps, W3 the lid A_jB_j of a
never-touching area; ``unknown`` are the A_iB_i still unknown at the end.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["Segment", "AreaMark", "MotionLog", "SliceView", "to_frame", "slice_views",
           "CLASSES"]

CLASSES = ("W1", "W2", "W3")
"""The known-contour classes of §3.1, in drawing order."""


@dataclass
class Segment:
    """A piece of known contour: ``cls`` in :data:`CLASSES`, ``points`` (k, 2) in the
    slice frame, ``known_at`` the motion index after which it is known (-1: not logged)."""

    cls: str
    points: np.ndarray
    known_at: int = -1


@dataclass
class AreaMark:
    """One A_iB_i of the area log (§3.3): ``index`` i, ends ``a``, ``b`` (2,), ``rule``
    (what created it) and ``outcome`` (how it ended)."""

    index: int
    a: np.ndarray
    b: np.ndarray
    rule: str
    outcome: str


@dataclass
class MotionLog:
    """The motions of one slice, in order (its rows of ``motions.csv``).

    index : (n,) int -- motion index within the slice.
    kind, phase, event : (n,) str -- motion kind, phase of the algorithm, event (Case 1 ... 4).
    joint0, joint1 : (n, 2) float -- joint P before and after the motion.
    theta0, theta1 : (n,) float -- probe direction angle before and after.
    tip1 : (n, 2) float -- tip after the motion, P + L t (§3.2).
    tip_contact : (n,) bool -- the tip touches after the motion.
    area : (n,) int -- index i of the A_iB_i served (-1: none, the bootstrap).
    """

    index: np.ndarray
    kind: np.ndarray
    phase: np.ndarray
    event: np.ndarray
    joint0: np.ndarray
    joint1: np.ndarray
    theta0: np.ndarray
    theta1: np.ndarray
    tip1: np.ndarray
    tip_contact: np.ndarray
    area: np.ndarray

    def __len__(self) -> int:
        return len(self.index)

    @classmethod
    def from_table(cls, table, family: int, index: int) -> "MotionLog":
        """The rows of one slice (``family``, plane ``index``) of a motion table -- a
        structured array or a mapping of column name -> (n,) array -- ordered by motion."""
        rows = np.flatnonzero((np.asarray(table["family"]).astype(int) == family)
                              & (np.asarray(table["slice"]).astype(int) == index))
        rows = rows[np.argsort(np.asarray(table["index"])[rows].astype(int), kind="stable")]

        def col(name, kind=float):
            return np.asarray(table[name])[rows].astype(kind)

        def xy(x, y):
            return np.column_stack([col(x), col(y)]).reshape(-1, 2)

        return cls(index=col("index", int), kind=col("kind", str), phase=col("phase", str),
                   event=col("event", str), joint0=xy("joint_x0", "joint_y0"),
                   joint1=xy("joint_x1", "joint_y1"), theta0=col("theta0"),
                   theta1=col("theta1"), tip1=xy("tip_x1", "tip_y1"),
                   tip_contact=np.nan_to_num(col("tip_contact")).astype(bool),
                   area=np.nan_to_num(col("area"), nan=-1).astype(int))


@dataclass
class SliceView:
    """What a 2D figure of one slice shows (all points (k, 2) in the slice frame).

    family, position, index : int -- family, position in it (``--slice``), plane index.
    axis : str -- the family's axis label.
    segments : list of Segment -- W1, W2, W3.
    unknown : list of (2, 2) float -- A_iB_i still unknown at the end.
    areas : list of AreaMark -- the A_iB_i log.
    section : list of (k, 2) float or None -- true section loops (None: not available).
    motions : int -- motions of the slice (stats).
    coverage : float or None -- reachable coverage (metrics).
    coverage_sensor : float or None -- reachable coverage within the sensor's tolerance
        eps / 2 + 2 sigma (metrics of a run with a sensor model; None without one).
    method : str -- ``pulling`` or ``paper``.
    log : MotionLog or None -- the motion log (None: no motions.csv).
    frame : (origin, u, v) -- the plane's frame in world coordinates, each (3,).
    """

    family: int
    position: int
    index: int
    axis: str
    segments: list
    unknown: list
    areas: list
    section: list | None
    motions: int
    coverage: float | None
    method: str = "pulling"
    log: MotionLog | None = None
    frame: tuple = field(default=(), repr=False)
    coverage_sensor: float | None = None

    def coverage_text(self, short: bool = False) -> str:
        """The coverage as a caption says it: within the sensor's tolerance first when the
        run had a sensor model, with the noiseless tolerance's beside it (not ``short``).

        >>> v = SliceView(0, 0, 0, "z", [], [], [], None, 10, 0.95, coverage_sensor=0.98)
        >>> v.coverage_text(), v.coverage_text(short=True)
        ('0.980 within eps/2 + 2 sigma (0.950 within eps/2)', '0.980 (eps/2+2σ)')
        """
        cov = "n/a" if self.coverage is None else f"{self.coverage:.3f}"
        if self.coverage_sensor is None:
            return cov
        if short:
            return f"{self.coverage_sensor:.3f} (eps/2+2σ)"
        return f"{self.coverage_sensor:.3f} within eps/2 + 2 sigma ({cov} within eps/2)"

    def present(self) -> list[str]:
        """The classes of :data:`CLASSES` with at least one segment here, in order."""
        have = {s.cls for s in self.segments}
        return [c for c in CLASSES if c in have]

    def bounds(self) -> np.ndarray:
        """(2, 2) [min, max] of the known contour, unknown lids and true section."""
        pts = [s.points for s in self.segments] + list(self.unknown) + list(self.section or [])
        pts = [np.asarray(p, float).reshape(-1, 2) for p in pts if len(p)]
        if not pts:
            return np.array([[-1.0, -1.0], [1.0, 1.0]])
        allp = np.concatenate(pts)
        return np.array([allp.min(axis=0), allp.max(axis=0)])


def to_frame(points, origin, u, v) -> np.ndarray:
    """World points (k, 3) -> (k, 2) slice-frame coordinates ((p - origin).u, (p - origin).v)."""
    p = np.asarray(points, dtype=np.float64).reshape(-1, 3) - np.asarray(origin, float)
    return np.column_stack([p @ np.asarray(u, float), p @ np.asarray(v, float)])


def _known_at(seg: dict) -> int:
    value = seg.get("known_at", seg.get("motion", -1))
    return -1 if value is None else int(value)


def _view(doc: dict, position: int, axis: str, metric: dict, method: str) -> SliceView:
    frame = (doc["origin"], doc["u"], doc["v"])
    segments = [Segment(s["class"], to_frame(s["points"], *frame), _known_at(s))
                for s in doc["segments"] if s["class"] in CLASSES]
    areas = []
    for rec in doc.get("areas", []):
        ab = to_frame([rec["a"], rec["b"]], *frame)
        areas.append(AreaMark(int(rec["index"]), ab[0], ab[1], rec.get("rule", ""),
                              rec.get("outcome", "")))
    return SliceView(
        family=int(doc["family"]), position=position, index=int(doc["index"]), axis=axis,
        segments=segments, unknown=[to_frame(w, *frame) for w in doc.get("unknown", [])],
        areas=areas, section=None, motions=int(doc.get("stats", {}).get("motions", 0)),
        coverage=metric.get("coverage"), coverage_sensor=metric.get("coverage_sensor"),
        method=method, frame=frame)


def slice_views(sensing: dict, metrics: dict | None = None) -> list[SliceView]:
    """Every slice of a run as a :class:`SliceView` (no section, no log yet), in document order.

    Parameters
    ----------
    sensing : dict -- the ``sensing.json`` document.
    metrics : dict, optional -- the ``metrics.json`` document (coverage per slice).
    """
    fams = sensing.get("families", [])
    per_family: dict[int, list] = {}
    for doc in sensing["slices"]:
        per_family.setdefault(int(doc["family"]), []).append(doc)
    mets: dict[int, list] = {}
    for m in (metrics or {}).get("slices", []):
        mets.setdefault(int(m.get("family", 0)), []).append(m)
    # runs written before --method existed ran the one method there was: pulling
    method = str((metrics or {}).get("method", sensing.get("method", "pulling")))
    out = []
    for fam, docs in per_family.items():
        axis = fams[fam]["axis"] if fam < len(fams) else str(fam)
        fam_metrics = mets.get(fam, [])
        for k, doc in enumerate(docs):
            metric = fam_metrics[k] if k < len(fam_metrics) else {}
            out.append(_view(doc, k, axis, metric, method))
    return out
