"""recon3d: slice-based pulling-motion tactile sensing of 3D meshes, end to end.

Sensing over slices (:mod:`recon3d.sensing`), the reconstructed watertight
surface (:mod:`recon3d.surface`), its 3D scores (:mod:`recon3d.score`),
files (:mod:`recon3d.io`), pictures (:mod:`recon3d.viz`), many runs on Dask
(:mod:`recon3d.jobs`) and the command line (``recon3d``, :mod:`recon3d.cli`);
the run parameters in one place (:mod:`recon3d.config`).

Example (the README has more)::

    import recon3d
    res = recon3d.run("fig17_pocket", axis=["z", "x"], slices=6)
    res.metrics["total"]["surface"]["fscore"]["1%"]
    res.save("out/pocket")
"""
from recon3d.api import Result, WorkerDied, __version__, run
from recon3d.checks import InputError
from recon3d.config import RunConfig
from recon3d.io.ply import read_ply_labels
from recon3d.records import LABELS

__all__ = ["run", "Result", "RunConfig", "InputError", "WorkerDied", "LABELS",
           "read_ply_labels", "__version__"]
