"""One in-plane ray at a time on Embree's C API, callable from compiled code.

:class:`slicer.contact.embree.EmbreeContact` answers batches through
``embreex``: about 1 us of Python and numpy per call however few its rays.
A probe motion resolves a contact by bisection, fan after fan of ~16 rays,
so that per-call cost, not Embree, was most of the sensing time. This module
gives the probe simulator's compiled kernels (:mod:`core2d.sim.kernels`) a
*ray function* instead: a C-callable function (numba ``cfunc``)

    ray(ctx, ox, oy, dx, dy, max_dist, out) -> None

that casts the 2D ray with ``rtcIntersect1`` on a scene of its own and
writes ``out[:3] = distance, x, y`` (``inf, nan, nan`` for a miss), with the
same float64 refinement against the hit triangle's section segment as the
batched path (:func:`slicer.contact.refine.segment_hit`).

The scene is built as ``embreex`` builds its own (robust traversal, high
build quality, un-indexed float32 triangles, the same float32 rays with
``tnear = 0``), so both give the same primitive for every ray: the compiled
path is the batched path without the Python between the rays (tested ray
for ray, ``tests/test_slicer_embree_direct.py``).

The library and the device come from :mod:`slicer.contact.embree_device`:
one device per process for every direct scene, and every Embree call that
can fail checked (a RuntimeError naming the call). :func:`available` is
False when no Embree 4 library loads, and callers keep to
``EmbreeContact.cast``.

Examples
--------
>>> import ctypes, trimesh
>>> from slicer.contact.embree import EmbreeContact
>>> from slicer.planes import make_planes
>>> box = trimesh.creation.box(extents=[2.0, 2.0, 2.0])
>>> contact = EmbreeContact(box, make_planes(box, "z", offsets=[0.3])[0])
>>> address, context = contact.ray_kernel
>>> ray = ctypes.CFUNCTYPE(None, ctypes.c_void_p, *[ctypes.c_double] * 5,
...                        ctypes.c_void_p)(address)
>>> out = np.zeros(3)
>>> ray(context.ctypes.data, -3.0, 0.5, 1.0, 0.0, 10.0, out.ctypes.data)
>>> out.tolist()  # as contact.cast([[-3.0, 0.5]], [[1.0, 0.0]], 10.0)
[2.0, -1.0, 0.5]
"""
from __future__ import annotations

import ctypes
import functools
import os
import weakref

import numba
import numpy as np
from numba import types

from slicer.contact.embree_device import check, device, library
from slicer.contact.refine import segment_hit

__all__ = ["available", "DirectScene", "ray_function"]

_ROBUST = 1 << 2  # RTC_SCENE_FLAG_ROBUST
_BUILD_HIGH = 2  # RTC_BUILD_QUALITY_HIGH
_TRIANGLE = 0  # RTC_GEOMETRY_TYPE_TRIANGLE
_INDEX, _VERTEX = 0, 1  # RTC_BUFFER_TYPE_*
_UINT3, _FLOAT3 = 0x5003, 0x9003  # RTC_FORMAT_*
_INVALID_ID = 0xFFFFFFFF  # RTC_INVALID_GEOMETRY_ID
_HEAD = 8  # int64 words before the ray-hit record: scene, segments, offsets
_RAYHIT = 16  # float64 words kept for one RTCRayHit (80-96 bytes, 16-aligned)


def available() -> bool:
    """Can this process build direct scenes (an Embree 4 library loads)?"""
    return library() is not None


