"""``tyre fit-mf`` refuses, before fitting, an aligning moment of the wrong sign or without
a curve, camber settings in radians under a degree header and one force in another unit
than the other (by their peaks), and checks each file of several on its own rows (naming
that file)."""

from __future__ import annotations

import io
import math
import sys
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from frictionlaws.base.errors import InputError
from frictionlaws.cli import main
from frictionlaws.tyre import MagicFormula, TyreData
from frictionlaws.tyre.data import write_tydex
from frictionlaws.tyre.data.synthetic import sweep_data
from frictionlaws.tyre.mf.fit.checks import check_plausible, rising_side
from frictionlaws.tyre.synthetic_rig import moved_tyre, rig_data

EXAMPLES = ("MagicFormula52", "MagicFormula61", "MagicFormula62")
TRUTH = MagicFormula.from_file("MagicFormula61")
SMALL = dict(n=9, loads=(0.5, 1.0, 1.5), pressures=(1.0,), cambers_deg=(0.0,))


def _rig(truth: MagicFormula = TRUTH) -> TyreData:
    return rig_data(truth, **SMALL, combined=False)


def _refused(capsys, files: list[Path], target: Path) -> str:
    """The one error line of ``tyre fit-mf`` (exit 2, nothing written), last on stderr
    after what the checks warned of before the refusal."""
    code = main(["tyre", "fit-mf", *map(str, files), "-o", str(target)])
    out, err = capsys.readouterr()
    *warned, last = err.strip().splitlines()
    assert code == 2 and not out and all(w.startswith("warning: ") for w in warned), err
    assert last.startswith("error:") and not target.exists()
    return last


@pytest.mark.parametrize("example", EXAMPLES)
@pytest.mark.parametrize("kind", ["lateral", "combined"])
def test_mz_of_the_packaged_tyres_passes_and_negated_is_refused(example: str,
                                                                kind: str) -> None:
    """Near pure side slip the packaged tyres' Mz opposes Fy, cambered up to 6 deg too."""
    truth = MagicFormula.from_file(example)
    with pytest.warns(Warning):  # cambers beyond the files' ranges: extrapolated
        data = sweep_data(truth, kind, loads=(0.3, 1.0, 2.0), cambers_deg=(-6.0, 0.0, 6.0),
                          pressures=(1.0,), n=9)
    check_plausible(data, truth.fnomin)
    data.mz = -data.mz
    with pytest.raises(InputError, match="Mz has the sign of Fy on .* rows with |alpha| "
                                         "of 1-4 deg.*looks reversed") as err:
        check_plausible(data, truth.fnomin)
    assert err.value.column == "Mz" and err.value.row is not None


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(share=st.floats(0.0, 1.0), seed=st.integers(0, 2**16))
def test_mz_with_the_sign_of_fy_on_most_small_angle_rows_is_refused(share: float,
                                                                    seed: int) -> None:
    data = _rig()
    near = np.flatnonzero((np.abs(data.alpha) >= math.radians(1.0))
                          & (np.abs(data.alpha) <= math.radians(4.0))
                          & rising_side(data) & np.isfinite(data.mz))
    flip = np.random.default_rng(seed).permutation(near)[:round(share * near.size)]
    data.mz[flip] = -data.mz[flip]
    if 2 * flip.size > near.size:
        with pytest.raises(InputError, match="Mz has the sign of Fy|carries no curve"):
            check_plausible(data, TRUTH.fnomin)
    elif share < 0.3:
        check_plausible(data, TRUTH.fnomin)


@pytest.mark.parametrize("grip", [0.6, 0.3, 0.1])
def test_low_friction_roads_pass_and_their_negated_mz_is_refused_where_fy_rises(
        grip: float) -> None:
    """On a wet or icy road (the tyre's friction scaled to ``grip``) the aligning moment
    turns over below 2 deg; the data pass, and Mz negated is refused where F_y still rises
    at 1 deg or more (at a grip of 0.3 and below it has turned over by 1 deg: unchecked)."""
    truth = moved_tyre("MagicFormula61", {"LMUX": grip, "LMUY": grip})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the peak friction of an icy road is warned of
        data = rig_data(truth, loads=(0.5, 1.0, 1.5), pressures=(1.0,), cambers_deg=(0.0,),
                        combined=False)
        check_plausible(data, truth.fnomin)
        data.mz = -data.mz
        if grip >= 0.6:
            with pytest.raises(InputError, match="Mz has the sign of Fy"):
                check_plausible(data, truth.fnomin)
        else:
            check_plausible(data, truth.fnomin)


