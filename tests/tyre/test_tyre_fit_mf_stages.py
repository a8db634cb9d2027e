"""The staged Magic Formula fit on rig-like data: combined slip, aligning moment, checks."""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from frictionlaws.base.errors import ExtrapolationWarning, FitError, InputError
from frictionlaws.cli import main
from frictionlaws.tyre import MagicFormula, TyreData, fit_mf, read_tyre_data
from frictionlaws.tyre.mf.fit.checks import check_plausible
from frictionlaws.tyre.synthetic_rig import moved_tyre, rig_data, truth_errors


@pytest.fixture(autouse=True)
def _quiet_extrapolation():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        yield


@pytest.mark.slow
def test_rig_data_of_another_tyre_are_recovered_within_the_stated_shares(
        tmp_path: Path) -> None:
    truth = moved_tyre()
    data = rig_data(truth)
    res = fit_mf(data, fittyp=61, template="MagicFormula61")
    fitted = MagicFormula.from_file(res.write(tmp_path / "fitted.tir"))
    worst = truth_errors(truth, fitted)
    # the shares of the MF room's held-out line (measured 0.22, 0.32, 0.21, 0.39, 0.59 %)
    assert worst["Fx0"] < 0.005 and worst["Fy0"] < 0.005, worst
    assert worst["Fx"] < 0.01 and worst["Fy"] < 0.01, worst
    assert worst["Mz"] < 0.02, worst
    # quadratic pressure terms need three pressures: named, at the template's value
    assert {"PPX2", "PPY4"} <= set(res.undetermined)
    for name in ("RBX1", "RBY1", "RVY1", "QBZ1", "QDZ1", "QDZ6", "SSZ1", "SSZ2", "PPZ1",
                 "QDZ4"):  # gamma^2 beside gamma: cambers of both signs separate them
        assert name in res.values and 0 < res.stderr[name] < math.inf, name
    # gamma |gamma| beside gamma: cambers of one magnitude do not
    assert {"QDZ10", "QDZ11"} <= set(res.undetermined)
    assert set(res.errors) == {"x", "y", "x_all", "y_all", "mz"}
    # the rows near pure slip are used despite the jitter (none dropped)
    near_x = np.isfinite(data.fx) & (np.abs(data.alpha) <= math.radians(1.0))
    assert res.errors["x"]["n"] == near_x.sum()
    assert res.errors["mz"]["n"] == len(data)
    text = (tmp_path / "fitted.tir").read_text()
    assert "alpha* = tan(alpha)" in text and "FITTED by frictionlaws" in text
    assert "Mz (every row, combined slip)" in text
    lim = fitted.limits
    assert lim["gamma"] == pytest.approx((data.gamma.min(), data.gamma.max()))
    assert lim["pressure"] == pytest.approx((data.pressure.min(), data.pressure.max()))
    assert lim["fz"] == pytest.approx((data.fz.min(), data.fz.max()))
    assert lim["alpha"] == pytest.approx((data.alpha.min(), data.alpha.max()))
    assert lim["kappa"] == pytest.approx((data.kappa.min(), data.kappa.max()))


def test_an_mz_column_without_a_lateral_fit_is_refused(tmp_path: Path) -> None:
    truth = moved_tyre()
    data = rig_data(truth, n=7, loads=(0.5, 1.0, 1.5), pressures=(1.0,), cambers_deg=(0.0,),
                    combined=False)
    no_fy = TyreData.from_arrays(fz=data.fz, kappa=data.kappa, alpha=data.alpha,
                                 gamma=data.gamma, pressure=data.pressure, fx=data.fx,
                                 mz=data.mz)
    with pytest.raises(InputError, match="the Mz column cannot be fitted") as err:
        fit_mf(no_fy, fittyp=61, template="MagicFormula61")
    assert "Mz" in str(err.value) and "leave out the Mz column" in str(err.value)
    csv = tmp_path / "no_fy.csv"
    csv.write_text("Fz [N],kappa [-],alpha [rad],Fx [N],Mz [N m]\n" + "".join(
        f"{z!r},{k!r},{a!r},{x!r},{m!r}\n" for z, k, a, x, m in zip(
            *(v.tolist() for v in (data.fz, data.kappa, data.alpha, data.fx, data.mz)))))
    target = tmp_path / "out.tir"
    assert main(["tyre", "fit-mf", str(csv), "-o", str(target)]) == 2
    assert not target.exists()
    without_mz = fit_mf(TyreData.from_arrays(fz=data.fz, kappa=data.kappa, alpha=data.alpha,
                                             fx=data.fx), fittyp=61)
    assert "PDX1" in without_mz.values and "mz" not in without_mz.errors


