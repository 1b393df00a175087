"""Exceptions and warnings raised by :mod:`meshes`."""
from __future__ import annotations

__all__ = ["MeshError", "MeshWarning", "one_line"]


class MeshError(ValueError):
    """A mesh or scene cannot be provided; the message is one line.

    Raised for an unknown scene name, a missing, empty, unreadable or
    unsupported file, a file without faces, and bad scene parameters.
    """


class MeshWarning(UserWarning):
    """A mesh was loaded but is questionable (e.g. not watertight)."""


def one_line(text: object, limit: int = 200) -> str:
    """Collapse ``str(text)`` to a single line of at most ``limit`` characters.

    Examples
    --------
    >>> one_line("a\\n  b")
    'a b'
    """
    flat = " ".join(str(text).split())
    return flat if len(flat) <= limit else flat[: limit - 3] + "..."
