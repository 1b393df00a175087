"""Command line: ``recon3d scenes | run | show | batch | bench``.

Every user error ends with one line on stderr and exit status 2; no
traceback. Python warnings print as one line (``recon3d: warning: ...``),
never with a line of source code.
"""
from __future__ import annotations

import argparse
import re
import sys
import warnings

from recon3d.usage import UsageError, warn

__all__ = ["main", "UsageError", "warn", "build_parser"]

_NEGATIVE_AXIS = re.compile(r"^-[^-]")


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors (UsageError) instead of usage + error lines."""

    def error(self, message):
        raise UsageError(f"{self.prog}: {message} (see '{self.prog} --help')")


def _show_warning(message, category, filename, lineno, file=None, line=None):
    warn(message)


def _cmd_scenes(args: argparse.Namespace) -> int:
    import meshes

    for name in meshes.names():
        print(f"{name}\t{meshes.describe(name)}")
    return 0


def _cmd_show(args: argparse.Namespace) -> int:
    from pathlib import Path

    from recon3d.plot import coverage_plotter, has_display
    from recon3d.scene import read_scene

    path = Path(args.dir)
    vtm = path / "scene.vtm" if path.is_dir() else path
    if not vtm.is_file():
        raise UsageError(f"no scene.vtm in {path} (write one with 'recon3d run ... --out DIR')")
    if not has_display():
        raise UsageError(f"no display to open a window (DISPLAY is not set); look at "
                         f"{vtm.parent / 'coverage.png'} or open {vtm} in ParaView")
    try:
        blocks = read_scene(vtm)
    except ValueError as exc:
        raise UsageError(str(exc)) from None
    coverage_plotter(blocks, title=vtm.parent.name, off_screen=False).show()
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="recon3d",
        description="Slice-based pulling-motion tactile sensing of 3D meshes "
        "(Kaneko & Tsuji, WAFR 2000, extended to 3D).",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    p = sub.add_parser("scenes", help="list built-in scenes as NAME<TAB>description")
    p.set_defaults(func=_cmd_scenes)
    from recon3d.run_cmd import add_run_parser

    add_run_parser(sub)
    from recon3d.batch_cmd import add_batch_parser

    add_batch_parser(sub)
    p = sub.add_parser("show", help="open a run's scene in an interactive pyvista window",
                       description="Open DIR/scene.vtm (written by 'recon3d run') in an "
                       "interactive window with the two coverage panels; needs a display.")
    p.add_argument("dir", metavar="DIR", help="output directory of 'recon3d run'")
    p.set_defaults(func=_cmd_show)
    from recon3d.bench_cmd import add_bench_parser

    add_bench_parser(sub)
    return parser


def _join_axis_values(argv: list[str]) -> list[str]:
    """``--axis -1,0,0`` -> ``--axis=-1,0,0`` (argparse takes ``-1,0,0`` for an option)."""
    out, i = [], 0
    while i < len(argv):
        if argv[i] == "--axis" and i + 1 < len(argv) and _NEGATIVE_AXIS.match(argv[i + 1]):
            out.append(f"--axis={argv[i + 1]}")
            i += 2
        else:
            out.append(argv[i])
            i += 1
    return out


def main(argv: list[str] | None = None) -> int:
    argv = _join_axis_values(list(sys.argv[1:] if argv is None else argv))
    parser = build_parser()
    with warnings.catch_warnings():
        warnings.showwarning = _show_warning
        try:
            args = parser.parse_args(argv)
            return int(args.func(args) or 0)
        except UsageError as exc:
            print(f"recon3d: error: {exc}", file=sys.stderr)
            return 2
        except KeyboardInterrupt:
            print("recon3d: interrupted", file=sys.stderr)
            return 130


if __name__ == "__main__":
    sys.exit(main())
