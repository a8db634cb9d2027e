"""Unit parsing and conversion (frictionlaws.base.units)."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from frictionlaws.base import units
from frictionlaws.base.errors import InputError


@pytest.mark.parametrize(
    ("value", "unit", "quantity", "expected"),
    [
        (0.2, "MPa", "p", 2e5),
        (200, "kPa", "p", 2e5),
        (2, "bar", "p", 2e5),
        (0.2, "N/mm^2", "p", 2e5),
        (0.2, "N/mm²", "p", 2e5),
        (1, "psi", "p", 6894.757293168361),
        (5e4, "Pa", "p", 5e4),
        (3.6, "km/h", "v", 1.0),
        (1000, "mm/s", "v", 1.0),
        (1.38, "m/s", "v", 1.38),
        (20, "degC", "T", 293.15),
        (20, "°C", "T", 293.15),
        (68, "degF", "T", 293.15),
        (-40, "degF", "T", 233.15),
        (300, "K", "T", 300.0),
        (2, "kN", "F_N", 2000.0),
        (1, "kgf", "F_N", 9.80665),
        (1, "lbf", "F_N", 4.4482216152605),
        (1, "kg", "F_N", 9.8),
        (500, "g", "F_N", 4.9),
        (12.5, "%", "s", 0.125),
        (0.3, "", "s", 0.3),
        (0.3, "-", "mu", 0.3),
        (0.3, "1", "mu", 0.3),
    ],
)
def test_to_si(value: float, unit: str, quantity: str, expected: float) -> None:
    out = units.to_si(value, unit, quantity)
    assert float(out) == pytest.approx(expected, rel=1e-12)


def test_to_si_arrays_keep_shape_and_offset_is_absolute() -> None:
    out = units.to_si(np.array([[0.0, 100.0], [-273.15, 20.0]]), "degC", "T")
    assert out.shape == (2, 2)
    np.testing.assert_allclose(out, [[273.15, 373.15], [0.0, 293.15]], atol=1e-12)


def test_kg_load_uses_thesis_gravity_and_says_so() -> None:
    # thesis: 1 kg -> 9.8 N -> 0.03119 MPa on 314.16 mm^2
    f = units.to_si(1.0, "kg", "F_N")
    assert float(f) == 9.8
    assert float(f) / 314.16e-6 / 1e6 == pytest.approx(0.03119, abs=5e-6)
    note = units.conversion_note("kg", "F_N", column="NL [kg]")
    assert note is not None and "9.8" in note and "NL [kg]" in note and "kgf" in note
    assert units.conversion_note("kgf", "F_N") is None
    assert units.conversion_note("N", "F_N") is None
    assert units.conversion_note("MPa", "p") is None


@pytest.mark.parametrize(
    ("unit", "quantity", "fragment"),
    [
        ("Mpa", "p", "did you mean 'MPa'"),
        ("bananas", "p", "unknown unit 'bananas'"),
        ("m/", "v", "unknown unit"),
        ("m", "p", "is a length, expected a pressure"),
        ("m/s", "p", "is a velocity, expected a pressure"),
        ("MPa", "v", "is a pressure, expected a velocity"),
        ("C", "T", "did you mean 'degC'"),
        ("N", "T", "is a force, expected a temperature"),
        ("kg", "p", "is a mass, expected a pressure"),
        ("m", "F_N", "is a length, expected a force"),
        ("MPa", "mu", "expected a dimensionless friction coefficient"),
        ("rpm", "v", "expected a velocity"),
    ],
)
def test_bad_units_name_the_column_and_what_was_expected(
    unit: str, quantity: str, fragment: str
) -> None:
    with pytest.raises(InputError) as exc:
        units.to_si([1.0], unit, quantity, column=f"x [{unit}]", file="data.csv")
    msg = str(exc.value)
    assert fragment in msg
    assert exc.value.column == f"x [{unit}]"
    assert exc.value.file == "data.csv"
    assert "file 'data.csv'" in msg


@pytest.mark.parametrize(
    ("text", "expected", "si"),
    [
        ("314.16 mm^2", "area", 314.16e-6),
        ("314.16 mm**2", "area", 314.16e-6),
        ("3.1416 cm²", "area", 3.1416e-4),
        ("3.1416e-4 m^2", "area", 3.1416e-4),
        ("20 degC", "T", 293.15),
        ("0.2 MPa", "p", 2e5),
        ("5 km/h", "v", 5 / 3.6),
        ("1 kgf", "F_N", 9.80665),
        (3.1416e-4, "area", 3.1416e-4),
        (2, "area", 2.0),
    ],
)
def test_parse_quantity(text: str | float, expected: str, si: float) -> None:
    assert units.parse_quantity(text, expected) == pytest.approx(si, rel=1e-12)


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("314 mm", "is a length, expected an area"),
        ("0.000314", "has no unit"),
        ("mm^2", "is not a number with a unit"),
        ("", "is not a number with a unit"),
        ("abc", "is not a number with a unit"),
        ("314 bananas", "could not be read"),
        ("3 m/", "could not be read"),
    ],
)
def test_parse_quantity_errors(text: str, fragment: str) -> None:
    with pytest.raises(InputError) as exc:
        units.parse_quantity(text, "area", what="--area", file="f.csv")
    assert fragment in str(exc.value)
    assert "--area" in str(exc.value)
    assert exc.value.file == "f.csv"


def test_parse_quantity_rejects_non_finite_float() -> None:
    with pytest.raises(InputError, match="finite"):
        units.parse_quantity(float("nan"), "area")


def test_unknown_quantity_kind_is_a_programming_error() -> None:
    with pytest.raises(ValueError, match="unknown quantity kind"):
        units.to_si(1.0, "m", "length_of_rope")


def test_display_units_and_headers() -> None:
    assert units.display_unit("p") == "MPa"
    assert units.display_unit("v") == "m/s"
    assert units.display_unit("T") == "degC"
    assert units.display_unit("F_N") == "N"
    assert units.display_unit("mu") == ""
    assert units.header("p") == "p [MPa]"
    assert units.header("T") == "T [degC]"
    assert units.header("mu") == "mu"
    assert units.header("p", "kPa") == "p [kPa]"
    assert units.si_unit("p") == "Pa"
    assert "MPa" in units.examples("p")


def test_no_unit_markers() -> None:
    for marker in ("", "-", "1", " - ", None, "dimensionless"):
        assert units.is_no_unit(marker)
    assert not units.is_no_unit("%")
    assert not units.is_no_unit("MPa")


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.floats(min_value=-1e6, max_value=1e6, allow_nan=False, allow_subnormal=False),
             min_size=1, max_size=20),
    st.sampled_from([("p", "MPa"), ("p", "psi"), ("v", "km/h"), ("T", "degC"),
                     ("T", "degF"), ("F_N", "kgf"), ("F_N", "kg"), ("F_N", "kN"),
                     ("s", "%")]),
)
def test_from_si_inverts_to_si(values: list[float], kind_unit: tuple[str, str]) -> None:
    quantity, unit = kind_unit
    x = np.asarray(values)
    back = units.from_si(units.to_si(x, unit, quantity), unit, quantity)
    np.testing.assert_allclose(back, x, rtol=1e-12, atol=1e-9)


def test_units_module_does_not_import_pint_until_used() -> None:
    code = (
        "import sys, frictionlaws.base.units, frictionlaws.cli\n"
        "assert 'pint' not in sys.modules, 'pint imported at module import'\n"
        "assert 'pandas' not in sys.modules, 'pandas imported by the CLI at start-up'\n"
        "frictionlaws.base.units.check_unit('MPa', 'p')\n"
        "assert frictionlaws.base.units.to_si(1.0, 'MPa', 'p') == 1e6\n"
        "assert frictionlaws.base.units.from_si(293.15, 'degC', 'T') == 20.0\n"
        "assert frictionlaws.base.units.conversion_note('N', 'F_N') is None\n"
        "assert 'pint' not in sys.modules, 'pint loaded for a unit the table declares'\n"
        "assert frictionlaws.base.units.to_si(1.0, 'kPa', 'p') == 1e3\n"
        "assert 'pint' in sys.modules\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


def test_registry_is_built_once() -> None:
    assert units.unit_registry() is units.unit_registry()


@pytest.mark.parametrize(("unit", "quantity", "message"), [
    ("deg", "mu", "is an angle"),
    ("rad", "s", "is an angle"),
    ("turn", "s", "is an angle"),
    ("arcmin", "mu", "is an angle"),
    ("delta_degC", "T", "is a temperature difference"),
    ("delta_degF", "T", "is a temperature difference"),
    ("rpm", "frequency", "is an angular velocity"),
    ("rad/s", "frequency", "is an angular velocity"),
    ("Hz", "angular_velocity", "is a frequency"),
    ("1/s", "angular_velocity", "is a frequency"),
    ("kHz", "angular_velocity", "is a frequency"),
])
def test_units_pint_calls_compatible_but_mean_something_else(unit, quantity, message):
    """One unit policy: angles are not mu or slip; a temperature difference is not T; a
    frequency is not an angular velocity (nor the reverse): in a unit and in a quantity."""
    with pytest.raises(InputError, match=message):
        units.parse_unit(unit, quantity, column=f"{quantity} [{unit}]", file="f.csv")
    with pytest.raises(InputError, match=message):
        units.parse_quantity(f"10 {unit}", quantity, what="--x")


@pytest.mark.parametrize(("text", "si"), [
    ("10 rad/s", 10.0), ("10 rps", 20 * np.pi), ("60 rpm", 2 * np.pi), ("180 deg/s", np.pi)])
def test_an_angular_velocity_with_an_angle_in_its_unit_is_converted(text, si):
    assert units.parse_quantity(text, "angular_velocity") == pytest.approx(si, rel=1e-12)


@pytest.mark.parametrize(("unit", "quantity"), [
    ("%", "s"), ("percent", "s"), ("-", "mu"), ("", "mu"), ("degC", "T"), ("K", "T"),
    ("degF", "T"), ("rpm", "angular_velocity"),
])
def test_units_the_policy_keeps_accepting(unit, quantity):
    units.parse_unit(unit, quantity)


def test_to_display_is_the_one_si_to_display_conversion() -> None:
    """p in MPa, T in degC, v and mu as they are: the unit table's display units."""
    from frictionlaws.base.units import display_unit, to_display

    np.testing.assert_allclose(to_display([1e5, 2e6], "p"), [0.1, 2.0], rtol=1e-15)
    np.testing.assert_allclose(to_display(293.15, "T"), 20.0, rtol=1e-14)
    np.testing.assert_array_equal(to_display([0.5, 1.0], "v"), [0.5, 1.0])
    np.testing.assert_array_equal(to_display(0.7, "mu"), 0.7)
    assert (display_unit("p"), display_unit("T")) == ("MPa", "degC")