def test_a_tydex_file_with_mz_negated_is_refused_on_the_command_line(capsys,
                                                                     tmp_path: Path) -> None:
    data = sweep_data(TRUTH, "lateral", loads=(0.5, 1.0), cambers_deg=(0.0,),
                      pressures=(1.0,), n=9)
    data.mz = -data.mz
    tdx = write_tydex(data, tmp_path / "lat_mzflip.tdx")
    err = _refused(capsys, [tdx], tmp_path / "o.tir")
    assert f"file '{tdx}', column 'Mz'" in err and "looks reversed" in err


@pytest.mark.parametrize("kind", ["zero", "noise"])
def test_an_mz_column_without_a_curve_is_refused_before_fitting(capsys, tmp_path: Path,
                                                                kind: str) -> None:
    data = _rig()
    finite = np.isfinite(data.mz)
    noise = 0.003 * data.fz * np.random.default_rng(1).standard_normal(len(data))
    data.mz[finite] = 0.0 if kind == "zero" else noise[finite]
    with pytest.raises(InputError, match="Mz carries no curve to fit") as err:
        check_plausible(data, TRUTH.fnomin)
    assert err.value.column == "Mz"
    tdx = write_tydex(data, tmp_path / "mz_flat.tdx")
    err_line = _refused(capsys, [tdx], tmp_path / "o.tir")
    assert f"file '{tdx}', column 'Mz'" in err_line and "carries no curve" in err_line
    assert "<fitted .tir>" not in err_line


def _two_files(tmp_path: Path, bad: int, unit: str) -> tuple[list[Path], Path]:
    """Two TYDEX files of sweeps at other loads, file ``bad`` with ``unit`` wrong."""
    kind = "lateral" if unit == "alpha_rad" else "longitudinal"
    parts = [sweep_data(TRUTH, kind, loads=loads, cambers_deg=(0.0,), pressures=(1.0,), n=9)
             for loads in ((0.5, 1.0), (1.5,))]
    if unit == "alpha_rad":
        parts[bad].alpha = np.radians(parts[bad].alpha)  # written under [deg]
    else:  # percent written as a fraction
        parts[bad].kappa = 100.0 * parts[bad].kappa
    files = [write_tydex(p, tmp_path / f"part{i}.tdx") for i, p in enumerate(parts)]
    return files, files[bad]


@pytest.mark.parametrize("unit, column", [("alpha_rad", "alpha"),
                                          ("kappa_percent", "kappa")])
@pytest.mark.parametrize("bad", [0, 1])
def test_a_unit_wrong_in_one_file_of_two_is_refused_naming_that_file(
        capsys, tmp_path: Path, bad: int, unit: str, column: str) -> None:
    """Each file is checked on its own rows (the merged rows hide a unit wrong in one file),
    and the row named is that file's."""
    files, culprit = _two_files(tmp_path, bad, unit)
    err = _refused(capsys, files, tmp_path / "o.tir")
    assert f"file '{culprit}', column '{column}', row " in err, err
    assert " + " not in err
    row = int(err.split(", row ")[1].split(":")[0])
    assert row <= len(culprit.read_text().splitlines())


