"""The ``claims`` part of ``recon3d bench`` (pulling against pushing under friction),
its quick size run through the bench's own driver, table and chart."""
import csv

from recon3d.benchmark import claims
from recon3d.benchmark.run3d import PARTS, run_bench


def test_quick_claims_part_runs_every_method_at_each_mu(tmp_path):
    assert "claims" in PARTS
    lines = run_bench(tmp_path, quick=True, scheduler="serial", parts=("claims",), quiet=True)
    rows = list(csv.DictReader(open(tmp_path / "claims.csv")))
    tasks = claims.claims_tasks(True)
    mus = tasks[0]["mus"]
    assert len(rows) == len(tasks) * len(claims.METHODS) * len(mus)
    assert {(r["case"], r["method"], float(r["mu"])) for r in rows} == {
        (t["case"], m, mu) for t in tasks for m in claims.METHODS for mu in mus}
    by = {(r["case"], r["method"], float(r["mu"])): r for r in rows}
    for t in tasks:
        for mu in mus:  # pulling never pushes, so never jams; the follower pushes
            assert int(by[t["case"], "pulling", mu]["jams"]) == 0
            assert int(by[t["case"], "pulling", mu]["pushes"]) == 0
            assert by[t["case"], "finger", mu]["same_as_mu0"] == "True"
        assert int(by[t["case"], "follow", mus[0]]["pushes"]) > 0
        assert int(by[t["case"], "follow", mus[-1]]["jams"]) > 0
    assert (tmp_path / "claims.png").stat().st_size > 10_000
    assert any("pulling against pushing under tip friction" in line for line in lines)
    summ = list(csv.DictReader(open(tmp_path / "claims_summary.csv")))
    assert len(summ) == len(claims.METHODS) * len(mus)
