"""What the command line prints: one-line warnings, the estimate of a long run and the
end-of-run summary of ``recon3d run``."""
from __future__ import annotations

import sys
from pathlib import Path
from typing import TYPE_CHECKING

from recon3d.config import diagonal
from recon3d.spellings import number, percent

if TYPE_CHECKING:  # annotations only: warn() serves the parser, which loads no run
    from recon3d.api import Result
    from recon3d.records import MeshRun, SliceRun

__all__ = ["warn", "summary_lines", "coverage_lines", "format_seconds", "projected_seconds",
           "estimate_note", "LONG_RUN_SECONDS"]

LONG_RUN_SECONDS = 60.0
"""A run projected to take longer than this (wall seconds) gets an estimate note."""


def warn(message: str) -> None:
    """Print one warning line on stderr (``recon3d: warning: ...``).

    >>> warn("a coarse eps")  # doctest: +SKIP
    """
    print(f"recon3d: warning: {' '.join(str(message).split())}", file=sys.stderr)


def format_seconds(s: float | None) -> str:
    """Human duration.

    >>> format_seconds(42.0), format_seconds(4000.0), format_seconds(None)
    ('42 s', '1 h 06 min', 'n/a')
    """
    if s is None:
        return "n/a"
    if s < 60:
        return f"{s:.0f} s"
    if s < 3600:
        return f"{s / 60:.1f} min"
    return f"{int(s // 3600)} h {int(s % 3600 // 60):02d} min"


def projected_seconds(slices: int, first_seconds: float, slice_seconds: float,
                      jobs: int) -> float:
    """Wall seconds of sensing ``slices`` slices on ``jobs`` processes: the first wave
    (one slice per process, with their start-up) in ``first_seconds``, each further
    slice in ``slice_seconds`` on one process.

    >>> round(projected_seconds(2000, 2.2, 0.4, 2), 1), projected_seconds(3, 10.0, 10.0, 8)
    (401.8, 10.0)
    """
    jobs = max(1, min(jobs, slices))
    return first_seconds + (slices - jobs) * slice_seconds / jobs


def estimate_note(slices: int, first_seconds: float, slice_seconds: float, jobs: int,
                  longer_than: float = LONG_RUN_SECONDS) -> str | None:
    """The note printed early in a run that will take long (:func:`projected_seconds`).

    With several jobs the pool hands out the costliest slices first
    (:mod:`recon3d.sensing.order`), so the slices timed here are among the slowest and
    the projection leans long: the note says so.

    >>> estimate_note(2000, 2.2, 0.4, 2)
    'about 7 min or less for 2000 slices (first slice 2.2 s, then 0.40 s a slice, 2 jobs; the costliest slices go first)'
    >>> estimate_note(2000, 2.2, 0.4, 1)
    'about 13 min for 2000 slices (first slice 2.2 s, then 0.40 s a slice, 1 job)'
    >>> estimate_note(24, 2.2, 0.4, 2) is None  # 7 s: no note
    True
    """
    total = projected_seconds(slices, first_seconds, slice_seconds, jobs)
    if total <= longer_than:
        return None
    jobs = max(1, min(jobs, slices))
    less, tail = (" or less", "s; the costliest slices go first") if jobs > 1 else ("", "")
    return (f"about {max(1, round(total / 60))} min{less} for {slices} slices (first slice "
            f"{first_seconds:.1f} s, then {slice_seconds:.2f} s a slice, {jobs} job{tail})")


def _names(run: MeshRun, slices: list[SliceRun]) -> str:
    """``axis#k``: k counts the sensed slices of the axis from 0 (with ``--slices auto``
    not the candidate plane, which metrics.json keeps as ``candidate``)."""
    def position(s):
        return next(k for k, x in enumerate(run.families[s.family].slices) if x is s)

    shown = [f"{run.families[s.family].label}#{position(s)}" for s in slices[:12]]
    more = f" and {len(slices) - 12} more" if len(slices) > 12 else ""
    return ", ".join(shown) + more


def _speed(config) -> str:
    """The probe speed in mm/s, and in mesh units per second where those are not mm."""
    mm = f"{config.probe_speed:g} mm/s"
    return mm if config.units == "mm" else f"{mm} = {config.speed:g} {config.units}/s"


