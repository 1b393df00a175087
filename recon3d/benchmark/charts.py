"""Matplotlib charts of ``recon3d bench`` (plotting kept apart from the data).

Every function takes the rows written to the matching CSV and a PNG path.
"""
from __future__ import annotations

import numpy as np

from recon3d.viz import libs

__all__ = ["pareto_chart", "baseline_chart", "stability_chart", "sensor_chart",
           "claims_chart"]


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
    fig, axes = plt.subplots(1, 3, figsize=(19, 6.2), constrained_layout=True)
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
    axes[2].scatter([], [], marker="*", s=200, color="grey", edgecolors="black",
                    label="adaptive (--slices auto)")
    axes[2].plot([], [], "-", color="grey", label="Pareto front (per case)")
    axes[2].scatter([], [], s=10 + 3 * lo, color="grey", label=f"uniform, {lo} slices")
    axes[2].scatter([], [], s=10 + 3 * hi, color="grey", label=f"uniform, {hi} slices")
    axes[2].legend(loc="lower right", fontsize=9)
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
                   color=col[case], alpha=0.7, label=f"{case}: finger probing (one density)")
        best, front = -1.0, []  # the best coverage finger probing reaches within a robot time
        for r in fin:
            if r["coverage"] > best:
                best = r["coverage"]
                front.append(r)
        ax.step([r["robot_time_s"] for r in front], [r["coverage"] for r in front], "-",
                where="post", color=col[case], lw=1.3, alpha=0.9)
        ax.scatter([r["robot_time_s"] for r in pull], [r["coverage"] for r in pull], marker="*",
                   s=300, color=col[case], edgecolors="black", zorder=5)
    ax.scatter([], [], marker="*", s=200, color="grey", edgecolors="black",
               label="pulling (the paper's algorithm)")
    ax.plot([], [], "-", color="grey", label="finger probing: best coverage within a robot time")
    ax.axhline(0.99, color="black", lw=0.8, ls="--")
    ax.text(0.99, 0.99, "99 %", va="bottom", ha="right", fontsize=9,
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


def _x(rows, factor):
    """x values of a factor (eps / edge length for eps; categories as positions)."""
    vals = list(dict.fromkeys(r["value"] for r in rows))
    if isinstance(vals[0], str):
        return {v: i for i, v in enumerate(vals)}, vals
    return {v: float(v) for v in vals}, None


def stability_chart(rows, breaks, path) -> None:
    """One panel per factor: coverage (or F@1% for 3D rows) per method; crashes
    (red x), budget hits (black triangles) and each method's breaking point
    (vertical dashed line) marked."""
    plt = _plt()
    factors = list(dict.fromkeys(r["factor"] for r in rows))
    methods = list(dict.fromkeys(r["method"] for r in rows))
    col = _colours(methods)
    ncol = 3
    nrow = int(np.ceil(len(factors) / ncol))
    fig, axes = plt.subplots(nrow, ncol, figsize=(15, 4.2 * nrow), constrained_layout=True,
                             squeeze=False)
    for ax, factor in zip(axes.ravel(), factors):
        sel = [r for r in rows if r["factor"] == factor]
        xmap, cats = _x(sel, factor)
        for m in methods:
            rs = [r for r in sel if r["method"] == m]
            if not rs:
                continue
            key = "fscore_1" if m.endswith("3D") or factor == "mesh defects" else "coverage"
            xs = sorted(set(xmap[r["value"]] for r in rs))
            ys = [np.nanmean([r[key] for r in rs if xmap[r["value"]] == x] or [np.nan])
                  if any(np.isfinite(r[key]) for r in rs if xmap[r["value"]] == x) else np.nan
                  for x in xs]
            lab = f"{m} ({'F@1%' if key == 'fscore_1' else 'coverage'})"
            k = methods.index(m)  # overlapping curves stay visible: shrinking markers
            ax.plot(xs, ys, ("-" if key == "coverage" else "--") + "osD^"[k % 4], color=col[m],
                    label=lab, ms=10 - 2 * (k % 4), mfc="none" if k % 2 == 0 else col[m],
                    lw=2.4 - 0.5 * (k % 4), alpha=0.85)
            for r in rs:
                x = xmap[r["value"]]
                if r["crashed"]:
                    ax.scatter([x], [0.02], marker="x", color="red", s=80, zorder=5)
                elif r["budget_hit"]:
                    y = r[key] if np.isfinite(r[key]) else 0.05
                    ax.scatter([x], [y], marker="v", color="black", s=45, zorder=5)
            b = next((b for b in breaks if b["factor"] == factor and b["method"] == m), None)
            if b is not None and b["breaks_at"] is not None:
                ax.axvline(xmap[b["breaks_at"]], color=col[m], ls=":", lw=1.5)
        if cats is not None:
            ax.set_xticks(range(len(cats)), cats)
        elif factor in ("plane offset", "eps / edge"):
            ax.set_xscale("log")
            ax.minorticks_off()
        elif factor in ("noise", "taxel"):
            ax.set_xscale("symlog", linthresh=0.01)
            ax.set_xlim(-0.002, max(xmap.values()) * 1.3)
        unit = {"plane offset": "offset above a vertex / face, x diagonal",
                "noise": "contact noise sigma / eps", "taxel": "taxel spacing / eps",
                "resolution": "segments per circle",
                "eps / edge": "eps / median mesh edge length"}.get(factor, "degrees")
        ax.set_xlabel(unit if cats is None else "")
        ax.set_ylim(-0.03, 1.05)
        ax.set_title(factor)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, loc="lower left")
    for ax in axes.ravel()[len(factors):]:
        ax.axis("off")
    fig.suptitle("Stability: coverage / F@1% per method; x = crash, triangle = budget hit, "
                 "dotted line = where the method breaks (crash, budget, or a drop > 0.05)")
    fig.savefig(path, dpi=100)
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


