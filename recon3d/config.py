"""The parameters of a run: one dataclass, the single source of every spelling.

Each field of :class:`RunConfig` carries a :class:`Param` (its public name,
CLI flag, parser, help text, bounds and README wording). From them come

* the flags of ``recon3d run`` (:func:`recon3d.cli.run` loops over :data:`PARAMS`),
* the keywords of :func:`recon3d.run`, the ``[params]`` keys of a batch manifest
  and their documentation (rendered by :mod:`recon3d.spellings`),
* and the checks (:func:`validate`).

Defaults that derive from the mesh -- eps, tol, probe length, jobs -- are
resolved in one place, :func:`resolve`.

>>> [p.flag for p in PARAMS][:3]
['--axis', '--slices', '--max-slices']
>>> RunConfig(axes=("z", "x")).axes
('z', 'x')
"""
from __future__ import annotations

import dataclasses
import importlib.metadata
import os
from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

import numpy as np

import slicer
from recon3d.checks import (EPS_SHARE, EPS_WARN_SHARE, MM_PER_UNIT, TOL_SHARE, InputError,
                            at_least, check_axes, check_backend, check_choice, check_eps,
                            check_flag, check_slice_count, check_slice_spacing, check_slice_tol,
                            check_reads, check_slices, check_tol, parse_count_or_auto,
                            positive, units_note)
from recon3d.param import Param, param

if TYPE_CHECKING:  # annotations only: the parser of recon3d loads no trimesh (--help)
    import trimesh

__all__ = ["RunConfig", "Param", "PARAMS", "Resolved", "validate", "resolve", "diagonal",
           "package_version", "default_jobs", "COARSE", "METHODS"]

METHODS = ("pulling", "paper", "follow")
"""``--method``: the planner's flows (:mod:`core2d.planner.flow`) and the pushing
contour follower (:mod:`core2d.planner.follow`)."""

COARSE = 2.0
"""``--slices auto`` senses first at COARSE x eps (:mod:`recon3d.sensing.adaptive`)."""


def _axes(value) -> tuple:
    """``axis`` keyword -> the tuple of axes (one vector given as a list of numbers)."""
    axes = tuple(value) if isinstance(value, (list, tuple)) else (value,)
    if axes and all(isinstance(a, (int, float, np.number)) for a in axes):
        axes = (np.asarray(axes, dtype=float),)  # one vector given as a list
    return axes


def _auto(config) -> bool:
    return config.slices == "auto"


_LO, _HI = EPS_SHARE


