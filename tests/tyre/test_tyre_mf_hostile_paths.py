"""The newest tyre features as a hostile new user tries them: one warning path, options
that do not apply, clamped rows reported with the load evaluated.

Each case here was a confident wrong answer (exit 0) before the warnings took one path:
the JSON of ``tyre mf`` lost the extrapolation the text warned of; a load clamped at FZMAX
was reported with the load asked for (and ``tyre reduce`` divided the clamped force by
it); ``fy`` and the weighting functions did not warn of a slip ratio beyond the file's
range while ``fx`` warned twice; ``friction_scaling="degressive"`` was reported as used for
an MF 5.2 file; ``fit_mf`` accepted bootstrap options the command line refused.
"""

from __future__ import annotations

import inspect
import json
import warnings

import numpy as np
import pytest

from frictionlaws.base.errors import ExtrapolationWarning, InputError
from frictionlaws.cli import main
from frictionlaws.tyre import MagicFormula, TyreData, fit_mf, reduce_mf

xr = pytest.importorskip("xarray")

#: A value beyond the packaged MF 6.1 example's range, per input (SI).
BEYOND = {"kappa": 1.5, "alpha": 1.1, "fz": 25000.0, "gamma": 0.2, "pressure": 4.4e5}
#: The inputs within range (SI).
NOMINAL = {"kappa": 0.05, "alpha": 0.05, "fz": 4000.0, "gamma": 0.0, "pressure": None}


def _run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def _methods() -> list[str]:
    """The public evaluation methods of MagicFormula (its own, taking a load)."""
    return [name for name, f in vars(MagicFormula).items() if inspect.isfunction(f)
            and not name.startswith("_") and "fz" in inspect.signature(f).parameters]


def _cases() -> list[tuple[str, str]]:
    out = []
    for name in _methods():
        params = inspect.signature(getattr(MagicFormula, name)).parameters
        out += [(name, x) for x in BEYOND if x in params]
    return out


def test_the_sibling_methods_are_all_enumerated() -> None:
    assert {"fx0", "fy0", "fx", "fy", "weight_x", "weight_y", "mz", "mz0", "mu_x_peak",
            "mu_y_peak", "slip_stiffness", "cornering_stiffness", "longitudinal", "lateral",
            "steady_state"} <= set(_methods())


@pytest.mark.parametrize(("method", "beyond"), _cases())
def test_every_method_warns_once_of_an_input_beyond_the_file(method: str,
                                                             beyond: str) -> None:
    mf = MagicFormula.from_file("MagicFormula61")
    f = getattr(mf, method)
    params = inspect.signature(f).parameters
    kw = {k: (BEYOND[k] if k == beyond else v) for k, v in NOMINAL.items() if k in params}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        f(**kw)
    texts = [str(w.message) for w in caught]
    assert len(texts) == 1 and f"{beyond} of 1 of" in texts[0], texts
    assert caught[0].category is ExtrapolationWarning


@pytest.mark.parametrize("method", ["fx0", "fy0", "fx", "fy", "mu_x_peak", "longitudinal",
                                    "steady_state"])
def test_a_clamped_load_is_said_alike_by_every_method(method: str) -> None:
    mf = MagicFormula.from_file("MagicFormula61", loads_above_fzmax="clamp")
    f = getattr(mf, method)
    params = inspect.signature(f).parameters
    kw = {k: (25000.0 if k == "fz" else v) for k, v in NOMINAL.items() if k in params}
    with pytest.warns(ExtrapolationWarning) as caught:
        f(**kw)
    texts = [str(w.message) for w in caught]
    assert texts == ["MagicFormula61_Parameters: fz of 1 value(s), from 25000 to 25000, lies "
                     "above the property file's FZMAX 18000 (SI): evaluated at FZMAX "
                     "(clamped, loads_above_fzmax='clamp')"]


def test_the_summary_json_keeps_the_extrapolation_the_text_warns_of(capsys) -> None:
    code, out, err = _run(capsys, "tyre", "mf", "MagicFormula61", "--loads", "4,25")
    assert code == 0 and "warning:" in err
    assert "range 0..18000 (SI), 1 above it, up to 25000" in err  # what lies outside
    code, out, err_json = _run(capsys, "tyre", "mf", "MagicFormula61", "--loads", "4,25",
                               "--json")
    doc = json.loads(out)
    assert [w for w in doc["warnings"]
            if "fz of 1 of 2 value(s) lies outside" in w and "up to 25000" in w]
    assert doc["clamped"] == [False, False] and doc["loads_evaluated_N"] == [4000.0, 25000.0]


