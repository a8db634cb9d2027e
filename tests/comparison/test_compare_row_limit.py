"""``compare`` on large data is bounded: more than ``max_rows`` rows are subsampled.

Rule (module docstring of :mod:`frictionlaws.comparison.core`): data with more than
``max_rows`` rows (default :data:`~frictionlaws.comparison.core.MAX_ROWS`) are compared
on a seeded random subsample of ``max_rows`` rows, for every fit, fold, hold-out and
test, and the notes and ``settings["rows"]`` say so; smaller data are compared as they
are (``tests/comparison/test_pinned_compare.py`` pins that).  The tests use a small ``max_rows``
to stay fast.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest
from hostile import run_cli

from frictionlaws.base.errors import InputError
from frictionlaws.comparison import compare
from frictionlaws.comparison.core import MAX_ROWS

LAWS = "thirion,coulomb"


def _arrays(n: int, seed: int = 1) -> dict[str, np.ndarray]:
    """Saturating mu(p) with a little noise, p in 0.01..0.3 MPa, three speeds."""
    rng = np.random.default_rng(seed)
    p = rng.uniform(0.01e6, 0.3e6, n)
    v = rng.choice([0.5, 1.38, 2.77], n)
    mu = 1.0 / (0.7 + 1.5e-6 * p) + rng.normal(0.0, 0.005, n)
    return {"mu": mu, "p": p, "v": v}


def test_large_data_are_compared_on_a_seeded_subsample() -> None:
    data = _arrays(400)
    cmp = compare(LAWS, data, folds=3, holdout=None, max_rows=60)
    assert cmp.data.n == 60
    assert cmp.settings["rows"] == {"data": 400, "used": 60, "max_rows": 60}
    assert "400 rows" in cmp.notes[0] and "subsample of 60" in cmp.notes[0]
    doc = json.loads(cmp.to_json())
    assert doc["settings"]["rows"]["used"] == 60 and doc["notes"][0] == cmp.notes[0]
    assert doc["dataset"]["n"] == 60 and doc["dataset"]["n_data"] == 400
    for r in cmp.results:  # every part used the subsample only
        assert r.fit.metrics["n"] <= 60 and r.cv.predictions is not None
        assert r.cv.predictions.size == 60
    # the rows kept are rows of the data, in their order, and the same for the same seed
    kept = np.flatnonzero(np.isin(data["p"], cmp.data.arrays["p"]))
    assert kept.size == 60 and np.array_equal(data["p"][kept], cmp.data.arrays["p"])
    again = compare(LAWS, data, folds=3, holdout=None, max_rows=60)
    assert np.array_equal(again.data.arrays["p"], cmp.data.arrays["p"])
    assert [r.cv.rmse for r in again.results] == [r.cv.rmse for r in cmp.results]
    other = compare(LAWS, data, folds=3, holdout=None, max_rows=60, seed=5)
    assert not np.array_equal(other.data.arrays["p"], cmp.data.arrays["p"])


def test_data_within_the_limit_are_compared_as_they_are() -> None:
    data = _arrays(40)
    at_limit = compare(LAWS, data, folds=3, max_rows=40)
    every = compare(LAWS, data, folds=3, max_rows=None)
    assert at_limit.settings["rows"] == {"data": 40, "used": 40, "max_rows": 40}
    assert not any("subsample" in n for n in at_limit.notes)
    assert at_limit.ranking == every.ranking
    for a, b in zip(at_limit.results, every.results):
        assert a.cv.rmse == b.cv.rmse and a.fit.metrics["r2"] == b.fit.metrics["r2"]
        assert a.extrapolation_rmse == b.extrapolation_rmse or (
            np.isnan(a.extrapolation_rmse) and np.isnan(b.extrapolation_rmse))


@pytest.mark.parametrize("bad", [0, 2, 2.5, True, "100", -1])
def test_max_rows_is_a_whole_number_of_at_least_three(bad: object) -> None:
    with pytest.raises(InputError, match="max_rows"):
        compare(LAWS, _arrays(10), max_rows=bad)  # type: ignore[arg-type]


def test_the_cli_bounds_a_large_file_and_says_so(tmp_path) -> None:  # type: ignore[no-untyped-def]
    n = MAX_ROWS + 300
    d = _arrays(n)
    rows = "".join(f"{m:.6f},{p / 1e6:.6f},{v}\n" for m, p, v in zip(d["mu"], d["p"], d["v"]))
    path = tmp_path / "large.csv"
    path.write_text("mu,p [MPa],v [m/s]\n" + rows, encoding="utf-8")
    res = run_cli(["compare", str(path), "--laws", "thirion", "--holdout", "0", "--json"])
    assert res.code == 0, res.err
    doc = json.loads(res.out)
    assert doc["settings"]["rows"] == {"data": n, "used": MAX_ROWS, "max_rows": MAX_ROWS}
    assert f"{n} rows" in doc["notes"][0]
    text = run_cli(["compare", str(path), "--laws", "thirion", "--holdout", "0"])
    assert text.code == 0 and f"subsample of {MAX_ROWS}" in text.out


def test_the_cli_max_rows_option_sets_the_subsample_or_every_row(tmp_path) -> None:
    """``compare --max-rows N|all`` reaches the library; its default is the library's."""
    import argparse

    from frictionlaws.cli import cmd_compare
    from frictionlaws.comparison.core import MAX_ROWS

    assert cmd_compare._DEFAULT_MAX_ROWS == MAX_ROWS
    rng = np.random.default_rng(5)
    p = rng.uniform(0.01, 0.3, 40)
    path = tmp_path / "d.csv"
    pd.DataFrame({"mu": 1 / (0.7 + 1.5 * p), "p [MPa]": p, "v [m/s]": 1.0}).to_csv(
        path, index=False)
    for option, used in (("10", 10), ("all", 40), ("ALL", 40)):
        res = run_cli(["compare", str(path), "--laws", "thirion,coulomb", "--json",
                       "--max-rows", option])
        assert res.code == 0, res.err
        assert json.loads(res.out)["settings"]["rows"]["used"] == used
    for bad in ("2", "x", "1e3", "-5"):
        res = run_cli(["compare", str(path), "--max-rows", bad])
        assert res.code == 2 and "--max-rows" in res.err and "'all'" in res.err, res.err
    assert isinstance(cmd_compare._max_rows("all"), str)
    with pytest.raises(argparse.ArgumentTypeError):
        cmd_compare._max_rows("0")
