"""``recon3d batch``: a manifest of meshes x parameters on Dask equals the serial run."""
import csv
import json

import pytest

from recon3d.cli import main
from recon3d.io import without_timing

MANIFEST = """
meshes = ["fig17_pocket", "stepped_pyramid"]
[params]
slices = [2, 3]
eps_share = 0.025
"""




def _read(out):
    rows = list(csv.DictReader(open(out / "batch.csv")))
    docs = {}
    for d in sorted((out / "runs").iterdir()):
        docs[d.name] = ({k: without_timing(json.load(open(d / f"{k}.json")))
                         for k in ("metrics", "sensing")}, (d / "surface.ply").read_bytes(),
                        (d / "motions.csv").read_text())
    return rows, docs


def test_dask_cluster_with_two_workers_equals_the_serial_run(tmp_path, capsys):
    from distributed import LocalCluster

    (tmp_path / "m.toml").write_text(MANIFEST)
    outs = {}
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster:
        assert len(cluster.workers) == 2
        assert main(["batch", str(tmp_path / "m.toml"), "--out", str(tmp_path / "dask"),
                     "--scheduler", cluster.scheduler_address, "--quiet"]) == 0
    assert main(["batch", str(tmp_path / "m.toml"), "--out", str(tmp_path / "serial"),
                 "--scheduler", "serial", "--quiet"]) == 0
    for key in ("dask", "serial"):
        outs[key] = _read(tmp_path / key)
    rows_d, docs_d = outs["dask"]
    rows_s, docs_s = outs["serial"]
    assert len(rows_d) == 4 and [r["mesh"] for r in rows_d] == [
        "fig17_pocket", "fig17_pocket", "stepped_pyramid", "stepped_pyramid"]
    assert [r["slices"] for r in rows_d] == ["2", "3", "2", "3"]
    strip = [{k: v for k, v in r.items() if k != "seconds"} for r in rows_d]
    assert strip == [{k: v for k, v in r.items() if k != "seconds"} for r in rows_s]
    assert docs_d == docs_s
    assert float(rows_d[0]["fscore_1%"]) > 0.9  # the extruded pocket comes back
    assert "wrote" in capsys.readouterr().out


@pytest.mark.parametrize("text, message", [
    ("meshes = []", "non-empty list"),
    ("meshes = ['no_such_scene']", "no_such_scene"),
    ("meshes = ['bowl']\n[params]\nslices = 0", "at least"),
    ("meshes = ['bowl']\n[params]\nspeed = 1", "unknown parameters"),
    ("meshes = ['bowl']\n[params]\neps = 1.0\neps_share = 0.01", "not both"),
    ("meshes = ['bowl'", "not valid TOML"),
])
def test_bad_manifest_is_one_line_exit_2_and_writes_nothing(tmp_path, capsys, text, message):
    (tmp_path / "m.toml").write_text(text)
    out = tmp_path / "out"
    assert main(["batch", str(tmp_path / "m.toml"), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("recon3d: error:") and message in err[0]
    assert not out.exists()
