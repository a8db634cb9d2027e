"""pint Quantities given to the API are converted to SI, or refused when of the wrong kind.

A law call, its parameters, ``fit`` (arrays and ``fix``), ``predict``, a bound law
and an export's box all take a Quantity in any unit of the right kind and give the
numbers they give for the same value in SI; a Quantity of another kind is refused
naming the value.  (numpy alone strips the unit: ``0.1 MPa`` would be read as 0.1 Pa.)
"""

from __future__ import annotations

import numpy as np
import pint
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import frictionlaws as fl
from frictionlaws.base.errors import InputError
from frictionlaws.fe_export import export

U = pint.UnitRegistry()
THIRION = {"a": 1.0, "b": 2e-6}
#: (unit, factor to SI) per variable
UNITS = {
    "p": [("MPa", 1e6), ("kPa", 1e3), ("bar", 1e5), ("Pa", 1.0), ("N/mm**2", 1e6)],
    "v": [("mm/s", 1e-3), ("m/s", 1.0), ("km/h", 1 / 3.6)],
}


@settings(max_examples=40, deadline=None)
@given(value=st.floats(0.05, 5.0), unit=st.sampled_from(UNITS["p"]))
def test_law_call_converts_a_pressure_quantity(value, unit):
    name, factor = unit
    law = fl.get_law("thirion")
    got = law(p=value * U(name), **THIRION)
    assert got == pytest.approx(law(p=value * factor, **THIRION), rel=1e-12)


@settings(max_examples=30, deadline=None)
@given(v=st.floats(0.01, 5.0), unit=st.sampled_from(UNITS["v"]))
def test_law_call_converts_a_velocity_quantity_in_an_array(v, unit):
    name, factor = unit
    law = fl.get_law("exponential-decay")
    vs = np.array([v, 2 * v])
    got = law(v=vs * U(name), preset="rubber-steel")
    assert np.allclose(got, law(v=vs * factor, preset="rubber-steel"), rtol=1e-12)


def test_temperature_quantity_in_degc_is_kelvin_inside():
    law = fl.get_law("park")
    values = {"n": 0.2, "mu_s": 0.4, "mu_m": 1.2, "h10": 0.35, "v_m": 1e-3}
    point = {"p": 2e5, "v": 0.01}
    assert law(T=U.Quantity(20.0, "degC"), **point, **values) == pytest.approx(
        law(T=293.15, **point, **values), rel=1e-12)


def test_parameter_quantity_is_converted():
    law = fl.get_law("thirion")
    assert law(p=1e5, a=1.0, b=2.0 * U("1/MPa")) == pytest.approx(
        law(p=1e5, a=1.0, b=2e-6), rel=1e-12)


@pytest.mark.parametrize("call", [
    lambda law: law(p=0.1 * U.m, **THIRION),
    lambda law: law(p=1e5, a=1.0, b=2e-6 * U.s),
    lambda law: law.freeze(THIRION)(p=3 * U.kg),
])
def test_quantity_of_the_wrong_kind_is_refused(call):
    with pytest.raises(InputError, match="cannot be converted"):
        call(fl.get_law("thirion"))


def test_fit_predict_and_bound_take_quantities():
    p = np.array([0.1, 0.2, 0.4, 0.6, 0.8])
    mu = 1.0 / (1.0 + 2e-6 * p * 1e6) + np.array([0.01, -0.01, 0.005, -0.004, 0.002])
    si = fl.fit("thirion", {"mu": mu, "p": p * 1e6})
    q = fl.fit("thirion", {"mu": mu, "p": p * U.MPa})
    assert q.params["b"].value == pytest.approx(si.params["b"].value, rel=1e-6)
    assert q.predict(p=300 * U.kPa) == pytest.approx(si.predict(p=3e5), rel=1e-9)
    assert q.bound(p=0.3 * U.MPa) == pytest.approx(si.bound(p=3e5), rel=1e-9)
    fixed = fl.fit("thirion", {"mu": mu, "p": p * U.MPa}, fix={"b": 2.0 * U("1/MPa")})
    assert fixed.params["b"].value == pytest.approx(2e-6, rel=1e-12)
    started = fl.fit("thirion", {"mu": mu, "p": p * U.MPa}, initial={"b": 2.0 * U("1/MPa")})
    assert started.params["b"].value == pytest.approx(si.params["b"].value, rel=1e-6)
    with pytest.raises(InputError, match="initial 'b'"):
        fl.fit("thirion", {"mu": mu, "p": p * U.MPa}, initial={"b": 2.0 * U.m})
    with pytest.raises(InputError, match="array 'p'"):
        fl.fit("thirion", {"mu": mu, "p": p * U.m})


def test_export_box_takes_quantities():
    q = export("thirion", THIRION, "csv", {"p": (0.1 * U.MPa, 0.5 * U.MPa, 3)})
    si = export("thirion", THIRION, "csv", {"p": (1e5, 5e5, 3)})
    assert q.text.splitlines()[-3:] == si.text.splitlines()[-3:]
    with pytest.raises(InputError, match="box"):
        export("thirion", THIRION, "csv", {"p": (0.1 * U.m, 0.5 * U.m, 3)})
