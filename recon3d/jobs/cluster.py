"""Run many independent tasks on Dask: a local cluster by default, or an existing one.

``run_tasks(fn, items)`` maps a top-level (importable, picklable) function over
``items`` and returns the results in item order, whatever the completion
order. Without ``scheduler`` a ``distributed.LocalCluster`` is started with
one single-threaded worker process per core and closed afterwards; with
``scheduler="tcp://host:8786"`` the tasks go to that cluster (its workers must
have this package installed); with ``scheduler="serial"`` they run one after
another in this process (no Dask at all). Each task is a whole job (one
mesh and one parameter set), so tasks never share state and a Dask run
returns exactly what the serial run returns (tested).
"""
from __future__ import annotations

import logging
import sys
from collections.abc import Callable

from tqdm import tqdm

from recon3d.config import default_jobs

__all__ = ["run_tasks", "SERIAL"]

SERIAL = "serial"


def _bar(total, desc, quiet):
    return None if quiet else tqdm(total=total, desc=desc, unit="task", file=sys.stderr)


def run_tasks(fn: Callable, items, scheduler: str | None = None, workers: int | None = None,
              desc: str = "tasks", quiet: bool = False) -> list:
    """``[fn(item) for item in items]``, on Dask unless ``scheduler == "serial"``.

    Parameters
    ----------
    fn : callable -- a module-level function (workers import it by name).
    items : list -- its arguments, one task each.
    scheduler : str, optional -- None: a new LocalCluster; ``"serial"``: this
        process; otherwise the address of a running Dask scheduler.
    workers : int, optional -- LocalCluster worker processes (default: cores).
    desc : str -- progress bar label; ``quiet`` hides the bar.

    Returns
    -------
    list -- ``fn(item)`` for every item, in item order.
    """
    items = list(items)
    bar = _bar(len(items), desc, quiet)
    try:
        if scheduler == SERIAL or not items:
            out = []
            for item in items:
                out.append(fn(item))
                if bar is not None:
                    bar.update(1)
            return out
        return _on_dask(fn, items, scheduler, workers, bar)
    finally:
        if bar is not None:
            bar.close()


def _on_dask(fn, items, scheduler, workers, bar) -> list:
    # lazy: distributed takes seconds to load; --scheduler serial runs without it
    from distributed import Client, LocalCluster, as_completed

    cluster = None
    if scheduler is None:
        logging.getLogger("distributed").setLevel(logging.ERROR)
        n = max(1, min(workers or default_jobs(), len(items)))
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                               dashboard_address=None)
    try:
        with Client(cluster if cluster is not None else scheduler) as client:
            futures = client.map(fn, items, pure=False)
            index = {f.key: k for k, f in enumerate(futures)}
            out = [None] * len(items)
            for fut in as_completed(futures):
                out[index[fut.key]] = fut.result()
                if bar is not None:
                    bar.update(1)
            return out
    finally:
        if cluster is not None:
            cluster.close()
