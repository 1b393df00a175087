"""The logic and charts of ``recon3d bench`` on hand-made rows (the sweeps themselves run in bench)."""
import csv
import math

import numpy as np
import pytest

from recon3d.benchmark.baseline import equal_coverage
from recon3d.benchmark.charts import baseline_chart, pareto_chart
from recon3d.benchmark.pareto import FULL, QUICK, adaptive_summary, pareto_front
from recon3d.benchmark.run3d import write_csv
from recon3d.benchmark.stability import breaking_points
from recon3d.benchmark.stability_charts import sensor_chart, stability_chart


def _p(case, method, slices, share, wall, cd, cov, f1=0.9, cpu=None, robot=100.0):
    return {"case": case, "method": method, "slices": slices, "eps_share": share, "wall_s": wall,
            "cpu_s": cpu or wall, "chamfer_l1_diag": cd, "coverage": cov, "fscore_1": f1,
            "robot_time_s": robot}


PARETO = [_p("a", "uniform", 4, 0.01, 1.0, 3e-3, 0.98), _p("a", "uniform", 8, 0.01, 2.0, 1e-3, 0.99),
          _p("a", "uniform", 8, 0.005, 4.0, 2e-3, 1.0), _p("b", "uniform", 4, 0.01, 9.0, 5e-3, 0.9),
          _p("a", "adaptive", 5, 0.01, 1.5, 1e-3, 0.99)]


def test_pareto_front_is_per_case_and_per_objective():
    assert pareto_front(PARETO).tolist() == [True, False, False, True, True]
    assert pareto_front(PARETO, y="coverage", lower_is_better=False).tolist() == [
        True, False, True, True, True]


def test_adaptive_summary_compares_with_the_uniform_run_at_max_slices():
    plan = {"auto_max": 8, "auto_share": 0.01}
    (row,) = adaptive_summary(PARETO, plan)
    assert row["case"] == "a" and row["uniform_slices"] == 8 and row["adaptive_slices"] == 5
    assert row["time_ratio"] == pytest.approx(0.75) and not row["target_met"]  # 5 > 8 / 2


@pytest.mark.parametrize("plan", [pytest.param(FULL, id="full"), pytest.param(QUICK, id="quick")])
def test_each_sweep_has_the_uniform_run_its_adaptive_run_is_compared_with(plan):
    rows = [_p(c, "uniform", n, e, 1.0, 1e-3, 1.0) for c in ("a",) for n in plan["slices"]
            for e in plan["eps_shares"]] + [_p("a", "adaptive", 3, plan["auto_share"], 1, 1e-3, 1)]
    assert len(plan["eps_shares"]) >= 4 and len(plan["slices"]) >= 4 and len(plan["scenes"]) >= 4
    (row,) = adaptive_summary(rows, plan)  # empty when no uniform run matches
    assert row["uniform_slices"] == plan["auto_max"]


def _b(method, cov, motions, path, dirs=0, sp=0.0):
    return {"case": "c", "method": method, "coverage": cov, "motions": motions,
            "joint_path": path, "robot_time_s": path / 20 + 0.2 * motions, "directions": dirs,
            "spacing_eps": sp}


def test_equal_coverage_takes_the_cheapest_finger_density_that_covers_as_much():
    rows = [_b("pulling", 0.99, 100, 1000), _b("finger", 0.95, 50, 500, 8, 2),
            _b("finger", 0.995, 1000, 20000, 32, 0.5), _b("finger", 0.999, 4000, 80000, 64, 0.25)]
    (r,) = equal_coverage(rows)
    assert r["reached"] and r["finger_density"] == "32 dirs x 0.5 eps"
    assert r["robot_time_ratio"] == pytest.approx((1000 + 200) / (50 + 20))
    assert r["motions_ratio"] == pytest.approx(10.0)
    (r,) = equal_coverage([_b("pulling", 1.0, 100, 1000)] + rows[1:3])
    assert not r["reached"] and r["finger_coverage"] == 0.995


def _s(value, method, cov, crashed=False, hit=False):
    return {"factor": "f", "value": value, "method": method, "coverage": cov, "fscore_1": np.nan,
            "crashed": crashed, "error": "Boom: x" if crashed else "", "budget_hit": hit,
            "eps": 1.0, "edge": 1.0}


