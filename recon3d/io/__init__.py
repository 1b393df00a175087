"""Files: the JSON documents (:mod:`.documents`), ``surface.ply`` (:mod:`.ply`), the one
staged all-or-nothing writer (:mod:`.staged`) and the outputs of a run (:mod:`.outputs`)."""
from recon3d.io.documents import without_timing
from recon3d.io.ply import read_ply_labels

__all__ = ["without_timing", "read_ply_labels"]
