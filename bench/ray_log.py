"""A ray function that logs every ray the compiled engine casts, cast by cast (bench only).

:mod:`bench.sensing_worker` replays the rays of a sensing run on raw
embreex. The compiled engine (:mod:`core2d.sim.kernels`) casts ray by ray
through a contact model's ray function and stops each window at its first
hit, so the rays it casts are not the batches the Python engine would
issue. :class:`RayLog` wraps a ray function in another (a numba ``cfunc``
with the same contract) that calls it and appends ``(ox, oy, dx, dy,
cast)`` to a buffer. Casts are told apart by the engine's cast counter
(``count[0]``, incremented after every window), read through a pointer,
and by a mark the worker sets before every call into the engine
(:meth:`RayLog.new_cast`).

Layout of the context (int64 words, then float64 rows of 5)::

    [inner fn, inner ctx, counter address (0: none), rays, capacity, last tag,
     new-cast mark, cast id] + capacity x (ox, oy, dx, dy, cast id)
"""
from __future__ import annotations

import functools

import numba
import numpy as np
from llvmlite import ir
from numba import types
from numba.extending import intrinsic

from core2d.sim.kernels import _call

__all__ = ["RayLog"]

_HEAD = 8


@intrinsic
def _address(typingctx, ptr):
    """A pointer as a 64-bit integer."""
    def codegen(context, builder, signature, args):
        return builder.ptrtoint(args[0], ir.IntType(64))

    return types.int64(ptr), codegen


_SIGNATURE = types.void(types.voidptr, types.float64, types.float64, types.float64,
                        types.float64, types.float64, types.CPointer(types.float64))


def _logged(ctx, ox, oy, dx, dy, max_dist, out):  # pragma: no cover - compiled
    head = numba.carray(ctx, _HEAD, np.int64)
    _call(head[0], head[1], ox, oy, dx, dy, max_dist, _address(out))
    tag = _counter(head[2]) if head[2] != 0 else -1
    if head[6] != 0 or tag != head[5]:
        head[7] += 1
        head[6], head[5] = 0, tag
    k = head[3]
    if k < head[4]:
        rows = numba.carray(ctx, _HEAD + 5 * head[4], np.float64)
        at = _HEAD + 5 * k
        rows[at], rows[at + 1], rows[at + 2], rows[at + 3] = ox, oy, dx, dy
        rows[at + 4] = head[7]
    head[3] = k + 1


@intrinsic
def _counter(typingctx, addr):
    """The int64 at address ``addr``."""
    def codegen(context, builder, signature, args):
        ptr = builder.inttoptr(args[0], ir.IntType(64).as_pointer())
        return builder.load(ptr)

    return types.int64(types.int64), codegen


class RayLog:
    """A logging ray function around ``(address, context)`` of a contact model.

    capacity : rays kept before :meth:`take` must be called.
    """

    def __init__(self, ray_kernel, capacity: int = 1 << 21):
        self.inner = ray_kernel  # kept alive here
        self.buf = np.zeros(_HEAD + 5 * capacity)
        head = self.head
        head[0], head[1] = int(ray_kernel[0]), int(ray_kernel[1].ctypes.data)
        head[4] = capacity
        self.ray_kernel = (_function(), self.buf)

    @property
    def head(self) -> np.ndarray:
        return self.buf[:_HEAD].view(np.int64)

    def new_cast(self, counter: np.ndarray | None = None) -> None:
        """The next ray starts a cast; ``counter`` (int64 array) is the
        engine's cast counter for the call that follows (None: no counter)."""
        head = self.head
        head[2] = 0 if counter is None else counter.ctypes.data
        head[6] = 1

    def take(self) -> tuple[np.ndarray, np.ndarray]:
        """The rays logged since the last call, as (origins (n, 2), directions
        (n, 2)), and the cast id of each (n,); the log is emptied."""
        head = self.head
        n = int(head[3])
        if n > head[4]:
            raise RuntimeError(f"ray log overflow: {n} rays, capacity {head[4]}")
        rows = self.buf[_HEAD:_HEAD + 5 * n].reshape(n, 5).copy()
        head[3] = 0
        return rows[:, :4], rows[:, 4].astype(np.int64)


@functools.lru_cache(maxsize=1)
def _function() -> int:
    """Address of the logging ray function (compiled once per process)."""
    return numba.cfunc(_SIGNATURE, nopython=True)(_logged).address
