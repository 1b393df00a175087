"""The parser and ``main`` (subcommands: ``scenes`` here, the others one module each):
one line per error (exit status 2), one line per warning.

Every user error -- an :class:`recon3d.InputError` from the checks or an
argparse error -- ends with one line on stderr and exit status 2; no
traceback. Python warnings print as one line (``recon3d: warning: ...``),
never with a line of source code. A sensing worker that died is one line and
exit status 1; SIGINT, SIGTERM and SIGHUP one line and 128 + the signal
(:mod:`recon3d.cli.signals`); a closed stdout (``| head``) nothing and 141.

Building the parser loads no mesh, sensing or plotting library (``recon3d --help`` and
``recon3d run --help`` answer at once): each subcommand imports what it runs inside its
``command``.
"""
from __future__ import annotations

import argparse
import atexit
import os
import re
import sys
import warnings

from recon3d.checks import InputError
from recon3d.cli import batch, bench, figure, run, show
from recon3d.cli.printing import warn
from recon3d.cli.signals import closed_stdout, exit_status, interrupted_line, interrupts
from recon3d.config import package_version

__all__ = ["main", "entry", "end", "build_parser"]

_NEGATIVE_AXIS = re.compile(r"^-[^-]")


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors (InputError) instead of usage + error lines."""

    def error(self, message):
        # main prints "recon3d: error: "; a subcommand's messages name it ("run: ...")
        where = self.prog.removeprefix("recon3d").strip()
        raise InputError(f"{where + ': ' if where else ''}{message} (see '{self.prog} --help')")


def _show_warning(message, category, filename, lineno, file=None, line=None):
    warn(message)


def _cmd_scenes(args: argparse.Namespace) -> int:
    import meshes  # lazy: the scenes load trimesh and manifold3d; the parser needs neither

    for name in meshes.names():
        print(f"{name}\t{meshes.describe(name)}")
    return 0


def _description(module) -> str | None:
    """A subcommand's description: the second paragraph of its module doc (None under -OO)."""
    parts = (module.__doc__ or "").split("\n\n")
    return " ".join(parts[1].split()) if len(parts) > 1 else None


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="recon3d",
        description="Slice-based pulling-motion tactile sensing of 3D meshes "
        "(Kaneko & Tsuji, WAFR 2000, extended to 3D).",
    )
    parser.add_argument("--version", action="version", version=f"recon3d {package_version()}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    p = sub.add_parser("scenes", help="list built-in scenes as NAME<TAB>description")
    p.set_defaults(func=_cmd_scenes)
    for name, cmd in (("run", run), ("batch", batch), ("show", show), ("figure", figure),
                      ("bench", bench)):
        p = sub.add_parser(name, help=cmd.HELP, description=_description(cmd))
        cmd.add_arguments(p)
        p.set_defaults(func=cmd.command)
    return parser


def join_axis_values(argv: list[str]) -> list[str]:
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
    """Run the command line on ``argv`` (default ``sys.argv[1:]``); the exit status."""
    argv = join_axis_values(list(sys.argv[1:] if argv is None else argv))
    parser = build_parser()
    with warnings.catch_warnings(), interrupts():  # SIGTERM/SIGHUP like SIGINT (.signals)
        warnings.showwarning = _show_warning
        try:
            args = parser.parse_args(argv)
            status = int(args.func(args) or 0)
            sys.stdout.flush()  # a closed stdout shows here, not in the flush at exit
            return status
        except InputError as exc:
            print(f"recon3d: error: {exc}", file=sys.stderr)
            return 2
        # -- processes: a worker that died (not the user's input), a signal, stdout closed
        except RuntimeError as exc:
            from recon3d.api import WorkerDied  # lazy: loaded by the run that raised it

            if not isinstance(exc, WorkerDied):
                raise
            print(f"recon3d: error: {exc}", file=sys.stderr)
            return 1
        except KeyboardInterrupt as exc:  # SIGINT, SIGTERM, SIGHUP
            print(interrupted_line(exc), file=sys.stderr)
            return exit_status(exc)
        except BrokenPipeError:
            return closed_stdout()


def entry() -> None:
    """The ``recon3d`` console script and ``python -m recon3d``: :func:`main`, then
    :func:`end`."""
    end(main())


def end(status: int) -> None:
    """End the process with ``status`` without the interpreter's teardown.

    By the time :func:`main` returns every file is written and closed and every child
    process joined; what is left is freeing the run's meshes, VTK objects and numba's
    modules one by one, which took 0.8 - 1.3 s of a 7 - 11 s ``recon3d run`` (measured on
    ``fig18_overhangs``). The exit handlers (:mod:`atexit`: multiprocessing's, logging's,
    temporary directories') still run, and the standard streams are flushed; only the
    module teardown is skipped. Code that calls :func:`main` itself (the tests) keeps the
    ordinary exit.
    """
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # a closed pipe: main has said so already
            pass
    atexit._run_exitfuncs()
    os._exit(status)
