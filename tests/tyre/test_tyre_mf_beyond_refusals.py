"""Hostile values for the inputs and options past steady rolling (phit, omega, turn_slip,
limit_checks, the transient's histories): generated, each refused with an InputError
naming it, or evaluated to numbers (never another exception, never an infinity, never a
numpy warning); on the command line, one line and exit 2."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from frictionlaws.base.errors import ExtrapolationWarning, InputError
from frictionlaws.cli import main
from frictionlaws.tyre import MagicFormula, transient_slip

MF61 = MagicFormula.from_file("MagicFormula61")

#: Values no input takes: text (numbers too: they go through the number parser at the
#: edges), bytes, booleans, complex numbers, ragged and nested sequences, None in a list.
NOT_NUMBERS = st.one_of(
    st.text(max_size=8), st.binary(max_size=4), st.booleans(), st.complex_numbers(),
    st.just([[1.0], [2.0, 3.0]]), st.just([1.0, None]), st.just({"a": 1}),
    st.lists(st.sampled_from(["1", "2.5", "nan"]), min_size=1, max_size=3))
#: Numbers past a finite value.
NOT_FINITE = st.sampled_from([np.nan, np.inf, -np.inf, [0.0, np.nan], [np.inf, 1.0]])
#: Finite numbers of every size, the extremes included.
ANY_FINITE = st.floats(allow_nan=False, allow_infinity=False)


def _outcome(**kw: object) -> str:
    """'refused' (InputError), or 'numbers' after checking the outputs hold no infinity
    and no numpy warning escaped; any other exception fails the test."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            out = MF61.steady_state(0.02, [0.0, 0.05], 4000.0, **kw)
        except InputError as err:
            assert str(err) and "\n" not in str(err)
            return "refused"
    assert not any(issubclass(w.category, RuntimeWarning) for w in caught), \
        [str(w.message) for w in caught]
    assert all(not np.isinf(v).any() for v in out.values())
    return "numbers"


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(name=st.sampled_from(["phit", "omega", "vx", "pressure"]),
       value=st.one_of(NOT_NUMBERS, NOT_FINITE))
def test_an_input_that_is_no_finite_number_is_refused(name: str, value: object) -> None:
    kw = {name: value, "turn_slip": name == "phit"}
    assert _outcome(**kw) == "refused"


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(phit=ANY_FINITE, omega=ANY_FINITE, vx=ANY_FINITE, limits=st.booleans())
def test_any_finite_spin_wheel_speed_and_speed_gives_numbers_or_a_refusal(
        phit: float, omega: float, vx: float, limits: bool) -> None:
    _outcome(phit=phit, omega=omega, vx=vx, turn_slip=True, limit_checks=limits)


@pytest.mark.parametrize("name", ["turn_slip", "limit_checks", "saturate"])
@pytest.mark.parametrize("value", ["yes", "no", 1, 0, None, np.array([True])])
def test_an_option_that_is_not_true_or_false_is_refused(name: str, value: object) -> None:
    with pytest.raises(InputError, match=f"{name} must be True or False"):
        MF61.steady_state(0.0, 0.0, 4000.0, **{name: value})


def test_a_wheel_speed_past_floating_point_is_refused_naming_the_row() -> None:
    with pytest.raises(InputError, match=r"Re is not finite at row 1 .*omega \[rad/s\] = "
                                         r"1e\+200"):
        MF61.steady_state(0.0, 0.0, 4000.0, omega=[10.0, 1e200])


def test_a_wheel_speed_that_leaves_no_deflection_gives_no_vertical_stiffness() -> None:
    with pytest.warns(ExtrapolationWarning, match=r"no deflection \(a load too small"):
        out = MF61.steady_state(0.0, 0.0, 4000.0, omega=1e30)
    assert np.isnan(out["Cz"]) and out["rho"] == 0


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(name=st.sampled_from(["t", "vx", "fz", "alpha", "gamma", "phit", "omega", "kappa",
                             "initial"]),
       value=st.one_of(NOT_NUMBERS, NOT_FINITE, st.just([0.0, 1.0, 2.0, 3.0])))
def test_the_transient_refuses_every_hostile_history(name: str, value: object) -> None:
    args: dict = {"t": [0.0, 0.1, 0.2], "vx": 20.0, "fz": 4000.0, "turn_slip": True}
    if name == "initial" and value == [0.0, 1.0, 2.0, 3.0]:
        value = (0.0,)
    args[name] = value
    with pytest.raises(InputError) as err:
        transient_slip(MF61, args.pop("t"), args.pop("vx"), args.pop("fz"), **args)
    assert "\n" not in str(err.value)


TIR = "datasets/mf-examples/MagicFormula61_Parameters.converted.tir"


@pytest.mark.parametrize("argv", [
    ["--phit", "0.5"],                        # turn slip without the model
    ["--phit", "x", "--turn-slip"],
    ["--phit", "0.5,inf", "--turn-slip"],
    ["--omega", "1e200"],                     # past floating point
    ["--omega", "nan"],
    ["--omega", "5 m"],                       # a length is no wheel speed
    ["--no-limit-checks", "--saturate"],
    ["--turn-slip", "--phit", "1e999"],
])
def test_the_cli_refuses_bad_values_of_the_new_options_in_one_line(
        argv: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    import os
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    assert main(["tyre", "mf", os.path.join(root, TIR), *argv]) == 2
    *warned, last = capsys.readouterr().err.strip().splitlines()
    assert last.startswith("error:") and "Traceback" not in last
    assert all(w.startswith("warning: ") for w in warned)  # what ran before the refusal
