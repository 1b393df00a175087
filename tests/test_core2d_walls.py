"""The walls of DESIGN.md, visible in the layout of core2d.

* core2d is pure 2D: no module imports a 3D library or another package.
* Three rooms: ``core2d/sim`` (the simulator, owns the geometry),
  ``core2d/planner`` (the paper's algorithm, sees sensor readings only) and
  ``core2d/truth`` (reachability and metrics against the true contour). The
  planner imports neither of the others; the simulator and the ground truth
  import neither the planner nor each other.
* At run time only the simulator queries the contact model.
* The planner is typed against the probe protocol
  (:class:`core2d.planner.robot.Robot`), which the simulated probe
  implements; it reads none of the simulator's internals and keeps its own
  counters.
"""
import ast
import pathlib
import re
import sys

import numpy as np
import pytest

from slicer.contact.exact import ExactContact
from core2d import sense_slice

CORE2D = pathlib.Path(__file__).resolve().parents[1] / "core2d"
FORBIDDEN = {"trimesh", "embreex", "manifold3d", "pyvista", "vtk", "slicer", "meshes", "recon3d"}
SHARED = {"core2d.planar", "core2d.readings", "core2d.resolution", "core2d.result",
          "core2d.visibility", "core2d.motionlog"}
# room -> core2d modules it may import besides its own room and SHARED
ALLOWED = {"sim": set(), "planner": set(), "truth": set()}
SIMULATOR = {"core2d.sim.search", "core2d.sim.compiled"}  # the ray engines


def _imports(path):
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            yield from (a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:  # relative: resolve against the file's package
                pkg = ".".join(path.relative_to(CORE2D.parent).with_suffix("").parts[:-node.level])
                yield f"{pkg}.{node.module}" if node.module else pkg
            elif node.module:
                yield node.module


def test_core2d_imports_no_3d_library():
    files = sorted(CORE2D.rglob("*.py"))
    assert len(files) >= 15
    for path in files:
        bad = FORBIDDEN.intersection(m.split(".")[0] for m in _imports(path))
        assert not bad, f"{path.relative_to(CORE2D)} imports {bad}"


@pytest.mark.parametrize("room", sorted(ALLOWED))
def test_each_room_imports_only_itself_and_the_shared_modules(room):
    files = sorted((CORE2D / room).glob("*.py"))
    assert files
    for path in files:
        for mod in _imports(path):
            if not mod.startswith("core2d"):
                continue
            ok = mod in SHARED or mod in ALLOWED[room] or mod.startswith(f"core2d.{room}")
            assert ok, f"core2d/{room}/{path.name} imports {mod}"


def test_planner_modules_never_touch_the_contact_model():
    """The planner never names the contact model, the ray fans, or the
    evaluation modules: it commands motions and reads readings."""
    files = sorted((CORE2D / "planner").glob("*.py"))
    for path in files:
        src = path.read_text()
        for pattern in (r"probe\.contact\b", r"\.cast\(", r"\._fan\(", r"\._search\(",
                        r"\._cast\(", r"\bray_kernel\b", r"\bkernels\b", r"\breachability\b",
                        r"\bmetrics\b", r"\bloops\b", r"\.engine\b",
                        # simulator internals and counters: the planner keeps its own
                        r"\bprobe\.(ang_tol|fan_step|tip_zone|stats|eps|tol)\b",
                        r"\b_Run\b"):
            assert not re.search(pattern, src), f"core2d/planner/{path.name} matches {pattern!r}"


def test_the_simulated_probe_implements_the_planner_protocol():
    from core2d.planner.robot import Robot
    from core2d.sim.probe import Probe

    loop = np.array([[0, 0], [10, 0], [10, 5], [0, 5]], float)
    probe = Probe(ExactContact([loop]), (np.array([5.0, 2.5]), 7.0), eps=1.0)
    assert isinstance(probe, Robot)
    missing = {name for name in dir(Robot) if not name.startswith("_")} - set(dir(probe))
    assert not missing


def test_no_compiled_branches_outside_the_engines():
    """The ray engine is chosen once (core2d.sim.engine.make_engine)."""
    for path in sorted((CORE2D / "sim").glob("*.py")):
        src = path.read_text()
        assert "_compiled" not in src, path.name
        if path.name != "compiled.py":  # the compiled engine alone calls the kernels
            assert "core2d.sim.kernels" not in set(_imports(path)), path.name


class _Guarded:
    """A contact model that fails when called from anywhere but the simulator."""

    def __init__(self, loops):
        self.inner = ExactContact(loops)
        self.callers = set()

    def cast(self, origins, dirs, max_dist):
        caller = sys._getframe(1).f_globals["__name__"]
        self.callers.add(caller)
        assert caller in SIMULATOR, f"{caller} queried the geometry directly"
        return self.inner.cast(origins, dirs, max_dist)


@pytest.mark.parametrize("method", ["pulling", "finger"])
def test_only_the_simulator_queries_geometry_at_run_time(method):
    loop = np.array([[0, 0], [100, 0], [100, 50], [60, 50], [50, 20], [40, 50], [0, 50]], float)
    guarded = _Guarded([loop])
    res = sense_slice(guarded, (np.array([50.0, 25.0]), 57.0), eps=1.0, method=method)
    assert guarded.callers and guarded.callers <= SIMULATOR
    assert (res.w1 or res.w2) and res.stats.pushes == 0
