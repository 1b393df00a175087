"""One slice in the style of the paper's Figs. 17-18 (§5), drawn with matplotlib.

Panel (a), the section: the known contour by class -- W1 traced by the tip,
W2 the straight approximation of an area with Dist(A, B) < eps, W3 the lid
of a never-touching area (§3.1) -- continuous; the unknown areas A_iB_i
dotted; the true section as a thin grey line; the probe postures as thin
lines from the joint P towards the tip (all, or every n-th); the A_iB_i labels
that do not overlap; a scale bar in mesh units.

Panel (b), the workspace, when a motion log exists: the joint path coloured by
motion index, with arrows for the moving direction of the joint, around the
section. The probe is long (L = 2 x the workspace diameter, DESIGN.md) so its
joint stays in F far from the section: panel (a) shows where the probe
touches, panel (b) where the joint went.
"""
from __future__ import annotations

import math

import numpy as np

from recon3d.viz import libs
from recon3d.viz.sliceview import CLASSES, SliceView

__all__ = ["CLASS_COLORS", "UNKNOWN_COLOR", "SECTION_COLOR", "POSTURE_COLOR", "PATH_CMAP", "TRANSFER_KINDS",
           "draw_section", "draw_known", "draw_unknown", "draw_postures", "draw_labels",
           "draw_joint_path", "scale_bar", "view_limits", "slice_title", "slice_figure",
           "legend_entries", "legend_handles", "nice_length"]

CLASS_COLORS = {"W1": "#1565c0", "W2": "#2e9d3a", "W3": "#d62728"}
"""Known contour colours: W1 blue, W2 green, W3 red."""
UNKNOWN_COLOR = "#000000"
SECTION_COLOR = "#9a9a9a"
POSTURE_COLOR = "#b39b73"
PATH_CMAP = "cividis"
TRANSFER_KINDS = ("approach", "transfer")
"""Motion kinds that move the joint freely through F (drawn as chords, path not logged)."""
_WIDTH = {"W1": 2.0, "W2": 2.4, "W3": 2.4}
_CLASS_NAMES = {"W1": "W1 traced by the tip", "W2": "W2 Dist(A,B) < eps",
                "W3": "W3 lid, never touching"}
_NOISY_W2 = "W2 Dist(A,B) < eps + jitter"


def _lines(ax, polylines, **kwargs):
    """A LineCollection of (k, 2) polylines (none drawn when empty)."""
    polylines = [np.asarray(p, float) for p in polylines if len(p) >= 2]
    if not polylines:
        return None
    coll = libs.collections().LineCollection(polylines, **kwargs)
    ax.add_collection(coll)
    return coll


def draw_section(ax, view: SliceView, **kwargs):
    """The true section (closed loops) as a thin grey line; None when unknown."""
    if not view.section:
        return None
    loops = [np.vstack([lp, lp[:1]]) for lp in view.section]
    style = dict(colors=SECTION_COLOR, linewidths=0.8, zorder=1)
    return _lines(ax, loops, **{**style, **kwargs})


def draw_known(ax, view: SliceView, upto: int | None = None, scale: float = 1.0) -> dict:
    """The known contour by class (continuous); with ``upto``, only the segments known
    after motion ``upto`` (segments without a logged motion always). {class: collection}."""
    out = {}
    for cls in CLASSES:
        segs = [s.points for s in view.segments
                if s.cls == cls and (upto is None or s.known_at <= upto)]
        coll = _lines(ax, segs, colors=CLASS_COLORS[cls], linewidths=_WIDTH[cls] * scale,
                      zorder=4 + CLASSES.index(cls), capstyle="round")
        if coll is not None:
            out[cls] = coll
    w2 = [s.points.mean(axis=0) for s in view.segments
          if s.cls == "W2" and (upto is None or s.known_at <= upto)]
    if w2:  # a W2 is shorter than eps: a dot makes it visible at the section's scale
        w2 = np.array(w2)
        out["W2 marks"] = ax.scatter(w2[:, 0], w2[:, 1], s=9 * scale, c=CLASS_COLORS["W2"],
                                     zorder=5, linewidths=0)
    return out


def draw_unknown(ax, lids, scale: float = 1.0):
    """Unknown areas A_iB_i as dotted lines (the paper's Figs. 17-18)."""
    return _lines(ax, lids, colors=UNKNOWN_COLOR, linewidths=1.6 * scale,
                  linestyles=(0, (1, 1.5)), zorder=8)


def draw_postures(ax, view: SliceView, every: int = 1):
    """The probe posture after every ``every``-th motion, joint -> tip, thin."""
    if view.log is None or not len(view.log):
        return None
    keep = slice(every - 1, None, every) if every > 1 else slice(None)
    segs = np.stack([view.log.joint1[keep], view.log.tip1[keep]], axis=1)
    segs = segs[np.isfinite(segs).all(axis=(1, 2))]
    return _lines(ax, list(segs), colors=POSTURE_COLOR, linewidths=0.3, alpha=0.25,
                  zorder=2)


