"""The walls of recon3d, visible in its layout (model: test_core2d_walls.py).

* Rooms, each with one job: ``sensing/``, ``surface/``, ``score/``, ``io/``,
  ``viz/``, ``jobs/``, ``cli/``, ``benchmark/``; the shared modules
  ``checks`` <- ``param`` <- ``config`` <- ``spellings`` <- ``records`` import no room, nor
  does ``numerics`` (standard library only, imported first by ``__init__``); ``api`` joins the
  rooms for ``recon3d.run``. Every arrow points one way (ALLOWED).
* Nothing imports ``recon3d.cli`` but ``recon3d/__main__.py`` (and the
  console script); ``surface/``, ``score/``, ``io/`` and ``viz/`` never
  import ``sensing/``.
* Imports sit at the top of a module unless a comment on that line or the
  line before says why it is lazy; pyvista, matplotlib and VTK are
  imported in one place only, ``recon3d/viz/libs.py``, so ``import recon3d``
  loads none of them (nor Dask); its public names load on first use
  (``recon3d.__getattr__``), so ``import recon3d`` loads no trimesh, SciPy
  or numba either, and the arrows of its name table are checked too.
"""
import ast
import pathlib
import subprocess
import sys

import pytest

RECON3D = pathlib.Path(__file__).resolve().parents[1] / "recon3d"
SHARED = {"recon3d.checks", "recon3d.param", "recon3d.config", "recon3d.spellings", "recon3d.records",
          "recon3d.numerics"}
LIBS = "recon3d.viz.libs"
# room (or top-level module) -> recon3d modules it may import besides itself and SHARED
ALLOWED = {
    "shared": set(),
    "viz": set(),
    "surface": {LIBS},
    "score": {"recon3d.surface", LIBS},
    # a slice's motions.csv rows and the samples of its section on holes, in its worker
    "sensing": {"recon3d.surface", "recon3d.io", "recon3d.score"},
    "io": {"recon3d.viz"},
    "api": {"recon3d.sensing", "recon3d.surface", "recon3d.score", "recon3d.io",
            "recon3d.viz"},
    "jobs": {"recon3d.api", "recon3d.io"},
    "benchmark": {"recon3d", "recon3d.api", "recon3d.io", "recon3d.jobs", LIBS},
    "cli": {"recon3d.api", "recon3d.io", "recon3d.viz", "recon3d.jobs", "recon3d.benchmark"},
    "init": {"recon3d.api", "recon3d.io"},  # the public names
    "main": {"recon3d.cli"},
}
HEAVY = ("pyvista", "matplotlib", "vtk", "vtkmodules")


def _room(path):
    rel = path.relative_to(RECON3D)
    if len(rel.parts) > 1:
        return rel.parts[0]
    return {"__init__.py": "init", "__main__.py": "main", "api.py": "api"}.get(
        rel.name, "shared")


def _module(path):
    return ".".join(("recon3d",) + path.relative_to(RECON3D).with_suffix("").parts)


def _is_module(name):
    if not name.startswith("recon3d."):
        return False
    rel = RECON3D.joinpath(*name.split(".")[1:])
    return rel.with_suffix(".py").is_file() or (rel / "__init__.py").is_file()


def _imports(path):
    """(module imported, line, nested in a function or class?) for every import."""
    tree = ast.parse(path.read_text())
    parents = {}
    for node in ast.walk(tree):
        for child in ast.iter_child_nodes(node):
            parents[child] = node
    for node in ast.walk(tree):
        if not isinstance(node, (ast.Import, ast.ImportFrom)):
            continue
        up, nested = parents.get(node), False
        while up is not None:
            nested |= isinstance(up, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef))
            up = parents.get(up)
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif node.level:  # relative: resolve against the file's package
            pkg = _module(path).split(".")[:-node.level]
            names = [".".join(pkg + ([node.module] if node.module else []))]
        else:  # a submodule where the name is one (from recon3d.viz import libs)
            names = [f"{node.module}.{a.name}" if _is_module(f"{node.module}.{a.name}")
                     else node.module for a in node.names]
        for name in names:
            yield name, node.lineno, nested


FILES = sorted(RECON3D.rglob("*.py"))


def test_the_rooms_exist_and_the_top_level_is_small():
    rooms = sorted(p.name for p in RECON3D.iterdir() if (p / "__init__.py").is_file())
    assert rooms == ["benchmark", "cli", "io", "jobs", "score", "sensing", "surface", "viz"]
    top = sorted(p.name for p in RECON3D.glob("*.py"))
    assert top == ["__init__.py", "__main__.py", "api.py", "checks.py", "config.py",
                   "numerics.py", "param.py", "records.py", "spellings.py"]


@pytest.mark.parametrize("path", FILES, ids=lambda p: str(p.relative_to(RECON3D)))
def test_every_import_arrow_points_one_way(path):
    room = _room(path)
    own = _module(path) if room in ("shared", "api", "init", "main") else f"recon3d.{room}"
    for mod, line, _ in _imports(path):
        if mod != "recon3d" and not mod.startswith("recon3d."):
            continue
        ok = (mod in SHARED or mod == own or mod.startswith(own + ".")
              or any(mod == a or mod.startswith(a + ".") for a in ALLOWED[room]))
        assert ok, f"{path.relative_to(RECON3D)}:{line} ({room}) imports {mod}"


def test_the_shared_modules_import_one_way_and_no_room():
    order = ["recon3d.checks", "recon3d.param", "recon3d.config", "recon3d.spellings", "recon3d.records"]
    for k, name in enumerate(order):
        path = RECON3D / f"{name.split('.')[1]}.py"
        mods = {m for m, _, _ in _imports(path) if m.startswith("recon3d")}
        assert mods <= set(order[:k]), f"{name} imports {sorted(mods - set(order[:k]))}"


