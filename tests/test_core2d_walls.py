"""The two walls of DESIGN.md: core2d is pure 2D, and its planner sees sensor
readings only."""
import ast
import re
import pathlib
import sys

import numpy as np

from slicer.exact import ExactContact
from core2d import sense_slice

CORE2D = pathlib.Path(__file__).resolve().parents[1] / "core2d"
FORBIDDEN = {"trimesh", "embreex", "manifold3d", "pyvista", "vtk", "slicer", "meshes", "recon3d"}
SIMULATOR = {"core2d.probe", "core2d.compliance"}
PLANNER = ["planner", "local_search", "tracing", "bootstrap", "areas", "regions"]


def _imports(path):
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            yield from (a.name.split(".")[0] for a in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module:
            yield node.module.split(".")[0]


def test_core2d_imports_no_3d_library():
    files = sorted(CORE2D.glob("*.py"))
    assert len(files) >= 10
    for path in files:
        bad = FORBIDDEN.intersection(_imports(path))
        assert not bad, f"{path.name} imports {bad}"


def test_planner_modules_never_touch_the_contact_model():
    """Only the simulator may call ``cast``; the planner modules never name
    the contact model, the ray fans, or the evaluation modules."""
    for name in PLANNER:
        src = (CORE2D / f"{name}.py").read_text()
        for pattern in (r"probe\.contact\b", r"\.cast\(", r"\._fan\(", r"\._search\(",
                        r"\._cast\(", r"\breachability\b", r"\bmetrics\b", r"\bloops\b"):
            assert not re.search(pattern, src), f"core2d/{name}.py matches {pattern!r}"


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


def test_only_the_simulator_queries_geometry_at_run_time():
    loop = np.array([[0, 0], [100, 0], [100, 50], [60, 50], [50, 20], [40, 50], [0, 50]], float)
    guarded = _Guarded([loop])
    res = sense_slice(guarded, (np.array([50.0, 25.0]), 57.0), eps=1.0)
    assert guarded.callers and guarded.callers <= SIMULATOR
    assert res.w1 and res.stats.pushes == 0
