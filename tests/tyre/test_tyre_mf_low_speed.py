"""Low speed, running backwards, a given wheel speed, instKya and no limit checks.

The agreement with MFeval 4.0 is in ``test_tyre_mf_mfeval_beyond.py``; here: what the
options mean and what is refused.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from frictionlaws.base.errors import InputError
from frictionlaws.tyre import MagicFormula

FZ = 5000.0


@pytest.fixture(scope="module")
def mf61() -> MagicFormula:
    return MagicFormula.from_file("MagicFormula61")


def _quiet(mf: MagicFormula, *args, **kw) -> dict:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return mf.steady_state(*args, **kw)


def test_speeds_at_and_below_vxlow_are_evaluated_with_a_warning(mf61: MagicFormula) -> None:
    with pytest.warns(UserWarning, match="VXLOW"):
        out = mf61.steady_state(0.05, np.radians(3.0), FZ, vx=[0.5, 1.0, -0.3])
    assert all(np.isfinite(out[n]).all() for n in ("Fx", "Fy", "Mz", "Mx", "My"))


def test_the_low_speed_reductions_join_the_outputs_above_vxlow(mf61: MagicFormula) -> None:
    vxlow = mf61.structure["VXLOW"]
    kappa, alpha = np.array([[-0.1], [0.04]]), np.radians([-5.0, 2.0])
    below = _quiet(mf61, kappa, alpha, FZ, vx=vxlow * (1 - 1e-9))
    above = _quiet(mf61, kappa, alpha, FZ, vx=vxlow * (1 + 1e-9))
    for name in ("Fx", "Fy", "Mz", "My", "t", "Mzr"):
        np.testing.assert_allclose(below[name], above[name], rtol=1e-6, atol=1e-6,
                                   err_msg=name)


def test_a_standing_wheel_carries_no_slip_force(mf61: MagicFormula) -> None:
    out = _quiet(mf61, np.array([[-0.2], [0.1]]), np.radians([-8.0, 4.0]), FZ,
                 np.radians(1.0), vx=0.0)
    for name in ("Fx", "Fy", "My"):
        np.testing.assert_array_equal(out[name], 0.0, err_msg=name)
    # without the limit checks nothing is reduced: the slip ratio acts as given (the
    # lateral slip alpha* = tan(alpha) sgn(V_x) is 0 at a standing wheel, as in MFeval)
    raw = _quiet(mf61, 0.1, np.radians(4.0), FZ, vx=0.0, limit_checks=False)
    assert abs(raw["Fx"]) > 1000.0


def test_running_backwards_turns_the_longitudinal_force_and_rolling_moment(
        mf61: MagicFormula) -> None:
    kappa = np.array([-0.3, -0.05, 0.02, 0.2])
    fwd = mf61.steady_state(kappa, 0.0, FZ, vx=12.0)
    back = mf61.steady_state(kappa, 0.0, FZ, vx=-12.0)
    np.testing.assert_allclose(back["Fx"], -fwd["Fx"], rtol=1e-12)
    np.testing.assert_allclose(back["My"], -fwd["My"], rtol=1e-12)
    assert np.all(back["omega"] < 0)


def test_a_given_wheel_speed_sets_the_rolling_radius_not_the_slip(mf61: MagicFormula) -> None:
    est = mf61.steady_state(0.05, np.radians(2.0), FZ, vx=20.0)
    given = mf61.steady_state(0.05, np.radians(2.0), FZ, vx=20.0, omega=est["omega"])
    assert given["omega"] == pytest.approx(est["omega"], rel=1e-15)
    assert given["Re"] == pytest.approx(est["Re"], rel=1e-9)
    assert given["Fx"] == est["Fx"] and given["Fy"] == est["Fy"]
    fast = mf61.steady_state(0.05, np.radians(2.0), FZ, vx=20.0, omega=2 * est["omega"])
    assert fast["omega"] == 2 * est["omega"] and fast["Fx"] == est["Fx"]


@pytest.mark.parametrize("omega", [np.nan, np.inf])
def test_a_wheel_speed_that_is_no_number_is_refused(mf61: MagicFormula, omega: float) -> None:
    with pytest.raises(InputError, match="omega"):
        mf61.steady_state(0.0, 0.0, FZ, omega=[60.0, omega])


def test_inst_kya_is_the_slope_of_fy_along_the_last_axis(mf61: MagicFormula) -> None:
    alpha = np.radians(np.linspace(-4.0, 6.0, 11))
    out = mf61.steady_state(np.array([[0.0], [0.05]]), alpha, FZ)
    slope = np.diff(out["Fy"], axis=-1) / np.diff(alpha)
    np.testing.assert_allclose(out["instKya"][:, :-1], slope, rtol=1e-12)
    np.testing.assert_allclose(out["instKya"][:, -1], slope[:, -1], rtol=1e-12)
    # one point, or an angle that does not change: no slope (MFeval: 0, or +-inf)
    assert np.isnan(mf61.steady_state(0.0, 0.02, FZ)["instKya"])
    flat = mf61.steady_state([0.0, 0.1], 0.02, FZ)["instKya"]
    assert np.isnan(flat).all()


def test_without_limit_checks_the_curvature_factors_are_not_capped() -> None:
    ref = MagicFormula.from_file("MagicFormula61")
    coeffs = {**ref.coefficients, "PEX1": 1.6, "PEX4": 0.0}  # E_x > 1: no longer capped
    mf = MagicFormula(coeffs, fnomin=ref.fnomin, version="6.1", structure=ref.structure,
                      limits=ref.limits, pressure=ref.pressure,
                      nominal_pressure=ref.nominal_pressure)
    kappa = np.linspace(0.02, 0.6, 8)
    capped = _quiet(mf, kappa, 0.0, FZ)["Fx"]
    free = _quiet(mf, kappa, 0.0, FZ, limit_checks=False)["Fx"]
    assert np.abs(capped - free).max() > 0.01 * np.abs(capped).max()
    lon = mf.longitudinal(FZ)
    x = lon.B * (kappa + lon.S_H)
    e = lon.E_a - lon.E_b * np.sign(x)
    assert np.all(e > 1)
    expected = lon.D * np.sin(lon.C * np.arctan(x - e * (x - np.arctan(x)))) + lon.S_V
    np.testing.assert_allclose(free, expected, rtol=1e-10)


def test_without_limit_checks_mx_and_my_are_reduced_below_fzmin() -> None:
    mf52 = MagicFormula.from_file("MagicFormula52")
    fzmin = mf52.limits["fz"][0]
    fz = 0.5 * fzmin
    plain = _quiet(mf52, 0.0, np.radians(2.0), fz, np.radians(1.0))
    raw = _quiet(mf52, 0.0, np.radians(2.0), fz, np.radians(1.0), limit_checks=False)
    assert raw["My"] == pytest.approx(plain["My"] * 0.5, rel=1e-9)
    assert abs(raw["Mx"]) < abs(plain["Mx"])


def test_saturating_without_limit_checks_is_refused(mf61: MagicFormula) -> None:
    with pytest.raises(InputError, match="saturate"):
        mf61.steady_state(0.0, 0.0, FZ, saturate=True, limit_checks=False)


def test_a_standing_wheel_needs_vxlow_for_the_limit_checks() -> None:
    ref = MagicFormula.from_file("MagicFormula61")
    structure = {k: v for k, v in ref.structure.items() if k != "VXLOW"}
    mf = MagicFormula(ref.coefficients, fnomin=ref.fnomin, version="6.1", structure=structure,
                      limits=ref.limits)
    with pytest.raises(InputError, match="VXLOW"):
        mf.steady_state(0.0, 0.0, FZ, vx=0.0)
    assert np.isfinite(mf.steady_state(0.0, 0.0, FZ, vx=0.0, limit_checks=False)["Fx"])
