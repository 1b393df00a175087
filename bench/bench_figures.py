"""What the 2D pictures cost: ``slices.png`` within a run, ``recon3d figure`` and its animation.

One run of each scene (``--slices``, default 8) is sensed once; then, each the minimum
of ``--repeat`` calls (default 3):

* ``save --no-png``: ``Result.save(png=False)`` (the JSON, PLY and VTK outputs);
* ``coverage.png``: the pyvista rendering of a run (OpenGL);
* ``slices.png``: :func:`recon3d.io.outputs.write_slices_png` (matplotlib Agg, already
  loaded by coverage.png in a run that draws both);
* ``figure``: one slice in the paper's style (:func:`recon3d.viz.figure2d.slice_figure`,
  saved as PNG), with the motion log when the run wrote one;
* ``animation``: its GIF at the default stride (once, not repeated).

Nothing is asserted: it measures.

    python -m bench.bench_figures
    python -m bench.bench_figures --scene comb --slices 24
"""
from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import recon3d
from recon3d.io.motions import read_log
from recon3d.io.outputs import write_slices_png
from recon3d.viz import animate, figure2d, libs, plot, rundata


def _best(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def _measure(scene: str, slices: int, repeat: int) -> dict:
    res = recon3d.run(scene, slices=slices)
    out = {"scene": scene, "slices": len(res.slices),
           "sensing s": res.metrics["seconds"]}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        out["save --no-png s"] = _best(lambda: res.save(tmp / "run", png=False), repeat)
        blocks = res.blocks()
        out["coverage.png s"] = _best(lambda: plot.save_png(blocks, tmp / "c.png"), repeat)
        doc = res.sensing_document()
        out["slices.png s"] = _best(lambda: write_slices_png(
            tmp / "s.png", doc, res.metrics, res.slices, scene), repeat)
        sensing, views = rundata.read_views(tmp / "run")
        view = rundata.attach_sections(views[len(views) // 2:][:1], sensing, tmp / "run")[0]
        rundata.attach_log(view, read_log(tmp / "run"))

        def figure():
            fig = figure2d.slice_figure(view, scene)
            fig.savefig(tmp / "f.png")
            libs.pyplot().close(fig)
        out["figure s"] = _best(figure, repeat)
        if view.log is not None:
            t0 = time.perf_counter()
            frames = animate.write_animation(view, tmp / "a.gif", scene)
            out["animation s"] = time.perf_counter() - t0
            out["frames"] = frames
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", action="append", default=None,
                    help="built-in scene (repeatable; default fig17_pocket and fig18_overhangs)")
    ap.add_argument("--slices", type=int, default=8)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    plot.prepare_offscreen()
    for scene in args.scene or ["fig17_pocket", "fig18_overhangs"]:
        row = _measure(scene, args.slices, args.repeat)
        print("  ".join(f"{k} {v:.3f}" if isinstance(v, float) else f"{k} {v}"
                        for k, v in row.items()), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
