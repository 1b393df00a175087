"""``python -m recon3d`` is the same as the ``recon3d`` console script."""
from recon3d.cli import entry

entry()
