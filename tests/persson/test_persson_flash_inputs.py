"""Hostile inputs to the flash-temperature settings (Flash) and to the figures built on them.

Every field of Flash is refused with an InputError naming it when it is not a finite
number (or a known name), out of its range, or of the wrong unit by its magnitude (a
specific heat capacity for the volumetric one, a conductivity in mW/(m K)).  Values
are generated, not only picked.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from frictionlaws.base.errors import InputError
from frictionlaws.persson import Flash, asphalt_like, flash_figures, friction, tread_compound
from frictionlaws.persson.flash import CLOSURES, CONTACT_TEMPERATURES

NOT_NUMBERS = st.one_of(st.text(max_size=8), st.none(), st.booleans(),
                        st.lists(st.floats(), max_size=2), st.just(complex(1, 1)))
NON_FINITE = st.sampled_from([math.nan, math.inf, -math.inf, np.float64("nan")])

#: field -> values outside its range (the plausible range of the quantity)
OUT_OF_RANGE = {
    "conductivity": st.one_of(st.floats(-1e6, 0.0099), st.floats(10.0001, 1e12)),
    "heat_capacity": st.one_of(st.floats(-1e9, 99_999.0), st.floats(1.0001e7, 1e15)),
    "heat_fraction": st.one_of(st.floats(-1e6, -1e-9), st.floats(1.0 + 1e-9, 1e6)),
    "sliding_distance": st.one_of(st.floats(-1e6, -1e-12), st.floats(1000.001, 1e12)),
    "tol": st.floats(-1e6, 0.0),
}


@settings(max_examples=60, deadline=None)
@given(name=st.sampled_from(sorted(OUT_OF_RANGE)), data=st.data())
def test_a_value_out_of_its_range_is_refused_naming_the_field(name, data):
    value = data.draw(OUT_OF_RANGE[name])
    with pytest.raises(InputError, match=f"flash temperature: {name} = "):
        Flash(**{name: value})


@settings(max_examples=60, deadline=None)
@given(name=st.sampled_from(sorted(OUT_OF_RANGE)), value=st.one_of(NOT_NUMBERS, NON_FINITE))
def test_a_value_that_is_not_a_finite_number_is_refused(name, value):
    with pytest.raises(InputError, match=rf"flash temperature: {name} = .* must be "):
        Flash(**{name: value})


@settings(max_examples=40, deadline=None)
@given(name=st.sampled_from(["closure", "contact_temperature"]),
       value=st.one_of(st.text(max_size=12), st.none(), st.integers(), st.floats()))
def test_an_unknown_choice_is_refused_listing_the_choices(name, value):
    choices = CLOSURES if name == "closure" else CONTACT_TEMPERATURES
    if value in choices:
        return
    with pytest.raises(InputError, match=f"{name} = .* must be one of '{choices[0]}'"):
        Flash(**{name: value})


@pytest.mark.parametrize(("kw", "hint"), [
    ({"heat_capacity": 1500.0}, r"specific heat capacity c in J/\(kg K\): give rho c"),
    ({"conductivity": 250.0}, r"mW/\(m K\)"),
    ({"heat_fraction": 50.0}, "not a percentage"),
])
def test_a_likely_unit_mistake_is_named(kw, hint):
    with pytest.raises(InputError, match=hint):
        Flash(**kw)


@pytest.mark.parametrize("max_iter", [0, -3, 2.5, True, "10", None])
def test_max_iter_must_be_a_whole_number_of_at_least_one(max_iter):
    with pytest.raises(InputError, match="max_iter"):
        Flash(max_iter=max_iter)


@pytest.mark.parametrize("kw", [{"conductivity": 0.01}, {"conductivity": 10.0},
                                {"heat_capacity": 1e5}, {"heat_capacity": 1e7},
                                {"sliding_distance": 0.0}, {"sliding_distance": 1000.0},
                                {"heat_fraction": 0}, {"conductivity": np.float32(0.3)},
                                {"max_iter": np.int64(5)}])
def test_the_ends_of_the_ranges_and_numpy_scalars_are_taken(kw):
    Flash(**kw)


@pytest.mark.parametrize("flash", [0.5, "volume", {"heat_fraction": 1.0}])
def test_friction_takes_a_flash_or_none(flash):
    with pytest.raises(InputError, match="flash must be a Flash"):
        friction(tread_compound(), asphalt_like(1e6), 0.1, 293.15, 2e5, flash=flash)


@pytest.mark.parametrize(("kw", "match"), [
    ({"T": 20.0}, r"T = 20.0 must be a number in 243.15 .. 343.15 K; if it is in degC"),
    ({"T": math.nan}, "T = nan must be a number"),
    ({"T": "293"}, "T = '293' must be a number"),
    ({"p": 0.2}, r"p = 0.2 must be a number in 1000 .. 1e\+08 Pa"),
    ({"p": -2e5}, "p = -200000.0 must be"),
    ({"flash": None}, "flash must be a Flash"),
])
def test_flash_figures_refuse_bad_conditions(kw, match):
    with pytest.raises(InputError, match=match):
        flash_figures(**kw)
