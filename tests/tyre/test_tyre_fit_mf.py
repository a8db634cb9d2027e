"""Fitting a Magic Formula property file to tyre test data: round trip, reader, CLI."""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from frictionlaws.base.errors import ExtrapolationWarning, InputError
from frictionlaws.cli import main
from frictionlaws.tyre import MagicFormula, TyreData, fit_mf, read_property_file, read_tyre_data

CASES = (("MagicFormula52", 6), ("MagicFormula61", 61), ("MagicFormula62", 62))


@pytest.fixture(autouse=True)
def _quiet_extrapolation():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        yield


def synthetic(name: str, n_slip: int = 31, seed: int = 1) -> tuple[MagicFormula, TyreData,
                                                                   dict]:
    """Pure-slip data from a property file: 5 loads x 3 pressures x 3 cambers, 1 % noise.

    The noise is Gaussian with a standard deviation of 1 % of the peak |F| of each
    curve.  Slip ratios -0.3..0.3, slip angles -15..15 deg.
    """
    mf = MagicFormula.from_file(name)
    rng = np.random.default_rng(seed)
    grid = {"loads": mf.fnomin * np.array([0.4, 0.7, 1.0, 1.3, 1.6]),
            "pressures": (mf.nominal_pressure or 2.6e5) * np.array([0.85, 1.0, 1.15]),
            "cambers": np.array([-0.07, 0.0, 0.07]),
            "kappa": np.linspace(-0.3, 0.3, n_slip),
            "alpha": np.radians(np.linspace(-15, 15, n_slip))}
    k, a, n = grid["kappa"], grid["alpha"], n_slip
    cols: dict[str, list] = {c: [] for c in ("fz", "kappa", "alpha", "gamma", "pressure",
                                             "fx", "fy")}
    for fz in grid["loads"]:
        for p in grid["pressures"]:
            for g in grid["cambers"]:
                fx = mf.fx0(k, fz, g, pressure=p)
                fy = mf.fy0(a, fz, g, pressure=p)
                fx = fx + 0.01 * np.abs(fx).max() * rng.standard_normal(n)
                fy = fy + 0.01 * np.abs(fy).max() * rng.standard_normal(n)
                for c, v in (("fz", np.full(2 * n, fz)), ("kappa", np.r_[k, np.zeros(n)]),
                             ("alpha", np.r_[np.zeros(n), a]), ("gamma", np.full(2 * n, g)),
                             ("pressure", np.full(2 * n, p)),
                             ("fx", np.r_[fx, np.full(n, np.nan)]),
                             ("fy", np.r_[np.full(n, np.nan), fy])):
                    cols[c].append(v)
    data = TyreData.from_arrays(**{c: np.concatenate(v) for c, v in cols.items()})
    return mf, data, grid


def worst_error(truth: MagicFormula, fitted: MagicFormula, grid: dict) -> tuple[float, float]:
    """Largest |F_fit - F_true| over the data range, as a fraction of each curve's peak."""
    ex = ey = 0.0
    k, a = np.linspace(-0.3, 0.3, 121), np.radians(np.linspace(-15, 15, 121))
    for fz in grid["loads"]:
        for p in grid["pressures"]:
            for g in grid["cambers"]:
                tx, ty = truth.fx0(k, fz, g, p), truth.fy0(a, fz, g, p)
                ex = max(ex, np.abs(fitted.fx0(k, fz, g, p) - tx).max() / np.abs(tx).max())
                ey = max(ey, np.abs(fitted.fy0(a, fz, g, p) - ty).max() / np.abs(ty).max())
    return ex, ey


