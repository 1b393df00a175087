"""One Embree device per process (slicer.contact.embree_device).

A device per scene crashed a process after about 500 live slice scenes;
now thousands live on one shared device, a forked child makes its own, and
an Embree failure is a RuntimeError that names the call.
"""
import multiprocessing
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from slicer.contact.embree_device import PerProcess, check, device, library
from slicer.contact.embree_direct import DirectScene, available

pytestmark = pytest.mark.skipif(not available(), reason="no Embree 4 library to call directly")

_MANY_SCENES = textwrap.dedent("""
    import ctypes
    import numpy as np, trimesh
    import slicer

    box = trimesh.creation.box(extents=[2.0, 2.0, 2.0])
    alive = []
    for s in slicer.slice_mesh(box, "z", count=3000):
        contact = s.contact("embree")
        address, context = contact.ray_kernel  # a direct scene too
        alive.append(contact)
        d, p, n = contact.cast(np.array([[-3.0, 0.5]]), np.array([[1.0, 0.0]]), 10.0)
        out = np.zeros(3)
        ray = ctypes.CFUNCTYPE(None, ctypes.c_void_p, *[ctypes.c_double] * 5,
                               ctypes.c_void_p)(address)
        ray(context.ctypes.data, -3.0, 0.5, 1.0, 0.0, 10.0, out.ctypes.data)
        assert d[0] == 2.0 and out.tolist() == [2.0, -1.0, 0.5], (d, out)
    print("ALIVE", len(alive))
""")


def test_three_thousand_live_slice_scenes_in_one_process():
    """Each slice keeps its embreex scene and its direct scene alive (in a
    child process, so a crash fails this test instead of the session)."""
    out = subprocess.run([sys.executable, "-c", _MANY_SCENES], capture_output=True,
                         text=True, timeout=120)
    assert out.returncode == 0, (out.returncode, out.stderr[-2000:])
    assert "ALIVE 3000" in out.stdout


def test_one_device_per_process():
    assert device() is device() and device().handle


def _child_device(queue):
    tri = np.array([[[1.0, -1.0, -1.0], [1.0, 1.0, -1.0], [1.0, 0.0, 1.0]]], np.float32)
    scene = DirectScene(tri, np.array([[1.0, -1.0, 0.0, 2.0, 1.0, 0.0]]))
    queue.put((device().handle, bool(scene.context[0])))


@pytest.mark.skipif("fork" not in multiprocessing.get_all_start_methods(), reason="no fork")
def test_a_forked_child_makes_its_own_device():
    parent = device().handle
    ctx = multiprocessing.get_context("fork")
    queue = ctx.Queue()
    proc = ctx.Process(target=_child_device, args=(queue,))
    proc.start()
    child, built = queue.get(timeout=60)
    proc.join(60)
    assert proc.exitcode == 0 and built
    assert child != parent and device().handle == parent


def test_per_process_remakes_after_a_fork(monkeypatch):
    made = PerProcess(object)
    first = made.get()
    monkeypatch.setattr("os.getpid", lambda: -1)  # as in a forked child
    second = made.get()
    assert second is not first and made.get() is second and made._inherited == [first]


def test_an_embree_failure_names_the_call():
    lib, dev = library(), device().handle
    geom = check(dev, "rtcNewGeometry", lib.rtcNewGeometry(dev, 0))
    try:
        undefined_format = 0
        result = lib.rtcSetNewGeometryBuffer(geom, 1, 0, undefined_format, 16, 3)
        with pytest.raises(RuntimeError, match=r"Embree rtcSetNewGeometryBuffer failed "
                                               r"\(RTC_ERROR_INVALID_OPERATION\)"):
            check(dev, "rtcSetNewGeometryBuffer", result)
    finally:
        lib.rtcReleaseGeometry(geom)
    check(dev, "nothing")  # the error was read once
    with pytest.raises(RuntimeError, match="rtcNewScene failed"):
        check(dev, "rtcNewScene", 0)  # a NULL handle without an error code
