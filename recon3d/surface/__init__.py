"""The reconstructed surface: each slice closed and filled (:mod:`.closure`), a signed
distance field per family (:mod:`.field`), its level set and the fused solid
(:mod:`.solid`), the whole run (:mod:`.reconstruct`)."""
from recon3d.surface.reconstruct import Reconstruction, reconstruct

__all__ = ["reconstruct", "Reconstruction"]
