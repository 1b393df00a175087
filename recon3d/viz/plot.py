"""The coverage picture: two pyvista panels and a headline drawn from a scene multiblock.

(a) the reconstructed surface coloured by face label, the sensed slice
curves coloured W1/W2/W3/unknown on top, and an arrow per slicing axis;
(b) the ground truth coloured by its distance to the scored surface, in %
of the diagonal (the F-score's tau at 1% and 2% are bin edges of the colour
bar), with the ground truth outside the slab see-through grey and the
ground truth inside a hole of the section (no rod in the slice plane reaches
it) in its own colour. Below both: the headline scores of the run. Both
panels share one camera fitted to the object (:func:`recon3d.viz.view.fit_view`)
and carry an axis triad. Integer codes are mapped to colours explicitly
(string categories would be coloured alphabetically).
"""
from __future__ import annotations

import ctypes
import ctypes.util
import functools
import os
import textwrap
from pathlib import Path

import numpy as np

from recon3d.records import COVERAGE_CLASSES, CURVE_CLASSES, LABELS
from recon3d.viz import libs
from recon3d.viz.view import fit_view, frame

__all__ = ["LABEL_COLORS", "CURVE_COLORS", "OUTSIDE_COLOR", "HOLE_COLOR", "NARROW_COLOR", "DISTANCE_COLORS",
           "load_plotting", "DISTANCE_MAX", "WIDTH", "HEADLINE_ROWS", "headline_rows", "hex_rgb",
           "prepare_offscreen", "coverage_plotter",
           "save_png", "has_display"]

LABEL_COLORS = {1: "#3a7fd5", 2: "#4daf4a", 3: "#e41a1c", 4: "#d4d4d4", 5: "#c9a36b"}
"""Face label -> colour of panel (a)."""
CURVE_COLORS = {1: "#000000", 2: "#a6611a", 3: "#ffd92f", 4: "#ff00ff"}
"""Curve class -> colour: black W1 lines on the blue W1 faces, magenta unknown chords."""
OUTSIDE_COLOR, HOLE_COLOR, NARROW_COLOR = "#bdbdbd", "#2b8cbe", "#de77ae"
"""Panel (b): ground truth outside the slab (see-through), inside a hole of the section, in an
opening narrower than eps (closed by W2 by design, §3.1)."""
DISTANCE_COLORS = ("#1a9850", "#91cf60", "#fee08b", "#fc8d59", "#d73027", "#a50026")
"""Bins of 0.5% of the diagonal from 0 to DISTANCE_MAX; beyond it ``DISTANCE_ABOVE``."""
DISTANCE_MAX, DISTANCE_ABOVE = 3.0, "#40004b"
WIDTH = 140
"""Characters of a headline line in the picture (longer lines wrap, indented)."""
HEADLINE_ROWS = 8
"""Rows the headline panel holds at font size 9; more rows shrink the font to fit (as many
more rows as the type is smaller, down to size 4)."""
CHAR = 0.0125
"""Width of a legend character at font size 9, as a share of a panel 800 pixels wide (measured
0.0115 on the pictures, rounded up)."""


def has_display() -> bool:
    """True where an interactive window can open (X11 or Wayland on Linux).

    A ``DISPLAY`` is opened (and closed) with Xlib first, so one that is set
    but unreachable (no X server there) counts as no display; without libX11
    there is no X display either.
    """
    if os.name == "nt" or os.uname().sysname == "Darwin":
        return True
    wayland = os.environ.get("WAYLAND_DISPLAY")
    if wayland and Path(os.environ.get("XDG_RUNTIME_DIR", "/nonexistent"), wayland).exists():
        return True
    display = os.environ.get("DISPLAY")
    return bool(display) and _x_display_opens(display)


@functools.lru_cache(maxsize=8)
def _x_display_opens(display: str) -> bool:
    """Whether Xlib can open ``display`` (libX11 through ctypes; False without it)."""
    lib = ctypes.util.find_library("X11")
    if lib is None:
        return False
    try:
        x11 = ctypes.CDLL(lib)
    except OSError:
        return False
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
    handle = x11.XOpenDisplay(display.encode())
    if not handle:
        return False
    x11.XCloseDisplay(handle)
    return True


