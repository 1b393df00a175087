"""Registry of built-in scenes: ``@scene`` registers a builder by name.

The only module-level state is :data:`SCENES`, filled once at import time by
the ``@scene`` decorators in the ``scenes_*`` modules and never changed after.
"""
from __future__ import annotations

import difflib
import inspect
from dataclasses import dataclass
from typing import Callable

from manifold3d import Error, Manifold

from .errors import MeshError, one_line

__all__ = ["Scene", "SCENES", "scene", "get", "names", "describe", "build",
           "unknown_scene"]


@dataclass(frozen=True)
class Scene:
    """A registered scene.

    Attributes
    ----------
    name : str
        Registry key (snake_case).
    builder : callable
        ``builder(**kwargs) -> manifold3d.Manifold``; every builder takes a
        ``resolution`` keyword.
    summary : str
        First line of the builder's docstring.
    bodies : int
        Intended number of disconnected bodies.
    """

    name: str
    builder: Callable[..., Manifold]
    summary: str
    bodies: int = 1


SCENES: dict[str, Scene] = {}


def scene(name: str | None = None, *, bodies: int = 1):
    """Decorator registering a scene builder under ``name`` (default: the
    function name). The function is returned unchanged.

    Examples
    --------
    >>> @scene(bodies=1)                                    # doctest: +SKIP
    ... def cube(*, resolution: int = 8):
    ...     '''A 10 mm cube.'''
    ...     return Manifold.cube((10, 10, 10))
    """

    def register(func: Callable[..., Manifold]) -> Callable[..., Manifold]:
        key = name or func.__name__
        doc = inspect.getdoc(func) or ""
        if not doc.strip():
            raise TypeError(f"scene {key!r} needs a docstring")
        if key in SCENES:
            raise TypeError(f"scene {key!r} registered twice")
        if "resolution" not in inspect.signature(func).parameters:
            raise TypeError(f"scene {key!r} needs a 'resolution' keyword")
        SCENES[key] = Scene(key, func, doc.strip().splitlines()[0], bodies)
        return func

    return register


def names() -> list[str]:
    """Sorted names of all registered scenes."""
    return sorted(SCENES)


def get(name: str) -> Scene:
    """The :class:`Scene` called ``name``; :class:`MeshError` (with close
    matches) when there is none."""
    try:
        return SCENES[name]
    except (KeyError, TypeError):
        raise unknown_scene(name) from None


def unknown_scene(name: str) -> MeshError:
    """The :class:`MeshError` for an unknown scene name, naming close
    matches (difflib) or else all scenes."""
    close = difflib.get_close_matches(str(name), list(SCENES), n=3, cutoff=0.5)
    hint = f"did you mean {', '.join(close)}?" if close else \
        f"known scenes: {', '.join(names())}"
    return MeshError(f"unknown scene {name!r} and no such file; {hint}")


def describe(name: str) -> str:
    """First line of the docstring of scene ``name``."""
    return get(name).summary


def build(name: str, **kwargs) -> Manifold:
    """Build scene ``name`` as a :class:`manifold3d.Manifold`.

    Raises
    ------
    MeshError
        Unknown name, unexpected keyword, or a bad parameter value.
    """
    entry = get(name)
    try:
        inspect.signature(entry.builder).bind(**kwargs)
    except TypeError as exc:
        raise MeshError(f"scene {name!r}: {one_line(exc)}") from None
    try:
        solid = entry.builder(**kwargs)
    except MeshError as exc:
        raise MeshError(f"scene {name!r}: {exc}") from None
    except ValueError as exc:
        raise MeshError(f"scene {name!r}: bad parameter: {one_line(exc)}") from None
    if solid.status() != Error.NoError or solid.is_empty():
        raise MeshError(f"scene {name!r}: manifold3d produced an empty solid "
                        f"({solid.status().name}) for {kwargs or 'defaults'}")
    return solid
