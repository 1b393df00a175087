"""Charts of the stability study (``stability.png``, ``sensor.png``).

Both take the rows of ``stability.csv`` (:mod:`.stability`). A method keeps
its colour, marker and name on every panel of both charts; the score of a
panel is the one its breaking points are judged by (:func:`.stability.score_key`).
"""
from __future__ import annotations

import numpy as np

from recon3d.benchmark.stability import SENSOR_FACTORS, score_key
from recon3d.viz import libs

__all__ = ["stability_chart", "sensor_chart", "method_label"]

_NAMES = {"pulling/embree": "pulling (Embree rays)", "pulling/exact": "pulling (exact 2D backend)",
          "pulling/trimesh": "pulling (trimesh rays)", "finger/embree": "finger probing",
          "paper/embree": "paper: Fig. 16 flow alone", "follow/embree": "follow: pushing follower",
          "pulling/embree 3D": "pulling, whole 3D run (F@1%)"}
_MARKS = "osD^vPX*"
_RING = 420
"""Area (points^2) of the ring around a breaking point: about twice the largest marker's width."""
_SCORES = {"coverage": "reachable coverage (within eps/2)",
           "coverage_sensor": "coverage within eps/2 + 2 sigma",
           "fscore_1": "F@1% of the 3D surface"}
_UNITS = {"plane offset": "plane offset above a face and its vertices / diagonal",
          "noise": "contact noise sigma / eps", "taxel": "taxel spacing / eps",
          "resolution": "segments per circle (bowl)",
          "eps / edge": "eps / median mesh edge length (bowl)",
          "islands/holes": "scene (mean over its z-slices)", "mesh defects": "mesh (whole run)"}


def method_label(method: str) -> str:
    """The name a chart gives a method of ``stability.csv`` (``pulling/embree`` ...)."""
    return _NAMES.get(method, method)


def _style(methods):
    """Per method: (colour, marker, marker size, filled), fixed by the method's
    place in :data:`_NAMES` (the same on every chart); earlier methods drawn
    larger so that equal curves stay visible underneath."""
    cmap = libs.pyplot().get_cmap("tab10")
    order = list(_NAMES) + [m for m in methods if m not in _NAMES]
    return {m: (cmap(k % 10), _MARKS[k % len(_MARKS)], 11 - 0.8 * k, k % 2 == 1)
            for k, m in ((order.index(m), m) for m in methods)}


def _mean(rs, key, v):
    xs = [r.get(key, np.nan) for r in rs if r["value"] == v]
    xs = [x for x in xs if isinstance(x, (int, float)) and np.isfinite(x)]
    return float(np.mean(xs)) if xs else np.nan


def _value_axis(ax, factor, values, cats):
    """Ticks at the factor's values (categories by name, plain numbers)."""
    if cats is not None:
        ax.set_xticks(range(len(cats)), cats)
        ax.set_xlim(-0.5, len(cats) - 0.5)
        return
    fmt = libs.ticker().FuncFormatter(lambda v, _: f"{v:g}")
    if factor in SENSOR_FACTORS:
        ax.set_xscale("symlog", linthresh=0.01, linscale=0.5)
        ax.set_xlim(-0.003, max(values) * 1.4)  # the last value off the frame
    elif factor in ("plane offset", "eps / edge"):
        ax.set_xscale("log")
    ax.set_xticks(sorted(values))
    ax.xaxis.set_major_formatter(fmt)
    ax.xaxis.set_minor_locator(libs.ticker().NullLocator())
    if factor == "plane offset":
        ax.tick_params(axis="x", labelrotation=30)