@pytest.mark.parametrize("unit", ["Fx_daN", "Fy_daN"])
@pytest.mark.parametrize("order", [1, -1])
def test_a_force_in_daN_beside_a_file_in_N_is_refused_naming_it(
        capsys, tmp_path: Path, unit: str, order: int) -> None:
    """A tenth of the force is a plausible tyre alone (on ice), not beside the same tyre's
    sweeps in N: the slopes near zero slip of the two files differ by a factor 10."""
    kw = dict(loads=(0.5, 1.0, 1.5), cambers_deg=(0.0,), pressures=(1.0,), n=9)
    kind = "longitudinal" if unit == "Fx_daN" else "lateral"
    good, bad = sweep_data(TRUTH, kind, **kw), sweep_data(TRUTH, kind, **kw, seed=12)
    setattr(bad, unit[:2].lower(), getattr(bad, unit[:2].lower()) / 10.0)
    files = [write_tydex(good, tmp_path / "good.tdx"), write_tydex(bad, tmp_path / "bad.tdx")]
    err = _refused(capsys, files[::order], tmp_path / "o.tir")
    assert f"file '{files[1]}', column '{unit[:2]}', row " in err, err
    assert "a factor" in err and "daN as N" in err


def test_files_of_one_tyre_agree() -> None:
    """Files of one tyre at other loads, pressures and sweep ranges are not refused."""
    from frictionlaws.tyre.data.table import join

    parts = [sweep_data(TRUTH, "lateral", loads=(0.4,), pressures=(0.85,), n=9,
                        cambers_deg=(0.0,), alpha_max_deg=4.0),
             sweep_data(TRUTH, "lateral", loads=(1.6,), pressures=(1.1,), n=9,
                        cambers_deg=(0.0,), alpha_max_deg=15.0),
             sweep_data(TRUTH, "longitudinal", loads=(0.4,), pressures=(0.85,), n=9,
                        cambers_deg=(0.0,), kappa_max=0.05),
             sweep_data(TRUTH, "longitudinal", loads=(1.6,), pressures=(1.1,), n=9,
                        cambers_deg=(0.0,), kappa_max=0.3)]
    named = [replace(p, source=f"{i}.tdx") for i, p in enumerate(parts)]
    check_plausible(join(named), TRUTH.fnomin, TRUTH.nominal_pressure)


def _lateral(truth: MagicFormula, cambers_deg, **kw) -> TyreData:
    """Slip-angle sweeps at ``cambers_deg``, read as from a file with a [deg] camber."""
    with warnings.catch_warnings():  # cambers beyond a file's range: extrapolated
        warnings.simplefilter("ignore")
        data = sweep_data(truth, "lateral", loads=(0.5, 1.0), cambers_deg=cambers_deg,
                          pressures=(1.0,), n=9, **kw)
    data.units = {"gamma": "deg"}
    return data


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(levels=st.lists(st.integers(-6, 6), min_size=2, max_size=4, unique=True),
       example=st.sampled_from(EXAMPLES), seed=st.integers(0, 2**16))
def test_camber_settings_in_radians_under_a_degree_header_are_never_passed_silently(
        levels: list[int], example: str, seed: int) -> None:
    """Camber settings of whole degrees, written in radians under a [deg] header, read as
    hundredths of a degree: refused by their camber thrust (57 times a tyre's), or warned
    of where the noise hides it; the same settings in degrees pass."""
    truth = MagicFormula.from_file(example)
    data = _lateral(truth, levels, seed=seed)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_plausible(data, truth.fnomin)
    data.gamma = np.radians(data.gamma)  # the numbers in radians, under [deg]
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        try:
            check_plausible(data, truth.fnomin)
        except InputError as err:
            assert err.column == "gamma" and err.row is not None
            assert "look like radians under a [deg] header" in str(err)
            return
    assert any("column 'gamma'" in str(w.message) and "write 'gamma [rad]'" in str(w.message)
               for w in said), [str(w.message) for w in said]
    assert max(levels) - min(levels) < 3  # wide settings are refused, not only warned of


