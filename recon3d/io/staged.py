"""One all-or-nothing writer for every output directory (run, batch, bench).

Every file is first written into a hidden staging directory inside the
output directory, then moved into place with ``os.replace``; on any error
the staging directory is removed, and so is the output directory when this
writer created it. Files are 0644, directories 0755.

>>> import tempfile, pathlib
>>> out = pathlib.Path(tempfile.mkdtemp()) / "new"
>>> with Staged(out) as stage:
...     _ = (stage / "a.txt").write_text("a")
>>> sorted(p.name for p in out.iterdir())
['a.txt']
"""
from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

__all__ = ["Staged"]


def _chmod_tree(path: Path) -> None:
    if path.is_dir():
        os.chmod(path, 0o755)
        for child in path.iterdir():
            _chmod_tree(child)
    else:
        os.chmod(path, 0o644)


class Staged:
    """``with Staged(out) as stage:`` write into ``stage``; on success, move it into ``out``.

    Parameters
    ----------
    out : path -- created if missing (and removed again if writing fails).
    replaces : iterable of str -- names in ``out`` that belong to the same set of
        outputs: removed when this write does not produce them (a stale file
        would not match the new data).

    Attributes
    ----------
    written : list of Path -- after the block: what was moved into ``out`` (sorted).
    """

    def __init__(self, out, replaces=()):
        self.out = Path(out)
        self.replaces = tuple(replaces)
        self.written: list[Path] = []
        self._stage: Path | None = None
        self._top: Path | None = None

    def __enter__(self) -> Path:
        top = self.out.absolute()  # the first directory this writer creates, if any
        while not top.parent.exists():
            top = top.parent
        created = not self.out.exists()
        self.out.mkdir(parents=True, exist_ok=True)
        if created:
            os.chmod(self.out, 0o755)
            self._top = top
        try:
            self._stage = Path(tempfile.mkdtemp(prefix=".recon3d-", dir=self.out))
        except BaseException:
            self._undo()
            raise
        return self._stage

    def __exit__(self, kind, value, tb) -> bool:
        if kind is None:
            try:
                self._commit()
                return False
            except BaseException:
                self._undo()
                raise
        self._undo()
        return False

    def _commit(self) -> None:
        stage, out = self._stage, self.out
        names = sorted(p.name for p in stage.iterdir())
        for name in set(self.replaces) - set(names):
            if (out / name).is_file():
                os.unlink(out / name)
        for name in names:
            _chmod_tree(stage / name)
            target = out / name
            if target.is_dir() and not target.is_symlink():
                shutil.rmtree(target)
            os.replace(stage / name, target)
        stage.rmdir()
        self.written = [out / n for n in names]

    def _undo(self) -> None:
        if self._stage is not None:
            shutil.rmtree(self._stage, ignore_errors=True)
        if self._top is not None:
            shutil.rmtree(self._top, ignore_errors=True)
