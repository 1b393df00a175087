"""The exploration of one slice, motion by motion: a GIF (Pillow) or an MP4 (ffmpeg).

Each frame shows the state after one motion (every ``stride``-th): panel (a)
the section with the contour known so far growing by class (W1, W2, W3,
§3.1; a segment appears after the motion that recorded it -- with no motion
index logged the final contour is shown throughout, and the title says so),
the current probe posture, the postures since the previous frame, the tip's
contact and the A_iB_i being served, dotted; panel (b) the workspace with the
joint path so far (moving direction by colour: motion index) and the whole
probe. The title names the motion, its kind, the phase of the algorithm
(Fig. 16) and its event (Case 1 ... 4).
"""
from __future__ import annotations

import math
import shutil
import subprocess
from pathlib import Path

import numpy as np

from recon3d.viz import libs
from recon3d.viz.figure2d import (CLASS_COLORS, PATH_CMAP, POSTURE_COLOR, TRANSFER_KINDS,
                                  draw_section, legend_entries, scale_bar, slice_title,
                                  view_limits)
from recon3d.viz.sliceview import CLASSES, SliceView

__all__ = ["MAX_FRAMES", "default_stride", "frame_motions", "write_animation", "FORMATS"]

MAX_FRAMES = 300
"""The default stride keeps an animation at or below this many frames."""
FORMATS = (".gif", ".mp4")


def default_stride(motions: int, max_frames: int = MAX_FRAMES) -> int:
    """The smallest stride giving at most ``max_frames`` frames.

    >>> default_stride(1742), default_stride(40)
    (6, 1)
    """
    return max(1, math.ceil(motions / max_frames))


def frame_motions(motions: int, stride: int) -> np.ndarray:
    """(ceil(motions / stride),) int: the motion index each frame shows the state after
    (every ``stride``-th, the last motion always last).

    >>> frame_motions(10, 4).tolist()
    [3, 7, 9]
    """
    ends = np.arange(stride, motions + stride, stride)
    return np.minimum(ends, motions) - 1


class _Known:
    """The known contour by class as line collections that grow with the motion index."""

    def __init__(self, ax, view: SliceView, scale: float = 1.0):
        coll = libs.collections()
        self.parts = {}
        for cls in CLASSES:
            segs = [s for s in view.segments if s.cls == cls]
            lc = coll.LineCollection([], colors=CLASS_COLORS[cls], zorder=5,
                                     linewidths=(2.4 if cls != "W1" else 2.0) * scale)
            ax.add_collection(lc)
            self.parts[cls] = (lc, [s.points for s in segs],
                               np.array([s.known_at for s in segs], dtype=np.int64))
        _, w2, self.w2_when = self.parts["W2"]  # a W2 is shorter than eps: a dot shows it
        self.w2_at = np.array([p.mean(axis=0) for p in w2]).reshape(-1, 2)
        self.w2 = ax.scatter([], [], s=9 * scale, c=CLASS_COLORS["W2"], zorder=5, linewidths=0)

    def artists(self) -> list:
        return [lc for lc, _, _ in self.parts.values()] + [self.w2]

    def update(self, motion: int) -> None:
        for lc, pts, when in self.parts.values():
            lc.set_segments([p for p, w in zip(pts, when) if w <= motion])
        self.w2.set_offsets(self.w2_at[self.w2_when <= motion])


