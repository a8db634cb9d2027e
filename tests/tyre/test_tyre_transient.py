"""The transient slip model against the closed-form first-order responses and the steady state."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from frictionlaws.base.errors import InputError
from frictionlaws.tyre import MagicFormula, TransientSlip, transient_slip
from frictionlaws.tyre.transient import TRANSIENT_OUTPUTS, relax, relax_source, travelled

FZ = 4000.0
VX = 20.0


@pytest.fixture(scope="module")
def mf() -> MagicFormula:
    return MagicFormula.from_file("MagicFormula61")


def _sigma(mf: MagicFormula, fz: float = FZ) -> tuple[float, float]:
    out = mf.steady_state(0.0, 0.0, fz)
    return float(out["sigmax"]), float(out["sigmay"])


def _step_times(distance_to: float, sigma: float, n: int = 400) -> np.ndarray:
    """Times of a step at t = 0 (two samples at 0: the jump), one sample at s = sigma."""
    t_sigma = sigma / VX
    t = np.unique(np.concatenate([np.linspace(0.0, distance_to / VX, n), [t_sigma]]))
    return np.concatenate([[0.0], t])


@pytest.mark.parametrize("step_deg", [0.1, 0.5])
def test_a_step_in_slip_angle_reaches_63_percent_of_the_steady_force_after_one_relaxation_length(
        mf: MagicFormula, step_deg: float) -> None:
    _, sy = _sigma(mf)
    t = _step_times(5 * sy, sy)
    alpha = np.where(np.arange(t.size) >= 1, np.radians(step_deg), 0.0)
    r = transient_slip(mf, t, VX, FZ, alpha=alpha)
    # the lagged slip is the exact first-order response at every sample
    expected = np.radians(step_deg) * -np.expm1(-r.distance / sy)
    assert np.abs(r.alpha_t - expected).max() <= 1e-13
    at = int(np.argmin(np.abs(r.distance - sy)))
    assert r.distance[at] == pytest.approx(sy, rel=1e-12)
    share = (r.Fy[at] - r.Fy[0]) / (r.Fy_steady[-1] - r.Fy[0])
    assert share == pytest.approx(1 - np.exp(-1), rel=0.01)  # 63.2 % within 1 %


def test_a_step_in_slip_ratio_relaxes_over_the_longitudinal_relaxation_length(
        mf: MagicFormula) -> None:
    sx, _ = _sigma(mf)
    t = _step_times(5 * sx, sx)
    kappa = np.where(np.arange(t.size) >= 1, 0.002, 0.0)
    r = transient_slip(mf, t, VX, FZ, kappa=kappa)
    assert np.abs(r.kappa_t - 0.002 * -np.expm1(-r.distance / sx)).max() <= 1e-15
    at = int(np.argmin(np.abs(r.distance - sx)))
    share = (r.Fx[at] - r.Fx[0]) / (r.Fx_steady[-1] - r.Fx[0])
    assert share == pytest.approx(1 - np.exp(-1), rel=0.01)


def _sine_response(t: np.ndarray, amp: float, omega: float, rate: float,
                   y0: float) -> np.ndarray:
    """The exact response of dy/dt = rate (A sin(omega t) - y), y(0) = y0."""
    r = omega / rate
    steady = amp / (1 + r**2) * (np.sin(omega * t) - r * np.cos(omega * t))
    return steady + (y0 + amp * r / (1 + r**2)) * np.exp(-rate * t)


def test_a_stepped_sine_sweep_follows_the_closed_form_first_order_response(
        mf: MagicFormula) -> None:
    _, sy = _sigma(mf)
    rate = VX / sy
    amp, h = np.radians(1.0), 1e-4
    y0 = 0.0
    worst = 0.0
    for f in (0.5, 2.0, 8.0, 20.0):  # Hz: a segment of whole periods each, u continuous
        omega = 2 * np.pi * f
        t = np.arange(0.0, max(2, round(0.5 * f)) / f + h / 2, h)
        alpha = amp * np.sin(omega * t)
        r = transient_slip(mf, t, VX, FZ, alpha=alpha, initial=(0.0, y0))
        exact = _sine_response(t, amp, omega, rate, y0)
        worst = max(worst, np.abs(r.alpha_t - exact).max() / amp)
        # settled: the gain 1 / sqrt(1 + (omega sigma / V)^2) of the lag
        last = t >= t[-1] - 1 / f
        gain = np.abs(r.alpha_t[last]).max() / amp
        assert gain == pytest.approx(1 / np.hypot(1, omega * sy / VX), rel=2e-3)
        y0 = r.alpha_t[-1]
    # the piecewise-linear sampling of the sine is the only error: A omega^2 h^2 / 8
    assert worst <= (2 * np.pi * 20.0 * h) ** 2 / 8 * 1.01


def _chirp_error(mf: MagicFormula, n: int) -> float:
    """Largest difference of the lagged slip angle from scipy's DOP853 (rtol 1e-11) on the
    same piecewise-linear histories: speed 8 -> 32 m/s, load +-40 %, a 1-8 Hz chirp."""
    t = np.linspace(0.0, 0.3, n)
    vx = 8.0 + 80.0 * t  # m/s
    fz = FZ * (1 + 0.4 * np.sin(2 * np.pi * 3 * t))
    alpha = np.radians(2.0) * np.sin(2 * np.pi * (1 + 12 * t) * t)
    r = transient_slip(mf, t, vx, fz, alpha=alpha)

    def rhs(tau: float, y: np.ndarray) -> np.ndarray:
        rate = np.interp(tau, t, np.abs(vx)) * np.interp(tau, t, 1 / r.sigma_y)
        return rate * (np.interp(tau, t, alpha) - y)

    ref = solve_ivp(rhs, (t[0], t[-1]), [alpha[0]], t_eval=t, method="DOP853", rtol=1e-11,
                    atol=1e-14, max_step=t[1] - t[0]).y[0]
    return float(np.abs(r.alpha_t - ref).max() / np.abs(alpha).max())


@pytest.mark.slow
def test_varying_speed_and_load_converge_to_an_adaptive_integration_at_second_order(
        mf: MagicFormula) -> None:
    coarse, fine = _chirp_error(mf, 1201), _chirp_error(mf, 2401)
    assert 3.5 <= coarse / fine <= 4.5  # second order in the step
    assert fine <= 1e-6  # of the peak slip angle, at 1/8 ms steps


def test_a_slow_input_follows_the_steady_state_within_a_millionth_of_the_peak(
        mf: MagicFormula) -> None:
    t = np.linspace(0.0, 400.0, 4001)  # 10 km at 25 m/s
    # slow: the lag sigma d(alpha)/ds times the cornering stiffness is below 1e-6 of the
    # peak side force (0.02 deg over 10 km)
    alpha = np.radians(0.02) * t / t[-1]
    kappa = 1e-4 * t / t[-1]
    fz = FZ * (1 + 0.01 * t / t[-1])
    r = transient_slip(mf, t, 25.0, fz, alpha=alpha, kappa=kappa)
    grid = mf.steady_state(np.linspace(-0.3, 0.3, 61)[:, None],
                           np.radians(np.linspace(-15, 15, 61)), FZ)
    for name in ("Fx", "Fy", "Mz"):
        got, steady = getattr(r, name), getattr(r, f"{name}_steady")
        assert np.abs(got - steady).max() <= 1e-6 * np.abs(grid[name]).max(), name


def test_constant_inputs_are_the_steady_state_exactly(mf: MagicFormula) -> None:
    t = np.linspace(0.0, 1.0, 11)
    r = transient_slip(mf, t, VX, FZ, kappa=0.05, alpha=np.radians(3.0), gamma=0.02)
    for name in ("Fx", "Fy", "Mz"):
        assert np.array_equal(getattr(r, name), getattr(r, f"{name}_steady"))


def test_an_unsettled_start_decays_over_the_relaxation_length(mf: MagicFormula) -> None:
    sx, sy = _sigma(mf)
    t = np.linspace(0.0, 0.2, 201)
    r = transient_slip(mf, t, VX, FZ, initial=(0.01, 0.02))
    assert np.allclose(r.kappa_t, 0.01 * np.exp(-r.distance / sx), rtol=1e-12, atol=0)
    assert np.allclose(r.alpha_t, 0.02 * np.exp(-r.distance / sy), rtol=1e-12, atol=0)


def test_at_standstill_the_lagged_slips_hold() -> None:
    u = np.array([0.0, 1.0, 1.0, 0.5])
    y = relax(u, np.array([0.0, 0.0, 0.0]), y0=0.2)
    assert np.array_equal(y, [0.2, 0.2, 0.2, 0.2])


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.floats(0, 0.5), st.floats(-1, 1), st.floats(0, 1e3)),
                min_size=1, max_size=40),
       st.floats(-1, 1))
def test_the_lag_stays_within_the_range_of_its_input(steps: list, y0: float) -> None:
    # a first-order lag of a piecewise-linear input never leaves the range of the input
    # and its start, whatever the steps (zero-length ones too) and rates (huge ones too)
    lag = np.array([h * a for h, _, a in steps])
    u = np.array([0.0] + [x for _, x, _ in steps])
    y = relax(u, lag, y0)
    lo, hi = min(u.min(), y0), max(u.max(), y0)
    assert np.isfinite(y).all()
    assert np.all(y >= lo - 1e-12) and np.all(y <= hi + 1e-12)


def test_the_distance_is_the_integral_of_the_speed_magnitude() -> None:
    t = np.array([0.0, 1.0, 2.0, 2.0, 3.0])
    vx = np.array([2.0, -2.0, 4.0, 4.0, 4.0])
    s = travelled(t, vx)
    assert s == pytest.approx([0.0, 1.0, 1.0 + 20 / 12, 1.0 + 20 / 12, 5.0 + 20 / 12])


def test_a_wheel_speed_history_relaxes_the_slip_ratio_as_its_slip_speed(
        mf: MagicFormula) -> None:
    # sigma d(kappa')/dt + |V_x| kappa' = R_e Omega - V_x: the same lag as of the slip
    # ratio (R_e Omega - V_x) / |V_x| at a speed that does not stop
    t = np.linspace(0.0, 0.5, 501)
    free = VX / 0.3  # about free rolling [rad/s]
    omega = free * (1 - 0.08 * np.sin(2 * np.pi * 3 * t) ** 2)
    r = transient_slip(mf, t, VX, FZ, omega=omega)
    re = mf.steady_state(0.0, 0.0, FZ, vx=VX, omega=omega)["Re"]
    slip = (re * omega - VX) / VX
    np.testing.assert_allclose(r.kappa, slip, rtol=1e-12)
    lag = np.diff(r.distance) / r.sigma_x[0]
    np.testing.assert_allclose(r.kappa_t, relax(slip, lag), rtol=0, atol=1e-14)
    steady = mf.steady_state(slip, 0.0, FZ, vx=VX)["Fx"]
    np.testing.assert_allclose(r.Fx_steady, steady, rtol=1e-12)


def test_a_wheel_speed_far_from_free_rolling_and_a_standing_wheel_are_said_truly(
        mf: MagicFormula) -> None:
    # the slip ratio comes from the wheel speed: nothing to contradict, however far from
    # free rolling; where the wheel stands it is not defined, and the NaN is said
    t = np.linspace(0.0, 1.0, 11)
    vx = np.where(np.arange(t.size) < 3, 0.0, VX)
    with pytest.warns(UserWarning) as caught:
        r = transient_slip(mf, t, vx, FZ, omega=1.5 * VX / 0.3)
    said = [str(w.message) for w in caught]
    assert not any("contradicts the slip ratio" in w for w in said + r.warnings)
    standing = [w for w in r.warnings if "standing wheel" in w]
    assert len(standing) == 1 and "3 of 11 sample(s)" in standing[0]
    assert np.isnan(r.kappa[:3]).all() and np.isnan(r.Fx_steady[:3]).all()
    assert np.isfinite(r.kappa[3:]).all() and r.kappa[3] > 0.4
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a wheel that never stands: no word of it
        r = transient_slip(mf, t, VX, FZ, omega=VX / 0.3)
    assert not r.warnings


def test_at_standstill_a_spinning_wheel_winds_up_its_slip() -> None:
    # V_x = 0: kappa' integrates the slip speed R_e Omega / sigma
    w = np.array([0.5, 0.5, 0.5])
    y = relax_source(w, np.zeros(2), np.array([0.1, 0.1]), 0.0)
    np.testing.assert_allclose(y, [0.0, 0.05, 0.1], rtol=1e-15)


def test_running_backwards_turns_the_longitudinal_force(mf: MagicFormula) -> None:
    t = np.linspace(0.0, 0.2, 21)
    kappa = np.where(np.arange(t.size) >= 1, -0.05, 0.0)
    fwd = transient_slip(mf, t, VX, FZ, kappa=kappa)
    back = transient_slip(mf, t, -VX, FZ, kappa=kappa)
    np.testing.assert_allclose(back.kappa_t, fwd.kappa_t, rtol=1e-15)
    np.testing.assert_allclose(back.Fx, -fwd.Fx, rtol=1e-12)


def test_turn_slip_histories_reach_the_steady_state(mf: MagicFormula) -> None:
    t = np.linspace(0.0, 1.0, 11)
    r = transient_slip(mf, t, VX, FZ, alpha=np.radians(2.0), phit=0.3, turn_slip=True)
    steady = mf.steady_state(0.0, np.radians(2.0), FZ, vx=VX, phit=0.3, turn_slip=True)
    np.testing.assert_array_equal(r.Fy, steady["Fy"])
    assert r.sigma_y[0] == pytest.approx(steady["sigmay"])  # zeta_3 in K_y: sigma_y too


def test_slip_ratio_and_wheel_speed_together_are_refused(mf: MagicFormula) -> None:
    with pytest.raises(InputError, match="kappa or the wheel speed omega, not both"):
        transient_slip(mf, [0.0, 1.0], VX, FZ, kappa=0.01, omega=60.0)


def test_the_result_names_its_histories_with_units(mf: MagicFormula) -> None:
    r = transient_slip(mf, [0.0, 0.1], VX, FZ)
    assert isinstance(r, TransientSlip)
    assert set(r.as_dict()) == set(TRANSIENT_OUTPUTS)
    assert all(unit for unit, _ in TRANSIENT_OUTPUTS.values())


@pytest.mark.parametrize(("t", "kw", "match"), [
    ([0.0, 1.0, 0.5], {}, r"t must not decrease; t\[2\] = 0.5 s follows t\[1\] = 1 s"),
    ([[0.0, 1.0]], {}, "one-dimensional array of at least two sample times"),
    ([0.0], {}, "at least two sample times"),
    ([0.0, np.nan], {}, r"t must be finite; t\[1\]"),
    ([0.0, 1.0], {"alpha": [0.0, np.inf]}, r"alpha must be finite; alpha\[1\]"),
    ([0.0, 1.0], {"alpha": [0.0, 0.1, 0.2]}, "do not fit together"),
    ([0.0, 1.0, 2.0], {"kappa": [[0.0], [0.1], [0.2]]}, "length of t"),
    ([0.0, 1.0], {"fz": [4000.0, -1.0]}, "positive"),
])
def test_bad_histories_are_refused(mf: MagicFormula, t: list, kw: dict, match: str) -> None:
    args = {"vx": VX, "fz": FZ, **kw}
    with pytest.raises(InputError, match=match):
        transient_slip(mf, t, args.pop("vx"), args.pop("fz"), **args)