def prepare_offscreen() -> None:
    """Without a display, ask VTK for an EGL window (before VTK renders anything)."""
    if not has_display():
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")


def load_plotting() -> None:
    """Import pyvista's plotting (its slowest part) ahead of drawing, off screen."""
    prepare_offscreen()
    libs.pyvista_plotting()


def hex_rgb(color: str) -> tuple[float, float, float]:
    """``"#rrggbb"`` -> (3,) float RGB in [0, 1], as matplotlib's ``to_rgb`` gives it (without
    loading matplotlib, which a run that draws no chart does not need).

    >>> hex_rgb("#ff7f00")
    (1.0, 0.4980392156862745, 0.0)
    """
    if len(color) != 7 or color[0] != "#":
        raise ValueError(f"not a #rrggbb colour: {color!r}")
    return tuple(int(color[k:k + 2], 16) / 255 for k in (1, 3, 5))


def _categorical(plotter, mesh, array, colors, **kwargs):
    """Add ``mesh`` with each cell painted the colour of its integer code in ``array``."""
    codes = np.asarray(mesh.cell_data[array])
    table = np.zeros((max(colors) + 1, 3))
    for code, color in colors.items():
        table[code] = hex_rgb(color)
    rgb = (255 * table[np.clip(codes, 0, len(table) - 1)]).astype(np.uint8)
    plotter.add_mesh(mesh, scalars=rgb, rgb=True, preference="cell", **kwargs)


def _legend(plotter, entries, top: float = 0.89, step: float = 0.04) -> tuple:
    """A legend in the panel's top-left corner: per entry a swatch (a text box of spaces on a
    background of the colour, edged in grey), a gap, then black text. Returns the rectangle
    it takes (x0, x1, y0, y1, shares of the panel; :data:`CHAR` per character of text)."""
    if not entries:
        return ()
    for k, (name, color) in enumerate(entries):
        y = top - step * k
        swatch = plotter.add_text("    ", position=(0.02, y), viewport=True, font_size=9)
        prop = swatch.GetTextProperty()
        prop.SetBackgroundColor(*hex_rgb(color))
        prop.SetBackgroundOpacity(1.0)
        prop.SetFrame(True)
        prop.SetFrameColor(0.45, 0.45, 0.45)
        plotter.add_text(name, position=(0.075, y), viewport=True, font_size=9, color="black")
    width = 0.085 + CHAR * max(len(name) for name, _ in entries)
    return ((0.0, width, top - step * (len(entries) - 1) - 0.015, 1.0),)


def _split(mesh, array, codes):
    """(cells whose ``array`` is in ``codes``, the other cells), as two meshes."""
    keep = np.isin(mesh.cell_data[array], list(codes))
    return mesh.extract_cells(np.flatnonzero(keep)), mesh.extract_cells(np.flatnonzero(~keep))


def _arrows(p, blocks, bounds):
    """One arrow per slicing axis beside the object, labelled ``slices along z``; returns
    (n, 3) float: each arrow's start and label point (the camera keeps them in view)."""
    pv = libs.pyvista()
    normals = np.asarray(blocks.field_data["normals"], dtype=float).reshape(-1, 3) \
        if "normals" in blocks.field_data.keys() else np.zeros((0, 3))
    axes = [str(a) for a in blocks.field_data["axes"]] if "axes" in blocks.field_data.keys() \
        else []
    lo, hi = np.asarray(bounds[::2]), np.asarray(bounds[1::2])
    size = float(np.linalg.norm(hi - lo))
    ends = []
    for n, name in zip(normals, axes):
        start = lo - 0.06 * size * (1.0 - np.abs(n))
        p.add_mesh(pv.Arrow(start=start, direction=n, scale=0.35 * size, shaft_radius=0.025,
                            tip_radius=0.07), color="#202020")
        p.add_point_labels([start + 0.37 * size * n], [f"slicing axis {name}"], font_size=12,
                           text_color="black", shape_color="white", shape_opacity=0.7,
                           show_points=False, always_visible=True)
        ends += [start, start + 0.37 * size * n]
    return np.asarray(ends, dtype=np.float64).reshape(-1, 3)


