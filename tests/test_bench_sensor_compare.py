"""``python -m bench.sensor_compare`` on hand-made sensor-study rows."""
from __future__ import annotations

import numpy as np
import pytest

from bench.paired import pooled_change, sign_test
from bench.sensor_compare import compare, main, read_rows
from bench.sensor_study import write_csv


def _row(name, noise, taxel, repeat, cov, motions, base=100, budget=False, group="outlines"):
    """A slice run of reachable length 100 and detected length 100 (precision 1)."""
    return {"group": group, "name": name, "noise": noise, "taxel": taxel, "repeat": repeat,
            "sensor_seed": 1000 * repeat, "coverage_sensor": cov,
            "covered_length_sensor": 100.0 * cov, "reachable_length": 100.0,
            "covered_resolvable_length_sensor": 100.0 * cov, "resolvable_length": 100.0,
            "coverage_resolvable_sensor": cov, "precision_sensor": 1.0,
            "precise_length_sensor": 100.0, "detected_length": 100.0, "motions": motions,
            "ratio": motions / base, "budget_hit": budget}


def _study(covs, motions=(150, 150, 150, 150)):
    """Two outlines a, b: noiseless, then sigma 0.3 + T 0.25 with four sensor seeds;
    ``covs``: the noisy coverage of a per seed (b is always 0.99)."""
    rows = [_row(n, 0.0, 0.0, 0, 1.0, 100) for n in ("a", "b")]
    for j, (c, m) in enumerate(zip(covs, motions)):
        rows += [_row("a", 0.3, 0.25, j, c, m), _row("b", 0.3, 0.25, j, 0.99, 120)]
    return rows


@pytest.fixture
def csvs(tmp_path):
    def write(name, rows):
        path = tmp_path / name
        write_csv(path, rows)
        return path
    return write


def test_counts_runs_up_and_down_and_the_targets_per_seed_half(csvs):
    before = read_rows(csvs("before.csv", _study([0.97, 0.99, 0.97, 0.99])))
    after = read_rows(csvs("after.csv", _study([0.99, 0.99, 0.96, 0.97],
                                               motions=(150, 150, 150, 201))))
    text = compare(before, after)
    assert "sigma 0.3 eps, taxel 0.25 eps: 8 slice runs, coverage up 1, down 2, same 5; " \
           "motions changed in 1" in text
    assert "motions changed in 0" in text.splitlines()[1]  # the noiseless runs: the same
    first, second = text.split("sensor seeds j < 2:")[1].split("sensor seeds j >= 2:")
    assert "coverage >= 0.98 3 -> 4" in first  # a's seed 0 now meets 0.98
    assert "coverage >= 0.98 3 -> 2" in second  # a's seed 3 no longer does
    assert "motions <= 2 x noiseless 4 -> 3" in second  # 201 motions over 100
    assert "coverage 0.9850 -> 0.9900" in first and "coverage 0.9850 -> 0.9775" in second


def test_bad_input_is_one_line_and_status_2(csvs, tmp_path, capsys):
    good = csvs("good.csv", _study([0.97, 0.99, 0.97, 0.99]))
    notes = tmp_path / "notes.csv"
    notes.write_text("a,b\n1,2\n")
    assert main([str(notes), str(good)]) == 2
    assert main([str(tmp_path / "missing.csv"), str(good)]) == 2
    bad = tmp_path / "bad.csv"
    bad.write_text(good.read_text().replace("0.97", "zero", 1))
    assert main([str(good), str(bad)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 3 and all(line.startswith("sensor_compare: ") for line in err)
    assert "line 4" in err[2]


def test_the_lottery_interval_holds_zero_for_redrawn_runs_and_not_for_a_shift():
    """40 slice runs re-drawn (each moves by the lottery, no bias): the coverage interval
    holds 0 and the sign test finds nothing; the same runs all raised by 0.01: it does
    not, and the sign test rejects "up and down equally likely"."""
    rng = np.random.default_rng(7)
    before = rng.uniform(0.95, 1.0, 40) * 100.0
    redrawn = before + rng.normal(0.0, 1.0, 40)  # the lottery: +-0.01 of coverage
    reach = np.full(40, 100.0)
    same = pooled_change(before, redrawn, weight=reach)
    assert same.holds_zero() and same.low < 0 < same.high
    shifted = pooled_change(before, redrawn + 1.0, weight=reach)  # + 0.01 on every run
    assert not shifted.holds_zero() and shifted.low > 0.005
    up = int((redrawn > before).sum())
    assert sign_test(up, 40 - up) > 0.05 and sign_test(40, 0) < 1e-6


def test_motions_change_is_relative_and_its_interval_brackets_it():
    rng = np.random.default_rng(3)
    before = rng.integers(1000, 3000, 30).astype(float)
    after = before * 0.9 * rng.uniform(0.97, 1.03, 30)
    c = pooled_change(before, after, relative=True)
    assert abs(c.change - (after.sum() / before.sum() - 1)) < 1e-12
    assert c.low <= c.change <= c.high and c.high < -0.05  # about -10 %, not 0
    few = pooled_change(before[:5], after[:5], relative=True)
    assert np.isnan(few.low) and np.isnan(few.high)  # too few runs to resample
    with pytest.raises(ValueError):
        pooled_change(before, after[:-1])


def test_compare_prints_the_intervals_and_the_sign_test(csvs):
    before = read_rows(csvs("before.csv", _study([0.97, 0.99, 0.97, 0.99])))
    after = read_rows(csvs("after.csv", _study([0.99, 0.99, 0.96, 0.97])))
    text = compare(before, after)
    assert "up against down: sign test p = 1" in text  # 1 up, 2 down
    # 8 runs per level and group: too few for an interval, so none is printed
    assert "95 % interval" not in text


def test_a_keyed_study_against_one_that_is_not_is_flagged(csvs):
    rows = _study([0.97, 0.99, 0.97, 0.99])
    keyed = [dict(r, keyed=True) for r in rows]
    plain = read_rows(csvs("plain.csv", [dict(r, keyed=False) for r in rows]))
    both = read_rows(csvs("keyed.csv", keyed))
    assert "warning" not in compare(both, both) and "warning" not in compare(plain, plain)
    assert "no slice run is paired" in compare(plain, both)
    assert "no slice run is paired" not in compare(read_rows(csvs("old.csv", rows)), plain)
