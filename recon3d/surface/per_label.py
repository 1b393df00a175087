"""Per-component maximum and median of a field over labelled components (internal).

:func:`scipy.ndimage.maximum` and :func:`scipy.ndimage.median` with an ``index`` sort every
node of the grid by value (or by label and value) on each call, though the caps and steps
rules (:mod:`recon3d.surface.caps`, :mod:`recon3d.surface.steps`) ask about a few
components of a grid of 10^4 - 10^5 nodes, hundreds of times per run. These give the same
values for labels that have nodes, from the labelled nodes only and without a sort
(maximum) or sorting only those nodes (median). A label without nodes has no answer here
(0 for the maximum, NaN for the median); its value in scipy's is arbitrary, and its
callers look at it only where the label has nodes.

>>> import numpy as np
>>> lab = np.array([[1, 1, 0], [0, 2, 2], [3, 0, 2]])
>>> val = np.array([[-1.0, -3.0, 9.0], [9.0, 4.0, 0.5], [2.0, 9.0, 1.0]])
>>> label_maximum(val, lab, 4).tolist()
[-1.0, 4.0, 2.0, 0.0]
>>> label_median(val, lab, 4).tolist()
[-2.0, 1.0, 2.0, nan]
"""
from __future__ import annotations

import numpy as np

__all__ = ["label_maximum", "label_median"]


def _labelled(values, labels) -> tuple[np.ndarray, np.ndarray]:
    values, labels = np.broadcast_arrays(np.asarray(values), np.asarray(labels))
    keep = labels > 0
    return values[keep], labels[keep].astype(np.intp)


def label_maximum(values, labels, n: int) -> np.ndarray:
    """(n,) the maximum of ``values`` over the nodes of each label 1 .. n (0 without nodes).

    values : array -- any shape, numeric or bool (the answer keeps its dtype).
    labels : int array -- the same shape (broadcast), 0 for no component.
    """
    vals, labs = _labelled(values, labels)
    if vals.dtype == np.bool_:
        return np.bincount(labs[vals], minlength=n + 1)[1:n + 1] > 0
    out = np.full(n + 1, -np.inf if vals.dtype.kind == "f" else np.iinfo(vals.dtype).min,
                  dtype=vals.dtype)
    np.maximum.at(out, labs, vals)
    out[np.bincount(labs, minlength=n + 1)[:n + 1] == 0] = 0
    return out[1:n + 1]


def label_median(values, labels, n: int) -> np.ndarray:
    """(n,) the median of ``values`` over the nodes of each label 1 .. n (NaN without
    nodes): the middle value, or the mean of the two middle ones computed in the values'
    dtype (``(a + b) / 2.0``), as :func:`scipy.ndimage.median` does; float values.
    """
    vals, labs = _labelled(values, labels)
    order = np.lexsort((vals, labs))
    vals, labs = vals[order], labs[order]
    counts = np.bincount(labs, minlength=n + 1)[1:n + 1]
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
    has = counts > 0
    lo = (starts + (counts - 1) // 2)[has]
    hi = (starts + counts // 2)[has]
    out = np.full(n, np.nan, dtype=np.result_type(vals.dtype, np.float32))
    out[has] = (vals[lo] + vals[hi]) / 2.0
    return out
