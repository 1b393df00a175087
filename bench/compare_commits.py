"""Compare the outputs of two commits, case by case: are they byte-identical?

Each commit is exported with ``git archive`` into ``OUT/src-<hash>/`` (kept,
so its compiled kernels are cached there for the next call) and every case
runs as ``python -m recon3d run ... --no-png --quiet`` with that tree first on
``PYTHONPATH``, the two commits alternating case by case. ``sensing.json``
and ``metrics.json`` are then compared after removing the keys that depend
on the machine (:func:`recon3d.io.without_timing`): the JSON text of both documents,
keys sorted, must be the same byte for byte.

Cases: every built-in scene and every mesh of ``../shared/meshes`` at the
defaults (8 z-slices, eps = diagonal / 200, Embree), plus four variants that
take the other paths of a run (two slice families, adaptive slicing, the
exact backend, one process).

Usage (repository root, project venv)::

    python -m bench.compare_commits ec29520 HEAD
    python -m bench.compare_commits ec29520 HEAD --cases fig18_overhangs,gear --jobs 2
    python -m bench.compare_commits ec29520 WORKTREE --flags="--backend exact" --ignore rays

``AFTER`` may be ``WORKTREE``: the files of this checkout as they are,
uncommitted changes included. Exit status 1 when any case differs or fails.
"""
from __future__ import annotations

import argparse
import json
import os
import shlex
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

from recon3d.io import without_timing

ROOT = Path(__file__).resolve().parents[1]
SHARED_MESHES = ROOT.parent / "shared" / "meshes"
WORKTREE = "WORKTREE"
VARIANTS = {
    "fig18_overhangs@zx": ("fig18_overhangs", ["--axis", "z", "--axis", "x"]),
    "fig17_pocket@auto": ("fig17_pocket", ["--slices", "auto"]),
    "bowl@exact": ("bowl", ["--backend", "exact"]),
    "gear@jobs1": ("gear", ["--jobs", "1"]),
}


def _git(*args) -> str:
    return subprocess.run(["git", *args], cwd=ROOT, check=True, capture_output=True,
                          text=True).stdout.strip()


def export(commit: str, out: Path) -> tuple[str, Path]:
    """(short hash, source tree) of ``commit``; ``WORKTREE`` is this checkout itself."""
    if commit == WORKTREE:
        return WORKTREE.lower(), ROOT
    short = _git("rev-parse", "--short", commit)
    src = out / f"src-{short}"
    if not (src / "recon3d").is_dir():
        src.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile() as fh:
            subprocess.run(["git", "archive", short], cwd=ROOT, check=True, stdout=fh)
            fh.seek(0)
            with tarfile.open(fileobj=fh) as tar:
                tar.extractall(src, filter="data")
    return short, src


def cases(selected: str | None) -> dict[str, tuple[str, list[str]]]:
    """name -> (INPUT, extra flags): scenes, shared meshes (when present) and variants."""
    names = subprocess.run([sys.executable, "-m", "recon3d", "scenes"], cwd=ROOT, check=True,
                           capture_output=True, text=True).stdout.split("\n")
    out = {n.split("\t")[0]: (n.split("\t")[0], []) for n in names if n.strip()}
    if SHARED_MESHES.is_dir():
        for path in sorted(SHARED_MESHES.iterdir()):
            if path.suffix.lower() in (".stl", ".obj", ".ply", ".off", ".glb"):
                out[path.stem] = (str(path), [])
    out.update(VARIANTS)
    if selected:
        want = [c.strip() for c in selected.split(",") if c.strip()]
        missing = [c for c in want if c not in out]
        if missing:
            raise SystemExit(f"compare_commits: unknown cases {missing} (known: {sorted(out)})")
        out = {c: out[c] for c in want}
    return out


