"""Tyre test data that cannot give the coefficients asked for are refused before any fit."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from frictionlaws.base.errors import InputError
from frictionlaws.cli import main
from frictionlaws.tyre import MagicFormula, TyreData, read_tyre_data
from frictionlaws.tyre.mf.fit.checks import check_plausible
from frictionlaws.tyre.synthetic_rig import rig_data

HEADERS = ("Fz [N]", "kappa [-]", "alpha [deg]", "gamma [deg]", "pressure [kPa]", "Fx [N]",
           "Fy [N]", "Mz [N m]")
TRUTH = MagicFormula.from_file("MagicFormula61")


def _small() -> TyreData:
    return rig_data(TRUTH, n=7, loads=(0.7, 1.3), pressures=(1.0,), cambers_deg=(0.0,))


def _write(path: Path, data: TyreData, headers=HEADERS) -> Path:
    """``data`` as a CSV file under ``headers`` (degrees, kPa; NaN as a blank cell)."""
    cols = [data.fz, data.kappa, np.degrees(data.alpha), np.degrees(data.gamma),
            data.pressure / 1e3, data.fx, data.fy, data.mz]
    lines = [",".join(headers)] + [
        ",".join("" if math.isnan(v) else repr(float(v)) for v in row) for row in zip(*cols)]
    path.write_text("\n".join(lines) + "\n")
    return path


def _refused(capsys, csv: Path, target: Path, *options: str) -> str:
    """The one error line of ``tyre fit-mf`` (exit 2, nothing written)."""
    code = main(["tyre", "fit-mf", str(csv), "-o", str(target), *options])
    out, err = capsys.readouterr()
    assert code == 2 and not out and len(err.strip().splitlines()) == 1, err
    assert not target.exists()
    return err


@pytest.mark.parametrize(("header", "column", "expected"), [
    ("slipratio [-]", 1, ["Fx given", "no slip-ratio column", "slipratio [-]", "sr"]),
    ("alpha_deg", 2, ["Fy and Mz given", "no slip-angle column", "alpha_deg", "slip_angle"]),
])
def test_a_force_without_its_slip_column_is_refused_naming_the_unused_column(
        capsys, tmp_path: Path, header: str, column: int, expected: list[str]) -> None:
    headers = list(HEADERS)
    headers[column] = header
    csv = _write(tmp_path / "renamed.csv", _small(), headers)
    err = _refused(capsys, csv, tmp_path / "out.tir")
    assert all(text in err for text in expected), err


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(which=st.sampled_from(["kappa", "alpha"]), value=st.floats(-0.2, 0.2))
def test_a_constant_slip_is_refused_for_its_force(which: str, value: float) -> None:
    data = _small()
    setattr(data, which, np.full(len(data), value))
    force = "Fx given" if which == "kappa" else "Fy and Mz given"
    with pytest.raises(InputError, match=f"{force} but {which} is .* on every row "
                                         "\\(the column is constant\\)"):
        check_plausible(data, TRUTH.fnomin)


def test_the_usual_rig_names_are_read(tmp_path: Path) -> None:
    headers = ("FZ [N]", "SR [-]", "SA [deg]", "IA [deg]", "P [kPa]", "FX [N]", "FY [N]",
               "MZ [N m]")
    data = read_tyre_data(_write(tmp_path / "ttc.csv", _small(), headers))
    assert not data.unused and not data.missing and np.ptp(data.kappa) > 0.4
    check_plausible(data, TRUTH.fnomin, TRUTH.nominal_pressure, 0.3943)


@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(share=st.floats(0.0, 1.0), seed=st.integers(0, 2**16))
def test_fy_with_the_sign_of_alpha_on_most_rows_is_refused(share: float, seed: int) -> None:
    data = _small()
    wide = np.flatnonzero((np.abs(data.alpha) > math.radians(2.0)) & (np.abs(data.kappa) <= 0.01))
    flip = np.random.default_rng(seed).permutation(wide)[:round(share * wide.size)]
    data.fy[flip] = -data.fy[flip]
    if share > 0.8:
        with pytest.raises(InputError, match="sign of the slip angle.*sign_convention='sae'"):
            check_plausible(data, TRUTH.fnomin)
    elif 2 * flip.size > wide.size:  # as many flipped as not: no sign, perhaps no curve
        with pytest.raises(InputError, match="sign of the slip angle|carries no curve"):
            check_plausible(data, TRUTH.fnomin)
    elif share < 0.2:
        check_plausible(data, TRUTH.fnomin)


def test_the_sign_advice_names_the_other_convention(capsys, tmp_path: Path) -> None:
    data = _small()
    data.fy, data.mz = -data.fy, -data.mz
    err = _refused(capsys, _write(tmp_path / "flipped.csv", data), tmp_path / "o.tir")
    assert "Fy has the sign of the slip angle" in err and "--sign-convention sae" in err
    sae = _small()
    sae.fz, sae.alpha = -sae.fz, -sae.alpha  # SAE axes, but Fy and Mz left as in ISO
    err = _refused(capsys, _write(tmp_path / "half.csv", sae), tmp_path / "o.tir",
                   "--sign-convention", "sae")
    assert "after the conversion from SAE" in err and "--sign-convention iso" in err
    err = _refused(capsys, _write(tmp_path / "iso.csv", _small()), tmp_path / "o.tir",
                   "--sign-convention", "sae")
    assert "ISO-W axes already" in err and "--sign-convention iso" in err
    assert "give --sign-convention sae" not in err


@settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(rows=st.sets(st.integers(0, 55), min_size=1, max_size=20))
def test_blank_pressures_among_values_are_refused(tmp_path_factory, rows: set[int]) -> None:
    data = _small()
    data.pressure[sorted(rows)] = np.nan
    csv = _write(tmp_path_factory.mktemp("p") / "blanks.csv", data)
    with pytest.raises(InputError, match=f"{len(rows)} blank pressure cell") as err:
        read_tyre_data(csv)
    assert err.value.column == "pressure [kPa]"
    assert f"rows {min(rows) + 2}" in str(err.value)


def test_a_pressure_column_blank_on_every_row_is_not_measured(tmp_path: Path) -> None:
    data = _small()
    data.pressure[:] = np.nan
    read_tyre_data(_write(tmp_path / "none.csv", data))


@settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(rows=st.sets(st.integers(0, 55), min_size=1, max_size=12), token=st.sampled_from(
    ["", "nan", "NaN", "n/a", "null"]))
def test_rows_without_any_force_are_named_in_a_note(tmp_path_factory, rows: set[int],
                                                    token: str) -> None:
    """A row whose forces are all missing (blank or a missing-value token) is not lost
    silently: a note names it, and every other row is read."""
    data = _small()
    path = _write(tmp_path_factory.mktemp("f") / "gaps.csv", data)
    lines = path.read_text().splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("Fz")) + 1
    head = lines[start - 1].split(",")
    forces = [j for j, h in enumerate(head) if h.split(" ")[0] in ("Fx", "Fy", "Mz")]
    for r in rows:
        cells = lines[start + r].split(",")
        for j in forces:
            cells[j] = token
        lines[start + r] = ",".join(cells)
    path.write_text("\n".join(lines) + "\n")
    read = read_tyre_data(path)
    assert len(read) == len(data)
    said = [n for n in read.notes if "no Fx, Fy or Mz value" in n]
    assert len(said) == 1 and said[0].startswith(f"{len(rows)} row(s)")
    assert str(min(rows) + start + 1) in said[0]


@pytest.mark.parametrize("force", ["fx", "fy"])
@pytest.mark.parametrize("kind", ["zero", "noise"])
def test_forces_without_a_curve_are_refused_as_such(force: str, kind: str) -> None:
    data = _small()
    rng = np.random.default_rng(1)
    finite = np.isfinite(getattr(data, force))
    values = 0.0 if kind == "zero" else 0.03 * data.fz * rng.standard_normal(len(data))
    getattr(data, force)[finite] = np.broadcast_to(values, data.fz.shape)[finite]
    with pytest.raises(InputError, match="carries no curve") as err:
        check_plausible(data, TRUTH.fnomin)
    assert "percent" not in str(err.value) and err.value.column == force.capitalize()


def test_a_braking_sweep_to_lock_up_has_a_curve() -> None:
    kappa = -np.linspace(0.005, 1.0, 200)  # rises to mu 1.2 at 0.1, falls to 0.75 of it
    mu = np.where(-kappa < 0.1, -12.0 * kappa, 1.2 - 0.5 * (-kappa - 0.1))
    noise = 1 + 0.01 * np.random.default_rng(0).standard_normal(kappa.size)
    check_plausible(TyreData.from_arrays(fz=4000.0, kappa=kappa, fx=-mu * 4000.0 * noise),
                    4000.0)


def test_a_camber_of_90_degrees_is_impossible_not_a_unit(capsys, tmp_path: Path) -> None:
    data = _small()
    data.gamma[3] = math.pi / 2
    err = _refused(capsys, _write(tmp_path / "c90.csv", data), tmp_path / "o.tir")
    assert "camber 90 deg is impossible" in err and "[rad] header" not in err


def test_without_mz_or_combined_rows_the_report_says_so_and_shows_no_combined_errors(
        ) -> None:
    import warnings

    from frictionlaws.base.errors import ExtrapolationWarning
    from frictionlaws.tyre import fit_mf

    data = rig_data(TRUTH, n=7, loads=(0.7, 1.3), pressures=(1.0,), cambers_deg=(0.0,),
                    combined=False)
    data.mz[:] = np.nan
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        res = fit_mf(data, fittyp=61)
    assert set(res.errors) == {"x", "y"}
    report = res.report()
    assert "combined slip" not in report
    assert "aligning-moment coefficients (Q*Z*, SSZ*): the template's (no Mz column)" in report
    assert not any(k.startswith(("QBZ", "QDZ", "SSZ")) for k in res.values)


@pytest.mark.parametrize("measured", [False, True])
def test_the_written_pressure_range_is_the_data_s(measured: bool) -> None:
    """PRESMIN/PRESMAX of a fitted file are the pressures the data cover: the measured ones,
    or NOMPRES alone when no pressure was measured (never the template's range)."""
    from frictionlaws.tyre.mf.fit.template import build_file, template_file

    data = _small()
    if not measured:
        data.pressure[:] = np.nan
    tpl = template_file(None, "6.1")
    p_nom = tpl.si("OPERATING_CONDITIONS", "NOMPRES")
    notes: list[str] = []
    pf = build_file(tpl, 61, {}, p_nom, data, notes)
    span = (pf.si("INFLATION_PRESSURE_RANGE", "PRESMIN"),
            pf.si("INFLATION_PRESSURE_RANGE", "PRESMAX"))
    if measured:
        assert span == pytest.approx((data.pressure.min(), data.pressure.max()))
    else:
        assert span == pytest.approx((p_nom, p_nom))
        assert any("PRESMIN = PRESMAX = NOMPRES" in n for n in notes)
    assert span != (tpl.si("INFLATION_PRESSURE_RANGE", "PRESMIN"),
                    tpl.si("INFLATION_PRESSURE_RANGE", "PRESMAX"))


@pytest.mark.parametrize("broken", ["one force cell", "every load"])
def test_a_force_far_above_its_load_names_the_column_at_fault(broken: str) -> None:
    """One absurd force cell is named in its force column (by the load check or the curve
    check before it); loads in the wrong unit on every row are named in the load column."""
    data = _small()
    if broken == "one force cell":
        data.fx[int(np.flatnonzero(np.isfinite(data.fx))[3])] = 1e6  # 1000 times the load
    else:
        data.fz = data.fz / 1000.0  # kN given as N
    with pytest.raises(InputError, match="times the load Fz|carries no curve") as err:
        check_plausible(data, float(np.median(_small().fz)))
    assert err.value.column == ("Fx" if broken == "one force cell" else "Fz")
