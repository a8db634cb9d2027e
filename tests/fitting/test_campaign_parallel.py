"""Campaign work in parallel: batches, the bounded window, joblib and Dask equal to serial."""

from __future__ import annotations

import itertools

import numpy as np
import pandas as pd
import pytest

import frictionlaws as fl
from frictionlaws.fitting.campaign import (
    DASK_WORKER_CONFIG,
    MAX_BATCH,
    SCHEDULER_ENV,
    batch_size,
    compare_many,
    fit_many,
    iter_parallel,
    run_parallel,
)

THIRION = fl.get_law("thirion")


def _folder(tmp_path, count, name="many"):
    """``count`` small Thirion datasets (p in MPa), one file each, and one of a single row.

    The single-row file reads, so the campaign runs (an unreadable file would refuse it
    before any fit); Thirion's two parameters cannot be fitted to it: a failed record.
    """
    rng = np.random.default_rng(11)
    folder = tmp_path / name
    folder.mkdir()
    p = np.linspace(0.02, 0.8, 12)
    for i in range(count):
        mu = THIRION(p=p * 1e6, a=rng.uniform(0.2, 0.6), b=3e-6) \
            + 0.01 * rng.standard_normal(p.size)
        pd.DataFrame({"mu": mu, "p [MPa]": p}).to_csv(folder / f"d{i:03d}.csv", index=False)
    (folder / "zz_broken.csv").write_text("mu,p [MPa]\n0.5,0.1\n")
    return folder


@pytest.fixture(scope="module")
def cluster():
    """A two-worker LocalCluster started with the recommended worker configuration."""
    distributed = pytest.importorskip("dask.distributed")
    import dask

    with dask.config.set(DASK_WORKER_CONFIG), distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True,
            dashboard_address=None) as local, distributed.Client(local) as client:
        yield local.scheduler_address, client


@pytest.mark.parametrize(("total", "workers", "size"), [
    (1000, 2, MAX_BATCH), (100, 2, 6), (15, 2, 1), (0, 2, 1), (None, 2, 1),
    (10**5, 100, MAX_BATCH), (10**5, 10**4, 1), (50, 0, 6)])
def test_batch_size(total, workers, size):
    assert batch_size(total, workers) == size


def test_batches_keep_every_task_count_sensible():
    for total, workers in itertools.product((1, 7, 64, 333, 5000), (1, 2, 3, 16)):
        size = batch_size(total, workers)
        assert 1 <= size <= MAX_BATCH
        if size > 1:  # at least 8 tasks per worker whenever items are batched
            assert -(-total // size) >= 8 * workers


@pytest.mark.parametrize("with_len", [True, False])
def test_joblib_batches_keep_order_and_every_item(with_len):
    items = list(range(-61, 42))  # 103 items: batches of 6, the last one shorter
    source = items if with_len else iter(items)
    assert run_parallel(abs, source, jobs=2) == [abs(x) for x in items]


@pytest.mark.slow
def test_fit_many_in_batches_equals_serial_with_joblib_and_dask(tmp_path, cluster):
    folder = _folder(tmp_path, 40)  # batches of 2 datasets on 2 workers
    assert batch_size(41, 2) == 2
    serial = fit_many(["thirion", "coulomb"], folder)
    assert len(serial) == 82 and len(serial.errors) == 1  # thirion on one row
    frame = serial.to_frame()
    pd.testing.assert_frame_equal(frame, fit_many(["thirion", "coulomb"], folder,
                                                  jobs=2).to_frame())
    address, _ = cluster
    remote = fit_many(["thirion", "coulomb"], folder, scheduler=address)
    assert remote.records == serial.records
    streamed = fit_many(["thirion", "coulomb"], folder, scheduler=address,
                        output=tmp_path / "out.csv")
    assert len(streamed) == 82 and len(streamed.errors) == 1
    pd.testing.assert_frame_equal(frame, streamed.to_frame(), check_dtype=False)


@pytest.mark.slow
def test_compare_many_on_dask_equals_serial(tmp_path, cluster):
    folder = _folder(tmp_path, 6)
    serial = compare_many(folder, ["thirion", "coulomb"], folds=3)
    assert serial["error"].notna().sum() == 1 and len(serial) == 13
    address, _ = cluster
    pd.testing.assert_frame_equal(serial, compare_many(folder, ["thirion", "coulomb"],
                                                       folds=3, scheduler=address))
    pd.testing.assert_frame_equal(serial, compare_many(folder, ["thirion", "coulomb"],
                                                       folds=3, jobs=2))


def test_the_environment_alone_never_connects(tmp_path, cluster, monkeypatch):
    """A scheduler runs code here: FRICTIONLAWS_SCHEDULER set to a live cluster's address
    connects to nothing; the work runs here, with a warning that says so."""
    from frictionlaws.parallel import _network

    folder = _folder(tmp_path, 3)
    serial = fit_many("thirion", folder).records
    address, _ = cluster
    monkeypatch.setenv(SCHEDULER_ENV, address)

    def refuse(*args, **kwargs):
        raise AssertionError("connected to a scheduler named only in the environment")

    monkeypatch.setattr(_network, "connect_scheduler", refuse)
    with pytest.warns(UserWarning, match=f"{SCHEDULER_ENV} is set but is not read"):
        assert fit_many("thirion", folder).records == serial


def test_dask_window_is_bounded(cluster):
    """Items are read a window at a time: 3 batches per worker thread before a result."""
    address, _ = cluster
    taken = []

    def items():
        for i in range(1000):
            taken.append(i)
            yield i

    results = iter_parallel(abs, items(), scheduler=address, total=1000)
    assert next(results) == 0
    assert len(taken) == 3 * 2 * batch_size(1000, 2)
    rest = list(results)
    assert len(rest) == 999 and rest[-1] == 999 and len(taken) == 1000


def test_workers_run_with_the_recommended_configuration(cluster):
    _, client = cluster
    import dask

    profiled = client.run(lambda: dask.config.get("distributed.worker.profile.enabled"))
    assert set(profiled.values()) == {False}


def test_progress_counts_finished_datasets(tmp_path, capsys):
    folder = _folder(tmp_path, 3)
    fit_many("coulomb", folder, progress=True)
    assert "0/4" in capsys.readouterr().err  # counted in datasets (3 files, 1 broken)


def test_cli_fit_on_a_scheduler_equals_jobs(tmp_path, cluster, capsys):
    from frictionlaws.cli import main

    folder = _folder(tmp_path, 4)
    address, _ = cluster
    one, two = tmp_path / "dask.csv", tmp_path / "jobs.csv"
    assert main(["fit", "--law", "thirion", str(folder), "--scheduler", address,
                 "--out", str(one)]) == 1  # the broken file: a failed record, exit 1
    assert main(["fit", "--law", "thirion", str(folder), "--jobs", "2",
                 "--out", str(two)]) == 1
    assert "zz_broken" in capsys.readouterr().err
    assert one.read_text() == two.read_text()