class _Frames:
    """The figure of an animation and the artists each frame moves."""

    def __init__(self, view: SliceView, mesh: str, stride: int):
        plt, coll = libs.pyplot(), libs.collections()
        self.view, self.log, self.mesh = view, view.log, mesh
        self.fig = fig = plt.figure(figsize=(11.0, 5.4), dpi=80, layout="constrained")
        grid = fig.add_gridspec(1, 2, width_ratios=(1.5, 1.0))
        self.ax, self.bx = ax, bx = fig.add_subplot(grid[0, 0]), fig.add_subplot(grid[0, 1])
        view_limits(ax, view)
        for a in (ax, bx):
            a.set_xticks([])
            a.set_yticks([])
        draw_section(ax, view)
        scale_bar(ax)
        ax.legend(handles=legend_entries(view, True), loc="upper center", fontsize=8, ncol=3,
                  bbox_to_anchor=(0.5, -0.01), frameon=False)
        for lp in view.section or []:
            bx.fill(lp[:, 0], lp[:, 1], color="#dddddd", zorder=1)
        self.known = [_Known(ax, view), _Known(bx, view, scale=0.5)]
        self.trail = coll.LineCollection([], colors=POSTURE_COLOR, linewidths=0.5, alpha=0.6,
                                         zorder=2)
        ax.add_collection(self.trail)
        (self.probe,) = ax.plot([], [], color="#222222", lw=1.6, zorder=7)
        (self.tip,) = ax.plot([], [], "o", color="#222222", ms=4, zorder=8)
        (self.lid,) = ax.plot([], [], color="black", lw=1.6, ls=(0, (1, 1.5)), zorder=6)
        self.lid_label = ax.text(0, 0, "", fontsize=8, zorder=9, ha="center", va="bottom")
        log = self.log
        segs = np.stack([log.joint0, log.joint1], axis=1)
        self.segs = segs
        self.transfer = np.isin(log.kind, list(TRANSFER_KINDS))
        self.path = coll.LineCollection([], cmap=plt.get_cmap(PATH_CMAP), linewidths=0.9,
                                        zorder=3)
        self.path.set_clim(0, max(len(log) - 1, 1))
        self.jumps = coll.LineCollection([], colors="#999999", linewidths=0.4,
                                         linestyles=(0, (3, 3)), zorder=2)
        bx.add_collection(self.path)
        bx.add_collection(self.jumps)
        (self.whole,) = bx.plot([], [], color="#222222", lw=1.0, zorder=6)
        (self.joint,) = bx.plot([], [], "o", color="#222222", ms=4, zorder=7)
        fig.colorbar(self.path, ax=bx, fraction=0.046, pad=0.02, label="motion index")
        joints = np.concatenate([log.joint0, log.joint1, log.tip1])
        joints = joints[np.isfinite(joints).all(axis=1)]
        lo, hi = joints.min(axis=0), joints.max(axis=0)
        pad = 0.05 * float((hi - lo).max())
        bx.set_xlim(lo[0] - pad, hi[0] + pad)
        bx.set_ylim(lo[1] - pad, hi[1] + pad)
        bx.set_aspect("equal")
        bx.set_title("(b) workspace: joint path so far, the probe", fontsize=10)
        self.logged = any(s.known_at >= 0 for s in view.segments)
        ax.set_title("(a) section: contour known so far" if self.logged else
                     "(a) section: final contour (no motion index logged)", fontsize=10)
        self.suptitle = fig.suptitle(f"{slice_title(view, mesh)}\nmotion", fontsize=10)
        fig.canvas.draw()  # lay out once, then keep it: frames differ only in their artists
        fig.set_layout_engine("none")
        self.stride, self.previous = stride, -1
        self.areas = {a.index: a for a in view.areas}

    def moving(self) -> list:
        """The artists a frame changes (drawn over the static background)."""
        known = [a for k in self.known for a in k.artists()]
        return known + [self.trail, self.probe, self.tip, self.lid, self.lid_label, self.path,
                        self.jumps, self.whole, self.joint, self.suptitle]

    def draw(self, motion: int):
        log, k = self.log, motion
        for known in self.known:
            known.update(k)
        lo = self.previous + 1
        self.trail.set_segments(list(np.stack([log.joint1[lo:k + 1], log.tip1[lo:k + 1]],
                                              axis=1)))
        self.previous = k
        pose = np.array([log.joint1[k], log.tip1[k]])
        self.probe.set_data(pose[:, 0], pose[:, 1])
        self.whole.set_data(pose[:, 0], pose[:, 1])
        self.joint.set_data([pose[0, 0]], [pose[0, 1]])
        self.tip.set_data(*(([pose[1, 0]], [pose[1, 1]]) if log.tip_contact[k] else ([], [])))
        rec = self.areas.get(int(log.area[k]))
        if rec is not None:
            ab = np.array([rec.a, rec.b])
            self.lid.set_data(ab[:, 0], ab[:, 1])
            self.lid_label.set_position(tuple(0.5 * (rec.a + rec.b)))
            self.lid_label.set_text(f"$A_{{{rec.index}}}B_{{{rec.index}}}$")
        else:
            self.lid.set_data([], [])
            self.lid_label.set_text("")
        n = k + 1
        moved = np.isfinite(self.segs[:n]).all(axis=(1, 2))
        probe = moved & ~self.transfer[:n]
        self.path.set_segments(list(self.segs[:n][probe]))
        self.path.set_array(log.index[:n][probe].astype(float))
        self.jumps.set_segments(list(self.segs[:n][moved & self.transfer[:n]]))
        what = " ".join(x for x in (str(log.kind[k]), str(log.phase[k]), str(log.event[k]))
                        if x and x != "nan")
        self.suptitle.set_text(f"{slice_title(self.view, self.mesh)}\n"
                               f"motion {k + 1} / {len(log)}: {what}")


