"""Where the time of one ``recon3d run`` goes: wall and CPU per phase, per process.

Runs ``recon3d run SCENE --out DIR [flags]`` in a fresh interpreter whose phases are
wrapped with timestamps (nothing else changes): every process -- the main one, the
sensing workers, the side children (pictures, the coloured ground truth, a score's
distance call) -- appends one line per phase to a log, with its wall interval and its
CPU seconds (the calling thread's and the whole process's). Printed: the phases in start
order, grouped by process, with wall offsets from the interpreter's start, and the CPU of
every process; then each sensing worker's idle tail (the wall seconds from the end of its
last slice to the end of the last slice of any worker).

    python -m bench.run_timeline bored_block [--slices 8] [--jobs 2] [--no-png] [--profile]
                                 [--root DIR]

``--root``: the files of another checkout (e.g. ``out/compare/src-<hash>`` of
:mod:`bench.compare_commits`); phases it lacks are skipped.

``--profile``: cProfile of the main process too (top functions by cumulative time).
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

# (module, attribute, label): wrapped where the caller looks the name up
PHASES = [
    ("recon3d.cli.run", "load_input", "load_input"),
    ("recon3d.cli.run", "validate", "validate"),
    ("recon3d.cli.run", "cold_kernels", "cold_kernels"),
    ("recon3d.api", "sense_mesh", "sense_mesh"),
    ("recon3d.sensing.mesh", "family_slices", "family_slices"),
    ("recon3d.sensing.mesh", "sense_all", "sense_all (pool)"),
    ("recon3d.sensing.pool", "_beside", "beside thread"),
    ("recon3d.api", "reconstruct", "reconstruct"),
    ("recon3d.surface.reconstruct", "slice_region", "slice_region"),
    ("recon3d.surface.reconstruct", "family_solid", "family_solid"),
    ("recon3d.surface.reconstruct", "fuse", "fuse"),
    ("recon3d.api", "score", "score"),
    ("recon3d.score.families", "GroundTruthSamples", "gt samples"),
    ("recon3d.score.families", "surface_metrics", "surface_metrics"),
    ("recon3d.score.families", "contour_cloud", "contour_cloud"),
    ("recon3d.score.evaluate", "distances", "vtk distances"),
    ("recon3d.api", "metrics_document", "metrics_document"),
    ("recon3d.api", "unknown_chords", "unknown_chords"),
    ("recon3d.api.Result", "save", "save"),
    ("recon3d.api.Result", "_build_blocks", "scene blocks"),
    ("recon3d.api", "_coverage", "coverage mesh (no side)"),
    ("recon3d.io.outputs", "_save_scene", "scene.vtm"),
    ("recon3d.io.outputs", "write_json", "json"),
    ("recon3d.io.outputs", "write_motions", "motions.csv"),
    ("recon3d.io.documents", "sensing_document", "sensing_document"),
    ("recon3d.api", "sensing_document", "sensing_document (api)"),
    ("recon3d.io.outputs.ply", "write_ply", "surface.ply"),
    ("recon3d.io.outputs.plot", "load_plotting", "load_plotting"),
    ("recon3d.io.outputs", "write_slices_png", "slices.png"),
    ("recon3d.io.outputs", "_render", "coverage.png"),
    ("recon3d.io.side.Side", "result", "wait side"),
    ("recon3d.sensing.worker.WorkerState", "sense", "slice"),
    ("recon3d.sensing.worker.core2d", "sense_slice", "sense_slice"),
    ("recon3d.sensing.worker", "reachable_samples", "reachable_samples"),
    ("recon3d.sensing.worker", "slice_metrics", "slice_metrics"),
    ("recon3d.sensing.worker", "_covered", "_covered"),
    ("recon3d.sensing.worker", "slice_rows", "motion rows"),
    ("recon3d.io.side", "_child", "side child"),
    ("recon3d.sensing.pool", "_worker", "worker"),
]

_DRIVER = r"""
import json, os, sys, threading, time
T_IMPORT = time.time()
LOG = open(os.environ["TIMELINE_LOG"], "a", buffering=1)
MAIN = os.getpid()
def log(label, t0, t1, c0, c1, p0, p1, extra=""):
    LOG.write(json.dumps({"pid": os.getpid(), "main": os.getpid() == MAIN,
                          "thread": threading.current_thread().name, "label": label,
                          "t0": t0, "t1": t1, "cpu": c1 - c0, "pcpu": p1 - p0,
                          "extra": extra}) + "\n")
import importlib, functools
import recon3d.api, recon3d.cli.run
from recon3d.cli import main as cli_main
log("imports", T_IMPORT, time.time(), 0, time.thread_time(), 0, time.process_time())
def resolve(path):
    parts = path.split(".")
    for k in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:k]))
        except ImportError:
            continue
        for p in parts[k:]:
            obj = getattr(obj, p)
        return obj
