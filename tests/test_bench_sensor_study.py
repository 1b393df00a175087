"""``bench/sensor_study.py``'s tables from rows (no sensing): the share of the reachable
contour counted covered only behind W2 chords is printed beside the coverage."""
from __future__ import annotations

import math

import pytest

from bench.sensor_study import markdown, per_case, summarise, verdicts


def _row(name, cov, credit, noise=0.3, taxel=0.25, repeat=0):
    row = {"group": "outlines", "name": name, "noise": noise, "taxel": taxel, "repeat": repeat,
           "reachable_length": 100.0, "covered_length": 100.0 * cov, "coverage_sensor": cov,
           "covered_length_sensor": 100.0 * cov, "resolvable_length": 100.0,
           "covered_resolvable_length_sensor": 100.0 * cov, "coverage_resolvable_sensor": cov,
           "precise_length": 50.0, "precise_length_sensor": 50.0, "detected_length": 50.0,
           "precision_sensor": 1.0, "w3_count": 0, "w3_unsound_count": 0,
           "w3_unsound_count_sensor": 0, "motions": 100, "ratio": 1.0, "budget_hit": False}
    if credit is not None:
        row["w2_credit_length_sensor"] = 100.0 * credit
    return row


def test_the_w2_credit_is_pooled_and_printed():
    rows = [_row("comb-0", 0.90, 0.30), _row("star-0", 0.99, 0.02)]
    (s,) = summarise(rows)
    assert math.isclose(s["w2_credit_sensor"], 0.16)
    table = markdown([s])
    assert "of it behind W2 chords" in table.splitlines()[0]
    assert "| 0.9450 (0.9000) | 0.1600 |" in table
    cases = {c["case"]: c for c in per_case(rows)}
    assert math.isclose(cases["comb-0"]["w2_credit_sensor"], 0.30)
    assert "comb-0: coverage 0.9000 (behind W2 chords 0.3000)" in verdicts(rows)


def test_rows_without_the_column_print_a_dash():
    (s,) = summarise([_row("comb-0", 0.90, None)])
    assert "| 0.9000 (0.9000) | - |" in markdown([s])


def test_the_chart_draws_with_and_without_the_column(tmp_path):
    """The chart adds the coverage without the W2 credit when the rows have it, and still
    draws rows of an older CSV."""
    from bench.sensor_study import coverage_target
    from bench.sensor_study_chart import chart, without_credit

    for credit, name in ((0.30, "with.png"), (None, "without.png")):
        rows = [_row("comb-0", 0.90, credit, noise=0.0, taxel=0.0),
                _row("comb-0", 0.90, credit)]
        summary = summarise(rows)
        bare = without_credit(summary)
        assert bare == ([] if credit is None else [pytest.approx(0.60)] * 2)
        chart(summary, tmp_path / name, coverage_target)
        assert (tmp_path / name).stat().st_size > 0


@pytest.mark.parametrize("first, names", [(0, ["star-0", "star-1"]), (2, ["star-2", "star-3"])])
def test_first_outline_picks_the_outline_seeds(first, names):
    """``--first-outline`` starts each kind's seeds there: outlines the rules never saw."""
    from types import SimpleNamespace

    from bench.sensor_study import cases

    args = SimpleNamespace(groups=["outlines"], first_outline=first, per_kind=2, slices=1)
    got = [name for _, name, _, a in cases(args) if a[0] == "star"]
    assert got == names
    assert [a[1] for _, name, _, a in cases(args) if name in names] == [first, first + 1]


def _band(row, band):
    """``row`` with the band columns: coverage ``band`` over 80 of its 100 length units."""
    return {**row, "band_length": 80.0, "covered_band_length_sensor": 80.0 * band}


def test_the_band_column_is_pooled_printed_and_judged():
    """Coverage over the part eps + jitter resolves: pooled by length, printed beside the
    part eps resolves, counted in the verdicts but judging no case (a case that meets every
    target and not this one is not listed); rows of an older CSV print '-'."""
    rows = [_band(_row("comb-0", 0.90, 0.30), 0.95), _band(_row("star-0", 0.99, 0.02), 1.0)]
    (s,) = summarise(rows)
    assert math.isclose(s["band_sensor"], 0.975) and math.isclose(s["band_sensor_min"], 0.95)
    table = markdown([s])
    assert "over the part eps + jitter resolves (min)" in table.splitlines()[0]
    assert "| 0.9450 (0.9000) | 0.9750 (0.9500) |" in table
    text = verdicts(rows)
    assert "coverage over the part eps + jitter resolves (counted only) 1" in text
    assert "over the part eps + jitter resolves 0.9500" in text
    (mixed,) = summarise([_row("comb-0", 0.90, None), _band(_row("star-0", 0.95, None), 0.97)])
    assert mixed["band_sensor"] == mixed["band_sensor_min"] == 0.97  # an older row left out
    (old,) = summarise([_row("comb-0", 0.99, None)])
    assert "| 0.9900 (0.9900) | - (-) |" in markdown([old])
    assert "misses" not in verdicts([_row("comb-0", 0.99, None)])
    assert "misses" not in verdicts([_band(_row("star-1", 0.99, 0.0), 0.90)])


def test_the_band_leaves_out_a_slot_the_sensor_reads_as_w2():
    """A slot 1.5 eps wide and 6 eps deep: eps resolves its walls, a disc of the coarse
    sensor's W2 distance (eps + jitter = 2.52 eps at sigma 0.3 eps, taxels 0.25 eps) does
    not enter it. The band leaves out the slot's walls but the ends a disc that wide touches
    (each wall 6 eps long: between 2 x (6 - 2.52 / 2 - 1) and 2 x 6 + 1.5 fewer length units),
    and is the part eps resolves for the noiseless run."""
    import numpy as np

    from bench.sensor_study import _score
    from core2d.resolution import Resolution, repeated_reads
    from slicer import ExactContact

    w, d = 1.5, 6.0
    loop = np.array([[0, 0], [20, 0], [20, 10], [10 + w / 2, 10], [10 + w / 2, 10 - d],
                     [10 - w / 2, 10 - d], [10 - w / 2, 10], [0, 10]], dtype=float)
    assert Resolution.of(1.0, noise=0.3, taxel=0.25).w2_dist > w > 1.0
    rows = _score([loop], ExactContact([loop]), (np.array([10.0, 5.0]), 13.0), 1.0,
                  ((0.3, 0.25),), 0, 5000, 1, reads=1)  # one read: the coarse sensor
    quiet, noisy = rows
    assert quiet["band_length"] == quiet["resolvable_length"]
    assert quiet["covered_band_length_sensor"] == quiet["covered_resolvable_length_sensor"]
    left_out = noisy["resolvable_length"] - noisy["band_length"]
    assert noisy["reads"] == 1
    assert 2 * (d - 2.52 / 2 - 1.0) <= left_out <= 2 * d + w
    assert 0 <= noisy["covered_band_length_sensor"] <= noisy["band_length"]
    # averaged as recon3d run does (16 reads): the W2 distance of the means, 1.44 eps < w
    averaged = _score([loop], ExactContact([loop]), (np.array([10.0, 5.0]), 13.0), 1.0,
                      ((0.3, 0.25),), 0, 5000, 1)[1]
    assert averaged["reads"] == repeated_reads(1.0, 0.3, 0.25) == 16
    assert averaged["resolvable_length"] - averaged["band_length"] < 0.5 * left_out
