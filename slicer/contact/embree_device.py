"""The Embree library and this process's Embree devices.

Every slice builds Embree scenes, and a sensing run keeps thousands alive.
An Embree device per scene (what ``embreex`` does when it is given no
device, and what the direct scenes did) crashed the process after a few
hundred live scenes (a segfault in libembree4). So each process has one
device per binding, made on first use and shared by every scene:

* an ``embreex.rtcore.EmbreeDevice`` for the ``EmbreeScene`` of
  :mod:`slicer.contact.embree` (``embreex`` takes a device argument);
* a device on the C API (:func:`device`) for the scenes of
  :mod:`slicer.contact.embree_direct`. ``embreex`` does not expose its
  device's handle, so the two bindings cannot share one.

:class:`PerProcess` tracks the process id: a forked child makes its own
device and never uses or releases its parent's. The C-API device is
released at interpreter exit; Embree keeps a device alive while any scene
made on it lives, so scenes may outlive that release. Every C-API call that
can fail is checked (:func:`check`): a failure raises a RuntimeError that
names the call and Embree's error.

The library is the one ``embreex`` ships (``embreex.libs``) or one on the
loader path; :func:`library` is None when neither loads.

Examples
--------
>>> shared = PerProcess(object)
>>> shared.get() is shared.get()
True
>>> bool(device().handle) if library() else True
True
"""
from __future__ import annotations

import ctypes
import ctypes.util
import functools
import glob
import os
import threading
import weakref

__all__ = ["library", "check", "device", "PerProcess"]

_ERRORS = ("RTC_ERROR_NONE", "RTC_ERROR_UNKNOWN", "RTC_ERROR_INVALID_ARGUMENT",
           "RTC_ERROR_INVALID_OPERATION", "RTC_ERROR_OUT_OF_MEMORY",
           "RTC_ERROR_UNSUPPORTED_CPU", "RTC_ERROR_CANCELLED")


class PerProcess:
    """One object per process, made by ``make()`` on first use.

    A forked child calling :meth:`get` makes its own object; the parent's
    is kept referenced (never dropped, so never released, in the child).

    Parameters
    ----------
    make : callable
        Makes the object (no arguments).
    """

    def __init__(self, make):
        self._make = make
        self._pid = None
        self._obj = None
        self._inherited = []
        self._lock = threading.Lock()

    def get(self):
        """This process's object."""
        pid = os.getpid()
        if self._pid != pid:
            with self._lock:
                if self._pid != pid:
                    if self._obj is not None:
                        self._inherited.append(self._obj)
                    self._obj = self._make()
                    self._pid = pid
        return self._obj


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
def library():
    """The loaded Embree library (ctypes) or None; also made visible to
    numba's linker, so compiled code finds ``rtcIntersect1``."""
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


def check(handle: int, call: str, result: int = 1) -> int:
    """``result`` of the Embree ``call`` on device ``handle``, checked.

    Parameters
    ----------
    handle : int
        The device (0 for ``rtcNewDevice`` itself).
    call : str
        The call's name, for the message.
    result : int
        What the call returned; 0 (a NULL handle or pointer) is a failure.

    Returns
    -------
    int
        ``result``.

    Raises
    ------
    RuntimeError
        When Embree reports an error on the device or ``result`` is 0.
    """
    code = library().rtcGetDeviceError(handle)
    if code or not result:
        name = _ERRORS[code] if 0 <= code < len(_ERRORS) else f"error {code}"
        raise RuntimeError(f"Embree {call} failed ({name})")
    return result


class _Device:
    """A C-API Embree device, released at exit by the process that made it."""

    def __init__(self):
        lib = library()
        if lib is None:
            raise RuntimeError("no Embree 4 library could be loaded")
        self.handle = check(0, "rtcNewDevice", lib.rtcNewDevice(None))
        self._release = weakref.finalize(self, _release_device, lib, self.handle, os.getpid())


def _release_device(lib, handle, pid) -> None:
    if os.getpid() == pid:
        lib.rtcReleaseDevice(handle)


_DEVICE = PerProcess(_Device)


def device() -> _Device:
    """This process's C-API device (``.handle``), made on first use."""
    return _DEVICE.get()
