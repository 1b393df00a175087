"""Sensing: every slice of a mesh through the paper's 2D algorithm (meshes -> slicer -> core2d).

One entry point, :func:`sense_mesh` (:mod:`.mesh`), for a uniform or an
adaptive plan of planes (:mod:`.adaptive`); the per-slice work (:mod:`.worker`)
and the process pool (:mod:`.pool`) are internal; a worker process that
dies raises :class:`WorkerDied`.
"""
from recon3d.sensing.mesh import sense_mesh
from recon3d.sensing.pool import WorkerDied

__all__ = ["sense_mesh", "WorkerDied"]
