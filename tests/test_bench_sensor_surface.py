"""``python -m bench.sensor_surface --before``: the paired change of F@1 % between two
3D sensor studies, on hand-made rows (the runs themselves are bench work)."""
from __future__ import annotations

import numpy as np
import pytest

from bench.sensor_surface import paired_lines


def _rows(shift=0.0, keyed=True, seeds=4, scenes=("a", "b", "c")):
    """Noiseless rows and sigma 0.3 + T 0.25 rows per scene and seed; F@1 % spread
    over the runs, plus ``shift`` on every noisy run."""
    rng = np.random.default_rng(5)
    rows = [{"scene": s, "noise": 0.0, "taxel": 0.0, "seed": 0, "keyed": False,
             "fscore_1%": 1.0} for s in scenes]
    rows += [{"scene": s, "noise": 0.3, "taxel": 0.25, "seed": j, "keyed": keyed,
              "fscore_1%": float(0.8 + 0.15 * rng.random() + shift)}
             for s in scenes for j in range(seeds)]
    return rows


def test_a_shift_on_every_run_is_outside_the_lottery():
    (line,) = paired_lines(_rows(), _rows(shift=0.01))
    assert "12 paired runs" in line and "(+0.0100, 95 % interval +0.0100 .. +0.0100)" in line
    assert "up 12, down 0" in line


def test_runs_pair_by_scene_level_and_seed_not_by_order():
    before = _rows()
    after = [dict(r) for r in reversed(_rows())]  # the same runs in another order
    after[0]["fscore_1%"] += 0.05  # one run moved
    (line,) = paired_lines(before, after)
    assert "up 1, down 0" in line and "+0.0042" in line  # 0.05 over 12 runs
    assert "noiseless" not in line and "sigma 0.3 eps, taxel 0.25 eps" in line


def test_keyed_against_one_stream_is_flagged_and_missing_scores_skipped():
    after = _rows(keyed=False)
    after[3]["fscore_1%"] = None  # a run without a surface score
    lines = paired_lines(_rows(), after)
    assert lines[0].startswith("warning: one study's noise is keyed")
    assert "11 paired runs" in lines[1]
    assert len(paired_lines(_rows(), _rows(shift=0.01))) == 1  # both keyed: no warning


def test_the_command_pairs_its_runs_with_an_earlier_study(tmp_path, monkeypatch, capsys):
    """``--seeds 2 --keyed-noise --csv`` then ``--before``: every noisy level runs once per
    seed, keyed, the rows record seed and keying, and the second study prints the paired
    change against the first (the runs themselves stubbed: a row per call)."""
    import csv

    import bench.sensor_surface as ss

    calls, reads_seen = [], []

    def row(scene, slices, noise, taxel, seed=0, keyed=False, reads="auto", shift=0.0):
        calls.append((scene, noise, taxel, seed, keyed))
        reads_seen.append(reads)
        return {"scene": scene, "noise": noise, "taxel": taxel, "seed": seed,
                "keyed": bool(keyed and (noise or taxel)),
                "fscore_1%": 0.9 - noise / 10 + 0.01 * seed + shift, "coverage": 0.99,
                "unknown": 0, "bridges": 0, "motions": 100}

    monkeypatch.setattr(ss, "_row", row)
    first = tmp_path / "first.csv"
    args = ["--scenes", "a,b", "--levels", "0.3:0.25", "--seeds", "2", "--keyed-noise"]
    assert ss.main(args + ["--csv", str(first)]) == 0
    assert calls == [(s, n, t, k, kd) for s in "ab"
                     for n, t, k, kd in ((0.0, 0.0, 0, False), (0.3, 0.25, 0, True),
                                         (0.3, 0.25, 1, True))]
    rows = list(csv.DictReader(first.open()))
    assert [(r["seed"], r["keyed"]) for r in rows[:3]] == [("0", "False"), ("0", "True"),
                                                           ("1", "True")]
    capsys.readouterr()
    monkeypatch.setattr(ss, "_row", lambda *a, **k: row(*a, **k, shift=0.02))
    assert ss.main(args + ["--before", str(first)]) == 0
    out = capsys.readouterr().out
    assert "4 paired runs" in out and "(+0.0200," in out and "up 4, down 0" in out
    assert "warning" not in out
    assert set(reads_seen) == {"auto"}  # as recon3d run takes them, unless asked
    reads_seen.clear()
    assert ss.main(["--scenes", "a", "--levels", "0.3:0.25", "--reads", "15"]) == 0
    assert reads_seen == ["auto", 15] and "reads 15" in capsys.readouterr().out


@pytest.mark.parametrize("value", ["0", "many", "-3"])
def test_reads_must_be_auto_or_a_count(value, capsys):
    import bench.sensor_surface as ss

    with pytest.raises(SystemExit) as exc:
        ss.main(["--scenes", "a", "--reads", value])
    assert exc.value.code == 2
    assert capsys.readouterr().err.strip().splitlines()[-1].endswith(
        f"--reads is 'auto' or a number >= 1 (got {value!r})")


def test_an_unreadable_before_file_is_a_one_line_error(tmp_path, capsys):
    import bench.sensor_surface as ss

    with pytest.raises(SystemExit) as exc:
        ss.main(["--scenes", "a", "--before", str(tmp_path / "missing.csv")])
    assert exc.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1].endswith("--before: cannot read " + str(tmp_path / "missing.csv")
                            + ": No such file or directory")
