"""3D scores against the ground-truth mesh: the metric definitions (:mod:`.evaluate`)
and the scores of a run with each family's gain (:mod:`.families`)."""
from recon3d.score import closest, subdivide
from recon3d.score.families import score

__all__ = ["score", "compile_kernels"]


def compile_kernels() -> None:
    """Compile (or load from numba's cache) the compiled kernels that run after the
    sensing: the point-to-mesh distances (:func:`recon3d.score.closest.compile_kernels`) and
    the coloured ground truth's subdivision (:func:`recon3d.score.subdivide.compile_kernels`).
    The first run of a machine calls it beside the sensing (:mod:`recon3d.sensing.pool`)."""
    closest.compile_kernels()
    subdivide.compile_kernels()
