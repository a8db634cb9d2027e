"""The common units converted without pint agree with pint exactly (issue 15: no pint
registry on the plain fit path)."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from frictionlaws import units


@pytest.mark.parametrize("key", sorted(units._FAST))
def test_fast_conversion_agrees_with_pint(key):
    quantity, unit = key
    values = np.array([0.0, 0.03119, 1.5, 273.15, 1e6])
    ureg = units.unit_registry()
    kind = units.QUANTITIES[quantity]
    parsed = units.parse_unit(unit, quantity)  # pint accepts it for this quantity
    target = ureg.parse_units(kind.si) if kind.si else ureg.dimensionless
    want = np.asarray(ureg.Quantity(values, parsed).to(target).magnitude, float)
    np.testing.assert_allclose(units.to_si(values, unit, quantity), want, rtol=1e-15,
                               atol=1e-12)
    assert units.conversion_note(unit, quantity) is None
    units.check_unit(unit, quantity)


def test_scalar_gives_a_0d_array_and_a_mass_still_goes_through_pint():
    out = units.to_si(2.0, "MPa", "p")
    assert isinstance(out, np.ndarray) and out.shape == () and float(out) == 2e6
    assert float(units.to_si(1.0, "kg", "F_N")) == pytest.approx(units.G_THESIS)
    assert units.conversion_note("kg", "F_N") is not None


def test_loading_the_packaged_data_builds_no_pint_registry():
    code = ("import sys; import frictionlaws as fl; from frictionlaws.fitting import "
            "as_fit_data; as_fit_data('thesis-steel'); print('pint' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "False"