def _label_order(view: SliceView) -> list:
    """The areas that ended (not ``split``: their children carry the story), by label
    priority: never touching and still unknown first, then long A_iB_i."""
    first = {"W3": 0, "unknown": 0, "deferred": 1}
    leaves = [r for r in view.areas if r.outcome != "split"]
    return sorted(leaves, key=lambda r: (first.get(r.outcome, 2),
                                         -float(np.linalg.norm(r.b - r.a)), r.index))


def draw_labels(ax, view: SliceView, limit: int = 40, avoid=()) -> list:
    """The A_iB_i labels beside the middle of A_iB_i, on its free side V_i (on the right
    going from B_i to A_i, §3.3), skipping any that would overlap another label or a box
    in ``avoid`` (display-space Bboxes); the labels drawn."""
    renderer = ax.figure.canvas.get_renderer()
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    taken, drawn = list(avoid), []
    for rec in _label_order(view):
        if len(drawn) >= limit:
            break
        mid = 0.5 * (rec.a + rec.b)
        if not (x0 <= mid[0] <= x1 and y0 <= mid[1] <= y1):
            continue
        d = rec.a - rec.b
        side = np.array([d[1], -d[0]]) / max(float(np.linalg.norm(d)), 1e-300)
        text = ax.annotate(f"$A_{{{rec.index}}}B_{{{rec.index}}}$", mid,
                           xytext=tuple(9.0 * side), textcoords="offset points", fontsize=7,
                           ha="center", va="center", zorder=9, color="#222222")
        box = text.get_window_extent(renderer).expanded(1.1, 1.2)
        if any(box.overlaps(other) for other in taken) or not ax.bbox.contains(*box.p0):
            text.remove()
            continue
        taken.append(box)
        drawn.append(text)
    return drawn


def nice_length(span: float) -> float:
    """A round scale-bar length (1, 2 or 5 x 10^k) near a fifth of ``span``.

    >>> nice_length(100.0), nice_length(7.0)
    (20.0, 1.0)
    """
    target = max(span, 1e-12) / 5
    power = 10.0 ** math.floor(math.log10(target))
    return max(m * power for m in (1, 2, 5) if m * power <= target)


def scale_bar(ax, units: str = "mesh units") -> None:
    """A scale bar in the lower right corner of ``ax`` (data units = mesh units)."""
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    length = nice_length(x1 - x0)
    xe, ye = x1 - 0.04 * (x1 - x0), y0 + 0.05 * (y1 - y0)
    ax.plot([xe - length, xe], [ye, ye], color="black", lw=2.5, solid_capstyle="butt",
            zorder=10)
    ax.text(xe - length / 2, ye + 0.015 * (y1 - y0), f"{length:g} {units}", ha="center",
            va="bottom", fontsize=8, zorder=10)


def view_limits(ax, view: SliceView, margin: float = 0.12) -> None:
    """Frame the section (true and sensed) with a ``margin`` share on every side."""
    lo, hi = view.bounds()
    pad = margin * max(float((hi - lo).max()), 1e-9)
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")


def draw_joint_path(ax, view: SliceView, upto: int | None = None, arrows: int = 40):
    """The joint path, coloured by motion index, with arrows for its moving direction
    (about ``arrows`` of them); free transfers through F (:data:`TRANSFER_KINDS`, path
    not logged) as thin dashed chords; the section filled grey. The path collection."""
    log = view.log
    n = len(log) if upto is None else min(len(log), upto + 1)
    segs = np.stack([log.joint0[:n], log.joint1[:n]], axis=1)
    moved = np.isfinite(segs).all(axis=(1, 2)) & (np.linalg.norm(segs[:, 1] - segs[:, 0],
                                                                 axis=1) > 0)
    transfer = np.isin(log.kind[:n], list(TRANSFER_KINDS))
    plt = libs.pyplot()
    for lp in view.section or []:
        ax.fill(lp[:, 0], lp[:, 1], color="#dddddd", zorder=1)
    draw_known(ax, view, upto=upto, scale=0.5)
    _lines(ax, list(segs[moved & transfer]), colors="#999999", linewidths=0.4,
           linestyles=(0, (3, 3)), zorder=2)
    probe = moved & ~transfer
    coll = _lines(ax, list(segs[probe]), cmap=plt.get_cmap(PATH_CMAP), linewidths=0.9,
                  zorder=3)
    top = max(len(log) - 1, 1)
    if coll is not None:
        coll.set_array(log.index[:n][probe].astype(float))
        coll.set_clim(0, top)
        idx = np.flatnonzero(probe)
        pick = idx[np.linspace(0, len(idx) - 1, min(arrows, len(idx))).astype(int)]
        mid = 0.5 * (segs[pick, 0] + segs[pick, 1])
        d = segs[pick, 1] - segs[pick, 0]
        d /= np.linalg.norm(d, axis=1, keepdims=True)
        ax.quiver(mid[:, 0], mid[:, 1], d[:, 0], d[:, 1], log.index[pick].astype(float),
                  cmap=PATH_CMAP, clim=(0, top), angles="xy", pivot="mid", scale=28,
                  width=0.006, headwidth=4, headlength=5, zorder=4)
    joints = np.concatenate([log.joint0, log.joint1])
    joints = joints[np.isfinite(joints).all(axis=1)]
    if len(joints):
        lo, hi = joints.min(axis=0), joints.max(axis=0)
        pad = 0.05 * float((hi - lo).max())
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    return coll


