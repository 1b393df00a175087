"""The slices' filled regions are closed in the main process as the slices come back from the
sensing, and the reconstruction takes them: the same regions and the same surface as the
reconstruction closing them itself (``==``), and none closed after the sensing."""
import importlib

import numpy as np
import pytest
import shapely

from recon3d import api
from recon3d.config import RunConfig
from recon3d.sensing.regions import RegionsAsSensed
from recon3d.spellings import make_config
from recon3d.surface import reconstruct
from recon3d.surface.closure import closure_lengths, result_region

reconstruct_module = importlib.import_module("recon3d.surface.reconstruct")  # not the function


def _fresh(run):
    lengths = closure_lengths(run.eps, run.tol, run.config.noise, run.config.taxel)
    return [[result_region(s.result, *lengths) for s in fam.slices] for fam in run.families]


def _same_region(a, b):
    assert shapely.equals_exact(a.geometry, b.geometry, tolerance=0.0) or \
        (a.geometry.is_empty and b.geometry.is_empty)
    assert [p.kind for p in a.pieces] == [p.kind for p in b.pieces]
    for p, q in zip(a.pieces, b.pieces):
        assert np.array_equal(p.points, q.points)


@pytest.fixture(scope="module")
def counted_run():
    """A two-family run through ``execute``, counting the regions closed by the
    reconstruction itself (after the sensing) and those closed as slices came back."""
    calls = {"reconstruct": 0, "sensing": 0, "at_progress": []}
    mp = pytest.MonkeyPatch()
    real = reconstruct_module.result_region
    import recon3d.sensing.regions as regions_module
    real_sensing = regions_module.result_region

    def counting(where):
        def fn(*args, **kwargs):
            calls[where] += 1
            return (real if where == "reconstruct" else real_sensing)(*args, **kwargs)
        return fn

    mp.setattr(reconstruct_module, "result_region", counting("reconstruct"))
    mp.setattr(regions_module, "result_region", counting("sensing"))
    mesh, name, _ = api.load_input("fig18_overhangs")
    config = make_config(slices=3, axis=["z", "x"], jobs=2)
    try:
        res = api.execute(mesh, name, config,
                          progress=lambda s: calls["at_progress"].append(calls["sensing"]))
    finally:
        mp.undo()
    return res, calls


def test_regions_closed_as_slices_come_back_and_none_after(counted_run):
    res, calls = counted_run
    assert len(res.slices) == 6
    assert calls["at_progress"] == [1, 2, 3, 4, 5, 6]  # each one before the caller is told
    assert calls["reconstruct"] == 0


def test_the_same_regions_and_the_same_surface_as_closing_them_in_the_reconstruction(
        counted_run):
    res, _ = counted_run
    fresh = _fresh(res.sensing)
    for got, want in zip(res.recon.regions, fresh, strict=True):
        for a, b in zip(got, want, strict=True):
            _same_region(a, b)
    again = reconstruct(res.sensing)  # closing every region itself
    assert np.array_equal(again.surface.vertices, res.surface.vertices)
    assert np.array_equal(again.surface.faces, res.surface.faces)
    assert np.array_equal(again.surface.face_attributes["label"],
                          res.surface.face_attributes["label"])


def test_another_snap_or_an_unseen_slice(counted_run):
    res, _ = counted_run
    run = res.sensing
    assert RegionsAsSensed(None).for_run(run) is None  # adaptive plans: nothing given
    lengths = closure_lengths(run.eps, run.tol)
    assert RegionsAsSensed(lengths._replace(snap=3.0 * run.tol)).for_run(run) is None
    assert RegionsAsSensed(lengths._replace(jitter=0.1)).for_run(run) is None  # not its sensor
    partial = RegionsAsSensed(lengths)
    partial.add(run.families[0].slices[1])
    got = partial.for_run(run)
    for a, b in zip(sum(got, []), sum(_fresh(run), []), strict=True):
        _same_region(a, b)


def test_an_adaptive_plan_precomputes_nothing():
    assert RunConfig().slices != "auto"
    regions = RegionsAsSensed(None)

    class Fake:
        result = None

    regions.add(Fake())  # would fail on a real close
    assert regions._got == {}