@pytest.mark.parametrize("path", FILES, ids=lambda p: str(p.relative_to(RECON3D)))
def test_nothing_imports_the_cli_and_no_room_below_imports_sensing(path):
    room = _room(path)
    for mod, line, _ in _imports(path):
        if mod == "recon3d.cli" or mod.startswith("recon3d.cli."):
            assert room in ("cli", "main"), f"{path.relative_to(RECON3D)}:{line} imports {mod}"
        if mod == "recon3d.sensing" or mod.startswith("recon3d.sensing."):
            assert room not in ("surface", "score", "io", "viz", "shared"), \
                f"{path.relative_to(RECON3D)}:{line} imports {mod}"


@pytest.mark.parametrize("path", FILES, ids=lambda p: str(p.relative_to(RECON3D)))
def test_imports_sit_at_the_top_unless_a_comment_says_why_lazy(path):
    lines = path.read_text().splitlines()
    for mod, line, nested in _imports(path):
        if nested:
            said = " ".join(lines[max(0, line - 2):line])
            assert "# lazy" in said, f"{path.relative_to(RECON3D)}:{line}: import of {mod} " \
                                     f"inside a function without a '# lazy: why' comment"


@pytest.mark.parametrize("path", FILES, ids=lambda p: str(p.relative_to(RECON3D)))
def test_pyvista_and_matplotlib_come_through_viz_libs_only(path):
    for mod, line, _ in _imports(path):
        if mod.split(".")[0] in HEAVY:
            assert _module(path) == LIBS, f"{path.relative_to(RECON3D)}:{line} imports {mod}"


def _fresh_python(code: str) -> str:
    """What ``code`` prints in a new interpreter (stripped): what its imports loaded."""
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=True).stdout.strip()


def test_import_recon3d_loads_no_plotting_library_and_no_dask():
    code = ("import sys, recon3d, recon3d.cli, recon3d.jobs.batch, recon3d.benchmark.run3d; "
            "print(sorted(m for m in sys.modules if m.split('.')[0] in "
            "('pyvista', 'matplotlib', 'vtk', 'vtkmodules', 'dask', 'distributed')))")
    assert _fresh_python(code) == "[]"


def test_import_recon3d_is_light():
    """``import recon3d`` loads none of the heavy libraries (issue 20: <= 0.5 s; timed in
    bench/bench_import.py, not here): its public names load on first use (PEP 562)."""
    code = ("import sys, recon3d; "
            "print(sorted({m.split('.')[0] for m in sys.modules} & "
            "{'trimesh', 'scipy', 'numba', 'llvmlite', 'shapely', 'embreex', 'manifold3d', "
            "'networkx', 'pyvista', 'matplotlib', 'vtk', 'vtkmodules', 'dask', 'distributed', "
            "'core2d', 'slicer', 'meshes'}))")
    assert _fresh_python(code) == "[]"


def test_the_command_line_parser_loads_no_run():
    """``recon3d --help``, every subcommand's ``--help`` and ``--version`` build the whole
    parser and load none of the run's libraries: each subcommand imports what it runs
    inside its ``command`` (``recon3d --help`` 1.0 s before, 0.14 s after, idle 2-core
    machine)."""
    code = ("import sys, contextlib, io; from recon3d.cli import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            "    for argv in (['--help'], ['run', '--help'], ['batch', '--help'], "
            "['bench', '--help'], ['figure', '--help'], ['show', '--help'], ['--version']):\n"
            "        try:\n"
            "            main(argv)\n"
            "        except SystemExit as exc:\n"
            "            assert exc.code == 0, argv\n"
            "print(sorted({m.split('.')[0] for m in sys.modules} & "
            "{'trimesh', 'scipy', 'numba', 'llvmlite', 'shapely', 'embreex', 'manifold3d', "
            "'networkx', 'pyvista', 'matplotlib', 'vtk', 'vtkmodules', 'dask', 'distributed', "
            "'core2d', 'meshes'}))")
    assert _fresh_python(code) == "[]"


def test_the_lazy_public_names_obey_the_walls_and_resolve():
    """recon3d/__init__.py names its modules in strings (``_PUBLIC``), which the AST walk
    of the tests above cannot see: the same arrows are checked here, and every name loads."""
    import recon3d

    for name, mod in recon3d._PUBLIC.items():
        assert mod in SHARED or any(mod == a or mod.startswith(a + ".")
                                    for a in ALLOWED["init"]), f"{name} from {mod}"
        assert getattr(recon3d, name) is getattr(__import__(mod, fromlist=[name]), name)
    assert sorted(recon3d.__all__) == sorted(recon3d._PUBLIC)
    assert set(recon3d.__all__) <= set(dir(recon3d))
    with pytest.raises(AttributeError):
        recon3d.no_such_name


def test_pyvista_without_its_plotting_loads_no_matplotlib():
    """A ``--no-png`` run uses pyvista's data sets only (flying edges, distances): no
    matplotlib. (pyvista.plotting itself imports matplotlib.pyplot, so a run that draws
    coverage.png loads it there; recon3d's own colours are parsed in viz/plot.hex_rgb.)"""
    code = ("import sys, trimesh; from recon3d.viz import libs, plot; "
            "import recon3d.surface.solid, recon3d.score.evaluate; "
            "libs.polydata(trimesh.creation.box()); plot.hex_rgb('#ff7f0e'); "
            "print(sorted(m for m in sys.modules if m.split('.')[0] == 'matplotlib'))")
    assert _fresh_python(code) == "[]"


def test_files_stay_small():
    for path in FILES:
        n = len(path.read_text().splitlines())
        assert n <= 400, f"{path.relative_to(RECON3D)} has {n} lines"
