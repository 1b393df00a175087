"""``recon3d show DIR``: open a run's scene in an interactive pyvista window.

Open DIR/scene.vtm (written by 'recon3d run') in an interactive window with
the two coverage panels; needs a display.
"""
from __future__ import annotations

import os
from pathlib import Path

from recon3d.checks import InputError

__all__ = ["HELP", "add_arguments", "command"]

HELP = "open a run's scene in an interactive pyvista window"


def add_arguments(p) -> None:
    p.add_argument("dir", metavar="DIR", help="output directory of 'recon3d run'")


def command(args) -> int:
    from recon3d.viz import blocks, plot  # lazy: trimesh and the records; --help needs none

    path = Path(args.dir)
    vtm = path / "scene.vtm" if path.is_dir() else path
    if not vtm.is_file():
        raise InputError(f"no scene.vtm in {path} (write one with 'recon3d run ... --out DIR')")
    if not plot.has_display():
        display = os.environ.get("DISPLAY")
        why = f"DISPLAY {display} cannot be opened" if display else "DISPLAY is not set"
        raise InputError(f"no display to open a window ({why}); look at "
                         f"{vtm.parent / 'coverage.png'} or open {vtm} in ParaView")
    try:
        scene = blocks.read_scene(vtm)
    except ValueError as exc:
        raise InputError(str(exc)) from None
    plot.coverage_plotter(scene, title=vtm.parent.name, off_screen=False).show()
    return 0
