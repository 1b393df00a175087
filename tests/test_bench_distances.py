"""``bench/bench_distances.py``: one commit's build and query times, and its distances."""
from __future__ import annotations

import pytest
import trimesh

from bench.bench_distances import main


def test_the_bench_times_a_commit_and_compares_its_distances(tmp_path, capsys):
    mesh = tmp_path / "ball.ply"
    trimesh.creation.icosphere(subdivisions=3).export(mesh)
    assert main(["WORKTREE", "WORKTREE", "--repeat", "1", "--mesh", str(mesh)]) == 0
    out = capsys.readouterr().out
    assert "1280 faces, 642 query points" in out
    rows = [line for line in out.splitlines() if line.startswith("| worktree |")]
    assert len(rows) == 2 and all(row.endswith("| yes |") for row in rows)


def test_a_missing_mesh_is_one_error(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["--mesh", "/no/such/mesh.ply"])
    assert exc.value.code == 2
    assert "no such mesh file" in capsys.readouterr().err
