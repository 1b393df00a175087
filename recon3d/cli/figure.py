"""``recon3d figure DIR --slice K --out FILE``: one slice of a run in the paper's style.

Draw slice K of a run (written by 'recon3d run ... --out DIR') as the paper's
Figs. 17-18 do: the known contour by class (W1, W2, W3), unknown areas dotted,
the true section in grey, the probe postures, the joint path with its moving
direction, the A_iB_i labels and a scale bar (PNG, SVG or PDF by the suffix of
FILE). With --animate, write the exploration motion by motion instead (GIF, or
MP4 when ffmpeg is installed). Postures, joint path and animation come from
DIR/motions.csv; without it the figure says "no motion log".
"""
from __future__ import annotations

import argparse
import os
import sys
import tempfile
from pathlib import Path

from tqdm import tqdm

from recon3d.checks import InputError
from recon3d.viz import animate, figure2d, libs

__all__ = ["HELP", "add_arguments", "command", "FIGURE_SUFFIXES"]

HELP = "draw one slice of a run in the paper's style (PNG/SVG/PDF) or animate it (GIF/MP4)"

FIGURE_SUFFIXES = (".png", ".svg", ".pdf")


def _at_least_one(text: str) -> int:
    """argparse type: a whole number >= 1."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, got {value}")
    return value


def add_arguments(p) -> None:
    p.add_argument("dir", metavar="DIR", help="output directory of 'recon3d run'")
    p.add_argument("--slice", type=int, required=True, metavar="K",
                   help="the slice: its position in its family, from 0 (as captioned in "
                   "DIR/slices.png)")
    p.add_argument("--family", type=int, default=0, metavar="F",
                   help="the slice family (axis), from 0 in the order of --axis (default 0)")
    p.add_argument("--out", required=True, metavar="FILE",
                   help="file to write: .png, .svg or .pdf (a figure), .gif or .mp4 "
                   "(with --animate)")
    p.add_argument("--every", type=_at_least_one, default=1, metavar="N",
                   help="draw the probe posture after every N-th motion only (default 1: all)")
    p.add_argument("--dpi", type=_at_least_one, default=110, metavar="N",
                   help="resolution of a PNG figure in dots per inch (default 110; the "
                   "figure is 13 x 6 inches, 8 x 6 without a motion log)")
    p.add_argument("--no-labels", action="store_true",
                   help="leave out the A_iB_i labels")
    p.add_argument("--animate", action="store_true",
                   help="write the exploration motion by motion (GIF; MP4 needs ffmpeg)")
    p.add_argument("--stride", type=_at_least_one, default=None, metavar="N",
                   help="with --animate: motions per frame (default: the smallest that "
                   f"keeps the animation within {animate.MAX_FRAMES} frames)")
    p.add_argument("--fps", type=_at_least_one, default=10, metavar="N",
                   help="with --animate: frames per second (default 10)")


def _check_out(path: Path, suffixes) -> None:
    if path.suffix.lower() not in suffixes:
        raise InputError(f"--out {path}: the file type is set by its suffix, one of "
                         f"{', '.join(suffixes)}")
    if not path.parent.is_dir():
        raise InputError(f"--out {path}: no directory {path.parent}")


def _pick(views, family: int, position: int):
    """The view at ``position`` in ``family``; one-line errors naming what exists."""
    families = sorted({v.family for v in views})
    if family not in families:
        raise InputError(f"--family {family}: the run has families "
                         f"{', '.join(map(str, families)) or 'none'}")
    fam = [v for v in views if v.family == family]
    if not 0 <= position < len(fam):
        raise InputError(f"--slice {position}: family {family} has {len(fam)} slices "
                         f"(0 to {len(fam) - 1})")
    return fam[position]


def _write(path: Path, draw) -> None:
    """Call ``draw(tmp)`` on a temporary file next to ``path``, then move it into place:
    no half-written FILE if drawing fails or is interrupted."""
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=path.suffix, dir=path.parent)
    os.close(fd)
    try:
        draw(tmp)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


def command(args) -> int:
    out = Path(args.out)
    _check_out(out, animate.FORMATS if args.animate else FIGURE_SUFFIXES)
    # the run's files: meshes, the slicer, the records (core2d); `recon3d --help` needs none
    from recon3d.io.motions import read_log  # lazy: see above
    from recon3d.viz import rundata  # lazy: see above

    sensing, views = rundata.read_views(args.dir)
    view = _pick(views, args.family, args.slice)
    rundata.attach_log(view, read_log(args.dir))
    rundata.attach_sections([view], sensing, args.dir)
    mesh = str(sensing.get("mesh", ""))
    if args.animate:
        try:
            frames = _animate(view, out, mesh, args)
        except ValueError as exc:
            raise InputError(str(exc)) from None
        print(f"wrote {out} ({frames} frames)")
        return 0
    fig = figure2d.slice_figure(view, mesh, every=args.every, labels=not args.no_labels)
    try:
        _write(out, lambda tmp: fig.savefig(tmp, dpi=args.dpi))
    finally:
        libs.pyplot().close(fig)
    print(f"wrote {out}")
    return 0


def _animate(view, out: Path, mesh: str, args) -> int:
    if view.log is None or not len(view.log):
        raise ValueError(f"no motion log for slice {args.slice} of family {args.family} "
                         f"in {args.dir} (motions.csv): nothing to animate")
    stride = args.stride or animate.default_stride(len(view.log))
    total = len(animate.frame_motions(len(view.log), stride))
    bar = tqdm(total=total, desc="frames", unit="frame", file=sys.stderr, disable=None)
    frames = [0]

    def draw(tmp):
        frames[0] = animate.write_animation(view, tmp, mesh, stride=stride, fps=args.fps,
                                            progress=lambda i, n: bar.update(1))
    try:
        _write(out, draw)
    finally:
        bar.close()
    return frames[0]
