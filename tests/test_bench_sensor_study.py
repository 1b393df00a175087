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