@pytest.mark.parametrize("pressures", [(0.9, 1.1), (0.85, 1.0)])
def test_two_pressures_leave_the_quadratic_pressure_terms_and_fit_the_peak(
        pressures: tuple[float, float]) -> None:
    truth = moved_tyre()
    data = rig_data(truth, n=21, loads=(0.5, 1.0, 1.5), pressures=pressures,
                    cambers_deg=(0.0,), combined=False)
    res = fit_mf(data, fittyp=61)
    for k in ("PPX2", "PPX4", "PPY4"):
        assert k in res.undetermined and k not in res.values
    for k in ("PDX1", "PDY1", "PPX3", "PPY3"):
        assert k in res.values and k not in res.undetermined
    k, a = np.linspace(-0.25, 0.25, 101), np.radians(np.linspace(-12, 12, 97))
    for p in truth.nominal_pressure * np.linspace(min(pressures), max(pressures), 5):
        tx, ty = truth.fx0(k, truth.fnomin, 0.0, p), truth.fy0(a, truth.fnomin, 0.0, p)
        assert np.abs(res.model.fx0(k, truth.fnomin, 0.0, p) - tx).max() < 0.02 * np.abs(
            tx).max()
        assert np.abs(res.model.fy0(a, truth.fnomin, 0.0, p) - ty).max() < 0.02 * np.abs(
            ty).max()


def test_only_combined_rows_fit_nothing_and_write_nothing(tmp_path: Path) -> None:
    truth = MagicFormula.from_file("MagicFormula61")
    K, A = np.meshgrid(np.linspace(0.05, 0.2, 8), np.radians([4.0, 8.0]))
    fz = np.full(K.size, truth.fnomin)
    out = truth.steady_state(K.ravel(), A.ravel(), fz)
    data = TyreData.from_arrays(fz=fz, kappa=K.ravel(), alpha=A.ravel(), fx=out["Fx"],
                                fy=out["Fy"])
    with pytest.raises(FitError, match="nothing could be fitted"):
        fit_mf(data, fittyp=61)
    csv = tmp_path / "combined.csv"
    lines = ["Fz [N],kappa [-],alpha [rad],Fx [N],Fy [N]"]
    lines += [f"{a},{b},{c},{d},{e}" for a, b, c, d, e in
              zip(fz, K.ravel(), A.ravel(), out["Fx"], out["Fy"])]
    csv.write_text("\n".join(lines) + "\n")
    target = tmp_path / "out.tir"
    assert main(["tyre", "fit-mf", str(csv), "-o", str(target)]) != 0
    assert not target.exists()


def _sweep(amplitude: float, n: int = 21) -> TyreData:
    mf = MagicFormula.from_file("MagicFormula61")
    k = np.linspace(-amplitude, amplitude, n)
    a = np.radians(np.linspace(-10, 10, n))
    fz = np.full(n, mf.fnomin)
    return TyreData.from_arrays(fz=np.r_[fz, fz], kappa=np.r_[k, np.zeros(n)],
                                alpha=np.r_[np.zeros(n), a],
                                fx=np.r_[mf.fx0(k, fz), np.full(n, np.nan)],
                                fy=np.r_[np.full(n, np.nan), mf.fy0(a, fz)])


@settings(max_examples=25, deadline=None)
@given(amplitude=st.floats(0.05, 0.6), scale=st.sampled_from([100.0, 0.01]))
def test_slip_ratios_in_the_wrong_unit_are_refused_naming_percent(amplitude: float,
                                                                  scale: float) -> None:
    data = _sweep(amplitude)
    check_plausible(data, 6752.0)  # the honest data pass
    data.kappa = data.kappa * scale
    with pytest.raises(InputError, match="percent") as err:
        check_plausible(data, 6752.0)
    assert "kappa" in str(err.value)


