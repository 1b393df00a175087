"""``python -m recon3d`` is the same as the ``recon3d`` console script."""
import sys

from recon3d.cli import main

sys.exit(main())
