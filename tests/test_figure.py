"""The 2D pictures of a run: ``recon3d figure`` (one slice, its animation) and ``slices.png``.

Runs of fig17_pocket (W1, W2, no W3) and fig18_overhangs (W1, W2, W3: never touching
areas under the overhangs, the paper's Fig. 18) on two slices, with the motion log each
run writes (``motions.csv``).
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

import recon3d
from recon3d.cli.main import main
from recon3d.io.motions import read_log
from recon3d.viz import animate, figure2d, libs, multiples, rundata
from recon3d.viz.sliceview import Segment, SliceView, slice_views

def _run(tmp_path_factory, scene, png):
    out = tmp_path_factory.mktemp(scene) / "run"
    recon3d.run(scene, slices=2, jobs=1).save(out, png=png)
    assert (out / "motions.csv").is_file()
    return out


@pytest.fixture(scope="module")
def fig18(tmp_path_factory):
    return _run(tmp_path_factory, "fig18_overhangs", png=True)


@pytest.fixture(scope="module")
def fig17(tmp_path_factory):
    return _run(tmp_path_factory, "fig17_pocket", png=False)


def _rgb(path):
    from matplotlib.image import imread

    img = imread(path)
    return (img[..., :3] * 255).round().astype(int)


def _has_colour(rgb, colour, tol=12) -> int:
    """Pixels within ``tol`` (per channel) of the ``#rrggbb`` colour."""
    target = np.array([int(colour[k:k + 2], 16) for k in (1, 3, 5)])
    return int((np.abs(rgb - target) <= tol).all(axis=-1).sum())


def _classes_in(run, position):
    sensing = json.loads((run / "sensing.json").read_text())
    return {s["class"] for s in sensing["slices"][position]["segments"]}


@pytest.mark.parametrize("scene", ["fig17", "fig18"])
def test_the_figure_shows_every_class_present_and_no_other(scene, request, tmp_path):
    run = request.getfixturevalue(scene)
    png = tmp_path / "f.png"
    assert main(["figure", str(run), "--slice", "1", "--out", str(png)]) == 0
    assert (_rgb(png) < 240).any(axis=-1).mean() > 0.03  # not blank
    present = _classes_in(run, 1)
    assert "W1" in present
    assert ("W3" in present) == (scene == "fig18")  # the scenes are what the test needs
    sensing, views = rundata.read_views(run)
    view = rundata.attach_sections(views[1:2], sensing, run)[0]
    fig = figure2d.slice_figure(view, "m")
    fig.canvas.draw()
    rgb = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)
    (x0, y0), (x1, y1) = fig.axes[0].bbox.get_points()  # panel (a) only: not the legend
    h = rgb.shape[0]
    panel = rgb[int(h - y1) + 2:int(h - y0) - 2, int(x0) + 2:int(x1) - 2]
    for cls, colour in figure2d.CLASS_COLORS.items():
        found = _has_colour(panel, colour)
        assert (found > 20) == (cls in present), (cls, found, present)
    libs.pyplot().close(fig)


def test_the_figure_says_when_there_is_no_motion_log(fig17, tmp_path):
    sensing, views = rundata.read_views(fig17)
    view = views[0]
    fig = figure2d.slice_figure(view, "m")
    assert len(fig.axes) == 1 and "no motion log" in fig._suptitle.get_text()
    libs.pyplot().close(fig)
    rundata.attach_log(view, read_log(fig17))
    fig = figure2d.slice_figure(view, "m")
    assert len(fig.axes) == 3 and "no motion log" not in fig._suptitle.get_text()  # + colorbar
    libs.pyplot().close(fig)


def test_the_true_section_is_recomputed_in_the_slice_frame(fig18):
    sensing, views = rundata.read_views(fig18)
    rundata.attach_sections(views, sensing, fig18)
    for view in views:
        a = np.concatenate([lp for lp in view.section])
        b = np.concatenate([np.roll(lp, -1, axis=0) for lp in view.section])
        w1 = np.concatenate([s.points for s in view.segments if s.cls == "W1"])
        # distance of every traced point to the nearest edge of the true section
        ab, ap = b - a, w1[:, None, :] - a[None]
        t = np.clip((ap * ab).sum(-1) / np.maximum((ab * ab).sum(-1), 1e-300), 0, 1)
        d = np.linalg.norm(ap - t[..., None] * ab, axis=-1).min(axis=1)
        assert d.max() < sensing["eps"]  # traced points lie on the true section


