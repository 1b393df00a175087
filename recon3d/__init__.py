"""recon3d: slice-based pulling-motion tactile sensing of 3D meshes, end to end.

The pipeline over slices (:mod:`recon3d.pipeline`), the reconstructed
watertight surface (:mod:`recon3d.closure`, :mod:`recon3d.field`,
:mod:`recon3d.surface`), its 3D metrics (:mod:`recon3d.evaluate`), the
pyvista pictures (:mod:`recon3d.scene`, :mod:`recon3d.plot`) and the command
line (:mod:`recon3d.cli`).

Example (the README has more)::

    import recon3d
    res = recon3d.run("fig17_pocket", axis=["z", "x"], slices=6)
    res.metrics["total"]["surface"]["fscore"]["1%"]
    res.save("out/pocket")
"""
from recon3d.api import Result, run
from recon3d.checks import InputError
from recon3d.pipeline import RunConfig
from recon3d.save import read_ply_labels
from recon3d.surface import LABELS

__all__ = ["run", "Result", "RunConfig", "InputError", "LABELS", "read_ply_labels"]
