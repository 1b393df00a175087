"""Command line: ``recon3d scenes | run | bench``.

Every user error ends with one line on stderr and exit status 2; no traceback.
"""
from __future__ import annotations

import argparse
import sys

__all__ = ["main", "UsageError"]


class UsageError(Exception):
    """Bad input from the user: reported as one line, exit status 2."""


def _cmd_scenes(args: argparse.Namespace) -> int:
    import meshes

    for name in meshes.names():
        print(f"{name}\t{meshes.describe(name)}")
    return 0


def _not_yet(what: str):
    def run(args: argparse.Namespace) -> int:
        raise UsageError(f"'recon3d {what}' is not available yet in this version")

    return run


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="recon3d",
        description="Slice-based pulling-motion tactile sensing of 3D meshes "
        "(Kaneko & Tsuji, WAFR 2000, extended to 3D).",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    p = sub.add_parser("scenes", help="list built-in scenes as NAME<TAB>description")
    p.set_defaults(func=_cmd_scenes)
    p = sub.add_parser("bench", help="benchmarks (not yet)")
    p.set_defaults(func=_not_yet("bench"))
    from recon3d.run_cmd import add_run_parser

    add_run_parser(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
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
