"""The walls of slicer, read from its imports and checked by running it.

* Data flows one way (``meshes -> slicer -> core2d -> recon3d``): slicer
  imports neither core2d nor recon3d.
* Only the Embree modules (``slicer/contact/embree.py``, ``embree_direct.py``
  and ``embree_device.py``) import ``embreex``; the shared
  plane-crossing helper and the exact and trimesh backends import no ray
  engine, and nothing imports the Embree modules at import time.
* So a process without ``embreex`` slices, builds the trimesh backend and
  senses with it; asking for ``'embree'`` there fails with one clear line.
"""
import ast
import pathlib
import subprocess
import sys
import textwrap

from test_core2d_walls import _imports  # module names a file imports (resolved)

SLICER = pathlib.Path(__file__).resolve().parents[1] / "slicer"
EMBREE_MODULES = {"contact/embree.py", "contact/embree_direct.py", "contact/embree_device.py"}
ENGINE_FREE = {"contact/crossing.py", "contact/exact.py", "contact/refine.py"}


def _files():
    files = sorted(SLICER.rglob("*.py"))
    assert len(files) >= 12
    return {path.relative_to(SLICER).as_posix(): set(_imports(path)) for path in files}


def test_slicer_imports_no_later_package():
    for name, mods in _files().items():
        bad = {m for m in mods if m.split(".")[0] in {"core2d", "recon3d"}}
        assert not bad, f"slicer/{name} imports {bad}"


def test_only_the_embree_modules_import_embreex():
    files = _files()
    assert {"contact/trimesh_ray.py"} | ENGINE_FREE | EMBREE_MODULES <= set(files)
    users = {name for name, mods in files.items() if any(m.split(".")[0] == "embreex" for m in mods)}
    assert "contact/embree.py" in users and users <= EMBREE_MODULES, users


def test_the_crossing_helper_and_the_exact_backend_import_no_ray_engine():
    files = _files()
    for name in ENGINE_FREE:
        engines = {m for m in files[name] if m.split(".")[0] in {"embreex", "trimesh"}}
        assert not engines, f"slicer/{name} imports {engines}"


def test_no_module_imports_the_embree_modules_but_each_other():
    embree = {"slicer.contact.embree", "slicer.contact.embree_direct",
              "slicer.contact.embree_device"}
    for name, mods in _files().items():
        if name not in EMBREE_MODULES:
            assert not mods & embree, f"slicer/{name} imports {mods & embree}"


_WITHOUT_EMBREEX = textwrap.dedent("""
    import sys
    sys.modules["embreex"] = None  # as if embreex were not installed
    import numpy as np
    import meshes, slicer
    from core2d import sense_slice

    (s,) = slicer.slice_mesh(meshes.load("fig17_pocket"), "z", count=1)
    contact = s.contact("trimesh")
    rays = np.array([[-1e3, 0.0]]), np.array([[1.0, 0.0]])
    assert np.array_equal(contact.cast(*rays, 1e4)[0], s.contact("exact").cast(*rays, 1e4)[0])
    center, radius = s.bounding_circle()
    eps = s.scale / 15
    res = sense_slice(contact, (center, radius + eps), eps)
    assert res.stats.motions > 100 and res.w1, res.stats
    try:
        s.contact("embree")
    except ImportError as exc:
        print("ERROR", exc)
    print("LOADED", sorted(m for m in sys.modules if m.startswith("slicer")))
""")


def test_trimesh_backend_senses_without_embreex():
    out = subprocess.run([sys.executable, "-c", _WITHOUT_EMBREEX], capture_output=True,
                         text=True, timeout=300, cwd=SLICER.parent)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    error = [line for line in lines if line.startswith("ERROR")]
    assert error == ["ERROR contact backend 'embree' needs the 'embreex' package, which is "
                     "not installed; use 'trimesh' or 'exact'"]
    (loaded,) = [ast.literal_eval(line[7:]) for line in lines if line.startswith("LOADED")]
    assert "slicer.contact.trimesh_ray" in loaded
    assert not {m for m in loaded if m.startswith("slicer.contact.embree")}
