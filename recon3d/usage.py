"""What the command line tells the user: one-line errors and warnings.

Kept apart from :mod:`recon3d.cli` so that the subcommand modules
(``run_cmd``, ``batch_cmd``, ``bench_cmd``) can raise and warn without
importing the parser that imports them.
"""
from __future__ import annotations

import sys

__all__ = ["UsageError", "warn"]


class UsageError(Exception):
    """Bad input from the user: reported as one line, exit status 2."""


def warn(message: str) -> None:
    """Print one warning line on stderr (``recon3d: warning: ...``).

    >>> warn("a coarse eps")  # doctest: +SKIP
    """
    print(f"recon3d: warning: {' '.join(str(message).split())}", file=sys.stderr)
