"""Closing the sensed pieces of one slice into a filled region (recon3d.surface.closure)."""
import numpy as np
import pytest
import shapely

from recon3d.surface.closure import sample_pieces, slice_region

SQUARE = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])


def _chain(points):
    return np.asarray(points, dtype=float)


def test_closed_w1_loop_fills_its_polygon():
    loop = np.vstack([SQUARE, SQUARE[:1]])
    reg = slice_region([loop], [], [], [], snap=1e-6)
    assert reg.geometry.equals(shapely.Polygon(SQUARE))
    assert not [p for p in reg.pieces if p.kind == "bridge"]


@pytest.mark.parametrize("gap", [1e-7, 0.3, 4.0])
def test_gaps_are_bridged_small_or_large(gap):
    """An area left unknown or an opening between two objects leaves the curve
    open by ``gap``: the two free ends are joined by one bridge."""
    chain = _chain([[0.0, gap], [0.0, 10.0], [10.0, 10.0], [10.0, 0.0], [0.0, 0.0]])
    reg = slice_region([chain], [], [], [], snap=1e-6)
    assert reg.area == pytest.approx(100.0)
    bridges = [p for p in reg.pieces if p.kind == "bridge"]
    assert (len(bridges) == 1) == (gap > 1e-6)
    assert reg.bridge_length == pytest.approx(gap if gap > 1e-6 else 0.0)


def test_w2_w3_and_unknown_pieces_close_the_curve_and_keep_their_kind():
    w1 = [_chain([[0, 0], [10, 0], [10, 10]]), _chain([[6, 10], [0, 10], [0, 4]])]
    w2 = [_chain([[10, 10], [8, 10]])]
    w3 = [_chain([[8, 10], [6, 10]])]
    unknown = [_chain([[0, 4], [0, 0]])]
    reg = slice_region(w1, w2, w3, unknown, snap=1e-6)
    assert reg.area == pytest.approx(100.0)
    assert sorted(p.kind for p in reg.pieces) == ["W1", "W1", "W2", "W3", "unknown"]


def test_w3_lid_closes_an_undercut_pocket():
    """A lid across a pocket mouth puts the pocket inside the region."""
    u = _chain([[4, 10], [4, 6], [2, 6], [2, 2], [8, 2], [8, 6], [6, 6], [6, 10]])
    outer = _chain([[6, 10], [10, 10], [10, 0], [0, 0], [0, 10], [4, 10]])
    with_lid = slice_region([outer], [], [_chain([[4, 10], [6, 10]])], [], snap=1e-6)
    traced = slice_region([outer, u], [], [], [], snap=1e-6)
    pocket = shapely.Polygon(u).area
    assert with_lid.area == pytest.approx(100.0)
    assert traced.area == pytest.approx(100.0 - pocket)


def test_hole_is_filled_and_islands_are_kept_apart():
    hole = SQUARE[::-1] * 0.4 + 3.0
    reg = slice_region([np.vstack([SQUARE, SQUARE[:1]]), np.vstack([hole, hole[:1]])],
                       [], [], [], snap=1e-6)
    assert reg.area == pytest.approx(100.0)  # the probe cannot see a hole
    far = SQUARE + 20.0
    two = slice_region([np.vstack([SQUARE, SQUARE[:1]]), np.vstack([far, far[:1]])],
                       [], [], [], snap=1e-6)
    assert two.geometry.geom_type == "MultiPolygon" and two.area == pytest.approx(200.0)


def test_stray_and_duplicate_pieces_change_nothing():
    loop = np.vstack([SQUARE, SQUARE[:1]])
    stray = _chain([[30.0, 0.0], [40.0, 0.0]])  # straight: its bridge adds no area
    dup = _chain([[0, 0], [10, 0], [10, 10]])  # traced twice
    reg = slice_region([loop, dup], [stray], [], [], snap=1e-6)
    assert reg.area == pytest.approx(100.0)


def test_nothing_sensed_gives_an_empty_region():
    reg = slice_region([], [], [], [], snap=1e-6)
    assert reg.geometry.is_empty and reg.pieces == ()


def test_sample_pieces_spacing_and_owner():
    pts, owner = sample_pieces([_chain([[0, 0], [3, 0], [3, 4]]), _chain([[9, 9], [9, 9.5]])],
                               0.5)
    assert owner.tolist().count(1) == 2 and set(owner.tolist()) == {0, 1}
    d = np.hypot(*np.diff(pts[owner == 0], axis=0).T)
    assert d.max() <= 0.5 + 1e-12