def test_breaking_points_crash_budget_and_drop():
    rows = [_s(1, "m1", 1.0), _s(2, "m1", 0.99), _s(3, "m1", np.nan, crashed=True),
            _s(1, "m2", 1.0), _s(2, "m2", 0.9), _s(1, "m3", 1.0), _s(2, "m3", 1.0, hit=True),
            _s(1, "m4", 1.0), _s(2, "m4", 0.97)]
    got = {b["method"]: (b["breaks_at"], b["why"]) for b in breaking_points(rows)}
    assert got["m1"][0] == 3 and got["m1"][1].startswith("crash")
    assert got["m2"][0] == 2 and "coverage" in got["m2"][1]
    assert got["m3"] == (2, "budget hit")
    assert got["m4"] == (None, "")


def test_sensor_factors_break_on_the_coverage_the_sensor_allows():
    """Noise moves every reported contact: the strict coverage (within eps/2)
    drops with sigma by construction, the method breaks only when the
    coverage within eps/2 + 2 sigma drops."""
    rows = []
    for factor in ("noise", "f"):
        for value, strict, sensor in ((0, 1.0, 1.0), (1, 0.8, 0.98), (2, 0.7, 0.9)):
            rows.append({**_s(value, "m", strict), "factor": factor, "coverage_sensor": sensor})
    got = {b["factor"]: (b["breaks_at"], b["why"]) for b in breaking_points(rows)}
    assert got["noise"] == (2, "coverage_sensor 0.900 (from 1.000)")
    assert got["f"][0] == 1 and got["f"][1].startswith("coverage ")


def test_write_csv_leaves_nan_empty(tmp_path):
    write_csv(tmp_path / "x.csv", [{"a": 1, "b": math.nan}, {"a": 2, "c": "z"}])
    rows = list(csv.DictReader(open(tmp_path / "x.csv")))
    assert rows == [{"a": "1", "b": "", "c": ""}, {"a": "2", "b": "", "c": "z"}]


def test_charts_write_pngs(tmp_path):
    import matplotlib.image as mpimg

    fronts = {k: pareto_front(PARETO, y=k, lower_is_better=k == "chamfer_l1_diag")
              for k in ("chamfer_l1_diag", "fscore_1", "coverage")}
    pareto_chart(PARETO, fronts, tmp_path / "p.png")
    rows = [_b("pulling", 0.99, 100, 1000), _b("finger", 0.95, 50, 500, 8, 2)]
    baseline_chart(rows, tmp_path / "b.png")
    srows = [_s(1e-3, "m1", 1.0), _s(1e-9, "m1", np.nan, crashed=True)]
    stability_chart(srows, breaking_points(srows), tmp_path / "s.png")
    sens = [{"factor": f, "value": v, "method": m, "motions": 100 + 900 * v,
             "coverage_sensor": 1 - v / 4, "budget_hit": v == 1.0}
            for f in ("noise", "taxel") for v in (0.0, 0.3, 1.0) for m in ("m1", "m2")]
    sensor_chart(sens, tmp_path / "n.png")
    for name, width in (("p.png", 1800), ("b.png", 1000), ("s.png", 1400), ("n.png", 1200)):
        img = mpimg.imread(tmp_path / name)
        assert img.shape[1] >= width and img.std() > 0.01


