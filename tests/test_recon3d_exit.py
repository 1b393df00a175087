"""A Result kept until the interpreter exits leaves nothing alive that a binding
complains about: the kept scene (``Result.blocks``) holds copies of manifold3d's
arrays, not views that keep a ``Mesh64`` alive past nanobind's own teardown."""
import os
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]


def test_a_result_kept_to_exit_leaks_no_binding_object():
    code = ("import recon3d\n"
            "r = recon3d.run('stepped_pyramid', slices=2, backend='exact', jobs=1)\n"
            "r.blocks()\n"
            "print('ran')\n")
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env=env, cwd=ROOT, timeout=600)
    assert out.returncode == 0, out.stderr[-2000:]
    assert "ran" in out.stdout
    assert "leaked" not in out.stderr, out.stderr[:400]
