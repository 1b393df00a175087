"""One source for the run parameters: the fields of RunConfig give the flags of
``recon3d run``, the keywords of ``recon3d.run``, the batch manifest keys and the
README's options table; defaults that derive from the mesh are resolved once."""
import dataclasses
import inspect
import pathlib

import numpy as np
import pytest
import trimesh

import recon3d
from recon3d.checks import InputError
from recon3d.cli.main import build_parser
from recon3d.cli.run import COMMAND_FLAGS
from recon3d.config import PARAMS, RunConfig, resolve, validate
from recon3d.spellings import batch_keys, make_config, options_table
from recon3d.jobs.batch import read_manifest
from recon3d.records import diagonal

README = pathlib.Path(__file__).resolve().parents[1] / "README.md"


def _run_parser():
    sub = next(a for a in build_parser()._actions if a.dest == "command")
    return sub.choices["run"]


def test_every_field_but_bootstrap_is_a_documented_parameter():
    names = [f.name for f in dataclasses.fields(RunConfig)]
    assert [p.name for p in PARAMS] == [n for n in names if n != "bootstrap"]
    for p in PARAMS:
        assert p.help and p.doc and p.flag == "--" + p.key.replace("_", "-")


def test_cli_flags_are_the_parameters():
    flags = {s for a in _run_parser()._actions for s in a.option_strings}
    assert flags == {p.flag for p in PARAMS} | {"--out", "-h", "--help"} | {
        f for f, _, _ in COMMAND_FLAGS}
    args = _run_parser().parse_args(["scene", "--out", "o"])
    given = {p.key: getattr(args, p.key) for p in PARAMS}
    assert all(v is None for v in given.values())  # absent flags: the dataclass defaults
    args = _run_parser().parse_args(["scene", "--out", "o", "--slices", "auto", "--eps", "2",
                                     "--max-slices", "9", "--backend", "exact"])
    cfg = make_config(**{p.key: v for p in PARAMS if (v := getattr(args, p.key)) is not None})
    assert cfg == dataclasses.replace(RunConfig(), slices="auto", eps=2.0, max_slices=9,
                                      backend="exact")


def test_run_keywords_are_the_parameters_with_the_dataclass_defaults():
    sig = inspect.signature(recon3d.run)
    kw = [n for n, q in sig.parameters.items() if q.kind is q.KEYWORD_ONLY and n != "progress"]
    assert kw == [p.key for p in PARAMS]
    defaults = RunConfig()
    for p in PARAMS:
        want = getattr(defaults, p.name)
        assert make_config(**{p.key: sig.parameters[p.key].default}) == defaults
        assert sig.parameters[p.key].default == (want if p.key != "axis" else "z")
        assert f"{p.key} :" in recon3d.run.__doc__
    assert make_config() == defaults
    with pytest.raises(TypeError, match="unexpected keyword argument 'speed'"):
        make_config(speed=3)


def test_batch_keys_are_the_parameters_but_jobs_and_eps_share(tmp_path):
    assert batch_keys() == tuple(k for p in PARAMS if p.batch
                                 for k in ((p.key, "eps_share") if p.key == "eps" else (p.key,)))
    assert "jobs" not in batch_keys() and "eps_share" in batch_keys()
    body = "\n".join(f"{k} = {v}" for k, v in (("probe_speed", 5.0), ("motion_overhead", 0.0),
                                                ("max_motions", 50), ("slice_tol", 0.01)))
    (tmp_path / "m.toml").write_text(f"meshes = ['fig17_pocket']\n[params]\n{body}\n")
    (job,) = read_manifest(tmp_path / "m.toml")
    assert job.params["probe_speed"] == 5.0
    (tmp_path / "m.toml").write_text("meshes = ['fig17_pocket']\n[params]\nmax_motions = 0\n")
    with pytest.raises(InputError, match="params.max_motions must be at least 1"):
        read_manifest(tmp_path / "m.toml")


def test_readme_options_table_is_the_generated_one():
    text = README.read_text().splitlines()
    start = text.index("| option | default | meaning |")
    table = text[start:text.index("", start)]
    assert table == options_table([(f"`{f}`", doc) for f, _, doc in COMMAND_FLAGS])


@pytest.mark.parametrize("spelling, name", [("key", "max_motions"), ("flag", "--max-motions"),
                                            ("params", "params.max_motions")])
def test_error_messages_name_the_parameter_as_the_caller_spells_it(spelling, name):
    mesh = trimesh.creation.box(extents=[10.0, 10.0, 10.0])
    with pytest.raises(InputError, match=f"^{name} must be at least 1"):
        validate(mesh, make_config(max_motions=0), spelling)


def test_mesh_derived_defaults_are_resolved_in_one_place():
    mesh = trimesh.creation.box(extents=[3.0, 4.0, 12.0])
    d = diagonal(mesh)
    assert d == float(np.linalg.norm(np.ptp(mesh.bounds, axis=0))) == 13.0
    r = resolve(RunConfig(jobs=3), d)
    assert (r.eps, r.tol, r.first_eps, r.jobs, r.probe_length) == (d / 200, d / 200 / 20,
                                                                   d / 200, 3, None)
    auto = resolve(RunConfig(slices="auto", eps=1.0, tol=0.1), d, [[]])
    assert auto.first_eps == 2.0 and auto.probe_length == 4.0 * (1.0 + 2.0)
    assert auto.tol_share == 0.1


def test_manifest_doc_names_every_key():
    from recon3d.spellings import manifest_doc

    doc = manifest_doc()
    assert all(k in doc for k in batch_keys())
