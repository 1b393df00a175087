"""A family's field made in two halves (recon3d.surface.field.family_volume, ``pair``).

The slices' own fields and caps, then the gaps' layers, are split at the middle slice and
may run in a forked child beside this process (``recon3d.api`` does so). The field must be
the very field of one process doing all of it: compared ``==`` on a constructed case whose
run of chord-closed slices straddles the split (caps and run caps act there) and on a
sensed scene (bends, steps), with the confidence too, against the field made in one piece
(no split), the halves run in order, in reverse order and in a forked child of a fresh
interpreter (a test worker that has made a render window
may not fork).
"""
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import trimesh

import recon3d
import recon3d.api as api
import slicer
from recon3d.config import diagonal
from recon3d.surface import field
from recon3d.surface.caps import cap_unsensed
from recon3d.surface.closure import slice_region
from recon3d.surface.field import family_grid, family_volume

U = np.array([[-10, -6], [10, -6], [10, 6], [6, 6], [6, -2], [-6, -2], [-6, 6], [-10, 6]],
             dtype=float)


def _u_prism():
    """7 z-slices of a U prism; slices 2 - 4 closed the slot's mouth with an unknown chord
    (the case of ``test_recon3d_caps_runs``): the run straddles the split at slice 3."""
    loop = np.vstack([U, U[:1]])
    traced = slice_region([loop], [], [], [], 1e-9)
    closed = slice_region([U[[3, 2, 1, 0, 7, 6]]], [], [], [np.array([U[6], U[3]])], 1e-9)
    regions = [closed if i in (2, 3, 4) else traced for i in range(7)]
    mesh = trimesh.creation.extrude_polygon(trimesh.path.polygons.Polygon(U), 21.0)
    heights = np.array([c.plane.offset for c in slicer.slice_mesh(mesh, axis="z", count=7)])
    return regions, family_grid(regions, heights, 0.5)


def _sensed():
    """``fig18_overhangs``, 8 z-slices at eps = diagonal / 60: the regions the run closed and
    the grid of its family."""
    mesh = recon3d.api.load_input("fig18_overhangs", False)[0]
    res = recon3d.run("fig18_overhangs", slices=8, eps=diagonal(mesh) / 60, jobs=1)
    regions = res.recon.regions[0]
    heights = np.array([s.slice.plane.offset for s in res.sensing.families[0].slices])
    return regions, family_grid(regions, heights, res.recon.step)


@pytest.fixture(scope="module")
def sensed():
    return _sensed()


def _reversed(first, second):
    b = second()
    return first(), b


def _whole(regions, grid, **kw):
    """The field made in one piece: no split however many slices (the reference)."""
    split, field._SPLIT = field._SPLIT, 10 ** 9
    try:
        return family_volume(regions, grid, **kw)
    finally:
        field._SPLIT = split


@pytest.mark.parametrize("pair", [None, _reversed], ids=["in order", "reversed"])
@pytest.mark.parametrize("confidence", [False, True])
@pytest.mark.parametrize("case", ["u_prism", "fig18_overhangs"])
def test_the_halves_make_the_field_of_one_piece(case, confidence, pair, request):
    regions, grid = _u_prism() if case == "u_prism" else request.getfixturevalue("sensed")
    assert len(regions) >= field._SPLIT
    vol, conf = _whole(regions, grid, confidence=confidence)
    vol2, conf2 = family_volume(regions, grid, confidence=confidence, pair=pair)
    assert np.array_equal(vol, vol2)
    assert (conf is None and conf2 is None) or np.array_equal(conf, conf2)


def test_the_constructed_run_is_capped_at_the_split():
    """The case above tests what it means to: the gaps either side of the middle slice
    carry a cap (an independent call of the caps rule), so a half that lost one would
    differ."""
    regions, grid = _u_prism()
    half = len(regions) // 2
    nx, ny = grid.shape
    f = [field.slice_sdf(r, grid).reshape(ny, nx) for r in regions]
    gaps = np.diff(grid.heights)
    for i in (half - 2, half + 1):  # (1, 2) and (4, 5): a closed slice beside a traced one
        t = field._clip(float(gaps[i]), grid)
        cap = cap_unsensed(np.clip(f[i], -t, t), np.clip(f[i + 1], -t, t), regions[i],
                           regions[i + 1], grid, float(gaps[i]))
        assert cap is not None


@pytest.mark.parametrize("slices, calls", [(3, 0), (7, 2)])
def test_a_family_splits_when_it_has_enough_slices(slices, calls):
    regions, grid = _u_prism()
    grid = family_grid(regions[:slices], grid.heights[:slices], grid.step)
    seen = []

    def counting(first, second):
        seen.append(1)
        return first(), second()

    family_volume(regions[:slices], grid, pair=counting)
    assert len(seen) == calls


def test_a_run_makes_its_fields_halves_beside_itself(monkeypatch):
    """``recon3d.run`` hands the reconstruction its two-core ``pair``: the field's two
    phases go through it (and the scores' distance calls)."""
    names = []
    real = api._side_by_side

    def recording(first, second):
        names.append(first.__qualname__)
        return real(first, second)

    monkeypatch.setattr(api, "_side_by_side", recording)
    mesh = recon3d.api.load_input("fig17_pocket", False)[0]
    recon3d.run("fig17_pocket", slices=4, eps=diagonal(mesh) / 60, jobs=1)
    assert sum(n.startswith("family_volume") for n in names) == 2


def test_the_plain_route_splits_the_same():
    regions, grid = _u_prism()
    vol, _ = _whole(regions, grid, route="linear")
    vol2, _ = family_volume(regions, grid, route="linear", pair=_reversed)
    assert np.array_equal(vol, vol2)


def test_the_halves_in_a_forked_child_make_the_field_of_one_process():
    """The first half in a forked child (``recon3d.api._side_by_side``, as a run does), its
    result back through the pipe, against the field made in one piece: both cases, with and
    without the confidence, and the plain route. In a fresh interpreter: a test process that has made a render window (an
    earlier pyvista test in the same worker) may not fork."""
    code = (
        "import sys; sys.path.insert(0, sys.argv[1]); import recon3d; import numpy as np;"
        "import test_recon3d_field_halves as t; import recon3d.api as api;"
        "from recon3d.surface.field import family_volume;"
        "assert api.can_fork();"
        "runs = [(c, r, k) for c in (t._u_prism(), t._sensed())"
        " for r, k in (('warp', False), ('warp', True), ('linear', False))];"
        "ok = all(np.array_equal(x, y) for (rg, g), r, k in runs for x, y in zip("
        "t._whole(rg, g, route=r, confidence=k)[:1 + k],"
        "family_volume(rg, g, route=r, confidence=k, pair=api._side_by_side)[:1 + k]));"
        "sys.exit(0 if ok else 1)")
    here = str(Path(__file__).resolve().parent)
    done = subprocess.run([sys.executable, "-c", code, here], capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
