"""``slices.png``: every slice of a run at a glance, one small panel per slice and family.

Each panel shows the true section (thin grey) and the known contour by class
(W1, W2, W3, §3.1) with the unknown areas dotted, captioned with the slice,
its motions and its reachable coverage. Panels of one family share one scale
(a scale bar per family), so the section's change along the axis reads as it
is. Everything is drawn into a single matplotlib axes (each slice shifted into
its cell): a run with hundreds of slices still renders in about a second.
"""
from __future__ import annotations

import gc
import math

import numpy as np

from recon3d.viz import libs
from recon3d.viz.figure2d import (CLASS_COLORS, SECTION_COLOR, UNKNOWN_COLOR, legend_handles,
                                  nice_length)
from recon3d.viz.sliceview import CLASSES, SliceView

__all__ = ["grid_shape", "multiples_figure", "save_multiples"]

_GAP = 0.22  # share of a cell left around its section


def grid_shape(count: int, aspect: float) -> tuple[int, int]:
    """(rows, columns) for ``count`` panels of width/height ``aspect`` in a roughly 16:9 block.

    >>> grid_shape(8, 2.2), grid_shape(1, 1.0)
    ((3, 3), (1, 1))
    """
    cols = max(1, min(count, round(math.sqrt(count * 1.8 / max(aspect, 1e-3)))))
    return math.ceil(count / cols), cols


def _cell(views: list[SliceView]) -> np.ndarray:
    """(2,) cell size of a family: its largest section span, plus gaps and a caption row."""
    span = np.max([np.diff(v.bounds(), axis=0)[0] for v in views], axis=0)
    span = np.maximum(span, 1e-3 * max(float(span.max()), 1e-12))
    return span * (1 + 2 * _GAP) + np.array([0.0, 0.12 * float(span.max())])


def _caption(view: SliceView) -> str:
    return f"{view.axis} {view.position}: {view.motions} motions, cov {view.coverage_text(True)}"


def _layout(views: list[SliceView]):
    """Place every view: [(view, (2,) shift, (2,) caption anchor)], family headers
    [(x, y, text)] and the (2, 2) extent, all in mesh units (one scale for all)."""
    families: dict[int, list] = {}
    for v in views:
        families.setdefault(v.family, []).append(v)
    placed, headers, top, width = [], [], 0.0, 0.0
    header = 0.0
    for fam, fviews in families.items():
        cell = _cell(fviews)
        rows, cols = grid_shape(len(fviews), cell[0] / cell[1])
        header = 0.1 * float(cell.max()) if len(families) > 1 else 0.0
        if header:
            headers.append((0.0, top, f"family {fam} (axis {fviews[0].axis})"))
        top -= header
        for k, view in enumerate(fviews):
            r, c = divmod(k, cols)
            centre = np.array([(c + 0.5) * cell[0], top - (r + 0.5) * cell[1]])
            placed.append((view, centre - view.bounds().mean(axis=0),
                           np.array([centre[0], top - r * cell[1]])))
        width = max(width, cols * cell[0])
        top -= rows * cell[1]
    return placed, headers, np.array([[0.0, top], [width, 0.0]])


def multiples_figure(views: list[SliceView], title: str = "", width_in: float = 12.0):
    """The small multiples of ``views`` (module doc): a matplotlib Figure."""
    plt, coll = libs.pyplot(), libs.collections()
    placed, headers, extent = _layout(views)
    lines = {c: [] for c in CLASSES}
    section, unknown = [], []
    for view, shift, _ in placed:
        for seg in view.segments:
            lines[seg.cls].append(seg.points + shift)
        section += [np.vstack([lp, lp[:1]]) + shift for lp in view.section or []]
        unknown += [np.asarray(w, float) + shift for w in view.unknown]
    size = np.diff(extent, axis=0)[0]
    height_in = float(np.clip(width_in * size[1] / size[0], 2.0, 60.0)) + 0.8
    fig = plt.figure(figsize=(width_in, height_in), dpi=100)
    ax = fig.add_axes((0.01, 0.0, 0.98, 1.0 - 0.45 / height_in))
    ax.set_axis_off()
    if section:
        ax.add_collection(coll.LineCollection(section, colors=SECTION_COLOR, linewidths=0.6))
    for cls in CLASSES:
        if lines[cls]:
            ax.add_collection(coll.LineCollection(lines[cls], colors=CLASS_COLORS[cls],
                                                  linewidths=1.3 if cls == "W1" else 1.8))
    if unknown:
        ax.add_collection(coll.LineCollection(unknown, colors=UNKNOWN_COLOR, linewidths=1.2,
                                              linestyles=(0, (1, 1.5))))
    for view, _, anchor in placed:
        ax.text(anchor[0], anchor[1], _caption(view), ha="center", va="top", fontsize=7)
    for x, y, text in headers:
        ax.text(x, y, text, ha="left", va="top", fontsize=9, weight="bold")
    bar = nice_length(float(size[0]) / 2)
    room = 0.06 * float(size[0])  # a strip under the panels for the scale bar
    x1, y0 = extent[1, 0] - 0.02 * size[0], extent[0, 1] - 0.5 * room
    ax.plot([x1 - bar, x1], [y0, y0], color="black", lw=2.5, solid_capstyle="butt")
    ax.text(x1 - bar / 2, y0 + 0.1 * room, f"{bar:g} mesh units", ha="center", va="bottom",
            fontsize=8)
    ax.set_xlim(extent[0, 0], extent[1, 0])
    ax.set_ylim(extent[0, 1] - room, extent[1, 1])
    ax.set_aspect("equal", adjustable="box")
    present = [c for c in CLASSES if lines[c]]
    handles = legend_handles(present, bool(unknown), bool(section),
                             noisy=any(v.coverage_sensor is not None for v in views))
    fig.legend(handles=handles, loc="lower left", ncol=len(handles), fontsize=8,
               frameon=False)
    fig.suptitle(title, fontsize=10, y=1.0 - 0.08 / height_in, va="top")
    return fig


def save_multiples(views: list[SliceView], path, title: str = "") -> None:
    """Render :func:`multiples_figure` to ``path`` (Agg) and close it."""
    fig = multiples_figure(views, title)
    try:
        fig.savefig(path)
    finally:
        libs.pyplot().close(fig)
        # a closed figure is thousands of objects in reference cycles: collected now,
        # not at exit, where they reorder the teardown so that nanobind reports a live
        # manifold3d object of the sectioning as "leaked" (one-line-warnings contract)
        gc.collect()