@pytest.mark.slow
@pytest.mark.parametrize("name,fittyp", CASES)
def test_round_trip_reproduces_forces_and_coefficients(name: str, fittyp: int,
                                                       tmp_path: Path) -> None:
    truth, data, grid = synthetic(name)
    res = fit_mf(data, fittyp=fittyp, template=name)
    out = res.write(tmp_path / "fitted.tir")
    fitted = MagicFormula.from_file(out)  # the library's own reader accepts the file
    assert fitted.version == truth.version
    ex, ey = worst_error(truth, fitted, grid)
    assert ex < 0.01 and ey < 0.01, (ex, ey)
    assert res.values, "nothing was fitted"
    far = {k: (v, truth.coefficients.get(k, 0.0), res.stderr[k]) for k, v in res.values.items()
           if not abs(v - truth.coefficients.get(k, 0.0)) <= 3 * res.stderr[k]}
    assert not far, far
    if truth.version == "5.2":
        assert any("pressure column is not used" in n for n in res.notes)


def test_undetermined_coefficients_are_named_and_kept(tmp_path: Path) -> None:
    truth, data, _ = synthetic("MagicFormula61", n_slip=21)
    one = (data.pressure == data.pressure[0]) & (data.gamma == 0.0)
    sub = TyreData.from_arrays(fz=data.fz[one], kappa=data.kappa[one], alpha=data.alpha[one],
                               gamma=data.gamma[one], pressure=data.pressure[one],
                               fx=data.fx[one], fy=data.fy[one])
    tpl = read_property_file(Path(__file__).resolve().parents[2] / "datasets" /
                             "mf-examples" / "MagicFormula62_Parameters.json")
    tpl.sections["LONGITUDINAL_COEFFICIENTS"]["PPX1"] = -0.5
    res = fit_mf(sub, fittyp=61, template=tpl)
    for k in ("PPX1", "PPX3", "PPY1", "PDX3", "PDY3", "PKY6", "PVY3"):
        assert k in res.undetermined and k not in res.values
    assert res.property_file.sections["LONGITUDINAL_COEFFICIENTS"]["PPX1"] == -0.5
    assert any("left at the template's value" in n and "PPX1" in n for n in res.notes)
    for k in ("PDX1", "PKX1", "PDY1", "PKY1"):
        assert k in res.values and res.stderr[k] > 0


@pytest.mark.slow
def test_ten_thousand_points_fit() -> None:
    # its time is measured by benchmarks/bench_fit_mf.py against a baseline, not here
    _, data, _ = synthetic("MagicFormula62", n_slip=111)
    assert len(data) == 9990
    res = fit_mf(data, fittyp=62, template="MagicFormula62")
    assert res.errors["x"]["rmse"] < 0.01 * res.errors["x"]["peak"]


# --------------------------------------------------------------- CSV and CLI


def write_csv(path: Path, data: TyreData, *, sae: bool = False) -> Path:
    s = -1.0 if sae else 1.0
    lines = ["Fz [kN],kappa [%],alpha [deg],gamma [deg],pressure [kPa],Fx [N],Fy [N]"]
    for i in range(len(data)):
        fx = "" if math.isnan(data.fx[i]) else f"{data.fx[i]:.3f}"
        fy = "" if math.isnan(data.fy[i]) else f"{s * data.fy[i]:.3f}"
        lines.append(f"{s * data.fz[i] / 1000:.6f},{data.kappa[i] * 100:.6f},"
                     f"{s * math.degrees(data.alpha[i]):.6f},{math.degrees(data.gamma[i]):.6f},"
                     f"{data.pressure[i] / 1000:.4f},{fx},{fy}")
    path.write_text("\n".join(lines) + "\n")
    return path


def test_csv_units_and_sign_conventions(tmp_path: Path) -> None:
    _, data, _ = synthetic("MagicFormula61", n_slip=11)
    iso = read_tyre_data(write_csv(tmp_path / "iso.csv", data))
    sae = read_tyre_data(write_csv(tmp_path / "sae.csv", data, sae=True), sign_convention="sae")
    for d in (iso, sae):
        np.testing.assert_allclose(d.fz, data.fz, rtol=1e-9)
        np.testing.assert_allclose(d.alpha, data.alpha, atol=1e-8)
        np.testing.assert_allclose(d.kappa, data.kappa, atol=1e-8)
        np.testing.assert_allclose(d.pressure, data.pressure, rtol=1e-6)
        np.testing.assert_allclose(d.fy, data.fy, atol=1e-3)
    assert any("SAE axes converted" in n for n in sae.notes)
    with pytest.raises(InputError, match="SAE") as exc:
        read_tyre_data(tmp_path / "sae.csv")
    assert exc.value.row == 2 and "Fz" in str(exc.value)