def test_labels_never_overlap_and_some_are_skipped(fig18):
    sensing, views = rundata.read_views(fig18)
    view = views[1]
    fig = figure2d.slice_figure(view, "m", labels=False)
    ax = fig.axes[0]
    fig.canvas.draw()
    drawn = figure2d.draw_labels(ax, view, limit=1000)
    renderer = fig.canvas.get_renderer()
    boxes = [t.get_window_extent(renderer) for t in drawn]
    assert len(drawn) >= 5
    assert len(drawn) < sum(a.outcome != "split" for a in view.areas)  # crowded: some skipped
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:]:
            assert not a.overlaps(b)
    libs.pyplot().close(fig)


@pytest.mark.parametrize("argv, message", [
    (["figure", "{missing}", "--slice", "0", "--out", "{tmp}/f.png"], "is not a directory"),
    (["figure", "{run}", "--slice", "2", "--out", "{tmp}/f.png"], "family 0 has 2 slices"),
    (["figure", "{run}", "--slice", "-1", "--out", "{tmp}/f.png"], "family 0 has 2 slices"),
    (["figure", "{run}", "--slice", "0", "--family", "1", "--out", "{tmp}/f.png"],
     "the run has families 0"),
    (["figure", "{run}", "--slice", "0", "--out", "{tmp}/f.jpg"], "one of .png, .svg, .pdf"),
    (["figure", "{run}", "--slice", "0", "--out", "{tmp}/f.png", "--animate"],
     "one of .gif, .mp4"),
    (["figure", "{run}", "--slice", "0", "--out", "{tmp}/no/f.png"], "no directory"),
    (["figure", "{run}", "--slice", "0", "--out", "{tmp}/f.png", "--every", "0"],
     "must be at least 1"),
    (["figure", "{empty}", "--slice", "0", "--out", "{tmp}/f.png"], "no sensing.json"),
])
def test_bad_input_is_one_line_and_status_2(fig17, tmp_path, capsys, argv, message):
    (tmp_path / "empty").mkdir()
    argv = [a.format(run=fig17, tmp=tmp_path, missing=tmp_path / "nope",
                     empty=tmp_path / "empty") for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err and "Traceback" not in err
    assert not list(tmp_path.glob("f.*"))  # nothing written


def test_mp4_without_ffmpeg_is_a_clear_error(fig17, tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(animate.shutil, "which", lambda name: None)
    assert main(["figure", str(fig17), "--slice", "0", "--out", str(tmp_path / "f.mp4"),
                 "--animate"]) == 2
    assert "needs ffmpeg" in capsys.readouterr().err
    assert not (tmp_path / "f.mp4").exists()


def test_animation_without_a_motion_log_is_refused(fig17, tmp_path, capsys):
    run = tmp_path / "run"
    run.mkdir()
    for name in ("sensing.json", "metrics.json"):
        (run / name).write_bytes((fig17 / name).read_bytes())
    assert main(["figure", str(run), "--slice", "0", "--out", str(tmp_path / "a.gif"),
                 "--animate"]) == 2
    assert "no motion log" in capsys.readouterr().err


@pytest.mark.parametrize("stride", [None, 16])
def test_the_gif_has_one_frame_per_stride_motions(fig17, tmp_path, stride):
    from PIL import Image

    gif = tmp_path / "a.gif"
    extra = [] if stride is None else ["--stride", str(stride)]
    assert main(["figure", str(fig17), "--slice", "1", "--out", str(gif), "--animate"]
                + extra) == 0
    _, views = rundata.read_views(fig17)
    n = len(rundata.attach_log(views[1], read_log(fig17)).log)
    step = animate.default_stride(n) if stride is None else stride
    with Image.open(gif) as im:
        assert im.n_frames == math.ceil(n / step)
        assert im.n_frames <= animate.MAX_FRAMES


def test_default_stride_keeps_an_animation_within_max_frames():
    for n in (1, 299, 300, 301, 1742, 100000):
        s = animate.default_stride(n)
        assert len(animate.frame_motions(n, s)) <= animate.MAX_FRAMES
        assert s == 1 or len(animate.frame_motions(n, s - 1)) > animate.MAX_FRAMES
    assert animate.frame_motions(7, 3).tolist() == [2, 5, 6]


def _toy_view():
    square = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])
    segs = [Segment("W1", square[[0, 1]], 2), Segment("W1", square[[1, 2]], 9),
            Segment("W2", square[[2, 3]], 5), Segment("W3", square[[3, 0]], -1)]
    return SliceView(family=0, position=0, index=0, axis="z", segments=segs, unknown=[],
                     areas=[], section=[square], motions=12, coverage=1.0)