@dataclass(frozen=True)
class RunConfig:
    """Parameters of one run (the flags of ``recon3d run``, the keywords of ``recon3d.run``).

    The metadata of each field (:class:`Param`) is the single source of its
    spelling, help text, bounds and documentation; :func:`options_table`
    renders them. ``bootstrap`` is internal (initial insertions per slice).
    """

    axes: tuple = param(
        ("z",), key="axis", keyword_default="z",
        keyword_type="str | Sequence[float] | Sequence[str | Sequence[float]]",
        repeat=True, metavar="A", shown_default="`z`", convert=_axes, check=check_axes,
        help="slice normal: x, y, z, -x, ... or nx,ny,nz; repeat for several families fused "
        "into one surface (default z)",
        doc=(("slice normal: `x`, `y`, `z`, `-x`, … or `nx,ny,nz` (`--axis "
              "-1,0,0` works). Repeat it for several slice families fused into one surface"),))
    slices: int | Literal["auto"] = param(
        8, parse=parse_count_or_auto, metavar="N", shown_default="8",
        convert=check_slices,
        check=check_slice_count, when=lambda c: not _auto(c),
        help="slices per axis, at least 2 (default 8; more than extent / eps needs --force), "
        "or 'auto': adaptive slicing -- start coarse, add slices where neighbouring sensed "
        "sections differ, eps per slice from the features it shows",
        doc=(("planes per axis, evenly spaced strictly inside the mesh; a surface needs at "
              "least 2; **more than the mesh's extent along the axis / eps** (slices closer "
              "than eps) needs `--force`"),
             ("auto", "adaptive slicing (`recon3d.sensing.adaptive`): start with 3–5 "
              "of `--max-slices` evenly spaced candidates, add the middle candidate between "
              "neighbours whose sensed sections differ by more than `--slice-tol`, and sense "
              "each slice at 2 × eps, or at eps where it shows features (parts or pockets) "
              "narrower than 4 × eps")))
    max_slices: int = param(
        32, parse=int, metavar="N", shown_default="32", check=lambda v, n: at_least(v, n, low=3),
        when=_auto, help="--slices auto: candidate planes per axis (default 32)",
        doc=(("`--slices auto`: candidate planes per axis (the uniform run "
              "it replaces)"),))
    slice_tol: float = param(
        0.005, parse=float, metavar="S", shown_default="0.005", check=check_slice_tol,
        when=_auto, help="--slices auto: refine between neighbours whose sensed sections differ "
        "by more than this share of the diagonal (default 0.005)",
        doc=(("`--slices auto`: refine between neighbours whose sensed "
              "sections differ (Hausdorff) by more than S × diagonal"),))
    eps: float | None = param(
        None, parse=float, metavar="E", shown_default="diagonal / 200",
        help=f"the paper's epsilon, in mesh units (default: bounding-box diagonal / 200; "
        f"allowed: {_LO:g} to {_HI:g} x diagonal)",
        doc=((f"the paper's eps, in mesh units; must lie in **[{_LO:g}, {_HI:g}] × "
              f"the bounding-box diagonal** (outside: a unit mix-up or a meaningless run, "
              f"rejected); above {EPS_WARN_SHARE:g} × diagonal a warning says the numbers are "
              f"coarse"),))
    tol: float | None = param(
        None, parse=float, metavar="T", shown_default="eps / 20",
        help=f"contact resolution (default eps/20; allowed: eps*{TOL_SHARE:g} up to, not "
        f"including, eps)",
        doc=((f"contact resolution; must lie in **[eps / {1 / TOL_SHARE:g}, "
              f"eps)**"),))
    noise: float = param(
        0.0, parse=float, metavar="S", shown_default="0",
        check=lambda v, n: positive(v, n, allow_zero=True),
        help="sensor noise: Gaussian, standard deviation S x eps on every contact position and "
        "on the joint position reading (S x eps / probe length on its direction); default 0, "
        "the paper's perfect sensing",
        doc=(("sensor noise (`core2d.sim.sensor`): Gaussian with standard deviation S × eps on "
              "every reported contact and on the joint position reading, S × eps / probe "
              "length (radians) on the probe direction; the planner is told S, and "
              "`metrics.json` adds coverage and precision within eps / 2 + 2 S × eps "
              "(`*_sensor`)"),))
    taxel: float = param(
        0.0, parse=float, metavar="T", shown_default="0",
        check=lambda v, n: positive(v, n, allow_zero=True),
        help="taxel spacing T x eps: a contact is reported at the centre of the tactile element "
        "holding it, the tip being one (default 0: a continuous skin)",
        doc=(("tactile elements T × eps apart along the probe: a contact is reported at the "
              "centre of its element, the tip being an element of its own; the planner is "
              "told T"),))
    seed: int = param(
        0, parse=int, metavar="N", shown_default="0",
        check=lambda v, n: at_least(v, n, low=0),
        help="seed of the sensor noise (default 0; each slice draws from its own stream, so "
        "results do not depend on --jobs)",
        doc=(("seed of the sensor noise; each slice has its own stream (seed, family, "
              "plane), so the results do not depend on `--jobs`"),))
    keyed_noise: bool = param(
        False, switch=True, shown_default="off", check=check_flag,
        help="draw each reading's noise from its true posture (a key) instead of one stream "
        "per slice: two planners then meet the same draws where they read the same posture",
        doc=(("keyed sensor noise (common random numbers): each reading's draws come from a "
              "generator keyed by the seed, the probe's true posture and how often it was "
              "read before, so a planner change that adds one motion does not re-draw every "
              "later reading; for comparing two planners run by run (statistically the same "
              "sensor)"),))
    reads: int | Literal["auto"] = param(
        "auto", parse=parse_count_or_auto, metavar="N", shown_default="`auto`",
        check=check_reads,
        help="reads averaged at each reading point (default auto: the fewest that resolve "
        "eps/2, up to 16 towards means scattered by tol/2; 1 where 64 do not resolve eps/2)",
        doc=(("the robot reads its skin, joint and torque sensors N times where it stands "
              "(after a motion, at each step of a compliant trace) and averages them: the "
              "noise of the means is S / sqrt(N), the taxels' rounding stays; the planner is "
              "told that noise"),
             ("auto", "at least the fewest N that bring two readings of one point within "
              "eps/2, and up to 16 towards means scattered by tol / 2 at most "
              "(`core2d.resolution.repeated_reads`: 16 at `--noise 0.1` and at `--noise 0.3 "
              "--taxel 0.25`, 23 at `--noise 0.5`); 1 where no N up to 64 resolves eps/2")))
    read_time: float = param(
        0.001, parse=float, metavar="S", shown_default="0.001",
        check=lambda v, n: positive(v, n, allow_zero=True),
        help="seconds per read of a noisy sensor for the robot time (default 0.001: a 1 kHz "
        "skin)",
        doc=(("seconds per read of a real sensor (reading points × `--reads`) for the robot "
              "time; the paper's perfect sensing reads in no time"),))
    torque_threshold: float = param(
        0.0, parse=float, metavar="H", shown_default="0",
        check=lambda v, n: positive(v, n, allow_zero=True),
        help="torque-sensor threshold H x eps: a rotation is read blocked only when the "
        "surface intrudes at least this far into the torque check (default 0: any contact)",
        doc=(("torque sensor (`core2d.sim.sensor`): the blocked-rotation readings report a "
              "rotation blocked only when the surface intrudes at least H × eps into the "
              "check's rotation; the planner is told H"),))
    torque_noise: float = param(
        0.0, parse=float, metavar="S", shown_default="0",
        check=lambda v, n: positive(v, n, allow_zero=True),
        help="torque-sensor noise: Gaussian, standard deviation S x eps on the torque check's "
        "reading (default 0); the planner then reads it 5 times and takes the majority",
        doc=(("noise of the torque check's reading (standard deviation S × eps, a free rotation "
              "reads blocked when the noise exceeds the threshold); the planner is told S and "
              "takes each blocked-rotation flag at a final state by majority of 5 readings"),))
    backend: str = param(
        "embree", choices=slicer.BACKENDS, shown_default="`embree`", convert=check_backend,
        help="contact backend (default embree; trimesh: its generic ray engine, slow)",
        doc=(("`embree` (in-plane ray casts on the mesh), `exact` (2D polygon "
              "reference) or `trimesh` (trimesh's generic ray engine; ≈ 20–35 × slower than "
              "Embree per motion, for comparison)"),))
    method: Literal["pulling", "paper", "follow"] = param(
        "pulling", choices=METHODS, shown_default="`pulling`", metavar="M",
        check=lambda v, n: check_choice(v, n, METHODS),
        help="pulling (default: the paper's algorithm with the planner's map, deferral, "
        "revisits and audit), paper (the paper's Fig. 16 flow alone: dead ends and "
        "Area(G) = 0 become W3 at once, section 4.2.1) or follow (a contour follower from "
        "the first contacts, pushing on one side: the strategy the paper argues against)",
        doc=(("`pulling`: the paper's algorithm with the planner's additions (its map of what "
              "it recorded, deferral and revisits of dead ends, W3 only with a proof, the "
              "audit of loose ends); `paper`: the paper's Fig. 16 flow alone (dead ends and "
              "Area(G_i) = 0 become W3 at once, §4.2.1); `follow`: a contour follower "
              "tracing both ways from each first contact without the concave point search "
              "(Fig. 2(a): it pushes on one side; no W3). All write the same outputs; "
              "`metrics.json` records it"),))
    friction: float = param(
        0.0, parse=float, metavar="MU", shown_default="0",
        check=lambda v, n: positive(v, n, allow_zero=True),
        help="Coulomb friction coefficient mu at the probe tip: a pushing trace step whose "
        "rod axis lies within atan(mu) of the contact normal jams (sensed as the joint "
        "blocked); pulling steps slide (default 0: no friction)",
        doc=(("quasi-static Coulomb friction at the tip (`core2d.sim.friction`): a trace "
              "step that pushes (v·t > 0) with the rod axis within atan(MU) of the contact "
              "normal jams -- the tip sticks, the step is not made, the robot reads Case 4 "
              "-- and a pulling step slides; `stats.jams` counts the jams, `stats.pushes` "
              "the pushing steps made. The planner is not told MU"),))
    max_motions: int = param(
        20000, parse=int, metavar="M", shown_default="20000", check=lambda v, n: at_least(v, n),
        help="motion budget per slice (default 20000)",
        doc=(("motion budget per slice (reported when hit)"),))
    jobs: int | None = param(
        None, parse=int, metavar="N", shown_default="number of cores", batch=False,
        check=lambda v, n: at_least(v, n), when=lambda c: c.jobs is not None,
        help="parallel processes (default: number of cores; results do not depend on it)",
        doc=(("slices run in N processes; the results are identical for every N "
              "(tested)"),))
    units: Literal["mm", "cm", "m", "in", "ft"] = param(
        "mm", choices=tuple(MM_PER_UNIT), shown_default="`mm`", metavar="U",
        check=lambda v, n: check_choice(v, n, MM_PER_UNIT),
        help="length unit of the mesh: mm, cm, m, in or ft (default mm; the scenes are in mm)",
        doc=(("length unit of the mesh (`mm`, `cm`, `m`, `in`, `ft`): the probe speed (mm/s) "
              "is converted to mesh units for the robot time; a mesh under 1 mm or over 10 m "
              "across in these units gets a warning"),))
    probe_speed: float = param(
        20.0, parse=float, metavar="V", shown_default="20", check=lambda v, n: positive(v, n),
        help="joint speed for the robot time, mm per second (default 20), converted to mesh "
        "units with --units",
        doc=(("joint speed for the robot time, mm / s (converted to mesh "
              "units with `--units`)"),))
    motion_overhead: float = param(
        0.2, parse=float, metavar="S", shown_default="0.2",
        check=lambda v, n: positive(v, n, allow_zero=True),
        help="seconds per motion for the robot time (default 0.2)",
        doc=(("seconds per motion (stop, read the sensors, plan) for "
              "the robot time"),))
    force: bool = param(
        False, switch=True, shown_default="off", check=check_flag,
        help="run even with slices closer than eps (more than extent / eps per axis)",
        doc=(("allow `--slices` (or `--max-slices`) above extent / eps"),))
    drop_nonfinite: bool = param(
        False, switch=True, shown_default="off", batch=False, check=check_flag,
        help="drop NaN / inf vertices and their faces (with a warning) instead of refusing "
        "the mesh",
        doc=(("drop NaN / inf vertices and the faces using them, with a warning (the surface "
              "has holes there); without it such a mesh is refused"),))
    bootstrap: int = 12  # internal: initial insertions around each slice

    @property
    def speed(self) -> float:
        """The probe speed in mesh units per second (``probe_speed`` is in mm/s)."""
        return float(self.probe_speed) / MM_PER_UNIT[self.units]