@pytest.mark.parametrize("header,row,match", [
    ("Fz [N],alpha [-],Fy [N]", "4000,0.1,-100", "needs its unit"),
    ("Fz [N],alpha [m],Fy [N]", "4000,0.1,-100", "angle"),
    ("Fz [N],kappa [-],Fx [N]", "4000,abc,100", "'abc' is not a number"),
    ("Fz [m],kappa [-],Fx [N]", "4000,0.1,100", "force"),
    ("kappa [-],Fx [N]", "0.1,100", "no Fz column"),
    ("Fz [N],kappa [-]", "4000,0.1", "no Fx, Fy or Mz"),
    ("Fz [N],alpha [deg],Fy [N]", "4000,95,-100", "beyond 90"),
])
def test_csv_errors_name_file_column_row(tmp_path: Path, header: str, row: str,
                                         match: str) -> None:
    path = tmp_path / "bad.csv"
    path.write_text(f"{header}\n4000,0,0\n{row}\n" if "Fz" in header and header.count(",") == 2
                    else f"{header}\n{row}\n")
    with pytest.raises(InputError, match=match) as exc:
        read_tyre_data(path)
    assert str(path) in str(exc.value)


@pytest.mark.slow
def test_cli_fit_mf_writes_a_readable_tir_and_a_figure(tmp_path: Path,
                                                        capsys: pytest.CaptureFixture) -> None:
    _, data, _ = synthetic("MagicFormula61", n_slip=15)
    csv = write_csv(tmp_path / "data.csv", data)
    out, fig = tmp_path / "tyre.tir", tmp_path / "fit.png"
    assert main(["tyre", "fit-mf", str(csv), "--fittyp", "61", "-o", str(out),
                 "--plot", str(fig)]) == 0
    text = capsys.readouterr().out
    assert "PDX1" in text and "written:" in text
    assert fig.stat().st_size > 1000
    mf = MagicFormula.from_file(out)
    assert mf.version == "6.1"
    assert out.read_text().startswith("! FITTED by frictionlaws")
    # never overwrite an input; nothing partial on failure
    before = csv.read_text()
    assert main(["tyre", "fit-mf", str(csv), "-o", str(csv)]) == 2
    assert csv.read_text() == before
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "also an input" in err
    bad = tmp_path / "bad.csv"
    bad.write_text("Fz [N],kappa [-],Fx [N]\n4000,0.1,x\n")
    assert main(["tyre", "fit-mf", str(bad), "-o", str(tmp_path / "b.tir")]) == 2
    assert not (tmp_path / "b.tir").exists()
    assert "row 2" in capsys.readouterr().err


def test_a_template_object_is_checked_as_a_template_file_is() -> None:
    _, data, _ = synthetic("MagicFormula61", n_slip=11)
    tpl = read_property_file(Path(__file__).resolve().parents[2] / "datasets" /
                             "mf-examples" / "MagicFormula52_Parameters.json")
    with pytest.raises(InputError, match="the template is Magic Formula 5.2"):
        fit_mf(data, fittyp=61, template=tpl)
    tpl = read_property_file(Path(__file__).resolve().parents[2] / "datasets" /
                             "mf-examples" / "MagicFormula61_Parameters.json")
    tpl.sections["DIMENSION"]["UNLOADED_RADIUS"] = 0.0
    with pytest.raises(InputError, match="UNLOADED_RADIUS must be positive"):
        fit_mf(data, fittyp=61, template=tpl)