def test_real_small_cambers_that_read_as_radians_are_whole_degrees_pass() -> None:
    """+-0.35 deg read as radians is 20.05 deg, a whole degree: the camber thrust of a
    tyre (not 57 times it) says these are degrees."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_plausible(_lateral(TRUTH, (-0.35, 0.0, 0.35)), TRUTH.fnomin)


def test_camber_settings_in_radians_without_fy_are_warned_of(tmp_path: Path) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        data = sweep_data(TRUTH, "longitudinal", loads=(0.5, 1.0), cambers_deg=(0.0, 3.0),
                          pressures=(1.0,), n=9)
    data.gamma = np.radians(data.gamma)
    data.units = {"gamma": "deg"}
    with pytest.warns(UserWarning, match="column 'gamma', row .*the whole degrees 0, 3 .*no "
                                         "Fy near zero slip angle"):
        check_plausible(data, TRUTH.fnomin)


def test_a_tydex_file_with_camber_in_radians_is_refused_on_the_command_line(
        capsys, tmp_path: Path) -> None:
    data = _lateral(TRUTH, (-3.0, 0.0, 3.0))
    data.gamma = np.radians(data.gamma)
    tdx = write_tydex(data, tmp_path / "camber_rad.tdx")
    err = _refused(capsys, [tdx], tmp_path / "o.tir")
    assert f"file '{tdx}', column 'gamma', row " in err and "write 'gamma [rad]'" in err


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(grip=st.floats(0.5, 1.0), force=st.sampled_from(["fx", "fy"]),
       factor=st.sampled_from([0.1, 10.0]), seed=st.integers(0, 2**16))
def test_one_force_of_one_file_in_another_unit_is_refused_by_the_peaks(
        grip: float, force: str, factor: float, seed: int) -> None:
    """One file with both forces: a road of less grip (the tyre's friction scaled) passes;
    one force in daN under [N] (or N under [daN]) puts its peak friction 10 from the
    other's and is refused, naming that force."""
    base = TRUTH
    truth = MagicFormula({**base.coefficients, "LMUX": grip, "LMUY": grip},
                         fnomin=base.fnomin, version=base.version, limits=base.limits,
                         structure=base.structure, pressure=base.pressure,
                         nominal_pressure=base.nominal_pressure)
    data = rig_data(truth, **SMALL, combined=False, seed=seed)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_plausible(data, truth.fnomin)
    setattr(data, force, factor * getattr(data, force))
    name = force[0].upper() + force[1]
    with pytest.raises(InputError, match=f"the {name} column looks like another unit") as err:
        check_plausible(data, truth.fnomin)
    assert err.value.column == name and err.value.row is not None and "daN" in str(err.value)
    spiked = rig_data(truth, **SMALL, combined=False, seed=seed)
    row = int(np.argmax(np.abs(getattr(spiked, force)) / spiked.fz))
    getattr(spiked, force)[row] *= 1000  # a spike on one row is no peak: the load check's
    with pytest.raises(InputError, match="times the load Fz on this row|carries no curve") as err:
        check_plausible(spiked, truth.fnomin)
    assert err.value.column == name and err.value.row == row + 1


def test_a_single_force_in_daN_is_warned_of_naming_its_column() -> None:
    """A file of Fx alone in daN: a peak friction of 0.12, an icy road's; warned of (not
    refused: ice is real)."""
    data = sweep_data(TRUTH, "longitudinal", cambers_deg=(0.0,), **{
        k: v for k, v in SMALL.items() if k != "cambers_deg"})
    data.fx = data.fx / 10
    with pytest.warns(UserWarning, match=r"column 'Fx', row \d+: \|Fx\| / Fz peaks at 0.1"):
        check_plausible(data, TRUTH.fnomin)


def test_a_warning_of_the_data_read_from_standard_input_names_it_as_given(
        capsys, monkeypatch, tmp_path: Path) -> None:
    """What the data checks warn of names standard input '<stdin>' on stderr, as the report,
    JSON and file do, not the private copy the command reads."""
    data = sweep_data(TRUTH, "longitudinal", cambers_deg=(0.0,), loads=(0.5, 1.0), n=9,
                      pressures=(1.0,))
    data.fx = data.fx / 10
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        tdx = write_tydex(data, tmp_path / "fx_daN.tdx")
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(tdx.read_bytes())))
    assert main(["tyre", "fit-mf", "-", "-o", str(tmp_path / "o.tir")]) == 0
    err = capsys.readouterr().err
    assert "warning: file '<stdin>', column 'Fx'" in err and "frictionlaws-stdin-" not in err