def _params() -> tuple[Param, ...]:
    out = []
    for f in dataclasses.fields(RunConfig):
        p = f.metadata.get("param")
        if p is not None:
            key = p.key or f.name
            out.append(dataclasses.replace(p, name=f.name, key=key,
                                           flag=p.flag or "--" + key.replace("_", "-")))
    return tuple(out)


PARAMS: tuple[Param, ...] = _params()
"""The public run parameters, in CLI order."""

_BY_KEY = {p.key: p for p in PARAMS}



def diagonal(mesh: trimesh.Trimesh) -> float:
    """Bounding-box diagonal of a mesh (its referenced vertices, as ``mesh.bounds``).

    :func:`slicer.mesh_scale` of the bounds: bit for bit the norm of
    ``np.ptp(mesh.bounds, axis=0)`` (``mesh_scale(mesh)`` itself spans every
    vertex, unreferenced ones too).

    >>> import trimesh
    >>> diagonal(trimesh.creation.box(extents=[3.0, 4.0, 12.0]))
    13.0
    """
    return slicer.mesh_scale(mesh.bounds)


def package_version() -> str:
    """The version of the installed distribution ``pulling-probe-3d`` (``recon3d
    --version``, ``recon3d.__version__``)."""
    try:
        return importlib.metadata.version("pulling-probe-3d")
    except importlib.metadata.PackageNotFoundError:  # pragma: no cover - not installed
        return "0+unknown"


