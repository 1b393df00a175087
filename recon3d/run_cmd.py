"""``recon3d run`` -- placeholder until the pipeline lands (issue "core2d")."""
from __future__ import annotations

import argparse

__all__ = ["add_run_parser"]


def add_run_parser(sub) -> None:
    p = sub.add_parser("run", help="sense every slice of a mesh (not yet)")
    p.add_argument("input", help="built-in scene name or mesh file")
    p.add_argument("--out", required=True, help="output directory")

    def run(args: argparse.Namespace) -> int:
        from recon3d.cli import UsageError

        raise UsageError("'recon3d run' is not available yet in this version")

    p.set_defaults(func=run)
