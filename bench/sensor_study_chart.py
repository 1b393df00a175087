"""The sensor study's chart (:mod:`bench.sensor_study`): per group, motions over the
noiseless run and reachable coverage within eps/2 + 2 sigma, per sensor level."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

__all__ = ["chart", "without_credit"]


def chart(summary, path: Path, coverage_target) -> None:
    """Per group (columns): motions over the noiseless run (total and worst
    slice) with the budget hits written above, and reachable coverage within
    eps/2 + 2 sigma (total, worst slice, and the total without the contour counted
    covered only behind W2 chords when the rows have it), per sensor level.
    ``coverage_target(noise, taxel)`` gives a level's target (dotted) or None."""
    from recon3d.viz import libs

    plt = libs.pyplot()
    groups = list(dict.fromkeys(s["group"] for s in summary))
    fig, axes = plt.subplots(2, len(groups), figsize=(5.5 * len(groups), 8),
                             constrained_layout=True, squeeze=False)
    for j, g in enumerate(groups):
        rs = [s for s in summary if s["group"] == g]
        x = np.arange(len(rs))
        labels = [f"σ {s['noise']:g}\nT {s['taxel']:g}"
                  + (f"\n{s['reads']} reads" if s.get("reads", 1) > 1 else "") for s in rs]
        top, bottom = axes[0, j], axes[1, j]
        top.bar(x - 0.2, [s["ratio"] for s in rs], 0.4, label="total", color="tab:blue")
        top.bar(x + 0.2, [s["ratio_max"] for s in rs], 0.4, label="worst slice",
                color="tab:orange")
        top.axhline(2.0, color="k", ls=":", lw=1, label="target 2×")
        for xi, s in zip(x, rs):
            if s["budget"]:
                top.annotate(f"{s['budget']} budget hit{'s' * (s['budget'] > 1)}",
                             (xi, s["ratio_max"]), ha="center", va="bottom", fontsize=8,
                             color="red")
        top.set_ylim(0, 1.12 * max(max(s["ratio_max"] for s in rs), 2.0))
        top.set_ylabel("motions / noiseless motions")
        runs = max(s["slices"] for s in rs) // max(rs[0]["slices"], 1)  # sensor seeds
        top.set_title(f"{g} ({rs[0]['slices']} slices): motions"
                      + (f"\n{runs} sensor seeds per noisy level" if runs > 1 else ""))
        bottom.plot(x, [s["coverage_sensor"] for s in rs], "o-", label="total")
        bottom.plot(x, [s["cov_sensor_min"] for s in rs], "v--", label="worst slice")
        bare = without_credit(rs)
        if bare:
            bottom.plot(x, bare, "s-.", color="tab:green", ms=5,
                        label="total, contour behind W2 chords not counted")
        targets = [(xi, coverage_target(s["noise"], s["taxel"])) for xi, s in zip(x, rs)]
        for k, (xi, t) in enumerate([(xi, t) for xi, t in targets if t is not None]):
            bottom.hlines(t, xi - 0.35, xi + 0.35, color="k", ls=":", lw=1.2,
                          label="target (0.99 at σ 0.1; 0.98 at σ 0.3, T 0.25)" if k == 0 else None)
        low = min([s["cov_sensor_min"] for s in rs] + bare)
        bottom.set_ylim(min(0.8, low - 0.02), 1.005)
        bottom.set_ylabel("reachable coverage within eps/2 + 2σ")
        bottom.set_title(f"{g}: coverage")
        for ax in (top, bottom):
            ax.set_xticks(x, labels, fontsize=8)
            ax.set_xlabel("sensor level (noise σ, taxel T, in eps; reads averaged per point)")
            ax.grid(True, alpha=0.3, axis="y")
            ax.legend(fontsize=8)
    fig.savefig(path, dpi=100)
    plt.close(fig)


def without_credit(summary) -> list[float]:
    """Each summary's coverage within eps/2 + 2 sigma without the contour counted covered
    only behind W2 chords; [] when a summary lacks that share (an older CSV)."""
    bare = [s["coverage_sensor"] - s.get("w2_credit_sensor", math.nan) for s in summary]
    return bare if all(b == b for b in bare) else []
