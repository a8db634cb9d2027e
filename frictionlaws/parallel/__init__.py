"""The one room for parallel work (worker counts, batching, progress, the joblib and Dask
back ends): :mod:`~frictionlaws.parallel.runner` holds it and this package names its
public interface; :mod:`~frictionlaws.parallel._network` is the connection to a Dask
scheduler that the runner makes.
"""

from __future__ import annotations

from .runner import (
    DASK_WORKER_CONFIG,
    MAX_BATCH,
    MAX_CHUNK,
    SCHEDULER_ENV,
    batch_size,
    batches,
    check_jobs,
    chunk_size,
    iter_chunks,
    iter_parallel,
    local_workers,
    run_parallel,
    starmap_local,
)

__all__ = ["local_workers", "batches", "iter_parallel", "run_parallel", "batch_size",
           "check_jobs", "starmap_local", "SCHEDULER_ENV", "DASK_WORKER_CONFIG", "MAX_BATCH",
           "iter_chunks", "chunk_size", "MAX_CHUNK"]
