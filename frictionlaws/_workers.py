"""How many local worker processes a piece of parallel work gets: one rule for all.

``jobs`` as the user gives it (N, or -1 for one per core) is a ceiling, never a demand:
a pool never has more processes than the machine has cores (CPU-bound fits only queue
for them, each process paying its start-up and its memory) or than there are tasks
(an idle worker costs its start-up and gains nothing).
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Iterator
from typing import Any

__all__ = ["local_workers", "batches"]


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
