"""Contact models: the in-plane ray queries of one slice.

Each model answers ``cast(origins, dirs, max_dist)`` (the contract of
:mod:`core2d.sim.contact`); there are three backends:

* ``embree`` -- :mod:`slicer.contact.embree` (``embreex`` batches) and
  :mod:`slicer.contact.embree_direct` (one ray from compiled code on
  Embree's C API), refined in float64 by :mod:`slicer.contact.refine`, on
  one Embree device per process (:mod:`slicer.contact.embree_device`);
* ``trimesh`` -- :mod:`slicer.contact.trimesh_ray`, trimesh's generic ray
  engine, for users without Embree;
* ``exact`` -- :mod:`slicer.contact.exact`, rays against the reference
  contour's segments (the reference of the tests).

The two mesh backends share :mod:`slicer.contact.crossing` (the triangles
crossing the plane). Only the Embree modules import ``embreex``, and only
when :func:`contact_class` is asked for ``'embree'``: the others load
without it.

Examples
--------
>>> contact_class("exact").__name__
'ExactContact'
>>> contact_class("ray")
Traceback (most recent call last):
...
ValueError: backend must be one of ('embree', 'exact', 'trimesh'), got 'ray'
"""
from __future__ import annotations

import importlib

__all__ = ["BACKENDS", "contact_class"]

BACKENDS = ("embree", "exact", "trimesh")
"""The contact backends by name (``Slice.contact(name)``)."""

_CLASSES = {
    "embree": ("slicer.contact.embree", "EmbreeContact"),
    "exact": ("slicer.contact.exact", "ExactContact"),
    "trimesh": ("slicer.contact.trimesh_ray", "TrimeshContact"),
}


def contact_class(backend: str) -> type:
    """The contact model class of a backend, its module imported on first use.

    Parameters
    ----------
    backend : {'embree', 'exact', 'trimesh'}

    Returns
    -------
    type
        ``EmbreeContact`` and ``TrimeshContact`` are built from
        ``(mesh, plane)``, ``ExactContact`` from ``(loops, chains=...)``.

    Raises
    ------
    ValueError
        For an unknown backend name.
    ImportError
        For ``'embree'`` when ``embreex`` is not installed.
    """
    if backend not in _CLASSES:
        raise ValueError(f"backend must be one of {BACKENDS}, got {backend!r}")
    module, name = _CLASSES[backend]
    try:
        return getattr(importlib.import_module(module), name)
    except ModuleNotFoundError as exc:
        if exc.name != "embreex":
            raise
    raise ImportError(f"contact backend {backend!r} needs the 'embreex' package, which "
                      f"is not installed; use 'trimesh' or 'exact'", name="embreex")
