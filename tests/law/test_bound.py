"""BoundLaw: a law bound to checked values, their source and the fitted ranges."""

from __future__ import annotations

import json
import pickle
import warnings
from pathlib import Path

import numpy as np
import pytest

from frictionlaws.base.errors import DomainError, ExtrapolationWarning, InputError
from frictionlaws.fitting import fit, load_result
from frictionlaws.law.bound import BoundLaw, Source, as_bound, bound_from_result, freeze
from frictionlaws.law.registry import get_law


@pytest.fixture(scope="module")
def fitted():
    return fit("thirion", "thesis-steel")


def test_freeze_evaluates_like_the_law_vectorised() -> None:
    law = get_law("thirion")
    bound = law.freeze({"a": 0.2, "b": 3e-6})
    p = np.array([1e4, 1e5, 5e5])
    np.testing.assert_array_equal(bound(p=p), law(p=p, a=0.2, b=3e-6))
    assert isinstance(bound(p=1e5), float)
    assert bound.values == {"a": 0.2, "b": 3e-6}
    assert bound.source == Source("values", given=("a", "b"))
    assert bound.source.describe() == "given values"


def test_freeze_with_a_preset_and_an_override() -> None:
    law = get_law("exponential-decay")
    preset = next(iter(law.presets))
    bound = law.freeze({"mu_d": 0.5}, preset=preset)
    assert bound.values["mu_d"] == 0.5
    assert bound.values["mu_s"] == law.presets[preset]["mu_s"]
    assert bound.source.describe() == f"preset '{preset}' with given values"
    assert freeze("exponential-decay", preset=preset).source.describe() == f"preset '{preset}'"


@pytest.mark.parametrize(("values", "message"), [
    ({"a": 0.2}, "needs parameter"),
    ({"a": 0.2, "b": 3e-6, "zz": 1}, "does not take zz"),
    ({"a": -1.0, "b": 3e-6}, "outside its bounds"),
    ({"a": float("nan"), "b": 3e-6}, "not a finite number"),
])
def test_values_are_checked_once_when_bound(values: dict, message: str) -> None:
    with pytest.raises(InputError, match=message):
        get_law("thirion").freeze(values)


def test_direct_construction_checks_values_too() -> None:
    law = get_law("thirion")
    with pytest.raises(InputError, match="missing b"):
        BoundLaw(law, {"a": 0.2})
    with pytest.raises(InputError, match="outside its bounds"):
        BoundLaw(law, {"a": 0.2, "b": -1.0})
    with pytest.raises(InputError, match="fitted range of unknown variable"):
        BoundLaw(law, {"a": 0.2, "b": 3e-6}, fitted_ranges={"q": (0, 1)})
    with pytest.raises(InputError, match="source kind"):
        Source("guess")


def test_evaluation_checks_the_domain_as_the_law_does() -> None:
    bound = get_law("thirion").freeze({"a": 0.2, "b": 3e-6})
    with pytest.raises(DomainError, match="p = -1"):
        bound(p=[1e5, -1.0])
    with pytest.raises(InputError, match="non-finite"):
        bound(p=[np.nan])
    with pytest.raises(InputError, match="needs variable"):
        bound()


def test_a_fit_binds_with_its_ranges_and_warns_outside_them(fitted) -> None:
    bound = fitted.bound
    assert bound.law is fitted.law and bound.values == fitted.values
    lo, hi = fitted.data["ranges"]["p"]
    assert bound.fitted_ranges["p"] == (lo, hi)
    assert set(bound.stderr) == {"a", "b"} and bound.converged
    assert bound.source.kind == "fit" and bound.source.dataset == "thesis-steel"
    assert bound.source.describe().startswith("fit to thesis-steel (n = 19, R^2 = ")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        bound(p=(lo + hi) / 2)  # inside: no warning
    with pytest.warns(ExtrapolationWarning, match="p outside the fitted range"):
        bound(p=2 * hi)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        bound(p=2 * hi, warn=False)
    assert fitted.extrapolation({"p": 2 * hi}) == bound.extrapolation({"p": 2 * hi})


def test_pickle_round_trip_and_repr(fitted) -> None:
    bound = fitted.bound
    again = pickle.loads(pickle.dumps(bound))
    assert again == bound and again.law is bound.law
    assert again(p=1e5, warn=False) == bound(p=1e5, warn=False)
    text = repr(bound)
    assert text.startswith("<BoundLaw thirion(a=") and "fit to thesis-steel" in text
    assert "fitted on p " in text and " Pa" in text and "F_N" not in text  # law's variables
    assert repr(get_law("coulomb").freeze({"mu0": 0.9})) == \
        "<BoundLaw coulomb(mu0=0.9); from given values>"


def test_to_dict_is_json_with_units(fitted) -> None:
    doc = json.loads(json.dumps(fitted.bound.to_dict()))
    assert doc["law"] == "thirion" and doc["values"]["b"]["unit"] == "1/Pa"
    assert doc["values"]["a"]["stderr"] > 0
    assert doc["fitted_ranges"]["p"]["unit"] == "Pa"
    assert doc["source"]["kind"] == "fit"


def test_a_saved_result_binds_with_the_file_as_source(fitted, tmp_path: Path) -> None:
    path = tmp_path / "fit.json"
    fitted.save(path)
    bound = bound_from_result(load_result(path), Source("file", file=str(path)))
    assert bound.source.describe() == f"file {path}"
    assert bound.fitted_ranges == fitted.bound.fitted_ranges
    assert freeze("thirion", {"a": 0.2, "b": 3e-6}, source=str(path)).source.file == str(path)


def test_as_bound_checks_the_law(fitted) -> None:
    assert as_bound(fitted, law="thirion") == fitted.bound
    with pytest.raises(InputError, match="for law 'thirion', not 'coulomb'"):
        as_bound(fitted.bound, law="coulomb")
    with pytest.raises(InputError, match="expected a BoundLaw"):
        as_bound({"a": 1})


def test_export_takes_a_bound_law(fitted) -> None:
    from frictionlaws.fe_export import export

    box = {"p": (1e4, 5e5, 5)}
    via_bound = export(fitted.bound, None, "csv", box)
    via_result = export("thirion", fitted, "csv", box)
    assert via_bound.text == via_result.text
    assert "parameters from: fit to thesis-steel" in via_bound.text
    assert "standard error" in via_bound.text
    assert any("beyond the fitted data" in w for w in via_bound.warnings)
    frozen = get_law("thirion").freeze({"a": 0.2, "b": 3e-6})
    assert export(frozen, None, "csv", box).text == export("thirion", {"a": 0.2, "b": 3e-6},
                                                            "csv", box).text
    with pytest.raises(InputError, match="carries its values"):
        export(frozen, {"a": 0.3}, "csv", box)


def test_brush_model_takes_a_bound_law(fitted) -> None:
    from frictionlaws.tyre.brush import BrushModel

    a = BrushModel(fitted.bound).cornering([3000.0], [1, 2, 3])
    b = BrushModel(fitted).cornering([3000.0], [1, 2, 3])
    assert a.to_dict()["cornering_stiffness_kN_per_deg"] == \
        b.to_dict()["cornering_stiffness_kN_per_deg"]
    assert BrushModel(fitted.bound).fitted_ranges == fitted.bound.fitted_ranges
    with pytest.raises(InputError, match="not both"):
        BrushModel(fitted.bound, {"a": 0.1})
