"""How the run parameters and the numbers of a run are spelled.

Numbers: :func:`number` is the one formatter of every number a run prints or
draws (the summary, ``repr(Result)``, coverage.png): no negative zero, ``n/a``
for a missing value.

Parameters, from :data:`recon3d.config.PARAMS`:

The keywords of :func:`recon3d.run` (:func:`make_config`, :func:`run_signature`,
:func:`numpydoc_params`), the ``[params]`` keys of a batch manifest
(:func:`batch_keys`, :func:`manifest_doc`) and the README's options table
(:func:`options_table`) are all rendered here from the one table of
:class:`recon3d.config.Param`.

>>> make_config(slices=4, axis=["z", "x"]).axes
('z', 'x')
>>> "eps_share" in batch_keys() and "jobs" not in batch_keys()
True
"""
from __future__ import annotations

import dataclasses
import inspect

from recon3d.config import PARAMS, RunConfig

__all__ = ["number", "percent", "BATCH_ONLY", "batch_keys", "make_config", "keyword_defaults", "run_signature",
           "options_table", "numpydoc_params", "manifest_doc"]

_BY_KEY = {p.key: p for p in PARAMS}


def number(x, spec: str = ".3f") -> str:
    """``x`` formatted with ``spec``; a value that rounds to zero never shows a minus sign.

    >>> number(-0.0000004), number(-0.0004, "+.3f"), number(None), number(0.25, "+.3f")
    ('0.000', '+0.000', 'n/a', '+0.250')
    """
    if x is None:
        return "n/a"
    text = format(x, spec)
    if text.startswith("-") and float(text.rstrip("%")) == 0.0:  # rounds to -0
        text = format(0.0, spec)
    return text


def percent(share, digits: int = 0) -> str:
    """A share in [0, 1] as a percentage (no negative zero).

    >>> percent(0.6666), percent(None), percent(-1e-9, 1)
    ('67%', 'n/a', '0.0%')
    """
    return "n/a" if share is None else number(100.0 * share, f".{digits}f") + "%"
BATCH_ONLY = {"eps_share": ("eps", "eps as a share of the mesh diagonal (instead of eps in "
                                   "mesh units)")}
"""Manifest keys that are not run parameters: key -> (the parameter it sets, meaning)."""


def batch_keys() -> tuple[str, ...]:
    """The keys of a manifest's ``[params]``: the run parameters (not jobs) and eps_share."""
    out = []
    for p in PARAMS:
        if p.batch:
            out.append(p.key)
            out += [k for k, (target, _) in BATCH_ONLY.items() if target == p.key]
    return tuple(out)


def make_config(**params) -> RunConfig:
    """A :class:`RunConfig` from :func:`recon3d.run`'s keywords (converted, not yet checked)."""
    kw = {}
    for key, value in params.items():
        p = _BY_KEY.get(key)
        if p is None:
            raise TypeError(f"run() got an unexpected keyword argument {key!r}")
        kw[p.name] = p.convert(value) if p.convert is not None else value
    return RunConfig(**kw)


def keyword_defaults() -> dict:
    """The defaults of :func:`recon3d.run`'s keywords: key -> value."""
    fields = {f.name: f.default for f in dataclasses.fields(RunConfig)}
    return {p.key: fields[p.name] if p.keyword_default is None else p.keyword_default
            for p in PARAMS}


def run_signature(first=(), last=()) -> inspect.Signature:
    """The signature of :func:`recon3d.run`: ``first``, the parameters (keyword-only), ``last``."""
    types = {f.name: f.type for f in dataclasses.fields(RunConfig)}
    kw = [inspect.Parameter(k, inspect.Parameter.KEYWORD_ONLY, default=v, annotation=(
        _BY_KEY[k].keyword_type or types[_BY_KEY[k].name])) for k, v in keyword_defaults().items()]
    return inspect.Signature([*first, *kw, *last])


def options_table(extra=()) -> list[str]:
    """The README's table of ``recon3d run`` options (Markdown lines).

    extra : list of (option, meaning) -- flags of the command that are not
        run parameters (``--no-png``, ``--quiet``), appended with no default.
    """
    rows = []
    for p in PARAMS:
        for row in p.doc:
            if isinstance(row, str):  # the flag with its metavar, and the default
                rows.append((f"`{f'{p.flag} {p.metavar}'.strip()}`", p.shown_default, row))
            else:  # (a value of the flag spelled out, meaning)
                rows.append((f"`{p.flag} {row[0]}`", "", row[1]))
    rows += [(option, "", meaning) for option, meaning in extra]
    return ["| option | default | meaning |", "|---|---|---|"] + [
        f"| {option} | {default + ' ' if default else ''}| {meaning} |"
        for option, default, meaning in rows]


def numpydoc_params() -> str:
    """The run parameters as a numpydoc ``Parameters`` block (for :func:`recon3d.run`)."""
    types = {f.name: f.type for f in dataclasses.fields(RunConfig)}
    defaults = keyword_defaults()
    return "\n".join(f"{p.key} : {p.keyword_type or types[p.name]}, default "
                     f"{defaults[p.key]!r}\n    {p.help}." for p in PARAMS)


def manifest_doc() -> str:
    """The ``[params]`` keys of a batch manifest, in a sentence (``recon3d batch --help``)."""
    extra = "; ".join(f"{k}: {meaning}" for k, (_, meaning) in BATCH_ONLY.items())
    return (f"[params] keys: {', '.join(batch_keys())} (the keywords of recon3d.run but jobs; "
            f"{extra}).")
