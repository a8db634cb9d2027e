"""The one rule of every resampling: resamples that cannot vary give no standard error.

Each bootstrap of the project is tried on a design whose resamples cannot vary (one unit
in each stratum): the fit's condition bootstrap (and through it a campaign's fits and the
fits of processed tribometer tables, which carry a condition column), the tyre sweep
bootstrap, API and command line alike.  Each refuses or warns with the reason; none gives
a standard error of 0.  A shared fit has no resampling: the command line refuses it.
"""

from __future__ import annotations

import math
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import frictionlaws as fl
from frictionlaws.base.errors import ExtrapolationWarning, InputError
from frictionlaws.cli import main
from frictionlaws.fitting.campaign import fit_many
from frictionlaws.fitting.resampling import (
    MIN_DETERMINED,
    cannot_vary,
    check_can_vary,
    no_spread,
    spread_errors,
)

# ------------------------------------------------------------------- the rule itself


@pytest.mark.parametrize(("sizes", "strata", "varies"), [
    ([1], None, False), ([0], None, False), ([], None, False), ([2], None, True),
    ([1, 1, 1], "load level", False), ([1, 2, 1], "load level", True),
    ([5], None, True)])
def test_a_design_varies_only_with_two_units_in_some_stratum(sizes, strata, varies) -> None:
    reason = cannot_vary(sizes, unit="sweep", strata=strata)
    assert (reason is None) == varies
    if not varies:
        with pytest.raises(InputError, match="cannot vary") as err:
            check_can_vary(sizes, unit="sweep", strata=strata, method="the test bootstrap",
                           source="data.csv")
        assert "standard error of 0" in str(err.value) and "data.csv" in str(err.value)
    if strata and not varies:
        assert f"each of the {len(sizes)} strata ({strata})" in reason


def test_resampled_values_that_do_not_spread_give_no_error() -> None:
    rng = np.random.default_rng(1)
    flat = 0.4 + 1e-17 * rng.standard_normal(50)  # rounding of identical refits
    spread = 0.4 + 1e-3 * rng.standard_normal(50)
    few = np.r_[spread[:MIN_DETERMINED - 1], np.full(41, np.nan)]
    se = spread_errors(np.column_stack([flat, spread, few]))
    assert math.isnan(se[0]) and math.isnan(se[2])
    assert se[1] == pytest.approx(np.std(spread, ddof=1))
    assert no_spread(flat) and not no_spread(spread) and no_spread(few)


# ------------------------------------------------------- the fit's condition bootstrap


def _one_condition(n: int = 6) -> dict[str, np.ndarray]:
    return {"mu": np.array([0.50, 0.52, 0.49, 0.51, 0.50, 0.53])[:n], "p": np.full(n, 2e5)}


def test_the_fit_bootstrap_of_one_condition_withholds_every_error_with_the_reason() -> None:
    res = fl.fit("coulomb", _one_condition(), uncertainty="bootstrap", n_boot=30)
    assert all(e.stderr is None and e.ci95 is None for e in res.params.values())
    text = " ".join(res.warnings)
    assert "cannot vary" in text and "one test condition" in text, res.warnings
    assert "0 +/-" not in res.report() and "+/- 0 " not in res.report()


def test_a_condition_column_with_one_condition_is_refused_the_same_way() -> None:
    # rows at three pressures, all labelled as one test condition (the column the
    # bootstrap resamples): the resamples are the data itself
    data = {"mu": np.array([0.62, 0.55, 0.50, 0.46, 0.43, 0.40]),
            "p": np.array([1e5, 1e5, 2e5, 2e5, 3e5, 3e5])}
    frame = __import__("pandas").DataFrame({"mu": data["mu"], "p [Pa]": data["p"],
                                            "condition_id": ["run"] * 6})
    res = fl.fit("coulomb", frame, uncertainty="bootstrap", n_boot=30)
    assert all(e.stderr is None for e in res.params.values())
    assert any("cannot vary" in w for w in res.warnings), res.warnings