def sensor_chart(rows, path, factors=("noise", "taxel")) -> None:
    """The stability study's sensor factors: per factor, motions (log) and
    reachable coverage within eps/2 + 2 sigma per method, against the
    sensor figure in eps; budget hits (black triangles) marked on both."""
    plt = _plt()
    factors = [f for f in factors if any(r["factor"] == f for r in rows)]
    methods = list(dict.fromkeys(r["method"] for r in rows if r["factor"] in factors))
    col = _colours(methods)
    fig, axes = plt.subplots(2, max(len(factors), 1), figsize=(6.5 * max(len(factors), 1), 8),
                             constrained_layout=True, squeeze=False)
    for j, factor in enumerate(factors):
        sel = [r for r in rows if r["factor"] == factor]
        for i, (key, label) in enumerate((("motions", "motions per slice"),
                                          ("coverage_sensor", "coverage within eps/2 + 2 sigma"))):
            ax = axes[i, j]
            for k, m in enumerate(methods):
                rs = sorted((r for r in sel if r["method"] == m), key=lambda r: r["value"])
                if not rs:
                    continue
                xs = [float(r["value"]) for r in rs]
                ax.plot(xs, [r[key] for r in rs], "-" + "osD^"[k % 4], color=col[m], label=m,
                        ms=9 - 2 * (k % 4), mfc="none" if k % 2 == 0 else col[m])
                hit = [r for r in rs if r["budget_hit"]]
                ax.scatter([float(r["value"]) for r in hit], [r[key] for r in hit], marker="v",
                           color="black", s=60, zorder=5)
            ax.set_xscale("symlog", linthresh=0.01)
            if key == "motions":
                ax.set_yscale("log")
            else:
                ax.set_ylim(-0.03, 1.05)
            ax.set_xlabel(("contact noise sigma" if factor == "noise" else "taxel spacing")
                          + " / eps")
            ax.set_ylabel(label)
            ax.set_title(f"{factor}: {label}")
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=8)
    fig.suptitle("Stability under a real sensor (core2d.SensorModel), fig18_overhangs middle "
                 "slice; triangle = budget hit")
    fig.savefig(path, dpi=100)
    plt.close(fig)
