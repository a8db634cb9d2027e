"""The one room for parallel work: worker counts, batching, progress, and the joblib and
Dask back ends every parallel caller uses (campaigns, comparisons, report figures, the
bootstrap, tribometer processing, synthetic campaigns).

``jobs`` as the user gives it (N, or -1 for one per core) is a ceiling, never a demand:
a pool never has more processes than the machine has cores (CPU-bound fits only queue
for them, each process paying its start-up and its memory) or than there are tasks
(an idle worker costs its start-up and gains nothing).
"""

from __future__ import annotations

import importlib
import itertools
import os
import warnings
from collections import deque
from collections.abc import Callable, Iterable, Iterator, Sequence, Sized
from typing import Any

import numpy as np

from ..base.errors import InputError

__all__ = ["local_workers", "batches", "iter_parallel", "run_parallel", "batch_size",
           "check_jobs", "starmap_local", "SCHEDULER_ENV", "DASK_WORKER_CONFIG", "MAX_BATCH",
           "iter_chunks", "chunk_size", "MAX_CHUNK"]


def local_workers(jobs: int, tasks: int | None = None) -> int:
    """The worker processes for ``tasks`` tasks when ``jobs`` were asked for.

    Parameters
    ----------
    jobs : int
        The processes asked for: N >= 1, or -1 for one per core.
    tasks : int, optional
        The number of tasks, when known.

    Returns
    -------
    int
        ``min(jobs, cores, tasks)``, at least 1 (``cores`` as joblib counts them, which
        respects a container's CPU limit).
    """
    if jobs == 1:
        return 1
    from joblib import cpu_count

    cores = max(1, int(cpu_count()))
    workers = cores if jobs == -1 else min(int(jobs), cores)
    if tasks is not None:
        workers = min(workers, max(1, int(tasks)))
    return max(1, workers)


def batches(items: Iterable[Any], size: int) -> Iterator[list[Any]]:
    """``items`` in lists of ``size`` (the last one shorter), read lazily."""
    it = iter(items)
    while batch := list(itertools.islice(it, size)):
        yield batch


#: An environment variable that once named a Dask scheduler: it is never read to connect
#: (a scheduler runs code here; only an address given explicitly connects), and a run
#: that finds it set warns so.
SCHEDULER_ENV = "FRICTIONLAWS_SCHEDULER"


def _unread_environment() -> None:
    """Warn when :data:`SCHEDULER_ENV` is set: it does not connect by itself."""
    if os.environ.get(SCHEDULER_ENV):
        warnings.warn(f"the environment variable {SCHEDULER_ENV} is set but is not read: a "
                      "Dask scheduler is trusted with code execution, so it is connected "
                      "to only when its address is given explicitly; the work runs here",
                      UserWarning, stacklevel=3)


def iter_parallel(func: Callable[[Any], Any], items: Iterable[Any], *, jobs: int = 1,
                  scheduler: str | None = None, progress: bool = False,
                  total: int | None = None) -> Iterator[Any]:
    """Apply ``func`` to each item serially, on local processes or on a Dask cluster.

    The results come in order, each as soon as it (and those before it) is done.

    In parallel the items travel in batches (:func:`batch_size` items per task, so
    the cost of scheduling a task is shared by several items) and a bounded window
    of batches is in flight (a few per worker), so neither the caller's memory nor
    the scheduler's queue grows with the number of items.  Both back ends batch
    alike; the results are the same as serially, in the same order.

    Parameters
    ----------
    func : callable
        A module-level function (picklable) of one item.
    items : iterable
        The items; read lazily, a window at a time.
    jobs : int
        1: serial; N > 1: N local worker processes (joblib's loky backend);
        -1: one per core.
    scheduler : str, optional
        A Dask scheduler address (``tcp://host:8786`` or ``tls://host:8786``); the work
        goes to that cluster as Dask futures.  Connecting trusts the scheduler and its
        workers with code execution in this process (Dask exchanges pickles): only an
        address given here connects, never an environment variable
        (:func:`frictionlaws.parallel._network.connect_scheduler`).
    progress : bool
        Show a progress bar (tqdm) on stderr, counting finished items.
    total : int, optional
        Number of items (default ``len(items)`` when it has one), for the batch
        size and the progress bar.

    Yields
    ------
    object
        The results, in the order of ``items``; the caller may consume them as they
        come, so nothing but the current results is held.
    """
    total = _checked(jobs, scheduler, items, total)
    if scheduler is not None:
        results: Iterable[Any] = _on_dask(func, items, scheduler, total)
    elif jobs == 1:
        results = map(func, items)
    else:
        results = _on_joblib(func, items, jobs, total)
    yield from _progress(results, progress, total)