def _panel_a(p, blocks):
    surf, curves = blocks["surface"], blocks["curves"]
    p.add_text("(a) reconstructed surface, by face label", font_size=11, color="black",
               position="upper_edge")
    entries = []
    if surf.n_cells:
        caps, body = _split(surf, "label", {5})
        if body.n_cells:
            _categorical(p, body, "label", LABEL_COLORS, ambient=0.25)
        if caps.n_cells:  # see-through: caps are where a slab ends, not object surface
            _categorical(p, caps, "label", LABEL_COLORS, ambient=0.25, opacity=0.35)
        present = set(np.unique(surf.cell_data["label"]).tolist())
        entries = [(f"face: {LABELS[c]}", LABEL_COLORS[c]) for c in sorted(LABELS)
                   if c in present]
    if curves.n_cells:
        _categorical(p, curves, "class", CURVE_COLORS, line_width=2)
        seen = set(np.unique(curves.cell_data["class"]).tolist())
        entries += [(f"slice curve: {CURVE_CLASSES[c]}", CURVE_COLORS[c]) for c in sorted(seen)]
    taken = _legend(p, entries)
    return taken, _arrows(p, blocks, blocks.bounds)


def _panel_b(p, gt):
    pv = libs.pyvista()
    p.add_text("(b) ground truth, by distance to the surface", font_size=11, color="black",
               position="upper_edge")
    if not gt.n_cells:
        return ()
    outside, inside = _split(gt, "coverage", {0})
    hole, rest = _split(inside, "coverage", {4})
    narrow, scored = _split(rest, "coverage", {5})
    entries = []
    if scored.n_cells and "distance" in scored.point_data.keys():
        p.add_mesh(scored, scalars="distance", cmap=list(DISTANCE_COLORS), clim=[0, DISTANCE_MAX],
                   n_colors=len(DISTANCE_COLORS), above_color=DISTANCE_ABOVE, ambient=0.25,
                   show_scalar_bar=False)
        title = p.add_text("distance to the surface, % of the diagonal (F@1% counts < 1)",
                           position=(0.2, 0.135), viewport=True, font_size=9, color="black")
        bar = p.add_scalar_bar(" ", n_labels=7, fmt="%.1f", vertical=False, color="black",
                               position_x=0.2, position_y=0.04, width=0.6, height=0.08,
                               title_font_size=14, label_font_size=13, above_label="> 3")
        _white_behind(title, bar)
        entries.append(("beyond 3% of the diagonal", DISTANCE_ABOVE))
    elif scored.n_cells:
        p.add_mesh(scored, color="#9a9a9a", ambient=0.25)
    if hole.n_cells:
        p.add_mesh(hole, color=HOLE_COLOR, ambient=0.25)
        entries.append(("inside a hole (no rod in the slice plane reaches it)", HOLE_COLOR))
    if narrow.n_cells:
        p.add_mesh(narrow, color=NARROW_COLOR, ambient=0.25)
        entries.append(("in an opening narrower than eps (W2 by design)", NARROW_COLOR))
    if outside.n_cells:
        p.add_mesh(outside, color=OUTSIDE_COLOR, opacity=0.3)
        entries.append(("outside the slab (not scored)", OUTSIDE_COLOR))
    return _legend(p, entries)


def _white_behind(text, bar) -> None:
    """A white backing behind the colour bar and its title, so that a part of the object
    drawn under them does not run through their text."""
    prop = text.GetTextProperty()
    prop.SetBackgroundColor(1.0, 1.0, 1.0)
    prop.SetBackgroundOpacity(0.85)
    bar.DrawBackgroundOn()
    bar.GetBackgroundProperty().SetColor(1.0, 1.0, 1.0)
    bar.GetBackgroundProperty().SetOpacity(0.85)


def headline_rows(lines, width: int = WIDTH) -> list[str]:
    """The headline's lines wrapped at ``width`` characters, nothing cut.

    A continuation row is indented four spaces past its line's own indent.

    >>> headline_rows(["  abc def ghi", ""], width=9)
    ['  abc def', '      ghi']
    """
    rows = []
    for line in (str(s) for s in lines):
        if not line.strip():
            continue
        lead = " " * (len(line) - len(line.lstrip()))
        rows += textwrap.wrap(line.strip(), width, initial_indent=lead, subsequent_indent=lead + "    ",
                              break_long_words=True, break_on_hyphens=False) \
            if len(line) > width else [line]
    return rows


