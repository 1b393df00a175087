"""Matplotlib charts of ``recon3d bench`` (plotting kept apart from the data).

Every function takes the rows written to the matching CSV and a PNG path
(the stability study's charts: :mod:`.stability_charts`).
"""
from __future__ import annotations

import numpy as np

from recon3d.viz import libs

__all__ = ["pareto_chart", "baseline_chart", "claims_chart"]


def _plt():
    return libs.pyplot()


def _colours(cases):
    plt = _plt()
    cmap = plt.get_cmap("tab10")
    return {c: cmap(i % 10) for i, c in enumerate(cases)}


def _plain_log_x(ax):
    """Log x axis with plain tick labels (1, 2, 5, 10, ...)."""
    FuncFormatter, LogLocator = libs.ticker().FuncFormatter, libs.ticker().LogLocator
    ax.set_xscale("log")
    ax.xaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    ax.xaxis.set_minor_locator(LogLocator(base=10, subs=tuple(range(1, 10))))
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.xaxis.set_minor_formatter(FuncFormatter(lambda v, _: ""))


def pareto_chart(rows, fronts, path) -> None:
    """CPU time against Chamfer-L1 / diagonal, F@1% and 2D reachable coverage.

    rows : list of dict (pareto.csv); fronts : dict key -> (n,) bool Pareto
    flags for the keys ``chamfer_l1_diag``, ``fscore_1``, ``coverage``.
    Uniform runs are dots (area grows with the slice count), adaptive runs
    stars; the Pareto front of each case is joined by a line.
    """
    plt = _plt()
    cases = list(dict.fromkeys(r["case"] for r in rows))
    col = _colours(cases)
    slices = [r["slices"] for r in rows if r["method"] == "uniform"] or [1]
    fig, axes = plt.subplots(1, 3, figsize=(19, 6.8), constrained_layout=True)
    panels = (("chamfer_l1_diag", "Chamfer-L1 / diagonal (log; lower is better)"),
              ("fscore_1", "F-score at 1 % of the diagonal (higher is better)"),
              ("coverage", "2D reachable coverage (higher is better)"))
    for ax, (key, label) in zip(axes, panels):
        front = fronts[key]
        for case in cases:
            idx = [i for i, r in enumerate(rows) if r["case"] == case]
            uni = [i for i in idx if rows[i]["method"] == "uniform"]
            ada = [i for i in idx if rows[i]["method"] == "adaptive"]
            ax.scatter([rows[i]["cpu_s"] for i in uni], [rows[i][key] for i in uni],
                       s=[10 + 3 * rows[i]["slices"] for i in uni], color=col[case], alpha=0.55,
                       edgecolors="none", label=case)
            ax.scatter([rows[i]["cpu_s"] for i in ada], [rows[i][key] for i in ada], marker="*",
                       s=280, color=col[case], edgecolors="black", linewidths=0.8, zorder=4)
            f = sorted((i for i in idx if front[i]), key=lambda i: rows[i]["cpu_s"])
            ax.plot([rows[i]["cpu_s"] for i in f], [rows[i][key] for i in f], "-",
                    color=col[case], lw=1.5, zorder=3)
        _plain_log_x(ax)
        if key == "chamfer_l1_diag":
            ax.set_yscale("log")
        ax.set_xlabel("CPU time of the whole run, s (log; one process)")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
    lo, hi = min(slices), max(slices)
    ax = axes[2]
    ax.scatter([], [], marker="*", s=200, color="white", edgecolors="black",
               label="adaptive (--slices auto)")
    ax.plot([], [], "-", color="black", label="Pareto front (per case)")
    for n in (lo, hi):
        ax.scatter([], [], s=10 + 3 * n, color="white", edgecolors="black",
                   label=f"uniform, {n} slices")
    handles, labels = ax.get_legend_handles_labels()  # below the panels: no data hidden
    fig.legend(handles, labels, loc="outside lower center", ncol=len(labels), fontsize=10,
               markerscale=0.8)
    fig.suptitle("Speed against accuracy: eps x slice count per case (one colour per case, "
                 "dot area = slices; line = Pareto front; star = --slices auto)")
    fig.savefig(path, dpi=100)
    plt.close(fig)