def test_a_campaign_group_of_one_condition_gets_no_bootstrap_error(tmp_path: Path) -> None:
    csv = tmp_path / "c.csv"
    csv.write_text("surface,p [MPa],mu\n" + "".join(
        f"a,0.1,{m}\n" for m in (0.5, 0.52, 0.49, 0.51)) + "".join(
        f"b,{p},{m}\n" for p, m in ((0.1, 0.5), (0.2, 0.45), (0.3, 0.41), (0.1, 0.52),
                                    (0.2, 0.44), (0.3, 0.40))))
    camp = fit_many("coulomb", csv, by="surface", uncertainty="bootstrap", n_boot=30)
    by_group = {r["group"]["surface"]: r["result"] for r in camp.records}
    assert by_group["a"]["params"]["mu0"]["stderr"] is None
    assert any("cannot vary" in w for w in by_group["a"]["warnings"])
    assert by_group["b"]["params"]["mu0"]["stderr"] > 0
    assert main(["fit", "--law", "coulomb", str(csv), "--by", "surface", "--uncertainty",
                 "bootstrap", "--boot", "30", "--out", str(tmp_path / "f.csv")]) == 0
    rows = (tmp_path / "f.csv").read_text().splitlines()
    a_row = next(r for r in rows if ",a," in r)
    assert ",bootstrap," in a_row and ",,,,bootstrap," in a_row  # stderr and CI empty


def test_a_shared_fit_has_no_resampling_and_refuses_one() -> None:
    code = main(["fit", "--law", "thirion", "thesis-steel", "--by", "p", "--shared", "b",
                 "--uncertainty", "bootstrap"])
    assert code == 2


# ------------------------------------------------------------ the tyre sweep bootstrap


def _sweeps(per: int):
    """Pure-slip sweeps of a rig at two loads, up and down (``per=2``) or up only (1)."""
    from frictionlaws.tyre import MagicFormula
    from frictionlaws.tyre.mf.fit.bootstrap import find_sweeps
    from frictionlaws.tyre.synthetic_rig import rig_data

    data = rig_data(MagicFormula.from_file("MagicFormula61"), n=9, loads=(0.5, 1.0),
                    pressures=(1.0,), cambers_deg=(0.0,), combined=False)
    labels = find_sweeps(data)
    return data if per == 2 else data.subset(np.flatnonzero(labels % 2 == 0))


def test_one_sweep_per_load_is_refused_before_any_fit_naming_the_reason(
        monkeypatch: pytest.MonkeyPatch) -> None:
    from frictionlaws.tyre import fit_mf
    from frictionlaws.tyre import fit_mf as module

    def no_fit(*args: object, **kwargs: object) -> None:
        raise AssertionError("fitted before the bootstrap was checked")

    monkeypatch.setattr(sys.modules[module.__module__], "_fit_directions", no_fit)
    data = _sweeps(per=1)
    with pytest.raises(InputError, match="sweep bootstrap cannot vary") as err:
        fit_mf(data, uncertainty="sweeps", resamples=20)
    assert "each of the 4 strata" in str(err.value) and "one sweep" in str(err.value)


def test_two_sweeps_per_load_are_resampled(tmp_path: Path) -> None:
    from frictionlaws.tyre.mf.fit.bootstrap import check_can_resample

    assert [len(s) for s in check_can_resample(_sweeps(per=2))] == [2, 2, 2, 2]


def test_the_command_line_refuses_a_sweep_bootstrap_that_cannot_vary(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    data = _sweeps(per=1)
    csv = tmp_path / "one.csv"
    csv.write_text("Fz [N],kappa [-],alpha [rad],Fx [N],Fy [N]\n" + "".join(
        f"{z!r},{k!r},{a!r},{x!r},{y!r}\n" for z, k, a, x, y in zip(
            data.fz.tolist(), data.kappa.tolist(), data.alpha.tolist(), data.fx.tolist(),
            data.fy.tolist())))
    out = tmp_path / "one.tir"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        code = main(["tyre", "fit-mf", str(csv), "-o", str(out), "--uncertainty", "sweeps",
                     "--boot", "20"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "cannot vary" in err[0], err
    assert not out.exists()