def _headline(p, blocks, title):
    lines = [str(s) for s in blocks.field_data["headline"]] \
        if "headline" in blocks.field_data.keys() else []
    size, rows = 9, headline_rows(lines) or [title]
    def room(size):  # rows the panel holds at that size (smaller type: a row's margin less)
        return int(HEADLINE_ROWS * 9 / size) - (size < 9)

    while size > 4 and len(rows) > room(size):  # smaller type, wider rows:
        size -= 1                               # everything stays in the panel
        rows = headline_rows(lines, int(WIDTH * 9 / size)) or [title]
    fits = room(size)
    if len(rows) > fits:  # even the smallest type cannot hold it: say what is left out
        rows = rows[:fits - 1] + [f"... and {len(rows) - fits + 1} more rows: see the summary "
                                  "and metrics.json"]
    p.add_text("\n".join(rows), position=(0.01, 0.04), viewport=True, font_size=size,
               color="black", font="courier")


def coverage_plotter(blocks, title: str = "", off_screen: bool = True,
                     window_size=(1600, 800)):
    """The two panels and the headline of a scene (module doc) as a ``pyvista.Plotter``.

    Parameters
    ----------
    blocks : pyvista.MultiBlock -- :func:`recon3d.viz.blocks.scene_blocks` or a read ``scene.vtm``.
    title : str -- the headline when the scene carries none.
    off_screen : bool
    window_size : (2,) int
    """
    pv = libs.pyvista()
    p = pv.Plotter(shape=(2, 2), groups=[(1, np.s_[:])], row_weights=[4, 1],
                   off_screen=off_screen, window_size=list(window_size), border=False)
    p.set_background("white")
    p.subplot(0, 0)
    taken, arrows = _panel_a(p, blocks)
    p.add_axes(color="black", line_width=3, viewport=(0.0, 0.0, 0.14, 0.2))
    p.subplot(0, 1)
    taken += _panel_b(p, blocks["ground_truth"])
    p.add_axes(color="black", line_width=3, viewport=(0.0, 0.0, 0.14, 0.2))
    p.subplot(1, 0)
    _headline(p, blocks, title)
    p.subplot(0, 0)
    p.link_views((0, 1))
    direction, up, _ = fit_view(np.asarray(blocks["ground_truth"].bounds).reshape(3, 2).T
                                if blocks["ground_truth"].n_cells else
                                np.asarray(blocks.bounds).reshape(3, 2).T)
    p.view_vector(direction, viewup=up)
    p.reset_camera()
    aspect = (window_size[0] / 2) / (window_size[1] * 4 / 5)  # a 3D panel: half wide, 4/5 high
    _fit_free(p.camera, np.r_[_drawn_points(blocks), arrows], aspect,
              taken)  # the views are linked: both panels' legends keep out
    return p


def _drawn_points(blocks, most: int = 20000) -> np.ndarray:
    """(n, 3) float: points of what the panels draw (every k-th, at most about ``most``)."""
    parts = [np.asarray(blocks[name].points) for name in ("ground_truth", "surface")
             if name in blocks.keys() and blocks[name] is not None and blocks[name].n_points]
    pts = np.concatenate(parts) if parts else np.asarray(blocks.bounds).reshape(3, 2).T
    return pts[::max(1, len(pts) // most)]


def _fit_free(camera, points, aspect: float, keep_out=()) -> None:
    """Zoom and shift the picture so that ``points`` fill the panels' free part
    (:data:`recon3d.viz.view.FREE`: above the colour bar, below the titles) clear of
    ``keep_out`` (the legends)."""
    m = np.array([[camera.GetCompositeProjectionTransformMatrix(aspect, -1, 1).GetElement(i, j)
                   for j in range(4)] for i in range(4)])
    h = np.c_[points, np.ones(len(points))] @ m.T
    zoom, center = frame(h[:, :2] / h[:, 3:], keep_out=keep_out)
    camera.zoom(zoom)
    camera.SetWindowCenter(*center)


def save_png(blocks, path, title: str = "", window_size=(1600, 800)) -> None:
    """Render :func:`coverage_plotter` offscreen to ``path`` (PNG)."""
    prepare_offscreen()
    p = coverage_plotter(blocks, title=title, off_screen=True, window_size=window_size)
    try:
        p.screenshot(str(path))
    finally:
        p.close()