def _comb_slice():
    """A block 0..20 x 0..10 with two slots 2 wide (x 4..6 and 12..14, floors at y = 2),
    traced all round, and an unknown chord from the first slot's floor across the tooth
    between them to the second slot's wall (as a split of an area that ended unknown lays
    it). The probe went down both slots (postures from above to the floors)."""
    outline = _chain([[0, 0], [20, 0], [20, 10], [14, 10], [14, 2], [12, 2], [12, 10],
                      [6, 10], [6, 2], [4, 2], [4, 10], [0, 10], [0, 0]])
    chord = _chain([[5.0, 2.0], [14.0, 8.0]])  # into the second slot, to its far wall
    postures = np.array([[[x, 40.0], [x + 0.1 * k, 2.0]] for x in (4.5, 5.0, 5.5, 12.5, 13.0)
                         for k in (-2, 0, 2)])
    truth = shapely.Polygon(outline)
    return outline, chord, postures, truth


def test_an_unknown_chord_the_probe_went_through_closes_nothing():
    """The chord crosses the slots the probe traced: with the probe's postures it is left
    out and the region is the true section; without them the chord fills most of both slots
    (the triangle it cuts off in the first, the part of the second below it)."""
    outline, chord, postures, truth = _comb_slice()
    seen = slice_region([outline], [], [], [chord], snap=1e-6, free=postures, margin=0.05)
    blind = slice_region([outline], [], [], [chord], snap=1e-6)
    assert seen.geometry.symmetric_difference(truth).area < 1e-6
    assert blind.geometry.difference(truth).area > 5.0  # slot space filled
    assert "unknown" not in [p.kind for p in seen.pieces]


def test_a_chord_no_posture_crosses_keeps_its_fill_and_a_touch_at_an_end_is_no_crossing():
    """Postures that end on the chord's ends (the probe touched A or B), or pass beside it,
    do not show the space behind it empty: the chord stays."""
    outline, chord, _, truth = _comb_slice()
    at_ends = np.array([[[5.0, 40.0], chord[0]], [[13.99, 40.0], [13.99, 8.0]],
                        [[-5.0, 40.0], [-5.0, -10.0]]])
    reg = slice_region([outline], [], [], [chord], snap=1e-6, free=at_ends, margin=0.05)
    assert "unknown" in [p.kind for p in reg.pieces]
    assert reg.geometry.difference(truth).area > 5.0


def test_unknown_chords_into_the_material_do_not_open_the_traced_contour():
    """The square traced all round but for a gap of 2 at its left side, and two unknown
    chords from the gap's ends into the material, meeting at (5, 5) (lids a noisy
    revisit's splits laid through material, ``gear`` z4 at sigma 0.3 eps). The chords take
    the gap's free ends, so no bridge closes the gap and the triangle between them is open
    to the outside: without the region of the sensed pieces alone it is left out. Unknown
    chords add what they close, never take away what the traced contour closes."""
    traced = _chain([[0.0, 4.0], [0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0],
                     [0.0, 6.0]])
    chords = [_chain([[0.0, 6.0], [5.0, 5.0]]), _chain([[5.0, 5.0], [0.0, 4.0]])]
    reg = slice_region([traced], [], [], chords, snap=1e-6, jitter=0.3)
    assert reg.area == pytest.approx(100.0)
    assert sorted(p.kind for p in reg.pieces) == ["W1", "unknown", "unknown"]
    # a perfect sensor's region is the pieces' (step 3b is a noisy sensor's)
    assert slice_region([traced], [], [], chords, snap=1e-6).area == pytest.approx(95.0)
    # an unknown chord across a pocket's mouth still closes the pocket
    pocket = _chain([[6.0, 10.0], [6.0, 6.0], [4.0, 6.0], [4.0, 10.0]])
    rim = _chain([[4.0, 10.0], [0.0, 10.0], [0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [6.0, 10.0]])
    lid = slice_region([rim, pocket], [], [], [_chain([[4.0, 10.0], [6.0, 10.0]])], snap=1e-6,
                       jitter=0.3)
    assert lid.area == pytest.approx(100.0)