@settings(max_examples=25, deadline=None)
@given(degrees=st.floats(2.0, 20.0))
def test_radians_under_a_degree_header_are_refused(tmp_path_factory: pytest.TempPathFactory,
                                                   degrees: float) -> None:
    mf = MagicFormula.from_file("MagicFormula61")
    a = np.radians(np.linspace(-degrees, degrees, 15))
    fy = mf.fy0(a, mf.fnomin)
    csv = tmp_path_factory.mktemp("alpha") / "sweep.csv"
    csv.write_text("Fz [N],alpha [deg],Fy [N]\n" + "".join(
        f"{mf.fnomin},{float(x)!r},{float(y)!r}\n" for x, y in zip(a, fy)))  # rad as deg
    with pytest.raises(InputError, match="radians under a \\[deg\\] header") as err:
        check_plausible(read_tyre_data(csv), mf.fnomin)
    assert "alpha" in str(err.value) and "row" in str(err.value)


def _small_sweeps(percent: float, degrees: float, mu_scale: float = 1.0
                  ) -> tuple[MagicFormula, TyreData]:
    """Sweeps of +-``percent`` % slip and +-``degrees`` deg at three loads (SI), on a
    tyre whose friction is scaled by ``mu_scale``."""
    base = MagicFormula.from_file("MagicFormula61")
    mf = MagicFormula({**base.coefficients, "LMUX": mu_scale, "LMUY": mu_scale},
                      fnomin=base.fnomin, version=base.version, limits=base.limits,
                      structure=base.structure)
    k = np.linspace(-percent, percent, 21) / 100
    a = np.radians(np.linspace(-degrees, degrees, 21))
    fz = np.repeat(mf.fnomin * np.array([0.5, 1.0, 1.5]), 21)
    kk, aa = np.tile(k, 3), np.tile(a, 3)
    nan = np.full(fz.size, np.nan)
    return mf, TyreData.from_arrays(
        fz=np.r_[fz, fz], kappa=np.r_[kk, 0 * kk], alpha=np.r_[0 * aa, aa],
        fx=np.r_[mf.fx0(kk, fz), nan], fy=np.r_[nan, mf.fy0(aa, fz)])


@settings(max_examples=20, deadline=None)
@given(percent=st.floats(0.3, 1.0), degrees=st.floats(0.5, 1.0),
       mu_scale=st.sampled_from([1.0, 0.1]))
def test_small_sweeps_in_percent_or_degrees_under_fraction_or_rad_are_refused(
        percent: float, degrees: float, mu_scale: float) -> None:
    mf, data = _small_sweeps(percent, degrees, mu_scale)
    check_plausible(data, mf.fnomin)  # the honest data pass, on ice too
    as_fraction = TyreData.from_arrays(fz=data.fz, kappa=data.kappa * 100, alpha=data.alpha,
                                       fx=data.fx, fy=data.fy)
    with pytest.raises(InputError, match="percent given as a fraction") as err:
        check_plausible(as_fraction, mf.fnomin)
    assert "kappa" in str(err.value) and "row" in str(err.value)
    as_rad = TyreData.from_arrays(fz=data.fz, kappa=data.kappa, alpha=np.degrees(data.alpha),
                                  fx=data.fx, fy=data.fy)
    with pytest.raises(InputError, match="degrees under a \\[rad\\] header") as err:
        check_plausible(as_rad, mf.fnomin)
    assert "alpha" in str(err.value)


def test_a_small_percent_sweep_under_a_fraction_header_writes_nothing(tmp_path: Path) -> None:
    mf, data = _small_sweeps(1.0, 1.0)
    csv = tmp_path / "small.csv"
    csv.write_text("Fz [N],kappa [-],alpha [rad],Fx [N],Fy [N]\n" + "".join(
        f"{z!r},{100 * k!r},{math.degrees(a)!r},{'' if np.isnan(x) else repr(x)},"
        f"{'' if np.isnan(y) else repr(y)}\n"
        for z, k, a, x, y in zip(*(v.tolist() for v in (data.fz, data.kappa, data.alpha,
                                                          data.fx, data.fy)))))
    target = tmp_path / "out.tir"
    assert main(["tyre", "fit-mf", str(csv), "-o", str(target)]) == 2
    assert not target.exists()