def run_case(src: Path, source: str, flags: list[str], dest: Path, jobs: int) -> tuple[float, str]:
    """Run one case with the tree ``src``; (wall seconds, error text or '')."""
    env = dict(os.environ, PYTHONPATH=str(src), VTK_DEFAULT_OPENGL_WINDOW="vtkEGLRenderWindow")
    if "--jobs" not in flags:
        flags = [*flags, "--jobs", str(jobs)]
    cmd = [sys.executable, "-m", "recon3d", "run", source, "--out", str(dest), "--no-png",
           "--quiet", *flags]
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, cwd=src, env=env, capture_output=True, text=True)
    err = "" if proc.returncode == 0 else (proc.stderr.strip().splitlines() or ["?"])[-1]
    return time.perf_counter() - t0, err


def _canonical(path: Path, ignore=()) -> str:
    return json.dumps(_without(without_timing(json.loads(path.read_text())), set(ignore)),
                      sort_keys=True)


def _without(doc, keys):
    """``doc`` without the keys ``keys`` at any depth."""
    if isinstance(doc, dict):
        return {k: _without(v, keys) for k, v in doc.items() if k not in keys}
    if isinstance(doc, list):
        return [_without(v, keys) for v in doc]
    return doc


def first_difference(a, b, where: str = "") -> str:
    """Path of the first place two JSON values differ ('' when equal)."""
    if type(a) is not type(b):
        return where or "/"
    if isinstance(a, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                return f"{where}/{k}"
            d = first_difference(a[k], b[k], f"{where}/{k}")
            if d:
                return d
        return ""
    if isinstance(a, list):
        if len(a) != len(b):
            return f"{where} (length {len(a)} vs {len(b)})"
        for i, (x, y) in enumerate(zip(a, b)):
            d = first_difference(x, y, f"{where}[{i}]")
            if d:
                return d
        return ""
    return "" if a == b else (where or "/")


def compare(dir_a: Path, dir_b: Path, ignore=()) -> str:
    """'identical' or the first difference of the two runs' documents (keys
    ``ignore`` aside)."""
    for name in ("sensing.json", "metrics.json"):
        ta, tb = _canonical(dir_a / name, ignore), _canonical(dir_b / name, ignore)
        if ta != tb:
            return f"{name} differs at {first_difference(json.loads(ta), json.loads(tb))}"
    return "identical"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.compare_commits", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("before", help="commit (hash, branch, HEAD~1, ...)")
    ap.add_argument("after", help=f"commit, or {WORKTREE} for this checkout as it is")
    ap.add_argument("--cases", default=None, help="comma-separated subset of the cases")
    ap.add_argument("--jobs", type=int, default=2, help="--jobs of every run (default 2)")
    ap.add_argument("--out", default=str(ROOT / "out" / "compare"),
                    help="work directory (default out/compare)")
    ap.add_argument("--ignore", default="",
                    help="comma-separated keys left out of the comparison at any depth, "
                         "e.g. rays (a change that casts fewer rays for the same results)")
    ap.add_argument("--flags", default="",
                    help="run flags added to every case, e.g. --flags='--backend exact'")
    args = ap.parse_args(argv)
    more = shlex.split(args.flags)
    ignore = [k for k in args.ignore.split(",") if k]
    out = Path(args.out).resolve()  # the runs start in their own trees
    trees = [export(c, out) for c in (args.before, args.after)]
    todo = cases(args.cases)
    print(f"before {trees[0][0]}  after {trees[1][0]}  {len(todo)} cases, --jobs {args.jobs}"
          + (f", with {args.flags}" if more else ""))
    print(f"{'case':28s} {'before s':>9s} {'after s':>9s}  result")
    bad = 0
    for name, (source, flags) in todo.items():
        walls, errors, dirs = [], [], []
        for short, src in trees:
            dest = out / short / name
            wall, err = run_case(src, source, [*flags, *more], dest, args.jobs)
            walls.append(wall)
            errors.append(err)
            dirs.append(dest)
        if any(errors):
            verdict = "FAILED: " + " | ".join(f"{t[0]}: {e}" for t, e in zip(trees, errors) if e)
        else:
            verdict = compare(*dirs, ignore)
        bad += verdict != "identical"
        print(f"{name:28s} {walls[0]:9.1f} {walls[1]:9.1f}  {verdict}", flush=True)
    aside = "".join(f", {k}" for k in ignore)
    print(f"{len(todo) - bad} of {len(todo)} cases identical (sensing.json and metrics.json, "
          f"timing fields{aside} aside)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
