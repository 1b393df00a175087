"""How one run parameter is declared: :class:`Param`, the metadata of a field.

:mod:`recon3d.config` declares every field of ``RunConfig`` with
:func:`param`; the flags, keywords, manifest keys, checks and README rows
all come from it.

>>> from dataclasses import dataclass
>>> @dataclass
... class C:
...     x: int = param(1, help="an x", doc=("an x",), shown_default="1")
>>> C.__dataclass_fields__["x"].metadata["param"].help
'an x'
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

__all__ = ["Param", "param"]


@dataclass(frozen=True)
class Param:
    """How one run parameter is spelled, parsed, checked and documented.

    key : str -- keyword of :func:`recon3d.run` and manifest key (default: the field name).
    flag : str -- CLI flag (default ``--key`` with dashes).
    parse : callable or None -- argparse ``type`` (None: str).
    repeat : bool -- the flag may be repeated (``action='append'``: axis).
    help : str -- argparse help (and the docstring of :func:`recon3d.run`).
    convert : callable(value) -- keyword value -> field value (may raise InputError).
    check : callable(value, name) -- bounds, told the caller's spelling of the name.
    when : callable(RunConfig) -> bool -- whether ``check`` applies (default always).
    choices : tuple, optional -- allowed values (CLI ``choices``).
    metavar : str -- metavar of the README table (``--axis A``).
    shown_default : str -- the README default column.
    doc : tuple -- README rows: a meaning (of ``flag metavar``), or (value, meaning) for
        a value spelled out (``--slices auto``).
    batch : bool -- a ``[params]`` key of batch manifests.
    keyword_default, keyword_type : str, optional -- the default and type as
        :func:`recon3d.run` takes them, where they differ from the field's (axis).
    switch : bool -- an on/off flag (``--force``): no value on the command line.
    """

    help: str
    doc: tuple
    shown_default: str
    parse: Callable | None = None
    key: str = ""
    flag: str = ""
    convert: Callable | None = None
    check: Callable | None = None
    when: Callable | None = None
    choices: tuple | None = None
    repeat: bool = False
    metavar: str = ""
    batch: bool = True
    keyword_default: str | None = None
    keyword_type: str | None = None
    switch: bool = False
    name: str = ""  # the field name (filled in below)


def param(default, **kw) -> Any:
    """A dataclass field carrying ``Param(**kw)`` in its metadata."""
    return field(default=default, metadata={"param": Param(**kw)})