@pytest.mark.parametrize("factor,likely", [(1e-3, "kN given as N"), (1e3, "N given as kN")])
def test_loads_in_the_wrong_unit_are_refused(factor: float, likely: str,
                                             tmp_path: Path) -> None:
    data = _sweep(0.2)
    data.fz = data.fz * factor
    with pytest.raises(InputError, match=likely):
        check_plausible(data, 6752.0)
    csv = tmp_path / "kn.csv"
    csv.write_text("Fz [N],kappa [-],Fx [N]\n" + "".join(
        f"{z},{k},{x}\n" for z, k, x in zip(data.fz, data.kappa, data.fx)
        if np.isfinite(x)))
    target = tmp_path / "out.tir"
    assert main(["tyre", "fit-mf", str(csv), "-o", str(target)]) == 2
    assert not target.exists()


@pytest.mark.parametrize("column,factor,match", [
    ("gamma", 57.3, "degrees under a \\[rad\\]"), ("pressure", 1e3, "another unit"),
    ("pressure", 1e-3, "another unit"), ("mz", 1e3, "N mm under")])
def test_cambers_pressures_and_moments_in_the_wrong_unit_are_refused(
        column: str, factor: float, match: str) -> None:
    truth = MagicFormula.from_file("MagicFormula61")
    data = rig_data(truth, n=7, combined=False)
    check_plausible(data, truth.fnomin, truth.nominal_pressure, 0.3943)
    setattr(data, column, getattr(data, column) * factor)
    with pytest.raises(InputError, match=match) as err:
        check_plausible(data, truth.fnomin, truth.nominal_pressure, 0.3943)
    assert "row" in str(err.value)


def test_columns_the_fit_does_not_use_are_named(tmp_path: Path) -> None:
    csv = tmp_path / "extra.csv"
    csv.write_text("Fz [N],kappa [-],Fx [N],Vx [m/s],Mx [N m]\n6000,0.1,5000,16,3\n")
    data = read_tyre_data(csv)
    assert any("columns not used" in n and "Vx [m/s]" in n and "Mx [N m]" in n
               for n in data.notes)


@pytest.mark.slow
@settings(max_examples=2, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_cambers_of_one_sign_leave_the_terms_they_cannot_separate_and_row_order_is_moot(
        seed: int) -> None:
    truth = moved_tyre()
    data = rig_data(truth, n=9, loads=(0.5, 1.0, 1.5), pressures=(1.0,),
                    cambers_deg=(0.0, 3.0))
    perm = np.random.default_rng(seed).permutation(len(data))
    shuffled = TyreData.from_arrays(fz=data.fz[perm], kappa=data.kappa[perm],
                                    alpha=data.alpha[perm], gamma=data.gamma[perm],
                                    pressure=data.pressure[perm], fx=data.fx[perm],
                                    fy=data.fy[perm], mz=data.mz[perm])
    a, b = fit_mf(data, fittyp=61), fit_mf(shuffled, fittyp=61)
    for k in ("QBZ5", "QDZ4", "QDZ10", "QDZ11"):  # |gamma| = gamma, gamma^2 = 3 deg gamma
        assert k in a.undetermined and k not in a.values
    assert abs(a.values["QBZ4"] - truth.coefficients["QBZ4"]) < 5 * a.stderr["QBZ4"] + 1.0
    assert sorted(a.undetermined) == sorted(b.undetermined)
    for k, v in a.values.items():
        assert b.values[k] == pytest.approx(v, rel=1e-3, abs=1e-3 * max(a.stderr[k], 1e-6))


@pytest.mark.slow
def test_one_pressure_off_nominal_is_where_the_written_file_is_evaluated(
        tmp_path: Path) -> None:
    truth = moved_tyre()
    data = rig_data(truth, n=11, loads=(0.5, 1.0, 1.5), pressures=(1.2,), cambers_deg=(0.0,),
                    combined=False)
    res = fit_mf(data, fittyp=61)
    fitted = MagicFormula.from_file(res.write(tmp_path / "fitted.tir"))
    measured = float(np.median(data.pressure))
    assert fitted.pressure == pytest.approx(measured)
    assert fitted.nominal_pressure == pytest.approx(truth.nominal_pressure)
    assert any("INFLPRES is set to" in n for n in res.notes)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ExtrapolationWarning)
        fitted.fx0(np.linspace(-0.2, 0.2, 11), truth.fnomin)
