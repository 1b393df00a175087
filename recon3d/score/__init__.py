"""3D scores against the ground-truth mesh: the metric definitions (:mod:`.evaluate`)
and the scores of a run with each family's gain (:mod:`.families`)."""
from recon3d.score.families import score

__all__ = ["score"]
