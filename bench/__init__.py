"""Benchmarks (``python -m bench.bench_cast``, ``python -m bench.bench_slicing``).

Importing the package pins the numerics first (:mod:`recon3d.numerics`), so a bench run
as ``python -m bench.NAME`` rounds as every run of the product does.
"""
import recon3d as _recon3d  # noqa: F401  (light: pins the numerics before numpy loads)
