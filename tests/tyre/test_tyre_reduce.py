"""Reducing a Magic Formula property file to a simple slip law."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from frictionlaws.base.errors import ExtrapolationWarning, InputError
from frictionlaws.law.registry import get_law
from frictionlaws.tyre import MagicFormula, equivalent_pacejka, mf_slip_curve, reduce_mf

EXAMPLES = Path(__file__).resolve().parents[2] / "datasets" / "mf-examples"


@pytest.fixture(scope="module")
def mf62():
    return MagicFormula.from_file(EXAMPLES / "MagicFormula62_Parameters.json")


@pytest.fixture(scope="module")
def mf52():
    return MagicFormula.from_file(EXAMPLES / "MagicFormula52_Parameters.json")


def test_equivalent_pacejka_reproduces_the_curve(mf62):
    for side in ("braking", "driving"):
        eq = equivalent_pacejka(mf62, 4000.0, side=side)
        s = np.linspace(0.01, 1.0, 100)  # beyond the horizontal shift
        mu_law = get_law("pacejka")(s=s, **eq)
        assert np.allclose(mu_law, mf_slip_curve(mf62, 4000.0, s, side=side), rtol=1e-12,
                           atol=1e-14)
    assert mf_slip_curve(mf62, 4000.0, 0.1, side="braking") > 0


@pytest.mark.parametrize("fz", [2500.0, 6000.0])
@pytest.mark.parametrize("name", ["mf52", "mf62"])
def test_pacejka_fit_recovers_the_magic_formula(name, fz, request):
    mf = request.getfixturevalue(name)
    red = reduce_mf(mf, "pacejka", fz=fz)
    exp = red.expected
    assert red.errors["rmse"] < 1e-6 and red.errors["r2"] > 1 - 1e-10
    for k in ("B", "C", "D", "E"):
        assert red.params[k] == pytest.approx(exp[k], rel=1e-4), k
    assert red.params["S_v"] == pytest.approx(exp["S_v"], abs=1e-5)
    assert red.errors["mu_peak_law"] == pytest.approx(red.errors["mu_peak_mf"], rel=1e-6)


def test_burckhardt_fit_reports_its_error(mf62):
    red = reduce_mf(mf62, "burckhardt", fz=4000.0)
    assert red.params["c4"] == 0.0 and red.fit.params["c4"].fixed
    assert any("c4 fixed at 0" in n for n in red.notes)
    assert not any("single value of v" in w for w in red.fit.warnings)
    e = red.errors
    # an approximation, not an identity: the error is real and reported
    assert 1e-3 < e["rmse"] < 0.05
    assert e["max_abs"] >= e["rmse"]
    assert np.sqrt(np.mean((red.mu_law - red.mu_mf) ** 2)) == pytest.approx(e["rmse"])
    assert e["mu_peak_law"] == pytest.approx(e["mu_peak_mf"], rel=0.06)
    assert e["s_peak_law"] == pytest.approx(e["s_peak_mf"], abs=0.05)
    text = red.report()
    assert "burckhardt" in text and "RMSE" in text and "F_z = 4000 N" in text
    d = json.loads(json.dumps(red.to_dict()))
    assert d["law"] == "burckhardt" and d["load_N"] == 4000.0
    assert d["fit"]["format"] == "frictionlaws-fit-result"


def test_other_slip_laws_and_driving_side(mf52):
    red = reduce_mf(mf52, "kiencke-daiss", fz=5000.0, side="driving", slip_max=0.5, n=101)
    assert red.side == "driving" and red.slip[-1] == 0.5
    assert red.errors["r2"] > 0.9


def test_reduce_from_a_path_and_extrapolation_warning():
    # the one warning path: issued once (the API), and held by the result (JSON, report)
    with pytest.warns(ExtrapolationWarning, match="fz of 1 of 1 value.*up to 20000") as caught:
        red = reduce_mf(str(EXAMPLES / "MagicFormula62_Parameters.json"), "pacejka",
                        fz=20000.0, n=51)
    assert len([w for w in caught if "fz of 1 of 1" in str(w.message)]) == 1
    assert any("fz" in n and "extrapolation" in n for n in red.warnings)
    assert red.to_dict()["warnings"] == red.warnings and not red.clamped
    assert all(f"warning: {w}" in red.report() for w in red.warnings)


def test_reduce_errors(mf62):
    with pytest.raises(InputError, match="sliding law"):
        reduce_mf(mf62, "thirion", fz=4000.0)
    with pytest.raises(InputError, match="positive load"):
        reduce_mf(mf62, "pacejka", fz=-1.0)
    with pytest.raises(InputError, match="slip_max"):
        reduce_mf(mf62, "pacejka", fz=4000.0, slip_max=1.5)
    with pytest.raises(InputError, match="side"):
        reduce_mf(mf62, "pacejka", fz=4000.0, side="sideways")
    with pytest.raises(InputError, match="n must be"):
        reduce_mf(mf62, "pacejka", fz=4000.0, n=3)


def test_cli_reduction_worse_than_the_mean_exits_1_and_saves_nothing(tmp_path, capsys):
    from frictionlaws.cli import main

    tir = (Path(__file__).resolve().parents[2] / "datasets" / "mf-examples"
           / "MagicFormula61_Parameters.converted.tir")
    save = tmp_path / "r.json"
    code = main(["tyre", "reduce", str(tir), "--load", "4", "--law", "burckhardt-sqrt",
                 "--slip-max", "1e-9", "--save", str(save)])
    assert code == 1
    assert "did not converge" in capsys.readouterr().err
    assert not save.exists()