def test_a_clamped_load_is_reported_with_the_load_evaluated_on_every_path(capsys) -> None:
    argv = ["tyre", "mf", "MagicFormula61", "--loads", "4,25", "--loads-above-fzmax", "clamp"]
    code, text, err = _run(capsys, *argv)
    assert code == 0 and "25*" in text and "evaluated at the file's FZMAX = 18 kN" in text
    assert "clamped" in err
    code, out, _ = _run(capsys, *argv, "--json")
    doc = json.loads(out)
    assert doc["loads_N"] == [4000.0, 25000.0] and doc["loads_evaluated_N"] == [4000.0, 18000.0]
    assert doc["clamped"] == [False, True] and any("clamped" in w for w in doc["warnings"])
    # the steady state: each row says so, its Fz is the load evaluated
    code, out, _ = _run(capsys, *argv[:3], "--kappa", "0.05", "--loads", "4,25",
                        "--loads-above-fzmax", "clamp", "--json")
    rows = json.loads(out)["rows"]
    assert [r["clamped"] for r in rows] == [[], ["fz"]]
    assert [r["fz"] for r in rows] == [4000.0, 25000.0]
    assert [r["Fz"] for r in rows] == [4000.0, 18000.0]
    assert any("clamped" in w for w in json.loads(out)["warnings"])


def test_reduce_at_a_clamped_load_is_the_curve_at_fzmax(capsys) -> None:
    with pytest.warns(ExtrapolationWarning, match="clamped"):
        red = reduce_mf(MagicFormula.from_file("MagicFormula61", loads_above_fzmax="clamp"),
                        "pacejka", fz=25000.0, n=51)
    assert red.clamped and red.fz == 25000.0 and red.fz_evaluated == 18000.0
    assert red.params["D"] == pytest.approx(red.expected["D"], rel=1e-9)  # one load
    code, out, _ = _run(capsys, "tyre", "reduce", "MagicFormula61", "--load", "25",
                        "--loads-above-fzmax", "clamp", "--json")
    doc = json.loads(out)
    assert doc["load_evaluated_N"] == 18000.0 and doc["clamped"] is True
    assert any("clamped" in w for w in doc["warnings"])


@pytest.mark.parametrize(("options", "not_applied"), [
    ({"friction_scaling": "degressive"}, "friction_scaling"),
    ({"loads_above_fzmax": "clamp"}, "loads_above_fzmax")])
def test_an_option_a_file_cannot_apply_is_noted_alike_on_every_path(
        tmp_path, capsys, options: dict[str, str], not_applied: str) -> None:
    from frictionlaws.tyre.mf.tir import format_tir, packaged_example, read_property_file

    pf = read_property_file(packaged_example("MagicFormula52"))
    del pf.sections["VERTICAL_FORCE_RANGE"]  # no FZMAX
    path = tmp_path / "t52.tir"
    path.write_text(format_tir(pf))
    with pytest.warns(UserWarning, match=f"{not_applied} = .* is not applied"):
        mf = MagicFormula.from_file(path, **options)
    assert [n for n in mf.notes if f"{not_applied} = " in n and "not applied" in n]
    applied = {"friction_scaling": "linear", "loads_above_fzmax": "extrapolate"}
    assert mf.applied_conventions[not_applied] == applied[not_applied]
    flag = [f"--{k.replace('_', '-')}" for k in options][0]
    argv = ["tyre", "mf", str(path), flag, list(options.values())[0]]
    code, text, err = _run(capsys, *argv)
    assert code == 0 and "not applied" in text and "not applied" in err
    code, out, _ = _run(capsys, *argv, "--json")
    doc = json.loads(out)
    assert doc["conventions"][not_applied] == applied[not_applied]
    assert [n for n in doc["notes"] if "not applied" in n]
    with pytest.warns(UserWarning):
        ds = MagicFormula.from_file(path, **options).steady_state(
            xr.DataArray([0.0, 0.05], dims="k"), 0.0, 4000.0)
    assert [n for n in ds.attrs["notes"] if "not applied" in n]


def test_xarray_results_keep_the_warnings() -> None:
    mf = MagicFormula.from_file("MagicFormula61")
    kappa = xr.DataArray([0.05, 1.5], dims="k")
    with pytest.warns(ExtrapolationWarning):
        out = mf.fx0(kappa, 4000.0)
    assert [w for w in out.attrs["warnings"] if "kappa of" in w]
    with pytest.warns(ExtrapolationWarning):
        ds = mf.steady_state(kappa, 0.0, 4000.0)
    assert [w for w in ds.attrs["warnings"] if "kappa of" in w]


def _tiny_data() -> TyreData:
    from frictionlaws.tyre.synthetic_rig import rig_data

    return rig_data(MagicFormula.from_file("MagicFormula61"), n=7, loads=(1.0,),
                    pressures=(1.0,), cambers_deg=(0.0,), combined=False)


@pytest.mark.parametrize("given", [{"resamples": 50}, {"seed": 3}, {"jobs": 2},
                                   {"sweeps": np.zeros(3)}])
def test_fit_mf_refuses_bootstrap_options_without_sweeps_as_the_cli_does(given) -> None:
    with pytest.raises(InputError, match=f"{next(iter(given))} is not used with "
                                         "uncertainty='asymptotic'"):
        fit_mf(_tiny_data(), **given)


def test_fit_mf_refuses_a_sign_convention_for_data_already_read() -> None:
    with pytest.raises(InputError, match="sign_convention='sae' is not used"):
        fit_mf(_tiny_data(), sign_convention="sae")