def test_unknown_areas_are_drawn_dotted_only_when_there_are_some():
    plt = libs.pyplot()
    view = _toy_view()
    for lids in ([], [np.array([[0.0, 5.0], [5.0, 10.0]])]):
        view.unknown = lids
        fig = figure2d.slice_figure(view, "m", labels=False)
        ax = fig.axes[0]
        dotted = [c for c in ax.collections
                  if c.get_linestyle()[0][1] is not None and len(c.get_segments())]
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        assert len(dotted) == len(lids)
        assert any("unknown" in t for t in labels) == bool(lids)
        plt.close(fig)


def test_a_noisy_run_says_its_tolerances_in_the_figures():
    """With a sensor model the W2 label names the jitter (its W2 distance), the title and the
    caption lead with the coverage within eps/2 + 2 sigma; without one, the paper's words."""
    from recon3d.viz.multiples import _caption

    plt = libs.pyplot()
    for sensor, w2, cov in ((None, "W2 Dist(A,B) < eps", "coverage 1.000"),
                            (0.97, "W2 Dist(A,B) < eps + jitter",
                             "coverage 0.970 within eps/2 + 2 sigma (1.000 within eps/2)")):
        view = _toy_view()
        view.coverage_sensor = sensor
        fig = figure2d.slice_figure(view, "m", labels=False)
        labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
        assert w2 in labels and cov in figure2d.slice_title(view)
        assert _caption(view).endswith("cov 1.000" if sensor is None else "cov 0.970 (eps/2+2σ)")
        plt.close(fig)


def test_the_animated_contour_grows_with_the_motion_index():
    plt = libs.pyplot()
    fig, ax = plt.subplots()
    known = animate._Known(ax, _toy_view())
    shown = {}
    for k in (0, 5, 9):
        known.update(k)
        shown[k] = {cls: len(lc.get_segments()) for cls, (lc, _, _) in known.parts.items()}
    assert shown[0] == {"W1": 0, "W2": 0, "W3": 1}  # not logged (-1): shown throughout
    assert shown[5] == {"W1": 1, "W2": 1, "W3": 1}
    assert shown[9] == {"W1": 2, "W2": 1, "W3": 1}
    plt.close(fig)


def test_slices_png_has_one_panel_per_slice(fig18):
    assert (fig18 / "slices.png").is_file()
    sensing = json.loads((fig18 / "sensing.json").read_text())
    metrics = json.loads((fig18 / "metrics.json").read_text())
    views = slice_views(sensing, metrics)
    rundata.attach_sections(views, sensing, fig18)
    fig = multiples.multiples_figure(views, "t")
    fig.canvas.draw()
    ax = fig.axes[0]
    captions = [t.get_text() for t in ax.texts if "motions" in t.get_text()]
    assert captions == [f"z {v.position}: {v.motions} motions, cov {v.coverage:.3f}"
                        for v in views]
    rgb = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)
    target = np.array([int(figure2d.CLASS_COLORS["W1"][k:k + 2], 16) for k in (1, 3, 5)])
    blue = (np.abs(rgb - target) <= 12).all(axis=-1)
    h = rgb.shape[0]
    for view, shift, _ in multiples._layout(views)[0]:
        (x0, y0), (x1, y1) = ax.transData.transform(view.bounds() + shift)
        cell = blue[int(h - y1):int(h - y0) + 1, int(x0):int(x1) + 1]
        assert cell.sum() > 50, view.position  # each slice drawn in its own panel
    libs.pyplot().close(fig)
    with pytest.raises(AssertionError):  # the check above can fail: an empty cell
        assert blue[:5, :5].sum() > 50


def test_no_png_writes_no_slices_png(fig17):
    assert not (fig17 / "slices.png").exists() and not (fig17 / "coverage.png").exists()