def _rgba(fig) -> np.ndarray:
    """(h, w, 4) uint8 copy of the canvas."""
    return np.array(fig.canvas.buffer_rgba())


class _Gif:
    """Frames collected as palette images, saved by Pillow at the end. One palette for
    all (the first frame's, fast octree): the GIF then stores only what changed."""

    def __init__(self, path, fps):
        self.path, self.fps, self.frames, self.palette = path, fps, [], None

    def add(self, rgba):
        pil = libs.pil_image()
        image = pil.fromarray(np.ascontiguousarray(rgba[..., :3]))
        if self.palette is None:
            self.palette = image.quantize(colors=96, method=pil.Quantize.FASTOCTREE)
        self.frames.append(image.quantize(palette=self.palette, dither=pil.Dither.NONE))

    def close(self):
        first, *rest = self.frames
        first.save(self.path, save_all=True, append_images=rest, loop=0, optimize=False,
                   duration=round(1000 / self.fps))


class _Mp4:
    """Raw RGBA frames piped to ffmpeg (H.264, even frame size)."""

    def __init__(self, path, fps, size):
        w, h = size
        self.proc = subprocess.Popen(
            ["ffmpeg", "-loglevel", "error", "-y", "-f", "rawvideo", "-pix_fmt", "rgba",
             "-s", f"{w}x{h}", "-r", str(fps), "-i", "-", "-vf",
             "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt", "yuv420p", str(path)],
            stdin=subprocess.PIPE)

    def add(self, rgba):
        self.proc.stdin.write(rgba.tobytes())

    def close(self):
        self.proc.stdin.close()
        if self.proc.wait() != 0:
            raise ValueError(f"ffmpeg failed (status {self.proc.returncode})")


def write_animation(view: SliceView, path, mesh: str = "", stride: int | None = None,
                    fps: int = 10, progress=None) -> int:
    """Write the animation of ``view`` (which needs a motion log) to ``path``.

    The static part of the figure is drawn once; each frame redraws only what
    moves (blitting), so a frame costs a few milliseconds.

    Parameters
    ----------
    view : SliceView with ``log``.
    path : ``.gif`` (Pillow) or ``.mp4`` (ffmpeg; ValueError when it is not installed).
    stride : int, optional -- motions per frame (default :func:`default_stride`).
    progress : callable(int, int), optional -- told (frame, frames) as frames are drawn.

    Returns
    -------
    int -- the number of frames written.
    """
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in FORMATS:
        raise ValueError(f"an animation is .gif or .mp4, not {path.suffix or 'no suffix'!r}")
    if view.log is None or not len(view.log):
        raise ValueError("no motion log for this slice (motions.csv): nothing to animate")
    if suffix == ".mp4" and shutil.which("ffmpeg") is None:
        raise ValueError("an MP4 needs ffmpeg on PATH (not found); write a .gif instead")
    stride = default_stride(len(view.log)) if stride is None else int(stride)
    motions = frame_motions(len(view.log), stride)
    frames = _Frames(view, mesh, stride)
    fig, canvas = frames.fig, frames.fig.canvas
    moving = frames.moving()
    for artist in moving:
        artist.set_animated(True)
    canvas.draw()
    background = canvas.copy_from_bbox(fig.bbox)
    h, w = _rgba(fig).shape[:2]
    out = _Mp4(path, fps, (w, h)) if suffix == ".mp4" else _Gif(path, fps)
    try:
        for i, k in enumerate(motions):
            frames.draw(int(k))
            canvas.restore_region(background)
            for artist in moving:
                fig.draw_artist(artist)
            out.add(_rgba(fig))
            if progress is not None:
                progress(i + 1, len(motions))
        out.close()
    finally:
        libs.pyplot().close(fig)
    return len(motions)
