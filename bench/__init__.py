"""Benchmarks (``python -m bench.bench_cast``, ``python -m bench.bench_slicing``)."""