def test_redraw_remakes_the_files_from_the_csvs_and_merges_parts(tmp_path):
    """Parts run apart are merged by ``--redraw`` into the files one run
    writes: the CSVs read back with their types (a round trip is byte for
    byte), the breaking points recomputed, the charts drawn."""
    from recon3d.benchmark.redraw import load_rows, read_csv, redraw
    from recon3d.benchmark.run3d import write_outputs

    stab = [dict(_s(v, m, c), coverage_sensor=c, motions=10, factor="noise")
            for v, m, c in ((0.0, "m1", 1.0), (0.3, "m1", 0.9), (0.0, "m2", 1.0), (0.3, "m2", 1.0))]
    stab.append(dict(_s("twin_posts", "m1", 0.97), coverage_sensor=math.nan, motions=5,
                     factor="islands/holes"))
    base = [_b("pulling", 0.99, 100, 1000), _b("finger", 0.95, 50, 500, 8, 2)]
    task = {"case": "", "factor": "", "value": math.nan, "slices": math.nan,
            "eps_share": math.nan, "seconds": 1.5, "error": ""}
    write_outputs(tmp_path / "a", {"stability": stab}, [dict(task, part="stability")], QUICK, True)
    write_outputs(tmp_path / "b", {"baseline": base}, [dict(task, part="baseline")], QUICK, True)
    back = read_csv(tmp_path / "a" / "stability.csv")
    assert back[1]["value"] == 0.3 and back[0]["crashed"] is False and back[4]["value"] == "twin_posts"
    assert math.isnan(back[4]["coverage_sensor"]) and back[0]["error"] == ""
    lines = redraw([tmp_path / "a", tmp_path / "b"], tmp_path / "c")
    assert lines[0] == "recon3d bench --quick: 2 tasks"
    for name in ("stability.csv", "breaks.csv", "baseline.csv", "baseline_ratios.csv"):
        src = tmp_path / ("a" if name in ("stability.csv", "breaks.csv") else "b") / name
        assert (tmp_path / "c" / name).read_bytes() == src.read_bytes()
    got = {b["method"]: b["breaks_at"] for b in read_csv(tmp_path / "c" / "breaks.csv")
           if b["factor"] == "noise"}
    assert got["m1"] == 0.3 and math.isnan(got["m2"])  # m2 never breaks
    for png in ("stability.png", "sensor.png", "baseline.png"):
        assert (tmp_path / "c" / png).stat().st_size > 10_000
    with pytest.raises(ValueError, match="found twice"):
        load_rows([tmp_path / "a", tmp_path / "c"])


def test_a_method_keeps_its_style_on_both_stability_charts():
    """stability.png and sensor.png list different methods; each keeps its
    colour and marker (the sensor chart lacks the 3D rows, trimesh in --quick)."""
    from recon3d.benchmark.stability_charts import _style

    every = ["pulling/embree", "pulling/exact", "pulling/trimesh", "finger/embree",
             "paper/embree", "follow/embree", "pulling/embree 3D"]
    some = ["paper/embree", "finger/embree", "pulling/embree"]
    a, b = _style(every), _style(some)
    assert all(a[m][:2] == b[m][:2] for m in some)
    assert len({a[m][:2] for m in every}) == len(every)


def test_the_sweep_runs_slice_counts_above_extent_over_eps():
    """The full sweep has 32 slices at eps = diagonal / 25 (more than extent /
    eps): such a run is a point of the chart, not an error (recon3d.run
    refuses it without force)."""
    from recon3d.benchmark.pareto import run_case

    # fig17_pocket: extent / eps = 40 / 4.75 = 8 at eps = diagonal / 25
    row = run_case({"case": "fig17_pocket", "source": "fig17_pocket", "method": "uniform",
                    "slices": 9, "eps_share": 1 / 25})
    assert row["slices"] == 9 and row["fscore_1"] > 0.9 and row["cpu_s"] > 0


def test_methods_breaking_at_one_value_each_get_their_own_ring(tmp_path):
    """Two methods break at the same noise value (one line there would show one
    colour only): each is marked by a ring at its own score, a crash at its red x."""
    rows = [dict(_s(v, m, c), coverage_sensor=c, factor="noise")
            for v, m, c in ((0.0, "m1", 1.0), (0.3, "m1", 0.9), (0.0, "m2", 1.0), (0.3, "m2", 0.6),
                            (0.0, "m3", 1.0), (0.3, "m3", 0.99))]
    rows += [_s(1, "m1", 1.0), _s(2, "m1", np.nan, crashed=True)]
    marks = stability_chart(rows, breaking_points(rows), tmp_path / "s.png")
    assert sorted(marks) == [("f", "m1", 2, 0.02), ("noise", "m1", 0.3, 0.9),
                             ("noise", "m2", 0.3, 0.6)]  # m3 holds: no ring