def coverage_lines(t: dict) -> list[str]:
    """The summary's 2D lines from the ``total`` of ``metrics.json``.

    The coverage counts the contour behind a W2 chord (§3.1); where that share
    (``w2_credit_length`` over the reachable length) is 0.001 or more, it is named, and
    so is the coverage over the part eps resolves where openings narrower than eps hold
    0.1 % of the reachable contour or more.

    With a sensor model (``coverage_sensor`` present) the figures first are those within
    the tolerance the sensor allows, eps / 2 + 2 sigma, and a second line gives them within
    eps / 2: a reading 2 sigma off the contour is as good as the sensor can tell, and read
    alone the noiseless tolerance's precision looks like a planner's error.

    >>> t = {"coverage": 0.95, "precision": 0.94, "w3_soundness": 1.0, "w3_count": 0}
    >>> print(*coverage_lines(t), sep="\\n")
      2D  reachable coverage 0.9500  precision 0.9400  W3 soundness 1.0000 (0 lids)
    >>> print(*coverage_lines(dict(t, reachable_length=100.0, resolvable_length=100.0,
    ...                               w2_credit_length=2.5)))
      2D  reachable coverage 0.9500 (0.0250 of it behind W2 chords, never touched)  precision 0.9400  W3 soundness 1.0000 (0 lids)
    >>> t.update(coverage_sensor=0.976, precision_sensor=0.998, w3_soundness_sensor=1.0,
    ...          sensor_tol=0.495)
    >>> print(*coverage_lines(t), sep="\\n")
      2D  reachable coverage 0.9760  precision 0.9980  W3 soundness 1.0000 (0 lids), within the sensor's tolerance eps/2 + 2 sigma = 0.495
          within eps/2: reachable coverage 0.9500  precision 0.9400  W3 soundness 1.0000
    """
    reach, resolved = t.get("reachable_length") or 0.0, t.get("resolvable_length") or 0.0
    noisy = t.get("coverage_sensor") is not None

    def figures(suffix):
        notes = []
        credit = (t.get("w2_credit_length" + suffix) or 0.0) / reach if reach > 0 else 0.0
        if credit >= 1e-3:  # never touched: the walls of slots W2 chords closed
            notes.append(f"{number(credit, '.4f')} of it behind W2 chords, never touched")
        if reach > 0 and resolved < reach * (1 - 1e-3):
            notes.append(f"{number(t.get('coverage_resolvable' + suffix), '.4f')} of the part "
                         f"eps resolves: {percent(1.0 - resolved / reach, 1)} of the reachable "
                         f"contour lies in openings narrower than eps, §3.1")
        narrow = f" ({'; '.join(notes)})" if notes else ""
        return (f"reachable coverage {number(t.get('coverage' + suffix), '.4f')}{narrow}  "
                f"precision {number(t.get('precision' + suffix), '.4f')}  W3 soundness "
                f"{number(t.get('w3_soundness' + suffix), '.4f')}")

    lids = f" ({t.get('w3_count', 0)} lids)"
    if not noisy:
        return [f"  2D  {figures('')}{lids}"]
    return [f"  2D  {figures('_sensor')}{lids}, within the sensor's tolerance eps/2 + 2 sigma = "
            f"{number(t.get('sensor_tol'), '.3g')}", f"      within eps/2: {figures('')}"]


def summary_lines(result: Result, files: list[Path] = ()) -> list[str]:
    """Lines of the summary of a :class:`recon3d.Result`."""
    run, m = result.sensing, result.metrics
    t, surf, ev = m["total"], m["total"].get("surface"), m["surface_eval"]
    fams = ", ".join(f"{f.label} x{len(f.slices)}" for f in run.families)
    lines = [f"{run.name}: slices {fams}, eps {number(run.eps, '.4g')}, tol "
             f"{number(run.tol, '.3g')}, {run.jobs} job{'s' if run.jobs > 1 else ''}, "
             f"{number(run.seconds, '.1f')} s sensing"]
    lines += coverage_lines(t)
    scores, chords = result.headline()
    lines.append(f"  3D  {scores[0]}")
    lines += [f"      {h}" for h in scores[1:]]
    if surf is not None:
        cd = None if surf["chamfer_l1"] is None else surf["chamfer_l1"] / diagonal(result.mesh)
        lines.append(f"      Chamfer-L1/diagonal {number(cd, '.2e')}  touched share "
                     f"{number(ev.get('touched_share'))} (reachable scored ground truth whose "
                     f"nearest slice point the probe touched)  {len(result.surface.faces)} "
                     f"faces, watertight {result.surface.is_watertight}")
    lines += [f"  {h}" for h in chords]
    lines.append(f"  cost motions {t.get('motions', 0)}  rays {t.get('rays', 0)}  pushes "
                 f"{t.get('pushes', 0)} (attempts stopped by the Case 3 guard "
                 f"{t.get('push_attempts', 0)}, jams {t.get('jams', 0)})  budget hits {t.get('budget_hits', 0)}  robot time "
                 f"{format_seconds(t.get('robot_time_s'))} (probe {_speed(run.config)} + "
                 f"{run.config.motion_overhead:g} s/motion"
                 + (f" + {t['sensor_reads']} sensor reads x {run.config.read_time:g} s, "
                    f"{run.reads} per reading point" if t.get("sensor_reads") else "") + ")")
    several = [s for s in run.slices if s.outer_loops > 1]
    if several:
        lines.append(f"  {len(several)} slices hold several objects (outside the paper's "
                     f"single-object assumption, §3.2; the planner probes between them, and a "
                     f"W3 lid bridging two would count as unsound): {_names(run, several)}")
    noref = [s for s in run.slices if not s.has_reference]
    if noref:
        lines.append(f"  {len(noref)} slices have no closed reference contour (open mesh): "
                     f"metrics null, left out of the 2D totals: {_names(run, noref)}")
    if files:
        lines.append(f"  wrote {files[0].parent}/: {' '.join(sorted(f.name for f in files))}")
    return lines