class DirectScene:
    """An Embree scene of float32 triangles and the context of its ray function.

    Parameters
    ----------
    triangles : (k, 3, 3) float32
        Scene triangles in the plane frame (``EmbreeContact.triangles``).
    table : (k, 6) float
        Per triangle its section segment ``(ax, ay, ex, ey, nx, ny)``.

    Attributes
    ----------
    context : (m,) float
        What :func:`ray_function` reads: the scene handle, the ray-hit record
        (one: a scene serves one thread) and the segment table. Pass
        ``context.ctypes.data``. The Embree scene is released with this
        object (by the process that made it), so keep it alive while the
        context is used.
    """

    def __init__(self, triangles, table):
        lib = library()
        if lib is None:
            raise RuntimeError("no Embree 4 library could be loaded")
        tri = np.ascontiguousarray(triangles, dtype=np.float32).reshape(-1, 3, 3)
        n = len(tri)
        dev = device().handle
        scene = check(dev, "rtcNewScene", lib.rtcNewScene(dev))
        self._release = weakref.finalize(self, _release, lib, scene, os.getpid())
        lib.rtcSetSceneFlags(scene, _ROBUST)
        check(dev, "rtcSetSceneFlags")
        lib.rtcSetSceneBuildQuality(scene, _BUILD_HIGH)
        check(dev, "rtcSetSceneBuildQuality")
        if n:
            geom = check(dev, "rtcNewGeometry", lib.rtcNewGeometry(dev, _TRIANGLE))
            try:
                _fill(lib, dev, geom, tri)
                lib.rtcCommitGeometry(geom)
                check(dev, "rtcCommitGeometry")
                check(dev, "rtcAttachGeometry", lib.rtcAttachGeometry(scene, geom) != _INVALID_ID)
            finally:
                lib.rtcReleaseGeometry(geom)
        lib.rtcCommitScene(scene)
        check(dev, "rtcCommitScene")
        # header | pad to 64 bytes | ray-hit record | segment table
        buf = np.zeros(_HEAD + 8 + _RAYHIT + 6 * n)
        pad = (-(buf.ctypes.data + 8 * _HEAD) % 64) // 8
        head = buf[:_HEAD].view(np.int64)
        head[0], head[1] = scene, n
        head[2] = _HEAD + pad
        head[3] = _HEAD + pad + _RAYHIT
        buf[head[3]:head[3] + 6 * n] = np.asarray(table, dtype=np.float64).reshape(-1)
        self.context = buf


def _fill(lib, dev, geom, tri) -> None:
    """Vertex and index buffers of ``geom``: the (k, 3, 3) triangles ``tri``
    un-indexed, as embreex builds them."""
    n = len(tri)
    vert = check(dev, "rtcSetNewGeometryBuffer",
                 lib.rtcSetNewGeometryBuffer(geom, _VERTEX, 0, _FLOAT3, 16, 3 * n))
    v = np.ctypeslib.as_array((ctypes.c_float * (12 * n)).from_address(vert))
    v.reshape(3 * n, 4)[:, :3] = tri.reshape(-1, 3)
    index = check(dev, "rtcSetNewGeometryBuffer",
                  lib.rtcSetNewGeometryBuffer(geom, _INDEX, 0, _UINT3, 12, n))
    np.ctypeslib.as_array((ctypes.c_uint * (3 * n)).from_address(index))[:] = (
        np.arange(3 * n, dtype=np.uint32))


def _release(lib, scene, pid) -> None:
    """Release a scene in the process that made it (a forked child leaves
    its parent's scenes alone)."""
    if os.getpid() == pid:
        lib.rtcReleaseScene(scene)


def _intersect():
    """``rtcIntersect1(scene, rayhit, args)`` for compiled code (pointers as
    64-bit integers; resolved by name once
    :func:`slicer.contact.embree_device.library` loaded it)."""
    return types.ExternalFunction("rtcIntersect1",
                                  types.void(types.int64, types.int64, types.int64))


_rtc_intersect1 = _intersect()
_SIGNATURE = types.void(types.voidptr, types.float64, types.float64, types.float64,
                        types.float64, types.float64, types.CPointer(types.float64))


def _ray(ctx, ox, oy, dx, dy, max_dist, out):  # pragma: no cover - compiled
    head = numba.carray(ctx, _HEAD, np.int64)
    n, rec, tab = head[1], head[2], head[3]
    mem = numba.carray(ctx, tab + 6 * n, np.float64)
    hit = mem[rec:rec + _RAYHIT]
    f, u = hit.view(np.float32), hit.view(np.uint32)
    f[0], f[1], f[2], f[3] = ox, oy, 0.0, 0.0  # org, tnear
    f[4], f[5], f[6], f[7] = dx, dy, 0.0, 0.0  # dir, time
    f[8] = np.float32(1e37)  # tfar, as embreex
    u[9], u[10], u[11] = 0xFFFFFFFF, 0, 0  # mask, id, flags
    for k in range(12, 17):
        f[k] = 0.0  # Ng, u, v
    for k in range(17, 24):
        u[k] = 0xFFFFFFFF  # primID, geomID, instID, instPrimID: invalid
    _rtc_intersect1(head[0], hit.ctypes.data, 0)
    prim = np.int32(u[17])
    s, px, py = np.inf, np.nan, np.nan
    if prim >= 0:
        table = mem[tab:].reshape((n, 6))
        s, px, py, _, _ = segment_hit(table, prim, ox, oy, dx, dy, max_dist)
    out[0], out[1], out[2] = s, px, py


def _compile():
    """The ray function's address, or 0 without an Embree library."""
    if library() is None:
        return 0
    return numba.cfunc(_SIGNATURE, nopython=True, cache=True, nogil=True)(_ray).address


@functools.lru_cache(maxsize=1)
def ray_function() -> int:
    """Address of the compiled ray function (0 when Embree cannot be loaded)."""
    return _compile()