def _declared_units() -> list[tuple[str, str]]:
    cases = []
    for name, kind in units.QUANTITIES.items():
        for unit in dict.fromkeys((kind.si, kind.display, "-")):
            if unit == "-" and kind.si:
                continue
            cases.append((name, unit))
    return cases


@pytest.mark.parametrize(("quantity", "unit"), _declared_units())
def test_declared_units_convert_as_pint_does(quantity: str, unit: str) -> None:
    """The table's own units (SI, display, no unit) skip pint and agree with it exactly."""
    kind = units.QUANTITIES[quantity]
    assert units._declared(unit, kind) is not None
    ureg = units.unit_registry()
    parsed = units.parse_unit(unit, quantity)  # pint accepts it for this quantity
    si = ureg.parse_units(kind.si) if kind.si else ureg.dimensionless
    x = np.array([-40.0, 0.0, 0.0312, 0.2496, 1.0, 123.456, 1e300])
    with np.errstate(over="ignore"):
        expected = ureg.Quantity(x, parsed).to(si).magnitude
    np.testing.assert_array_equal(units.to_si(x, unit, quantity), expected)
    back = ureg.Quantity(expected, si).to(parsed).magnitude
    np.testing.assert_array_equal(units.from_si(expected, unit, quantity), back)
    assert np.ndim(units.to_si(2.0, unit, quantity)) == 0
    assert units.to_si(x, unit, quantity) is not x


@pytest.mark.parametrize(("unit", "quantity"), [("mpa", "p"), ("", "p"), ("%", "s"),
                                                ("kg", "F_N"), ("degF", "T")])
def test_other_units_are_not_declared(unit: str, quantity: str) -> None:
    """Anything but the table's own spelling goes to pint (its checks and messages)."""
    assert units._declared(unit, units.QUANTITIES[quantity]) is None
