"""Write a run's outputs into a directory, all or nothing.

Every file is first written into a hidden staging directory inside the
output directory, then moved into place with ``os.replace``; on any error
the staging directory is removed, and so is the output directory when this
call created it. Files are 0644, directories 0755. A machine without
OpenGL cannot render ``coverage.png``: the other files are still written
and a ``RuntimeWarning`` says why the picture is missing.
"""
from __future__ import annotations

import json
import os
import shutil
import tempfile
import warnings
from pathlib import Path

import numpy as np

__all__ = ["OUTPUTS", "write_outputs", "write_ply", "read_ply_labels"]

OUTPUTS = ("sensing.json", "metrics.json", "surface.ply", "scene.vtm", "coverage.png")
"""Files of a complete run (``scene.vtm`` comes with its ``scene/`` folder)."""


def write_ply(path, surface) -> None:
    """Binary PLY with an ``int label`` face property (float32 vertices)."""
    import trimesh

    mesh = trimesh.Trimesh(surface.vertices, surface.faces, process=False)
    mesh.face_attributes["label"] = np.asarray(surface.face_attributes["label"], np.int32)
    Path(path).write_bytes(trimesh.exchange.ply.export_ply(mesh, encoding="binary"))


def read_ply_labels(path):
    """Load ``surface.ply`` as a trimesh with ``face_attributes['label']`` (f,) int32."""
    import trimesh

    mesh = trimesh.load(str(path), process=False)
    raw = mesh.metadata.get("_ply_raw", {}).get("face", {}).get("data")
    if raw is None or "label" not in raw.dtype.names:
        raise ValueError(f"{path} has no face property 'label'")
    mesh.face_attributes["label"] = np.asarray(raw["label"], dtype=np.int32)
    return mesh


def _render(blocks, path, title) -> None:
    from recon3d.plot import save_png

    try:
        save_png(blocks, path, title=title)
    except Exception as exc:  # VTK raises many kinds when OpenGL is missing
        msg = " ".join(str(exc).split())[:200]
        warnings.warn(f"coverage.png not written: {type(exc).__name__}: {msg} (needs OpenGL: "
                      f"EGL or a display; --no-png skips it)", RuntimeWarning, stacklevel=3)


def _json(path, obj, indent=1) -> None:
    """Write ``obj``; ``indent=None`` writes compact JSON through the C encoder
    (``json.dump`` and any indent take the pure-Python one: ~10x slower on
    the 10+ MB sensing document of a large run)."""
    text = json.dumps(obj, indent=indent, allow_nan=False)
    with open(path, "w") as fh:
        fh.write(text)


def _chmod_tree(path: Path) -> None:
    if path.is_dir():
        os.chmod(path, 0o755)
        for child in path.iterdir():
            _chmod_tree(child)
    else:
        os.chmod(path, 0o644)


def write_outputs(out, sensing: dict, metrics: dict, surface, blocks, title: str = "",
                  png: bool = True) -> list[Path]:
    """Write the outputs of one run into ``out``.

    Parameters
    ----------
    out : path -- created if missing (and removed again if writing fails).
    sensing, metrics : dict -- the JSON documents.
    surface : trimesh.Trimesh with ``face_attributes['label']``.
    blocks : pyvista.MultiBlock -- :func:`recon3d.scene.scene_blocks`.
    png : bool -- render ``coverage.png`` (needs an OpenGL context; see module doc).

    Returns
    -------
    list of Path -- the files written (the ``scene/`` folder included).
    """
    out = Path(out)
    top = out.absolute()  # the first directory this call creates, if any
    while not top.parent.exists():
        top = top.parent
    created = not out.exists()
    out.mkdir(parents=True, exist_ok=True)
    if created:
        os.chmod(out, 0o755)
    stage = Path(tempfile.mkdtemp(prefix=".recon3d-", dir=out))
    try:
        _json(stage / "sensing.json", sensing, indent=None)  # machine data: compact
        _json(stage / "metrics.json", metrics)
        write_ply(stage / "surface.ply", surface)
        blocks.save(str(stage / "scene.vtm"))
        if png:
            _render(blocks, stage / "coverage.png", title)
        names = sorted(p.name for p in stage.iterdir())
        for name in set(OUTPUTS) - set(names):  # a stale picture would not match the data
            if (out / name).is_file():
                os.unlink(out / name)
        for name in names:
            _chmod_tree(stage / name)
            target = out / name
            if target.is_dir() and not target.is_symlink():
                shutil.rmtree(target)
            os.replace(stage / name, target)
        stage.rmdir()
        return [out / n for n in names]
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        if created:
            shutil.rmtree(top, ignore_errors=True)
        raise
