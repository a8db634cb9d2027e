"""Chunks of items per task (:func:`frictionlaws.parallel.iter_chunks`): sizes, order, the
window of chunks in flight and the progress bar, serially and on local processes."""

from __future__ import annotations

import itertools

import pytest

from frictionlaws.parallel import MAX_CHUNK, chunk_size, iter_chunks


def _sums(chunk):
    """A chunk's result: its items and their sum (module level: picklable)."""
    return list(chunk), sum(chunk)


@pytest.mark.parametrize(("total", "workers", "size"), [
    (2000, 1, MAX_CHUNK), (2000, 2, 250), (10**5, 2, MAX_CHUNK), (10, 2, 1), (1, 4, 1),
    (None, 2, 64), (0, 2, 64), (2000, 16, 31), (9, 2, 1)])
def test_chunk_size(total, workers, size):
    assert chunk_size(total, workers) == size


def test_chunks_keep_every_worker_busy_to_the_end():
    for total, workers in itertools.product((1, 9, 64, 333, 5000, 10**5), (2, 3, 16)):
        size = chunk_size(total, workers)
        assert 1 <= size <= MAX_CHUNK
        if size < MAX_CHUNK:  # at least four chunks per worker unless chunks are full
            assert -(-total // size) >= min(total, 4 * workers)


@pytest.mark.parametrize("jobs", [1, 2])
def test_chunks_come_back_in_order_with_every_item(jobs):
    items = list(range(-300, 701))
    parts = list(iter_chunks(_sums, iter(items), jobs=jobs, total=len(items)))
    assert [x for chunk, _ in parts for x in chunk] == items
    assert sum(s for _, s in parts) == sum(items)
    assert len(parts) == (2 if jobs == 1 else 9)  # 1001 items: 8 chunks of 125 and one


def test_items_are_taken_a_window_at_a_time():
    """The items of a chunk are taken when it is cut: a result can change what follows."""
    taken = []

    def items():
        for i in range(3 * MAX_CHUNK):
            taken.append(i)
            yield i

    parts = iter_chunks(_sums, items(), total=3 * MAX_CHUNK)
    next(parts)
    assert len(taken) == MAX_CHUNK  # the first chunk only
    assert len(list(parts)) == 2


def test_the_progress_bar_counts_items(capsys):
    list(iter_chunks(_sums, range(700), progress=True, total=700))
    err = capsys.readouterr().err
    assert "0/700" in err and "dataset" in err