def wrap(fn, label):
    @functools.wraps(fn)
    def inner(*a, **k):
        t0, c0, p0 = time.time(), time.thread_time(), time.process_time()
        extra = ""
        if label == "side child":
            extra = getattr(a[1], "__name__", str(a[1]))
        if label == "slice":
            extra = str(a[1:3])
        try:
            return fn(*a, **k)
        finally:
            log(label, t0, time.time(), c0, time.thread_time(), p0, time.process_time(), extra)
    return inner
for mod, name, label in json.loads(os.environ["TIMELINE_PHASES"]):
    try:
        owner = resolve(mod)
        setattr(owner, name, wrap(getattr(owner, name), label))
    except AttributeError:  # an older checkout without this phase
        pass
code = cli_main(sys.argv[1:])
t = os.times()
log("main total", T_IMPORT, time.time(), 0, time.process_time(), 0, time.process_time(),
    f"children (waited) {t.children_user + t.children_system:.2f}")
"""

_PROFILE = r"""
import cProfile, pstats, io, sys
pr = cProfile.Profile()
pr.enable()
try:
    exec(compile(DRIVER, "driver", "exec"))
finally:
    pr.disable()
    s = io.StringIO()
    pstats.Stats(pr, stream=s).sort_stats("cumulative").print_stats(45)
    sys.stderr.write(s.getvalue())
"""


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.run_timeline", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("--slices", default="8")
    ap.add_argument("--jobs", default="2")
    ap.add_argument("--no-png", action="store_true")
    ap.add_argument("--profile", action="store_true", help="cProfile of the main process")
    ap.add_argument("--root", default=str(ROOT), help="checkout whose files run (default: this)")
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        logf = Path(tmp) / "log.jsonl"
        env = dict(os.environ, PYTHONPATH=str(args.root), TIMELINE_LOG=str(logf),
                   TIMELINE_PHASES=json.dumps(PHASES),
                   VTK_DEFAULT_OPENGL_WINDOW="vtkEGLRenderWindow")
        code = _DRIVER if not args.profile else f"DRIVER = {_DRIVER!r}\n" + _PROFILE
        cmd = [sys.executable, "-c", code, "run", args.scene, "--out", str(Path(tmp) / "out"),
               "--quiet", "--slices", args.slices, "--jobs", args.jobs]
        if args.no_png:
            cmd.append("--no-png")
        t0 = time.time()
        proc = subprocess.run(cmd, env=env, cwd=str(args.root), capture_output=True, text=True)
        wall = time.time() - t0
        if proc.returncode:
            sys.stderr.write(proc.stderr[-3000:])
            return 1
        if args.profile:
            print(proc.stderr[-12000:])
        rows = [json.loads(ln) for ln in logf.read_text().splitlines()]
    print(f"{args.scene}: {wall:.2f} s wall (parent's view, interpreter start included); "
          f"load {os.getloadavg()[0]:.1f}")
    pids = sorted({r["pid"] for r in rows}, key=lambda p: min(r["t0"] for r in rows
                                                              if r["pid"] == p))
    for pid in pids:
        mine = sorted((r for r in rows if r["pid"] == pid), key=lambda r: (r["t0"], -r["t1"]))
        role = "main" if mine[0]["main"] else next(
            (f"{r['label']} {r['extra']}" for r in mine if r["label"] in ("side child",
                                                                          "worker")), "?")
        print(f"-- pid {pid} ({role})")
        for r in mine:
            print(f"  {r['t0'] - t0:6.2f} .. {r['t1'] - t0:6.2f}  {r['t1'] - r['t0']:6.2f} s  "
                  f"cpu {r['cpu']:6.2f} (proc {r['pcpu']:6.2f})  {r['thread'][:14]:14s} "
                  f"{r['label']} {r['extra']}")
    _idle_tails(rows, t0)
    return 0


def _idle_tails(rows: list, t0: float) -> None:
    """Print each sensing worker's idle tail: from the end of its last slice to the end
    of the last slice of any worker (the pool waits that long for the slowest one)."""
    ends = {}
    for r in rows:
        if r["label"] == "slice" and not r["main"]:
            ends[r["pid"]] = max(ends.get(r["pid"], 0.0), r["t1"])
    if len(ends) < 2:
        return
    last = max(ends.values())
    tails = ", ".join(f"pid {pid} {last - t:.2f} s" for pid, t in sorted(ends.items()))
    print(f"sensing workers' idle tail (last slice ended at {last - t0:.2f} s): {tails}")


if __name__ == "__main__":
    sys.exit(main())
