"""Honest totals: shares of the ground truth, reachable F@1% over the reachable part,
per-family scores, unknown chords located, no negative zero, the camera fit."""
import numpy as np
import pytest
import trimesh

import recon3d
from recon3d.score.evaluate import ContourCloud, Domain, GroundTruthSamples, surface_metrics
from recon3d.score.report import chord_lines, surface_lines
from recon3d.spellings import number, percent
from recon3d.viz.view import fit_view

R = 10.0


def _doc(delta):
    """A metrics document of two families whose fused F@1% lies ``delta`` off the best."""
    block = {"fscore": {"1%": 0.5}, "reachable": {"fscore": {"1%": -1e-9}}}
    fam = {"slab_share": 0.5, "reachable_share": -1e-12, "touched_share": 1.0, "surface": block}
    return {"families": [{"axis": "z", "slices": 2}, {"axis": "x", "slices": 2}],
            "total": {"surface": block},
            "surface_eval": {"slab_share": 1.0, "reachable_share": 0.5, "notes": [],
                             "families": [dict(fam, axis="z"), dict(fam, axis="x")],
                             "fused_vs_best": {"axis": "z", "fscore_1%": delta}}}


def test_no_negative_zero_in_any_printed_number():
    text = "\n".join(surface_lines(_doc(-1e-9)))
    assert "-0.000" not in text and "-0%" not in text and "+0.000" in text
    assert number(-4e-7) == "0.000" and number(-0.0, "+.3f") == "+0.000"
    assert percent(-1e-9, 1) == "0.0%" and number(-0.03, "+.3f") == "-0.030"


def _labelled(mesh):
    mesh = mesh.copy()
    mesh.face_attributes["label"] = np.ones(len(mesh.faces), dtype=np.int32)
    return mesh


def test_reachable_f1_is_computed_over_the_reachable_part_only():
    """A sphere rebuilt 0.05 out on its east half (reachable) and 1.0 out on the west:
    the reachable F@1% is the F-score of the east half alone, computed here independently."""
    sphere = trimesh.creation.icosphere(subdivisions=5, radius=R)
    v = sphere.vertices.copy()
    v *= np.where(v[:, :1] < 0, (R + 1.0) / R, (R + 0.05) / R)
    rec = _labelled(trimesh.Trimesh(v, sphere.faces, process=False))
    t = np.linspace(0, 2 * np.pi, 400, endpoint=False)
    pts = np.concatenate([np.column_stack([R * np.cos(a) * np.cos(t), R * np.cos(a) * np.sin(t),
                                           np.full_like(t, R * np.sin(a))])
                          for a in np.linspace(-1.4, 1.4, 15)])
    east = pts[:, 0] >= 0
    cloud = ContourCloud(pts, east, east, np.zeros(len(pts), int),
                         Domain(np.array([[0.0, 0.0, 1.0]]), np.array([-R]), np.array([R])))
    gt = GroundTruthSamples(sphere, Domain(np.array([[0.0, 0.0, 1.0]]), np.array([-5.0]),
                                           np.array([2 * R])), count=20000)
    surf, extra = surface_metrics(rec, gt, cloud, count=20000)
    tau = 0.01 * float(np.linalg.norm(np.ptp(sphere.bounds, axis=0)))
    # independent: GT samples of the east half against the rebuilt sphere (radial gaps)
    g = gt.points[gt.points[:, 0] >= 0]
    r_gt = np.mean(np.abs(np.linalg.norm(g, axis=1) - R) <= tau + 0.05 + 1e-3)  # all within
    assert 0.05 < tau < 1.0 and r_gt == 1.0
    assert surf["reachable"]["fscore"]["1%"] == pytest.approx(1.0, abs=0.02)
    assert surf["fscore"]["1%"] == pytest.approx(0.5, abs=0.05)
    # the shares: slab z >= -5 of a sphere of radius 10 holds 3/4 of its area
    assert extra["slab_share"] == pytest.approx(0.75, abs=0.02)
    assert extra["reachable_share"] == pytest.approx(0.375, abs=0.02)
    assert 0 <= extra["reachable_share"] <= extra["slab_share"] <= 1


@pytest.fixture(scope="module")
def budget_run():
    """fig18_overhangs with a budget far too small: every slice ends with unknown chords."""
    return recon3d.run("fig18_overhangs", slices=2, max_motions=12, jobs=1)


def test_unknown_chords_are_counted_located_and_explained(budget_run):
    m = budget_run.metrics
    chords = m["unknown_chords"]
    assert chords and m["total"]["unknown_chords"] == len(chords)
    assert m["total"]["unknown_chord_length"] == pytest.approx(sum(c["length"] for c in chords))
    fam = budget_run.sensing.families[0]
    for c in chords:
        assert c["cause"] == "budget" and c["axis"] == "z" and c["note"] is not None
        s = fam.slices[c["slice"]]
        mid = np.array(c["middle"])
        assert mid @ np.asarray(fam.normal) == pytest.approx(s.slice.plane.offset, abs=1e-6)
        assert c["length"] == pytest.approx(np.linalg.norm(np.subtract(c["b"], c["a"])))
    lines = chord_lines(m)
    assert f"{len(chords)} unknown chord" in lines[0] and f"{len(chords)} from a budget hit" \
        in lines[0]
    assert lines[1].strip().startswith(f"z#{chords[0]['slice']} at (")


