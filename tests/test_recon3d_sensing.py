"""Sensing cuts the mesh once, in the parent, whatever ``jobs`` and the plan of planes."""
import os

import pytest

import recon3d
import slicer


@pytest.mark.parametrize("jobs, slices", [(1, 2), (2, 2), (2, "auto")])
def test_the_mesh_is_sliced_once_in_the_parent(tmp_path, monkeypatch, jobs, slices):
    log = tmp_path / "calls"
    log.write_text("")
    real = slicer.slice_mesh

    def counting(*args, **kwargs):  # forked workers inherit it: a cut there would show
        with open(log, "a") as fh:
            fh.write(f"{os.getpid()}\n")
        return real(*args, **kwargs)

    monkeypatch.setattr(slicer, "slice_mesh", counting)
    res = recon3d.run("fig17_pocket", axis=["z", "x"], slices=slices, max_slices=4, eps=3.0,
                      jobs=jobs)
    assert log.read_text().split() == [str(os.getpid())] * 2  # one cut per family
    assert res.sensing.jobs == jobs and all(s.slice is not None for s in res.slices)