def iter_chunks(func: Callable[[list[Any]], Any], items: Iterable[Any], *, jobs: int = 1,
                scheduler: str | None = None, progress: bool = False,
                total: int | None = None) -> Iterator[Any]:
    """Apply ``func`` to consecutive chunks of ``items``: serially, on local processes or Dask.

    For work that is cheaper done for many items at once (a campaign's datasets, fitted
    law by law in stacks): each task is one chunk (a list of :func:`chunk_size` items)
    and ``func`` returns one result for the whole chunk.  The calling process only cuts
    the chunks, schedules them and takes their results; on the joblib and Dask back ends
    alike a bounded window of chunks is in flight (a few per worker), so neither the
    caller's memory nor the scheduler's queue grows with the number of items.  The
    results are the same however the work ran, as long as ``func`` gives the same
    result for each item whatever chunk it is in.

    Parameters
    ----------
    func : callable
        A module-level function (picklable) of a list of items.
    items : iterable
        The items; read lazily, a window of chunks at a time (so an item made when it
        is taken can depend on the results taken before).
    jobs, scheduler : optional
        As for :func:`iter_parallel`.
    progress : bool
        Show a progress bar (tqdm) on stderr, counting the items of finished chunks.
    total : int, optional
        Number of items (default ``len(items)`` when it has one), for the chunk size
        and the progress bar.

    Yields
    ------
    object
        ``func(chunk)`` for each chunk, in the order of ``items``.
    """
    total = _checked(jobs, scheduler, items, total)
    if scheduler is not None:
        results: Iterable[tuple[int, Any]] = _on_dask(func, items, scheduler, total, True)
    elif jobs == 1:
        results = ((len(chunk), func(chunk)) for chunk in batches(items, chunk_size(total, 1)))
    else:
        results = _on_loky(func, items, jobs, total)
    if not progress:
        yield from (result for _, result in results)
        return
    bar = importlib.import_module("tqdm").tqdm(total=total, unit="dataset", leave=False)
    try:
        for count, result in results:
            bar.update(count)
            yield result
    finally:
        bar.close()


def _checked(jobs: Any, scheduler: str | None, items: Iterable[Any], total: int | None
             ) -> int | None:
    """The job count checked, the unread environment named; the number of items."""
    check_jobs(jobs)
    if scheduler is None:
        _unread_environment()
    if total is None and isinstance(items, Sized):
        total = len(items)
    return total


def run_parallel(func: Callable[[Any], Any], items: Iterable[Any], **kw: Any) -> list[Any]:
    """Run :func:`iter_parallel` to the end.

    Parameters
    ----------
    func : callable
        A module-level function (picklable) of one item.
    items : iterable
        The items.
    **kw
        ``jobs``, ``scheduler``, ``progress``, ``total`` as for :func:`iter_parallel`.

    Returns
    -------
    list
        The results, in the order of ``items``.
    """
    return list(iter_parallel(func, items, **kw))


#: Largest number of items in one task (a task then lasts well under a second for
#: a dataset and three laws, short enough to balance the workers at the end).
MAX_BATCH = 16


#: Tasks per worker the items are cut into at least (load balance at the end).
_TASKS_PER_WORKER = 8