def test_a_loose_end_chord_is_named_for_its_cause():
    """An unknown chord the planner reports for contour that stops at a loose
    end (rule "loose") is counted as such, not as a dead end."""
    from recon3d.score.unknowns import CAUSES, _cause
    assert _cause(False, "loose") == "loose end" and _cause(True, "loose") == "budget"
    assert _cause(False, "revisit") == "dead end"
    chords = [{"axis": "x", "slice": 7, "middle": [0.0, 1.0, 2.0], "length": 3.0,
               "cause": "loose end", "on_contour": 0.5, "note": "n"},
              {"axis": "x", "slice": 7, "middle": [0.0, 1.0, 2.0], "length": 3.0,
               "cause": "dead end", "on_contour": 0.5, "note": "n"}]
    head = chord_lines({"unknown_chords": chords})[0]
    assert "0 from a budget hit, 1 dead end (" in head
    assert f"1 loose end ({CAUSES['loose end']})" in head


def test_shares_of_a_run_are_consistent():
    """bowl, 4 z-slices: the slab share is the share of the ground truth between the first
    and the last slice plane (counted here on independent samples)."""
    res = recon3d.run("bowl", slices=4, jobs=1)
    ev = res.metrics["surface_eval"]
    offsets = [s.slice.plane.offset for s in res.slices]
    pts, _ = trimesh.sample.sample_surface(res.mesh, 40000, seed=7)
    inside = (pts[:, 2] >= min(offsets)) & (pts[:, 2] <= max(offsets))
    assert ev["slab_share"] == pytest.approx(inside.mean(), abs=0.01)
    assert 0 <= ev["reachable_share"] <= ev["slab_share"] <= 1
    assert ev["families"][0]["slab_share"] == ev["slab_share"]
    assert "coverage" not in ev and 0 <= ev["touched_share"] <= 1
    assert "unknown_chords" in res.metrics and "slab=" in repr(res)


@pytest.mark.parametrize("extent", [(100, 10, 60), (10, 100, 60), (60, 10, 100),
                                    (40, 30, 35), (30, 40, 35), (35, 30, 40), (100, 60, 55),
                                    (100, 60, 10)])
def test_camera_fit_puts_the_longest_extent_across_the_image(extent):
    direction, up, across = fit_view([[0, 0, 0], list(extent)])
    right = np.cross(up, direction)
    right /= np.linalg.norm(right)
    longest = int(np.argmax(extent))
    assert across == longest and up[longest] == 0.0
    # the screen width the box's edges span: the longest edge spans the most
    spans = [abs(right[k]) * extent[k] for k in range(3)]
    assert int(np.argmax(spans)) == longest
    if min(extent) < 0.5 * sorted(extent)[1]:  # flat: lies flat, thin axis up
        assert up[int(np.argmin(extent))] == 1.0


def test_the_picture_headline_wraps_long_lines_and_drops_no_word():
    """coverage.png's headline: a long unknown-chord line wraps (indented), nothing is cut."""
    from recon3d.viz.plot import WIDTH, headline_rows
    chords = [{"axis": "z", "slice": 3, "middle": [12.3456, 40.1234, 7.5], "length": 4.77,
               "cause": "dead end", "on_contour": 0.98, "note": "word " * 60}]
    lines = chord_lines({"unknown_chords": chords})
    assert max(len(s) for s in lines) > WIDTH
    rows = headline_rows(lines)
    assert max(len(r) for r in rows) <= WIDTH
    assert " ".join(rows).split() == " ".join(lines).split()
    assert len(rows) > len(lines) and rows[-1].startswith("      ")  # continued, indented


@pytest.mark.parametrize("count", [4, 8, 9, 14, 30])
def test_the_picture_headline_stays_inside_its_panel(count):
    """However many rows the headline has, its first row is drawn inside the headline panel
    (the picture's bottom fifth): a long list of unknown chords shrinks the type instead of
    pushing the run's name out of the picture (it did with 9 rows)."""
    import os
    from types import SimpleNamespace

    import pyvista as pv

    from recon3d.viz import plot

    pv.OFF_SCREEN = True
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    lines = ["case: slices z x16"] + [f"  z#{k} at (1.0, 2.0, 3.0), length 0.5: " + "word " * 20
                                      for k in range(count - 1)]
    blocks = SimpleNamespace(field_data={"headline": lines})
    p = pv.Plotter(shape=(2, 2), groups=[(1, np.s_[:])], row_weights=[4, 1], off_screen=True,
                   window_size=[1600, 800], border=False)
    p.subplot(1, 0)
    plot._headline(p, blocks, "")
    p.render()
    ren = p.renderer
    actor = [a for a in ren.GetViewProps() if a.IsA("vtkTextActor")][-1]
    box = [0.0] * 4
    actor.GetBoundingBox(ren, box)  # display pixels: xmin, xmax, ymin, ymax
    top = ren.GetViewport()[3] * p.window_size[1]
    p.close()
    assert 0 <= box[2] and box[3] <= top + 1, (box, top)