def stability_chart(rows, breaks, path) -> list[tuple]:
    """One panel per factor: each method's score (:func:`.stability.score_key`;
    3D runs dashed) against the factor's value; crashes (red x), budget hits
    (black triangles) and each method's breaking point (a dotted ring in its
    colour around its own point, so methods breaking at one value stay apart).
    Returns the rings drawn: ``(factor, method, value, score)`` each."""
    plt = libs.pyplot()
    marks = []
    factors = list(dict.fromkeys(r["factor"] for r in rows))
    methods = list(dict.fromkeys(r["method"] for r in rows))
    style = _style(methods)
    ncol = 3
    nrow = int(np.ceil(len(factors) / ncol))
    fig, axes = plt.subplots(nrow, ncol, figsize=(16, 4.3 * nrow + 1.0), constrained_layout=True,
                             squeeze=False)
    for ax, factor in zip(axes.ravel(), factors):
        sel = [r for r in rows if r["factor"] == factor]
        values = list(dict.fromkeys(r["value"] for r in sel))
        cats = values if isinstance(values[0], str) else None
        pos = {v: (i if cats else float(v)) for i, v in enumerate(values)}
        keys = set()
        for m in methods:
            rs = [r for r in sel if r["method"] == m]
            if not rs:
                continue
            key = "fscore_1" if factor == "mesh defects" else score_key(factor, m)
            keys.add(key)
            vs = [v for v in values if any(r["value"] == v for r in rs)]
            colour, mark, size, filled = style[m]
            ax.plot([pos[v] for v in vs], [_mean(rs, key, v) for v in vs],  # no line: categories
                    ls="none" if cats else "--" if key == "fscore_1" else "-", marker=mark,
                    color=colour, ms=size, mfc=colour if filled else "none", mew=1.6,
                    lw=2.0, alpha=0.85, label=method_label(m))
            for r in rs:
                if r["crashed"]:
                    ax.scatter([pos[r["value"]]], [0.02], marker="x", color="red", s=90, zorder=5)
                elif r["budget_hit"]:
                    y = r.get(key, np.nan)
                    ax.scatter([pos[r["value"]]], [y if np.isfinite(y) else 0.05], marker="v",
                               color="black", s=50, zorder=5)
            b = next((b for b in breaks if b["factor"] == factor and b["method"] == m), None)
            if b is not None and b["breaks_at"] in pos:
                y = _mean(rs, key, b["breaks_at"])
                y = y if np.isfinite(y) else 0.02  # a crash has no score: at its red x
                ax.scatter([pos[b["breaks_at"]]], [y], s=_RING, facecolors="none",
                           edgecolors=[colour], linewidths=2.0, linestyles=":", zorder=6)
                marks.append((factor, m, b["breaks_at"], y))
        _value_axis(ax, factor, pos.values(), cats)
        ax.set_xlabel(_UNITS.get(factor, "rotation, degrees"))
        ax.set_ylabel(" / ".join(_SCORES[k] for k in sorted(keys)), fontsize=9)
        ax.set_ylim(-0.03, 1.05)
        ax.set_title(factor)
        ax.grid(True, alpha=0.3)
    for ax in axes.ravel()[len(factors):]:
        ax.axis("off")
    handles = [libs.lines().Line2D([], [], color=style[m][0], marker=style[m][1], ms=9,
                                    mfc=style[m][0] if style[m][3] else "none", mew=1.6,
                                    label=method_label(m)) for m in methods]
    handles += [libs.lines().Line2D([], [], ls="none", marker="v", color="black",
                                     label="budget hit"),
                libs.lines().Line2D([], [], ls="none", marker="x", color="red", label="crash"),
                libs.lines().Line2D([], [], ls="none", marker="o", ms=_RING ** 0.5, mfc="none",
                                    mec="grey", mew=2.0, label="where it breaks (ring)")]
    fig.legend(handles=handles, loc="outside lower center", ncol=6, fontsize=10)
    fig.suptitle("Stability: where each method breaks (a crash, its budget of 5000 motions per "
                 "slice hit, or its score 0.05 below the first value's); eps = diagonal / 50 "
                 "(but eps / edge)")
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return marks


def sensor_chart(rows, path, factors=SENSOR_FACTORS) -> None:
    """The sensor factors: per factor, motions per slice (log) and coverage
    within eps/2 + 2 sigma per method against the sensor figure in eps;
    budget hits (black triangles) marked on both, their count in the title."""
    plt = libs.pyplot()
    factors = [f for f in factors if any(r["factor"] == f for r in rows)]
    methods = list(dict.fromkeys(r["method"] for r in rows if r["factor"] in factors))
    style = _style(methods)
    n = max(len(factors), 1)
    fig, axes = plt.subplots(2, n, figsize=(7.5 * n, 9), constrained_layout=True, squeeze=False)
    for j, factor in enumerate(factors):
        sel = [r for r in rows if r["factor"] == factor]
        hits = sum(bool(r["budget_hit"]) for r in sel)
        for i, (key, label) in enumerate((("motions", "motions per slice (log)"),
                                          ("coverage_sensor", _SCORES["coverage_sensor"]))):
            ax = axes[i, j]
            for m in methods:
                rs = sorted((r for r in sel if r["method"] == m), key=lambda r: r["value"])
                if not rs:
                    continue
                colour, mark, size, filled = style[m]
                ax.plot([float(r["value"]) for r in rs], [r[key] for r in rs], "-", marker=mark,
                        color=colour, ms=size, mfc=colour if filled else "none", mew=1.6, lw=1.8,
                        label=method_label(m))
                hit = [r for r in rs if r["budget_hit"]]
                ax.scatter([float(r["value"]) for r in hit], [r[key] for r in hit], marker="v",
                           color="black", s=70, zorder=5)
            _value_axis(ax, factor, {float(r["value"]) for r in sel}, None)
            if key == "motions":
                ax.set_yscale("log")
                tk = libs.ticker()
                ax.yaxis.set_major_locator(tk.LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
                ax.yaxis.set_major_formatter(tk.FuncFormatter(lambda v, _: f"{v:g}"))
                ax.yaxis.set_minor_formatter(tk.NullFormatter())
            else:
                ax.set_ylim(-0.03, 1.05)
            ax.set_xlabel(_UNITS[factor])
            ax.set_ylabel(label)
            ax.set_title(f"{factor}: {label}; budget hits: {hits or 'none'}")
            ax.grid(True, alpha=0.3)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    handles.append(libs.lines().Line2D([], [], ls="none", marker="v", color="black"))
    labels.append("budget hit (5000 motions)")
    fig.legend(handles, labels, loc="outside lower center", ncol=4, fontsize=10)
    fig.suptitle("A real sensor (core2d.SensorModel): the middle z-slice of fig18_overhangs, "
                 "eps = diagonal / 50, the planner told sigma and the taxel spacing\n"
                 "(each reading point averaged as recon3d run does: 2 reads at sigma 0.03 eps, "
                 "16 at 0.1 and 0.3 eps, else 1)")
    fig.savefig(path, dpi=100)
    plt.close(fig)
