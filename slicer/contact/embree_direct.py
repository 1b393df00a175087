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

The Embree library is the one ``embreex`` ships (``embreex.libs``) or one on
the loader path; :func:`available` is False when neither loads, and callers
keep to ``EmbreeContact.cast``.

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
import ctypes.util
import functools
import glob
import os
import weakref

import numba
import numpy as np
from numba import types

from slicer.contact.refine import segment_hit

__all__ = ["available", "DirectScene", "ray_function"]

_ROBUST = 1 << 2  # RTC_SCENE_FLAG_ROBUST
_BUILD_HIGH = 2  # RTC_BUILD_QUALITY_HIGH
_TRIANGLE = 0  # RTC_GEOMETRY_TYPE_TRIANGLE
_INDEX, _VERTEX = 0, 1  # RTC_BUFFER_TYPE_*
_UINT3, _FLOAT3 = 0x5003, 0x9003  # RTC_FORMAT_*
_HEAD = 8  # int64 words before the ray-hit record: scene, segments, offsets
_RAYHIT = 16  # float64 words kept for one RTCRayHit (80-96 bytes, 16-aligned)


def _library_paths() -> list[str]:
    """Embree 4 shared libraries: the one embreex bundles first."""
    found = []
    try:
        import embreex

        site = os.path.dirname(os.path.dirname(embreex.__file__))
        for sub in ("embreex.libs", ".dylibs", os.path.join("embreex", ".dylibs")):
            found += sorted(glob.glob(os.path.join(site, sub, "*embree4*")))
    except ImportError:  # pragma: no cover - embreex is a dependency
        pass
    name = ctypes.util.find_library("embree4")
    return found + ([name] if name else [])


@functools.lru_cache(maxsize=1)
def _library():
    """The loaded Embree library (ctypes) or None; also made visible to
    numba's linker, so the compiled ray function finds ``rtcIntersect1``."""
    from llvmlite import binding

    for path in _library_paths():
        try:
            lib = ctypes.CDLL(path)
            binding.load_library_permanently(path)
        except (OSError, RuntimeError):
            continue
        size, uint, cint = ctypes.c_size_t, ctypes.c_uint, ctypes.c_int
        for fname, res, args in (
            ("rtcNewDevice", size, [ctypes.c_char_p]), ("rtcReleaseDevice", None, [size]),
            ("rtcNewScene", size, [size]), ("rtcSetSceneFlags", None, [size, cint]),
            ("rtcSetSceneBuildQuality", None, [size, cint]),
            ("rtcNewGeometry", size, [size, cint]),
            ("rtcSetNewGeometryBuffer", size, [size, cint, uint, cint, size, size]),
            ("rtcCommitGeometry", None, [size]), ("rtcAttachGeometry", uint, [size, size]),
            ("rtcReleaseGeometry", None, [size]), ("rtcCommitScene", None, [size]),
            ("rtcReleaseScene", None, [size]), ("rtcGetDeviceError", cint, [size]),
        ):
            fn = getattr(lib, fname)
            fn.restype, fn.argtypes = res, args
        return lib
    return None


def available() -> bool:
    """Can this process build direct scenes (an Embree 4 library loads)?"""
    return _library() is not None


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
        object, so keep it alive while the context is used.
    """

    def __init__(self, triangles, table):
        lib = _library()
        if lib is None:
            raise RuntimeError("no Embree 4 library could be loaded")
        tri = np.ascontiguousarray(triangles, dtype=np.float32).reshape(-1, 3, 3)
        n = len(tri)
        device = lib.rtcNewDevice(None)
        scene = lib.rtcNewScene(device)
        lib.rtcSetSceneFlags(scene, _ROBUST)
        lib.rtcSetSceneBuildQuality(scene, _BUILD_HIGH)
        geom = lib.rtcNewGeometry(device, _TRIANGLE)
        if n:
            vert = lib.rtcSetNewGeometryBuffer(geom, _VERTEX, 0, _FLOAT3, 16, 3 * n)
            v = np.ctypeslib.as_array((ctypes.c_float * (12 * n)).from_address(vert))
            v.reshape(3 * n, 4)[:, :3] = tri.reshape(-1, 3)
            index = lib.rtcSetNewGeometryBuffer(geom, _INDEX, 0, _UINT3, 12, n)
            np.ctypeslib.as_array((ctypes.c_uint * (3 * n)).from_address(index))[:] = (
                np.arange(3 * n, dtype=np.uint32))
            lib.rtcCommitGeometry(geom)
            lib.rtcAttachGeometry(scene, geom)
        lib.rtcReleaseGeometry(geom)
        lib.rtcCommitScene(scene)
        if lib.rtcGetDeviceError(device) != 0:
            raise RuntimeError("Embree could not build the scene")
        self._release = weakref.finalize(self, _release, lib, scene, device)
        # header | pad to 64 bytes | ray-hit record | segment table
        buf = np.zeros(_HEAD + 8 + _RAYHIT + 6 * n)
        pad = (-(buf.ctypes.data + 8 * _HEAD) % 64) // 8
        head = buf[:_HEAD].view(np.int64)
        head[0], head[1] = scene, n
        head[2] = _HEAD + pad
        head[3] = _HEAD + pad + _RAYHIT
        buf[head[3]:head[3] + 6 * n] = np.asarray(table, dtype=np.float64).reshape(-1)
        self.context = buf


def _release(lib, scene, device) -> None:
    lib.rtcReleaseScene(scene)
    lib.rtcReleaseDevice(device)


def _intersect():
    """``rtcIntersect1(scene, rayhit, args)`` for compiled code (pointers as
    64-bit integers; resolved by name once :func:`_library` loaded it)."""
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
    if _library() is None:
        return 0
    return numba.cfunc(_SIGNATURE, nopython=True, cache=True, nogil=True)(_ray).address


@functools.lru_cache(maxsize=1)
def ray_function() -> int:
    """Address of the compiled ray function (0 when Embree cannot be loaded)."""
    return _compile()