def baseline_chart(rows, path) -> None:
    """Robot time against 2D reachable coverage: finger densities against pulling."""
    plt = _plt()
    cases = list(dict.fromkeys(r["case"] for r in rows))
    col = _colours(cases)
    fig, ax = plt.subplots(figsize=(10, 6.5), constrained_layout=True)
    for case in cases:
        fin = sorted((r for r in rows if r["case"] == case and r["method"] == "finger"),
                     key=lambda r: r["robot_time_s"])
        pull = [r for r in rows if r["case"] == case and r["method"] == "pulling"]
        ax.scatter([r["robot_time_s"] for r in fin], [r["coverage"] for r in fin], s=22,
                   color=col[case], alpha=0.7, label=case)
        best, front = -1.0, []  # the best coverage finger probing reaches within a robot time
        for r in fin:
            if r["coverage"] > best:
                best = r["coverage"]
                front.append(r)
        ax.step([r["robot_time_s"] for r in front], [r["coverage"] for r in front], "-",
                where="post", color=col[case], lw=1.3, alpha=0.9)
        ax.scatter([r["robot_time_s"] for r in pull], [r["coverage"] for r in pull], marker="*",
                   s=300, color=col[case], edgecolors="black", zorder=5)
    # the key's symbols white / black: no case colour (tab10 has grey) is taken for them
    ax.scatter([], [], s=22, color="white", edgecolors="black",
               label="finger probing, one density (dot)")
    ax.scatter([], [], marker="*", s=200, color="white", edgecolors="black",
               label="pulling (the paper's algorithm)")
    ax.plot([], [], "-", color="black", label="finger probing: best coverage within a robot time")
    ax.axhline(0.99, color="black", lw=0.8, ls="--")
    ax.text(0.01, 0.985, "99 %", va="top", ha="left", fontsize=9,
            transform=ax.get_yaxis_transform())
    _plain_log_x(ax)
    ax.set_xlabel("robot time, s (log): joint path / probe speed + motions x overhead")
    ax.set_ylabel("2D reachable coverage")
    ax.set_title("Finger probing swept in density (directions x line spacing) against pulling, "
                 "middle z-slice per case")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.savefig(path, dpi=110)
    plt.close(fig)


_CLAIMS = (("coverage", "2D reachable coverage"), ("jams", "jams (pushes stuck)"),
           ("pushes", "pushing steps made"))


def claims_chart(rows, path) -> None:
    """Coverage, jams and executed pushes against tip friction mu: one column
    per case, one line per method (claims.csv)."""
    plt = _plt()
    cases = list(dict.fromkeys(r["case"] for r in rows))
    methods = list(dict.fromkeys(r["method"] for r in rows))
    col = _colours(methods)
    marks = dict(zip(methods, "os^Dv<>"))
    fig, axes = plt.subplots(len(_CLAIMS), len(cases), figsize=(max(11.0, 3.2 * len(cases) + 1), 9),
                             squeeze=False, sharex=True, constrained_layout=True)
    for j, case in enumerate(cases):
        for i, (key, label) in enumerate(_CLAIMS):
            ax = axes[i, j]
            for k, m in enumerate(methods):
                sel = sorted((r for r in rows if r["case"] == case and r["method"] == m),
                             key=lambda r: r["mu"])
                shift = (k - (len(methods) - 1) / 2) * 0.008  # overlapping lines stay visible
                ax.plot([r["mu"] + shift for r in sel], [r[key] for r in sel], marker=marks[m],
                        ms=9 - 1.5 * k, lw=2.4 - 0.4 * k, color=col[m], label=m)  # under: larger
            if key == "coverage":
                ax.set_ylim(-0.02, 1.05)
                ax.set_title(case.replace(".ply", "").replace(".stl", ""), fontsize=10)
            else:
                ax.set_ylim(bottom=-0.05 * max(1.0, max(r[key] for r in rows if r["case"] == case)))
                ax.yaxis.set_major_locator(libs.ticker().MaxNLocator(integer=True))
            if j == 0:
                ax.set_ylabel(label)
            if i == len(_CLAIMS) - 1:
                ax.set_xlabel("tip friction mu")
            ax.grid(True, alpha=0.3)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    names = {"pulling": "pulling (default planner)", "paper": "paper (Fig. 16 alone)",
             "follow": "follow (pushing contour follower)", "finger": "finger probing"}
    fig.legend(handles, [names.get(n, n) for n in labels], loc="outside lower center",
               ncol=min(len(methods), 4), fontsize=9)
    fig.suptitle("Pulling against pushing under Coulomb friction at the tip, middle z-slice "
                 "per case\n(a push with the rod inside the friction cone jams; pulls slide; "
                 "overlapping lines are shifted slightly in mu)")
    fig.savefig(path, dpi=100)
    plt.close(fig)
