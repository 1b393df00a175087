"""Sensing: every slice of a mesh through the paper's 2D algorithm (meshes -> slicer -> core2d).

One entry point, :func:`sense_mesh` (:mod:`.mesh`), for a uniform or an
adaptive plan of planes (:mod:`.adaptive`); the per-slice work (:mod:`.worker`)
and the process pool (:mod:`.pool`) are internal, as are the slice regions closed in the main
process as slices come back (:mod:`.regions`); a worker process that
dies raises :class:`WorkerDied`; :func:`cold_kernels` (:mod:`.kernels`) says whether a run
will first compile the numba kernels (read from numba's cache, nothing compiled).
"""
from recon3d.sensing.kernels import COMPILE_NOTICE, cold_kernels
from recon3d.sensing.mesh import sense_mesh
from recon3d.sensing.pool import WorkerDied

__all__ = ["sense_mesh", "WorkerDied", "cold_kernels", "COMPILE_NOTICE"]