def default_jobs() -> int:
    """Number of cores this process may use (the default of ``jobs``)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not on Linux
        return max(1, os.cpu_count() or 1)


@dataclass(frozen=True)
class Resolved:
    """The defaults of a run that derive from the mesh, resolved once.

    diagonal : float -- bounding-box diagonal (:func:`diagonal`).
    eps, tol : float -- ``config.eps`` or diagonal / 200; ``config.tol`` or eps / 20.
    tol_share : float -- tol / eps as adaptive slicing scales it (1/20 by default).
    first_eps : float -- the eps of the first pass (COARSE x eps for ``--slices auto``).
    probe_length : float or None -- 4 x (largest slice radius + first_eps), when slices are given.
    jobs : int -- ``config.jobs`` or the number of cores.
    """

    diagonal: float
    eps: float
    tol: float
    tol_share: float
    first_eps: float
    probe_length: float | None
    jobs: int


def resolve(config: RunConfig, diag: float, slices=None) -> Resolved:
    """Fill in the mesh-derived defaults of ``config`` (the one place they are computed).

    slices : list of list of slicer.Slice, optional -- the cut families (for the probe length).

    >>> r = resolve(RunConfig(), 100.0)
    >>> r.eps, r.tol, r.first_eps
    (0.5, 0.025, 0.5)
    """
    eps = float(config.eps) if config.eps is not None else diag / 200.0
    tol = float(config.tol) if config.tol is not None else eps / 20.0
    share = (float(config.tol) / eps) if config.tol is not None else 1 / 20
    first = COARSE * eps if config.slices == "auto" else eps
    length = None
    if slices is not None:
        radius = max((s.bounding_circle()[1] for fam in slices for s in fam if not s.is_empty),
                     default=1.0)
        length = 4.0 * (radius + first)
    jobs = default_jobs() if config.jobs is None else int(config.jobs)
    return Resolved(diag, eps, tol, share, first, length, jobs)


def validate(mesh: trimesh.Trimesh, config: RunConfig, spelling: str = "key") -> list[str]:
    """Check ``config`` against ``mesh`` before any sensing; return warnings.

    spelling : 'key' (Python: ``eps``), 'flag' (CLI: ``--eps``) or 'params'
        (manifest: ``params.eps``) -- how error messages name parameters.
    """
    def name(p):
        return {"key": p.key, "flag": p.flag, "params": f"params.{p.key}"}[spelling]

    for p in PARAMS:
        if p.check is not None and (p.when is None or p.when(config)):
            p.check(getattr(config, p.name), name(p))
    diag = diagonal(mesh)
    if not np.isfinite(diag) or diag <= 0:
        raise InputError("the mesh has no extent")
    eps_name, tol_name = name(_BY_KEY["eps"]), name(_BY_KEY["tol"])
    if config.eps is not None:
        positive(config.eps, eps_name)
    if config.tol is not None:
        positive(config.tol, tol_name)
    res = resolve(config, diag)
    notes = [check_eps(res.eps, diag, eps_name), units_note(diag, config.units,
                                                            name(_BY_KEY["units"]))]
    if config.tol is not None:
        check_tol(res.tol, res.eps, tol_name)
    if not config.force:  # slices closer than eps, along each axis
        count = "max_slices" if _auto(config) else "slices"
        check_slice_spacing(getattr(config, count), mesh, config.axes, res.eps,
                            name(_BY_KEY[count]), name(_BY_KEY["force"]))
    if config.keyed_noise and not (config.noise or config.torque_noise):
        notes.append(f"{name(_BY_KEY['keyed_noise'])} has no effect: the sensor draws no noise "
                     f"({name(_BY_KEY['noise'])} and {name(_BY_KEY['torque_noise'])} are 0)")
    if config.reads not in ("auto", 1) and not (config.noise or config.torque_noise):
        notes.append(f"{name(_BY_KEY['reads'])} has no effect: the sensor draws no noise "
                     f"({name(_BY_KEY['noise'])} and {name(_BY_KEY['torque_noise'])} are 0)")
    return [n for n in notes if n]

