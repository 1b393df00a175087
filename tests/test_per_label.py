"""Per-component maximum and median (recon3d.surface.per_label) against scipy.ndimage's,
on random labelled grids: the same values, to the bit, for every label that has nodes."""
import numpy as np
import pytest
from scipy import ndimage

from recon3d.surface.per_label import label_maximum, label_median


def _grid(seed, dtype):
    rng = np.random.default_rng(seed)
    shape = tuple(int(s) for s in rng.integers(5, 60, size=2))
    comp, n = ndimage.label(rng.random(shape) < rng.uniform(0.2, 0.7))
    values = (rng.normal(size=shape) * 10.0 ** rng.uniform(-3, 3)).astype(dtype)
    values[rng.random(shape) < 0.1] = values.flat[0]  # ties
    return rng, comp, n, values


@pytest.mark.parametrize("seed", range(8))
@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_maximum_and_median_are_scipys(seed, dtype):
    rng, comp, n, values = _grid(seed, dtype)
    idx = np.arange(1, n + 1)
    got = label_maximum(values, comp, n)
    assert got.dtype == values.dtype
    np.testing.assert_array_equal(got, ndimage.maximum(values, comp, idx))
    # a thin subset of the labels (some labels left without nodes), as the steps rule asks
    edge = comp * (rng.random(comp.shape) < 0.3)
    has = label_maximum(edge > 0, edge, n)
    np.testing.assert_array_equal(has, np.asarray(ndimage.maximum(edge > 0, edge, idx), bool))
    assert 0 < has.sum() < n  # labels with and without nodes were asked
    med = label_median(values, edge, n)
    want = np.asarray(ndimage.median(values, edge, idx))
    np.testing.assert_array_equal(med[has], want[has])
    assert np.isnan(med[~has]).all()
    even = np.bincount(edge.ravel(), minlength=n + 1)[1:] % 2 == 0
    assert (even & has).any()  # a mean of two middle values was asked


def test_a_label_without_nodes_is_zero_for_the_maximum():
    values = -np.ones((2, 2))
    labels = np.array([[1, 1], [0, 0]])
    assert label_maximum(values, labels, 2).tolist() == [-1.0, 0.0]