def slice_title(view: SliceView, mesh: str = "", lines: int = 1) -> str:
    """``mesh . slice z 3 (family 0) . method pulling . 1742 motions . coverage 1.000``
    (with ``lines=2``, broken after the slice)."""
    parts = [mesh] if mesh else []
    parts += [f"slice {view.axis} {view.position} (family {view.family})",
              f"method {view.method}", f"{view.motions} motions",
              f"coverage {view.coverage_text()}"]
    if view.log is None:
        parts.append("no motion log")
    if lines == 2:
        head = len(parts) - (4 if view.log is None else 3)
        return "  ·  ".join(parts[:head]) + "\n" + "  ·  ".join(parts[head:])
    return "  ·  ".join(parts)


def legend_handles(classes, unknown: bool, section: bool, postures: bool = False,
                   noisy: bool = False) -> list:
    """Legend handles: ``classes`` (of :data:`CLASSES`), unknown, true section, postures;
    ``noisy``: the run had a sensor model, whose W2 distance is eps + the readings' jitter
    (:attr:`core2d.resolution.Resolution.w2_dist`)."""
    lines = libs.lines()
    names = dict(_CLASS_NAMES, W2=_NOISY_W2) if noisy else _CLASS_NAMES
    out = [lines.Line2D([], [], color=CLASS_COLORS[c], lw=_WIDTH[c], label=names[c],
                        marker="o" if c == "W2" else None, markersize=3)
           for c in classes]
    if unknown:
        out.append(lines.Line2D([], [], color=UNKNOWN_COLOR, lw=1.6, ls=(0, (1, 1.5)),
                                label="unknown $A_iB_i$"))
    if section:
        out.append(lines.Line2D([], [], color=SECTION_COLOR, lw=0.8, label="true section"))
    if postures:
        out.append(lines.Line2D([], [], color=POSTURE_COLOR, lw=1.0, label="probe postures"))
    return out


def legend_entries(view: SliceView, postures: bool) -> list:
    """:func:`legend_handles` of what ``view`` has."""
    return legend_handles(view.present(), bool(view.unknown), bool(view.section), postures,
                          view.coverage_sensor is not None)


def slice_figure(view: SliceView, mesh: str = "", every: int = 1, labels: bool = True):
    """The figure of one slice (module doc): a matplotlib Figure, one or two panels."""
    plt = libs.pyplot()
    two = view.log is not None and len(view.log) > 0
    fig = plt.figure(figsize=(13.0, 6.0) if two else (8.0, 6.0), dpi=110,
                     layout="constrained")
    grid = fig.add_gridspec(1, 2, width_ratios=(1.5, 1.0)) if two else fig.add_gridspec(1, 1)
    ax = fig.add_subplot(grid[0, 0])
    view_limits(ax, view)
    draw_section(ax, view)
    draw_postures(ax, view, every)
    draw_known(ax, view)
    draw_unknown(ax, view.unknown)
    scale_bar(ax)
    postures = "" if not two else (", probe postures" if every == 1 else
                                   f", probe postures (every {every}th)")
    ax.set_title(f"(a) section: known contour, unknown areas{postures}", fontsize=10)
    ax.set_xticks([])
    ax.set_yticks([])
    ax.legend(handles=legend_entries(view, two), loc="upper center", fontsize=8, ncol=3,
              bbox_to_anchor=(0.5, -0.01), frameon=False)
    if two:
        bx = fig.add_subplot(grid[0, 1])
        coll = draw_joint_path(bx, view)
        bx.set_title("(b) workspace: joint path, moving direction", fontsize=10)
        bx.set_xticks([])
        bx.set_yticks([])
        if coll is not None:
            fig.colorbar(coll, ax=bx, fraction=0.046, pad=0.02, label="motion index")
    fig.suptitle(slice_title(view, mesh, lines=1 if two else 2), fontsize=11)
    if labels:
        fig.canvas.draw()  # label extents need the final layout of the axes
        fig.set_layout_engine("none")  # keep that layout while labels are added
        draw_labels(ax, view)
    return fig
