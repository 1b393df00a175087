"""The coverage picture: two pyvista panels drawn from a scene multiblock.

(a) the reconstructed surface coloured by face label, the sensed slice
curves coloured W1/W2/W3/unknown, and the ground truth as a translucent
ghost; (b) the ground truth coloured touched / reachable but missed /
unreachable (outside the slab in light grey). Integer codes are mapped to
colours explicitly (string categories would be coloured alphabetically).
"""
from __future__ import annotations

import ctypes
import ctypes.util
import functools
import os
from pathlib import Path

import numpy as np

from recon3d.records import COVERAGE_CLASSES, CURVE_CLASSES, LABELS
from recon3d.viz import libs

__all__ = ["LABEL_COLORS", "CURVE_COLORS", "COVERAGE_COLORS", "VIEW", "hex_rgb",
           "prepare_offscreen", "coverage_plotter", "save_png", "has_display"]

LABEL_COLORS = {1: "#4c8fd6", 2: "#3cb44b", 3: "#e6194b", 4: "#cfcfcf", 5: "#c9a36b"}
CURVE_COLORS = {1: "#08306b", 2: "#00441b", 3: "#a50f15", 4: "#ff7f0e"}
COVERAGE_COLORS = {0: "#e8e8e8", 1: "#2ca02c", 2: "#ff7f0e", 3: "#6a51a3"}


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


def _legend(plotter, entries, size):
    """A legend box with black text (vtkLegendBoxActor colours text like the symbol)."""
    legend = plotter.add_legend([[name, color] for name, color in entries], bcolor="white",
                                face="rectangle", size=size, loc="upper left", border=True)
    for i in range(legend.GetNumberOfEntries()):
        legend.SetEntryColor(i, 0.0, 0.0, 0.0)
        legend.SetEntrySymbol(i, _swatch(entries[i][1]))
    return legend


def _swatch(color):
    """A filled square in ``color`` as a legend symbol (vtkPolyData with colours)."""
    pv = libs.pyvista()
    sq = pv.Rectangle([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]]).triangulate()
    sq.cell_data["rgb"] = np.tile((255 * np.array(hex_rgb(color))).astype(np.uint8),
                                  (sq.n_cells, 1))
    return sq


VIEW = (0.45, 0.6, 1.0)
"""Camera direction (towards the camera) of both panels; +y is up (the scenes' convention)."""


def _split(mesh, array, codes):
    """(cells whose ``array`` is in ``codes``, the other cells), as two meshes."""
    keep = np.isin(mesh.cell_data[array], list(codes))
    return mesh.extract_cells(np.flatnonzero(keep)), mesh.extract_cells(np.flatnonzero(~keep))


def _panel_a(p, surf, gt, curves, title):
    p.add_text(f"(a) reconstruction {title}".rstrip(), font_size=14, color="black")
    entries = []
    if surf.n_cells:
        caps, body = _split(surf, "label", {5})
        if body.n_cells:
            _categorical(p, body, "label", LABEL_COLORS, ambient=0.25)
        if caps.n_cells:  # see-through: caps are where a slab ends, not object surface
            _categorical(p, caps, "label", LABEL_COLORS, ambient=0.25, opacity=0.35)
        present = set(np.unique(surf.cell_data["label"]).tolist())
        entries = [(f"{c} {LABELS[c]}", LABEL_COLORS[c]) for c in sorted(LABELS) if c in present]
    if gt.n_cells:
        p.add_mesh(gt, color="#9a9a9a", opacity=0.08, style="surface")
    if curves.n_cells:
        _categorical(p, curves, "class", CURVE_COLORS, line_width=2)
        seen = set(np.unique(curves.cell_data["class"]).tolist())
        entries += [(f"curve {CURVE_CLASSES[c]}", CURVE_COLORS[c]) for c in sorted(seen)]
    entries.append(("ground truth (ghost)", "#9a9a9a"))
    _legend(p, entries, (0.24, 0.3))


def _panel_b(p, gt):
    p.add_text("(b) ground truth coverage", font_size=14, color="black")
    if not gt.n_cells:
        return
    outside, inside = _split(gt, "coverage", {0})
    if inside.n_cells:
        _categorical(p, inside, "coverage", COVERAGE_COLORS, ambient=0.25)
    if outside.n_cells:
        _categorical(p, outside, "coverage", COVERAGE_COLORS, ambient=0.25, opacity=0.3)
    shown = set(np.unique(gt.cell_data["coverage"]).tolist())
    _legend(p, [(COVERAGE_CLASSES[c], COVERAGE_COLORS[c]) for c in sorted(shown)],
            (0.24, 0.14))


def coverage_plotter(blocks, title: str = "", off_screen: bool = True,
                     window_size=(1600, 800)):
    """A two-panel ``pyvista.Plotter`` of a scene (see module doc).

    Caps and the ground truth outside the slab are drawn see-through, so the
    sensed part shows through the slab ends.

    Parameters
    ----------
    blocks : pyvista.MultiBlock -- :func:`recon3d.viz.blocks.scene_blocks` or a read ``scene.vtm``.
    title : str -- shown above panel (a).
    off_screen : bool
    window_size : (2,) int
    """
    pv = libs.pyvista()
    gt, surf, curves = blocks["ground_truth"], blocks["surface"], blocks["curves"]
    p = pv.Plotter(shape=(1, 2), off_screen=off_screen, window_size=list(window_size),
                   border=False)
    p.set_background("white")
    p.subplot(0, 0)
    _panel_a(p, surf, gt, curves, title)
    p.subplot(0, 1)
    _panel_b(p, gt)
    p.link_views()
    p.view_vector(VIEW, viewup=(0.0, 1.0, 0.0))
    p.camera.zoom(0.8)
    _pan_down(p.camera, 0.12)
    return p


def _pan_down(camera, share: float) -> None:
    """Move the picture down by ``share`` of the view height (room for the legends)."""
    up = np.asarray(camera.up, dtype=float)
    pos, focal = np.asarray(camera.position), np.asarray(camera.focal_point)
    height = 2.0 * np.linalg.norm(pos - focal) * np.tan(np.radians(camera.view_angle) / 2)
    shift = share * height * up / np.linalg.norm(up)
    camera.position = tuple(pos + shift)
    camera.focal_point = tuple(focal + shift)


def save_png(blocks, path, title: str = "", window_size=(1600, 800)) -> None:
    """Render :func:`coverage_plotter` offscreen to ``path`` (PNG)."""
    prepare_offscreen()
    p = coverage_plotter(blocks, title=title, off_screen=True, window_size=window_size)
    try:
        p.screenshot(str(path))
    finally:
        p.close()
