"""lmfit, pandas, xarray and Jupyter interoperability."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import frictionlaws as fl
from frictionlaws.base.errors import InputError
from frictionlaws.fitting import views as interop
from frictionlaws.law import evaluation
from frictionlaws.law import interop as law_interop


def test_lmfit_model_carries_bounds_and_fits_like_the_library():
    law = fl.get_law("thirion")
    model = law_interop.lmfit_model(law)
    params = model.make_params()
    assert model.independent_vars == ["p"]
    assert params["a"].min == law.param("a").bounds[0]
    assert params["b"].min == 0.0 and math.isinf(params["b"].max)
    p = np.linspace(2e4, 1e6, 40)
    rng = np.random.default_rng(3)
    mu = law(p=p, a=0.3, b=3e-6) * (1 + 0.01 * rng.standard_normal(p.size))
    params["a"].set(value=0.5)
    params["b"].set(value=1e-6)
    out = model.fit(mu, params, p=p)
    ours = fl.fit(law, {"p": p, "mu": mu})
    for k in ("a", "b"):
        assert out.params[k].value == pytest.approx(ours.params[k].value, rel=1e-5)
        assert out.params[k].stderr == pytest.approx(ours.params[k].stderr, rel=1e-2)


def test_lmfit_model_holds_settings_fixed_and_handles_a_constant_law():
    model = law_interop.lmfit_model(fl.get_law("savkoor"))
    params = model.make_params()
    assert params["p_ref"].vary is False and params["p_ref"].value == 1e5
    coulomb = law_interop.lmfit_model(fl.get_law("coulomb"), values={"mu0": 0.4})
    out = coulomb.eval(coulomb.make_params(), x=np.zeros(3))
    assert out.shape == (3,) and np.all(out == 0.4)


def test_lmfit_model_refuses_start_values_outside_bounds():
    with pytest.raises(InputError, match="outside its bounds"):
        law_interop.lmfit_model(fl.get_law("thirion"), values={"a": -1.0})


def test_params_frame_has_units_and_intervals():
    res = fl.fit("thirion", "thesis-steel")
    frame = interop.params_frame(res, units="si")
    assert list(frame.index) == ["a", "b"]
    assert frame.loc["b", "unit"] == "1/Pa" and frame.loc["a", "unit"] == "-"
    assert frame.loc["a", "ci95_low"] < frame.loc["a", "value"] < frame.loc["a", "ci95_high"]
    assert frame.attrs["law"] == "thirion"


def test_xarray_inputs_keep_their_dimensions():
    xr = pytest.importorskip("xarray")
    law = fl.get_law("savkoor")
    p = xr.DataArray([5e4, 1e5, 2e5], dims="p", coords={"p": [5e4, 1e5, 2e5]})
    v = xr.DataArray(np.geomspace(1e-4, 1, 5), dims="v")
    params = law.resolve(preset=None, values=law.defaults)
    out = evaluation.evaluate_labelled(law, {"p": p, "v": v}, params)
    assert out.dims == ("p", "v") and out.shape == (3, 5)
    assert out.name == "mu" and out.attrs["units"] == "1"
    plain = law.evaluate({"p": p.values[:, None], "v": v.values[None, :]}, params)
    np.testing.assert_allclose(out.values, plain)


def test_html_reprs_name_the_parameters():
    law = fl.get_law("thirion")
    text = law_interop.law_html(law)
    assert "<table>" in text and "1/Pa" in text and "thirion" in text
    res = fl.fit(law, "thesis-steel")
    text = interop.result_html(res)
    assert "converged" in text and "<td>b</td>" in text and "r2" in text


def test_plot_result_draws_data_fit_band_and_residuals(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    ds = fl.load_dataset("thesis-steel")
    res = fl.fit("thirion", ds)
    fig = interop.plot_result(res, ds)
    curve, resid = fig.axes
    assert len(curve.lines) == 2 and len(curve.collections) == 1  # band
    assert resid.get_xlabel() == "p [MPa]"
    half = interop.confidence_band(res, {"p": ds.arrays()["p"]})
    assert np.all(half > 0) and np.all(np.isfinite(half))
    loaded = fl.load_result(res.save(Path(tmp_path) / "r.json"))
    with pytest.raises(InputError, match="no data to plot"):
        interop.plot_result(loaded)


def test_results_and_laws_show_themselves_and_pickle():
    import pickle

    law = fl.get_law("thirion")
    assert pickle.loads(pickle.dumps(law)) is law
    res = fl.fit(law, "thesis-steel")
    assert len(repr(res)) < 200 and "thirion" in repr(res)
    assert "<table>" in res._repr_html_() and "<table>" in law._repr_html_()
    assert list(res.to_frame().index) == ["a", "b"]
    assert law.lmfit_model().independent_vars == ["p"]
    fig = res.plot()  # the fit keeps its data
    assert len(fig.axes) == 2


def test_law_call_keeps_xarray_dimensions():
    xr = pytest.importorskip("xarray")
    law = fl.get_law("thirion")
    p = xr.DataArray([1e5, 2e5, 4e5], dims="pressure")
    out = law(p=p, a=0.3, b=3e-6)
    assert out.dims == ("pressure",) and out.name == "mu"
    with pytest.raises(fl.InputError):
        law(p=-p, a=0.3, b=3e-6)


def test_the_result_exposes_lmfits_model_result_at_the_same_optimum():
    result = fl.fit("thirion", "thesis-steel")
    for mr in (result.lmfit_result, interop.model_result(result)):
        assert type(mr).__name__ == "ModelResult"
        for name, est in result.params.items():
            assert mr.params[name].value == pytest.approx(est.value, rel=1e-5)
        assert mr.chisqr == pytest.approx(result.metrics["chisqr"], rel=1e-6)
        assert "[[Fit Statistics]]" in mr.fit_report()


def test_a_result_read_from_a_file_cannot_give_lmfits_result(tmp_path):
    result = fl.fit("thirion", "thesis-steel")
    result.save(tmp_path / "r.json")
    loaded = fl.load_result(tmp_path / "r.json")
    with pytest.raises(fl.InputError, match="refit"):
        interop.model_result(loaded)


def test_confidence_band_is_undetermined_where_a_parameter_has_no_error():
    # savkoor on thesis-steel: n has an error, the bell's parameters cannot be told apart
    res = fl.fit("savkoor", "thesis-steel", on_invalid="drop")
    free = [k for k, e in res.params.items() if not e.fixed]
    missing = [k for k in free if res.params[k].stderr is None]
    assert missing and len(missing) < len(free)
    half = interop.confidence_band(res, {"p": np.array([2e5, 4e5]), "v": np.array([0.01, 1.0])})
    assert np.all(np.isnan(half))


@pytest.mark.parametrize("method", ["asymptotic", "sandwich", "bootstrap"])
def test_confidence_band_without_any_error_is_not_zero(method):
    # two rows, two parameters: no error anywhere, so no band (not a band of zero width)
    two = fl.fit("thirion", {"mu": np.array([0.8, 0.6]), "p": np.array([1e5, 4e5])},
                 uncertainty=method, n_boot=20)
    assert np.all(np.isnan(interop.confidence_band(two, {"p": np.array([2e5, 3e5])})))
