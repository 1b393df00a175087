"""The command line: ``recon3d scenes | run | show | batch | bench`` (:func:`main`).

Nothing in recon3d imports this package (``recon3d/__main__.py`` and the
``recon3d`` console script aside): the subcommands (:mod:`.run`,
:mod:`.batch`, :mod:`.bench`) call the rooms, and the error they report
as one line is :class:`recon3d.InputError`, raised outside.
"""
from recon3d.cli.main import entry, main

__all__ = ["main", "entry"]
