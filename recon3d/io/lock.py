"""Claim an output directory for one run: a second run into it is refused.

``with OutputLock(out, "--out"):`` creates ``out`` if it is missing, then
holds ``flock(LOCK_EX | LOCK_NB)`` on the directory's own file descriptor
until the block ends: no lock file, nothing left behind, and the kernel
drops the lock when the process dies however it dies. A second claim --
another ``recon3d run`` or ``batch`` -- fails at once with
:class:`recon3d.InputError` ("... is in use by another recon3d run").

What a claim may remove: when the block ends in an exception (an error, an
interrupt) the directories this claim created are removed again -- ``out``
and its new parents, the parents only when empty; an existing directory is
left as it was (the staged writer, :mod:`recon3d.io.staged`, has already
removed what it was writing). A refused claim removes nothing, not even a
directory it created: the run holding the lock may have taken it over.

Where ``flock`` does not exist (Windows) the claim only creates and removes.

>>> import tempfile, pathlib
>>> out = pathlib.Path(tempfile.mkdtemp()) / "new"
>>> with OutputLock(out):  # doctest: +ELLIPSIS
...     with OutputLock(out):
...         pass
Traceback (most recent call last):
recon3d.checks.InputError: out ... is in use by another recon3d run ...
>>> out.exists()
False
"""
from __future__ import annotations

import os
import shutil
from pathlib import Path

from recon3d.checks import InputError

try:
    import fcntl
except ImportError:  # pragma: no cover - Windows: no flock
    fcntl = None

__all__ = ["OutputLock"]

_ATTEMPTS = 5


class OutputLock:
    """``with OutputLock(out, name):`` hold ``out`` (created if missing) for this run.

    Parameters
    ----------
    out : path -- the output directory.
    name : str -- how the caller spells it in a message (``--out``, ``out``).

    Raises
    ------
    InputError -- on enter, when another run holds ``out``.
    """

    def __init__(self, out, name: str = "out"):
        self.out = Path(out)
        self.name = name
        self._fd: int | None = None
        self._created: list[Path] = []  # directories this claim made, deepest last

    def __enter__(self) -> Path:
        self._make()
        try:
            self._lock()
        except BaseException:
            self._created = []  # refused: remove nothing (see the module doc)
            raise
        return self.out

    def __exit__(self, kind, value, tb) -> bool:
        try:
            if kind is not None:
                self._remove_created()
        finally:
            if self._fd is not None:
                os.close(self._fd)  # releases the lock
                self._fd = None
        return False

    def _make(self) -> None:
        missing = []
        p = self.out.absolute()
        while not p.exists():
            missing.append(p)
            p = p.parent
        for d in reversed(missing):
            try:
                os.mkdir(d, 0o755)
            except FileExistsError:  # made by someone else meanwhile: not ours
                continue
            os.chmod(d, 0o755)
            self._created.append(d)

    def _lock(self) -> None:
        """flock the directory; again if it was replaced meanwhile (a removed one's lock
        is worthless)."""
        for _ in range(_ATTEMPTS):
            fd = os.open(self.out, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
            if fcntl is None:  # pragma: no cover
                self._fd = fd
                return
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                os.close(fd)
                raise InputError(f"{self.name} {self.out} is in use by another recon3d run "
                                 f"(wait for it to end, or choose another {self.name})") from None
            try:
                now = os.stat(self.out)
            except FileNotFoundError:
                now = None
            held = os.fstat(fd)
            if now is not None and (now.st_dev, now.st_ino) == (held.st_dev, held.st_ino):
                self._fd = fd
                return
            os.close(fd)
            self._make()
        raise InputError(f"{self.name} {self.out} keeps being replaced by another process")

    def _remove_created(self) -> None:
        out = self.out.absolute()
        if out in self._created:
            shutil.rmtree(out, ignore_errors=True)
        for d in reversed(self._created):  # new parents: only when empty
            if d != out:
                try:
                    os.rmdir(d)
                except OSError:
                    break