#: Batches in flight per worker thread (one running, the next ones queued).
_WINDOW = 3


#: Dask settings recommended for the workers of a campaign (start the workers with
#: them: ``dask.config.set`` before a ``LocalCluster``, or the environment variables
#: ``DASK_DISTRIBUTED__WORKER__PROFILE__ENABLED=False`` and
#: ``DASK_DISTRIBUTED__ADMIN__TICK__INTERVAL=500ms`` for ``dask worker``).  The
#: statistical profiler samples the running task's stack every 10 ms and the event
#: loop checks its health every 20 ms; with fits written in Python, that took a
#: fifth of the workers' CPU time in ``benchmarks/bench_campaign.py``.
DASK_WORKER_CONFIG: dict[str, Any] = {
    "distributed.worker.profile.enabled": False,
    "distributed.admin.tick.interval": "500ms",
}


#: Largest number of items in one chunk of :func:`iter_chunks` (a campaign's datasets,
#: fitted in stacks: a few hundred make numpy's loops worth their set-up).
MAX_CHUNK = 512


#: Chunks per worker :func:`iter_chunks` cuts the items into at least (balance at the end).
_CHUNKS_PER_WORKER = 4


def chunk_size(total: int | None, workers: int) -> int:
    """Choose the number of items per chunk for ``total`` items on ``workers`` workers.

    As many as fit :data:`MAX_CHUNK`, and at least four chunks per worker (all workers
    stay busy to the end); serially (one worker) chunks of :data:`MAX_CHUNK`.

    Parameters
    ----------
    total : int or None
        Number of items; ``None`` or 0 when not known.
    workers : int
        Worker processes (or threads) the chunks are spread over.

    Returns
    -------
    int
        Items per chunk, from 1 to :data:`MAX_CHUNK` (64 when ``total`` is not known
        and there are several workers).
    """
    if workers <= 1:
        return MAX_CHUNK
    if not total or total <= 0:
        return 64
    return max(1, min(MAX_CHUNK, total // (_CHUNKS_PER_WORKER * workers)))


def batch_size(total: int | None, workers: int) -> int:
    """Choose the number of items per task for ``total`` items on ``workers`` threads.

    Enough items to share the cost of scheduling a task, at most :data:`MAX_BATCH`,
    and at least eight tasks per worker so that all workers stay busy to the end.

    Parameters
    ----------
    total : int or None
        Number of items; ``None`` or 0 when not known.
    workers : int
        Worker threads (processes for joblib) the tasks are spread over.

    Returns
    -------
    int
        Items per task, from 1 (also when ``total`` is not known) to :data:`MAX_BATCH`.
    """
    if not total or total <= 0:
        return 1
    return max(1, min(MAX_BATCH, total // (_TASKS_PER_WORKER * max(workers, 1))))


def _run_batch(func: Callable[[Any], Any], batch: Sequence[Any]) -> list[Any]:
    """One task: ``func`` over a batch of items (runs on a worker)."""
    return [func(item) for item in batch]


def check_jobs(jobs: Any) -> None:
    """Refuse a job count that is not 1..1024 or -1 (one per core)."""
    if isinstance(jobs, bool) or not isinstance(jobs, (int, np.integer)) or not (
            jobs == -1 or 1 <= jobs <= 1024):
        raise InputError(f"jobs must be a whole number from 1 to 1024, or -1 for one per "
                         f"core (got {jobs!r})")


def _progress(results: Iterable[Any], on: bool, total: int | None) -> Iterable[Any]:
    if not on:
        return results
    tqdm = importlib.import_module("tqdm").tqdm  # untyped library: Any

    return tqdm(results, total=total, unit="dataset", leave=False)


def _on_joblib(func: Callable[[Any], Any], items: Iterable[Any], jobs: int,
               total: int | None) -> Iterator[Any]:
    """``func`` over ``items`` on ``jobs`` local processes (loky), in batches, in order."""
    joblib = importlib.import_module("joblib")  # untyped library: Any

    workers = local_workers(jobs, total)
    size = batch_size(total, workers)
    tasks = (joblib.delayed(_run_batch)(func, batch) for batch in batches(items, size))
    parallel = joblib.Parallel(n_jobs=workers, batch_size=1, pre_dispatch=_WINDOW * workers,
                               return_as="generator")
    for part in parallel(tasks):
        yield from part


def _on_loky(func: Callable[[Any], Any], items: Iterable[Any], jobs: int,
             total: int | None) -> Iterator[tuple[int, Any]]:
    """``func`` over chunks of ``items`` on ``jobs`` local processes: ``(items, result)``
    of each chunk, in order.

    One task a chunk, on the process pool of joblib's loky back end (the pool every
    ``jobs`` caller shares, its workers' thread limits set as joblib sets them); a window
    of :data:`_WINDOW` chunks per worker in flight.
    """
    joblib = importlib.import_module("joblib")  # untyped library: Any

    workers = local_workers(jobs, total)
    counts: deque[int] = deque()

    def tasks() -> Iterator[Any]:
        for batch in batches(items, chunk_size(total, workers)):
            counts.append(len(batch))
            yield joblib.delayed(func)(batch)

    parallel = joblib.Parallel(n_jobs=workers, batch_size=1, pre_dispatch=_WINDOW * workers,
                               return_as="generator")
    for result in parallel(tasks()):
        yield counts.popleft(), result


def _dask_client(address: str) -> Any:
    """A Dask client connected to ``address`` within one deadline; InputError naming why not."""
    from ._network import connect_scheduler  # asyncio and ssl: only with a Dask scheduler

    return connect_scheduler(address)


def _on_dask(func: Callable[[Any], Any], items: Iterable[Any], address: str,
             total: int | None, chunked: bool = False) -> Iterator[Any]:
    """``func`` over ``items`` on the Dask cluster at ``address``, results in order.

    Batches of items are submitted as futures (no joblib layer), sized by the
    cluster's worker threads; a window of :data:`_WINDOW` batches per thread is in
    flight and each is released as soon as its results are taken.  ``chunked`` as
    for :func:`_on_joblib`.
    """
    with _dask_client(address) as client:
        threads = sum(client.nthreads().values()) or 1
        size = chunk_size(total, threads) if chunked else batch_size(total, threads)
        window: deque[tuple[int, Any]] = deque()
        for batch in batches(items, size):
            future = (client.submit(func, batch, pure=False) if chunked
                      else client.submit(_run_batch, func, batch, pure=False))
            window.append((len(batch), future))
            if len(window) >= _WINDOW * threads:
                yield from _taken(window.popleft(), chunked)
        while window:
            yield from _taken(window.popleft(), chunked)


def _taken(entry: tuple[int, Any], chunked: bool) -> Iterator[Any]:
    """The result of one Dask future (released as it is taken)."""
    count, future = entry
    result = future.result()
    if chunked:
        yield count, result
    else:
        yield from result


def starmap_local(func: Callable[..., Any], calls: Iterable[tuple[Any, ...]],
                  workers: int) -> Iterator[Any]:
    """``func(*args)`` for each ``args`` of ``calls``, in order, on ``workers`` local
    processes (joblib's loky backend; 1: in this process).

    For work the caller has already cut into tasks (a comparison's fits, a report's
    figures, the bootstrap's batches of refits); :func:`iter_parallel` batches items itself.

    Parameters
    ----------
    func : callable
        A module-level function (picklable).
    calls : iterable of tuple
        The arguments of each call; read lazily.
    workers : int
        Processes (from :func:`local_workers`).

    Yields
    ------
    object
        The results, in the order of ``calls``.
    """
    if workers <= 1:
        for args in calls:
            yield func(*args)
        return
    joblib = importlib.import_module("joblib")  # untyped library: Any

    yield from joblib.Parallel(n_jobs=workers, return_as="generator")(
        joblib.delayed(func)(*args) for args in calls)
