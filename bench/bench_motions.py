"""Cost of the motion log: a run with and without the recorder and motions.csv.

``recon3d.run(SCENE, jobs=1)`` (defaults: 8 z-slices, eps = diagonal / 200,
Embree) then ``Result.save(png=False)``: what ``recon3d run --no-png`` does.
Every slice is sensed through :class:`core2d.sim.recorder.Recorder`; the run
"without the log" replaces the recorder by the bare probe and skips
motions.csv (here only, by patching ``core2d.sense.Recorder`` and
``recon3d.io.outputs.write_motions``). The two alternate ``--repeat`` times
after one untimed warm-up run; printed: the minimum of each of the sensing
wall seconds (``MeshRun.seconds``), the CPU seconds of ``recon3d.run`` (sense,
reconstruct, score) and of ``save`` -- CPU time, as the machine may be
shared -- and the time to format motions.csv
(:func:`recon3d.io.motions.motions_text`). Nothing is asserted: it measures
(target: the log costs < 5 % of a run).

    python -m bench.bench_motions
    python -m bench.bench_motions --scene fig17_pocket --repeat 5
"""
from __future__ import annotations

import argparse
import contextlib
import tempfile
import time
from pathlib import Path
from unittest import mock

import core2d.sense
import recon3d
import recon3d.io.outputs
from recon3d.io.motions import motions_text


def _bare(robot):
    """The probe itself, with a ``log()`` that records nothing (no recorder)."""
    robot.log = lambda: None
    return robot


def _run(scene: str, logged: bool, out: Path):
    """(Result, CPU seconds of the run, of the save) with or without the log."""
    with contextlib.ExitStack() as stack:
        if not logged:
            stack.enter_context(mock.patch.object(core2d.sense, "Recorder", _bare))
            stack.enter_context(mock.patch.object(recon3d.io.outputs, "write_motions",
                                                  lambda *a: None))
        t0 = time.process_time()
        res = recon3d.run(scene, jobs=1)
        t1 = time.process_time()
        res.save(out, png=False)
        return res, t1 - t0, time.process_time() - t1


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default="fig18_overhangs")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    sense = {True: float("inf"), False: float("inf")}
    run, save = dict(sense), dict(sense)
    with tempfile.TemporaryDirectory() as tmp:
        _run(args.scene, True, Path(tmp) / "warm")  # numba kernels, Embree scenes
        for k in range(args.repeat):
            for logged in (False, True):
                res, cpu_run, cpu_save = _run(args.scene, logged, Path(tmp) / f"{k}{logged}")
                sense[logged] = min(sense[logged], res.sensing.seconds)
                run[logged] = min(run[logged], cpu_run)
                save[logged] = min(save[logged], cpu_save)
    t0 = time.perf_counter()
    text = motions_text(res.slices)
    fmt = time.perf_counter() - t0
    print(f"{args.scene}: {len(res.slices)} slices, {text.count(chr(10)) - 1} motions, jobs=1, "
          f"min of {args.repeat} runs")
    for name, best in (("sensing wall", sense), ("run CPU", run), ("save CPU", save)):
        print(f"  {name:<12} without log {best[False]:7.2f} s   with log {best[True]:7.2f} s"
              f"   ({100 * (best[True] / best[False] - 1):+.1f} %)")
    print(f"  motions.csv text {fmt:.2f} s ({len(text) / 1e6:.1f} MB)")


if __name__ == "__main__":
    main()
