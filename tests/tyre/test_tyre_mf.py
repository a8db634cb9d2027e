"""Magic Formula (PAC2002 / MF 5.2, MF 6.1/6.2) from property files: reader and identities."""

from __future__ import annotations

import json
import math
import re
import warnings
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from frictionlaws.base.errors import ExtrapolationWarning, InputError
from frictionlaws.cli import main
from frictionlaws.tyre import MagicFormula, read_property_file
from frictionlaws.tyre.mf.equations import mf_curve
from frictionlaws.tyre.mf.tir import (
    CHRONO_PROVENANCE,
    converted_header,
    format_tir,
    read_json,
    read_tir,
)

EXAMPLES = Path(__file__).resolve().parents[2] / "datasets" / "mf-examples"
FILES = sorted(EXAMPLES.glob("MagicFormula*_Parameters.json"))
LOADS = (1500.0, 3000.0, 4500.0, 6752.0, 9000.0)


def _coeffs(name: str) -> dict:
    doc = json.loads((EXAMPLES / f"MagicFormula{name}_Parameters.json").read_text())
    out = dict(doc["SCALING_COEFFICIENTS"])
    out.update(doc["LONGITUDINAL_COEFFICIENTS"])
    out.update(doc["LATERAL_COEFFICIENTS"])
    out["FNOMIN"] = doc["VERTICAL"]["FNOMIN"]
    return out


@pytest.fixture(autouse=True)
def _quiet_extrapolation():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        yield


def test_example_files_present_and_complete():
    assert [f.name for f in FILES] == ["MagicFormula52_Parameters.json",
                                       "MagicFormula61_Parameters.json",
                                       "MagicFormula62_Parameters.json"]
    for f in FILES:
        mf = MagicFormula.from_file(f)
        assert mf.version == {"52": "5.2", "61": "6.1", "62": "6.2"}[f.name[12:14]]
        assert any("FITTYP" in n for n in mf.notes)


# ------------------------------------------------------------ the identities


def identity_failures(force, coeffs, loads, slip_of, span, rtol=1e-7):
    """Textbook identities of a pure-slip curve; returns the list of those that fail.

    ``force(slip, fz)`` is the curve, ``coeffs(fz)`` the MF factors,
    ``slip_of(x)`` maps the shifted slip x = (kappa or tan(alpha)) + S_H back to
    the argument of ``force``.
    """
    failures = []
    for fz in loads:
        k = coeffs(fz)
        D, S_V, S_H, K = float(k.D), float(k.S_V), float(k.S_H), float(k.K)
        # zero (pure) force at the shifted origin: F = S_V there
        f0 = force(slip_of(-S_H), fz)
        if not math.isclose(f0, S_V, rel_tol=rtol, abs_tol=1e-9 * D):
            failures.append(("origin", fz, f0, S_V))
        # slope at the shifted origin equals K (central difference in the slip variable)
        h = 1e-6
        slope = (force(slip_of(-S_H + h), fz) - force(slip_of(-S_H - h), fz)) / (2 * h)
        if not math.isclose(slope, K, rel_tol=1e-5):
            failures.append(("slope", fz, slope, K))
        # peaks: max F = D + S_V and min F = -D + S_V
        x = np.linspace(-span, span, 40001)
        f = force(slip_of(x), fz)
        for sign, target in ((1, D + S_V), (-1, -D + S_V)):
            i = int(np.argmax(sign * f))
            lo, hi = x[max(i - 1, 0)], x[min(i + 1, x.size - 1)]
            res = minimize_scalar(lambda t, s=sign, fz=fz: -s * force(slip_of(t), fz),
                                  bounds=(lo, hi), method="bounded",
                                  options={"xatol": 1e-12})
            peak = -res.fun * sign
            if not math.isclose(peak, target, rel_tol=rtol):
                failures.append(("peak", fz, peak, target))
    return failures


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.stem)
def test_fx0_textbook_identities(path):
    mf = MagicFormula.from_file(path)
    fails = identity_failures(mf.fx0, mf.longitudinal, LOADS, lambda x: x, 1.5)
    assert fails == []


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.stem)
def test_fy0_textbook_identities(path):
    mf = MagicFormula.from_file(path)
    # the lateral slip is tan(alpha): alpha = arctan(x)
    fails = identity_failures(mf.fy0, mf.lateral, LOADS, np.arctan, 2.5)
    assert fails == []


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.stem)
def test_identities_with_camber_and_pressure(path):
    mf = MagicFormula.from_file(path)
    for gamma, pressure in ((0.04, None), (-0.03, 2.2e5)):
        g, pr = gamma, pressure
        fails = identity_failures(
            lambda s, fz, g=g, pr=pr: mf.fx0(s, fz, g, pr),
            lambda fz, g=g, pr=pr: mf.longitudinal(fz, g, pr), (2000.0, 6000.0),
            lambda x: x, 1.5)
        fails += identity_failures(
            lambda s, fz, g=g, pr=pr: mf.fy0(s, fz, g, pr),
            lambda fz, g=g, pr=pr: mf.lateral(fz, g, pr), (2000.0, 6000.0), np.arctan, 2.5)
        assert fails == []


def test_misplaced_vertical_shift_fails_the_identities():
    """A curve with S_V inside the sine (a known bug elsewhere) must be caught."""
    mf = MagicFormula.from_file(EXAMPLES / "MagicFormula62_Parameters.json")

    def wrong_fx0(kappa, fz):
        k = mf.longitudinal(fz)
        x = np.asarray(kappa) + k.S_H
        E = np.minimum(k.E_a - k.E_b * np.sign(x), 1.0)
        bx = k.B * x
        # S_V added to the sine's argument instead of to the force
        return k.D * np.sin(k.C * np.arctan(bx - E * (bx - np.arctan(bx))) + k.S_V)

    fails = identity_failures(wrong_fx0, mf.longitudinal, LOADS, lambda x: x, 1.5)
    kinds = {f[0] for f in fails}
    assert {"origin", "peak"} <= kinds
    assert {f[1] for f in fails if f[0] == "origin"} == set(LOADS)
    # and the correct curve passes the same checker
    assert identity_failures(mf.fx0, mf.longitudinal, LOADS, lambda x: x, 1.5) == []


def test_vertical_shift_is_outside_the_sine():
    mf = MagicFormula.from_file(EXAMPLES / "MagicFormula62_Parameters.json")
    k = mf.longitudinal(4000.0)
    # far beyond the peak the sine part is bounded by D: F - S_V in [-D, D]
    f = mf.fx0(np.linspace(-1, 1, 2001), 4000.0)
    assert np.all(np.abs(f - k.S_V) <= k.D * (1 + 1e-12))
    assert abs(k.S_V) > 100.0  # the example has a sizeable shift, so the test has teeth


# ----------------------------------------------- hand-computed values (independent)


def test_values_at_nominal_load_by_hand_mf62():
    c = _coeffs("62")
    mf = MagicFormula.from_file(EXAMPLES / "MagicFormula62_Parameters.json")
    fz = c["FNOMIN"]  # dfz = 0; INFLPRES == NOMPRES so dpi = 0
    lon, lat = mf.longitudinal(fz), mf.lateral(fz)
    assert lon.mu == pytest.approx(c["PDX1"], rel=1e-12)
    assert lon.K == pytest.approx(fz * c["PKX1"], rel=1e-12)
    assert lon.C == pytest.approx(c["PCX1"])
    assert lon.S_H == pytest.approx(c["PHX1"], rel=1e-12)
    assert lon.S_V == pytest.approx(fz * c["PVX1"], rel=1e-12)
    assert lon.E(1.0) == pytest.approx(c["PEX1"] * (1 - c["PEX4"]), rel=1e-12)
    assert lat.mu == pytest.approx(c["PDY1"], rel=1e-12)
    ky = c["PKY1"] * fz * math.sin(c["PKY4"] * math.atan(1.0 / c["PKY2"]))
    assert lat.K == pytest.approx(ky, rel=1e-12)
    assert lat.S_H == pytest.approx(c["PHY1"], rel=1e-9)
    assert lat.S_V == pytest.approx(fz * c["PVY1"], rel=1e-12)
    # one point of the curve, typed out
    kappa = 0.05
    B = fz * c["PKX1"] / (c["PCX1"] * c["PDX1"] * fz)
    x = kappa + c["PHX1"]
    E = c["PEX1"] * (1 - c["PEX4"])
    F = c["PDX1"] * fz * math.sin(c["PCX1"] * math.atan(
        B * x - E * (B * x - math.atan(B * x)))) + fz * c["PVX1"]
    assert mf.fx0(kappa, fz) == pytest.approx(F, rel=1e-9)


def test_values_by_hand_mf52_load_dependence_and_camber():
    c = _coeffs("52")
    # the MF-Tyre 5.2 camber gamma itself (MFeval's forms take sin(gamma) with tan(alpha))
    mf = MagicFormula.from_file(EXAMPLES / "MagicFormula52_Parameters.json",
                                equations="published")
    fz = 4000.0
    dfz = (fz - c["FNOMIN"]) / c["FNOMIN"]
    g = 0.05
    lon, lat = mf.longitudinal(fz, g), mf.lateral(fz, g)
    assert lon.mu == pytest.approx((c["PDX1"] + c["PDX2"] * dfz) * (1 - c["PDX3"] * g**2))
    assert lon.K == pytest.approx(fz * (c["PKX1"] + c["PKX2"] * dfz) * math.exp(c["PKX3"] * dfz))
    assert lat.mu == pytest.approx((c["PDY1"] + c["PDY2"] * dfz) * (1 - c["PDY3"] * g**2))
    ky = (c["PKY1"] * c["FNOMIN"] * math.sin(2 * math.atan(fz / (c["PKY2"] * c["FNOMIN"])))
          * (1 - c["PKY3"] * g))
    assert lat.K == pytest.approx(ky)
    assert lat.S_H == pytest.approx(c["PHY1"] + c["PHY2"] * dfz + c["PHY3"] * g)
    assert lat.S_V == pytest.approx(fz * (c["PVY1"] + c["PVY2"] * dfz
                                          + (c["PVY3"] + c["PVY4"] * dfz) * g))
    E_pos = (c["PEY1"] + c["PEY2"] * dfz) * (1 - (c["PEY3"] + c["PEY4"] * g))
    assert lat.E(1.0) == pytest.approx(min(E_pos, 1.0))


def test_mf6_camber_and_pressure_terms_by_hand():
    c = _coeffs("61")
    mf = MagicFormula.from_file(EXAMPLES / "MagicFormula61_Parameters.json")
    fz, gamma, p = c["FNOMIN"], 0.05, 2.2e5
    dpi = (p - 2.6e5) / 2.6e5
    gs = math.sin(gamma)
    lon = mf.longitudinal(fz, 0.0, p)
    assert lon.mu == pytest.approx(c["PDX1"] * (1 + c["PPX3"] * dpi + c["PPX4"] * dpi**2))
    assert lon.K == pytest.approx(fz * c["PKX1"] * (1 + c["PPX1"] * dpi + c["PPX2"] * dpi**2))
    lat = mf.lateral(fz, gamma, p)
    assert lat.mu == pytest.approx(c["PDY1"] * (1 + c["PPY3"] * dpi + c["PPY4"] * dpi**2)
                                   * (1 - c["PDY3"] * gs**2))
    ky = (c["PKY1"] * fz * (1 + c["PPY1"] * dpi) * (1 - c["PKY3"] * abs(gs))
          * math.sin(c["PKY4"] * math.atan(
              fz / ((c["PKY2"] + c["PKY5"] * gs**2) * (1 + c["PPY2"] * dpi) * fz))))
    assert lat.K == pytest.approx(ky)
    svg = fz * c["PVY3"] * gs
    kyg0 = fz * c["PKY6"] * (1 + c["PPY5"] * dpi)
    assert lat.S_V == pytest.approx(fz * c["PVY1"] + svg)
    assert lat.S_H == pytest.approx(c["PHY1"] + (kyg0 * gs - svg) / ky)
    # the file's own pressure is nominal: the default evaluation has dpi = 0
    assert mf.mu_x_peak(fz) == pytest.approx(c["PDX1"])
    assert mf.mu_x_peak(fz, pressure=p) != pytest.approx(c["PDX1"])


def test_scaling_factors_apply():
    c = _coeffs("62")
    base = MagicFormula.from_file(EXAMPLES / "MagicFormula62_Parameters.json")
    scaled = MagicFormula({**base.coefficients, "LMUX": 0.8, "LKY": 1.2}, fnomin=base.fnomin,
                          version="6.2", friction_scaling="degressive")
    assert scaled.mu_x_peak(4000.0) == pytest.approx(0.8 * base.mu_x_peak(4000.0))
    assert scaled.cornering_stiffness(4000.0) == pytest.approx(
        1.2 * base.cornering_stiffness(4000.0))
    # MF 6.x degressive friction scaling of the vertical shift: 10*0.8/(1 + 9*0.8)
    lam = 10 * 0.8 / (1 + 9 * 0.8)
    assert scaled.longitudinal(c["FNOMIN"]).S_V == pytest.approx(c["FNOMIN"] * c["PVX1"] * lam)


def test_vectorised_shapes_and_scalars():
    mf = MagicFormula.from_file(EXAMPLES / "MagicFormula52_Parameters.json")
    k = np.linspace(-0.5, 0.5, 7)
    fz = np.array([[2000.0], [4000.0], [6000.0]])
    f = mf.fx0(k, fz)
    assert f.shape == (3, 7)
    assert f[1, 3] == pytest.approx(mf.fx0(k[3], 4000.0))
    assert isinstance(mf.fy0(0.02, 3000.0), float)
    assert isinstance(mf.mu_y_peak(3000.0), float)
    assert mf.mu_y_peak(fz).shape == (3, 1)
    # lateral force of a TYDEX file is negative for a positive slip angle (PKY1 < 0)
    assert mf.fy0(0.05, 4000.0) < 0 < mf.fx0(0.05, 4000.0)


def test_bad_inputs_raise_clear_errors():
    mf = MagicFormula.from_file(EXAMPLES / "MagicFormula62_Parameters.json")
    with pytest.raises(InputError, match="fz must hold positive"):
        mf.fx0(0.1, -100.0)
    with pytest.raises(InputError, match="fz must hold positive"):
        mf.fx0(0.1, [1000.0, np.nan])
    with pytest.raises(InputError, match="kappa must hold finite"):
        mf.fx0([0.1, np.nan], 3000.0)
    with pytest.raises(InputError, match="between -90 and 90"):
        mf.fy0(math.pi / 2, 3000.0)
    with pytest.raises(InputError, match="pressure -0.001 kPa is no tyre's inflation"):
        mf.fx0(0.1, 3000.0, pressure=-1.0)


@pytest.mark.parametrize("factor", [1e-3, 1e-2, 1e-5, 1e3, 1e4, 0.0, -1.0])
def test_a_pressure_off_by_a_unit_factor_is_refused_on_every_path(factor: float) -> None:
    """kPa, bar or psi numbers read as Pa (or Pa as kPa) give a pressure no tyre runs at,
    which the pressure terms would extrapolate to forces of any sign: refused before any
    output or warning, by the API's methods, the steady state and the command line."""
    mf = MagicFormula.from_file("MagicFormula61")
    bad = [2.6e5, 2.6e5 * factor]
    for call in (lambda: mf.fy0(0.05, 4000.0, 0.0, bad),
                 lambda: mf.fx(0.05, 0.02, 4000.0, 0.0, bad),
                 lambda: mf.steady_state(0.0, 0.05, 4000.0, 0.0, pressure=bad)):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            with pytest.raises(InputError, match=r"\(row 1\) is no tyre's inflation pressure"):
                call()
    assert main(["tyre", "mf", "MagicFormula61", "--alpha", "2", "--pressure",
                 f"{2.6e2 * factor:g}"]) == 2


def test_extrapolation_warns():
    mf = MagicFormula.from_file(EXAMPLES / "MagicFormula62_Parameters.json")
    with warnings.catch_warnings():
        warnings.simplefilter("error", ExtrapolationWarning)
        mf.fx0(np.linspace(-1, 1, 11), 4000.0)  # inside every range: silent
        with pytest.raises(ExtrapolationWarning, match="kappa"):
            mf.fx0(np.linspace(-1.5, 1.5, 11), 4000.0)
        with pytest.raises(ExtrapolationWarning, match="fz"):
            mf.fx0(0.1, 20000.0)
        with pytest.raises(ExtrapolationWarning, match="pressure"):
            mf.fx0(0.1, 4000.0, pressure=5e5)


# -------------------------------------------------------------- .tir reader

TIR_SNIPPET = """\
$-------------------------------------------------------------------info
! a hand-written test file: units not SI, comments everywhere
[MDI_HEADER]
FILE_TYPE                = 'tir'
FILE_VERSION             = 3.0
[UNITS]
LENGTH                   = 'mm'          $ millimetres
FORCE                    = 'kN'
ANGLE                    = 'radians'
MASS                     = 'kg'
TIME                     = 'second'
[MODEL]
PROPERTY_FILE_FORMAT     = 'PAC2002'     $Tire property type
TYRESIDE                 = 'LEFT $ not a comment'  $ but this is
[VERTICAL]
FNOMIN                   = 4.0           $Nominal wheel load [kN]
VERTICAL_STIFFNESS       = 0.2           $ kN/mm
[DIMENSION]
UNLOADED_RADIUS          = 310
[TIRE_CONDITIONS]
IP                       = 2.2D-4        $ kN/mm^2 = 0.22 MPa, Fortran exponent
IP_NOM                   = 2.2d-4
[SHAPE]
{radial width}
 1.0    0.0
 1.0    0.4
 0.95   0.9    $ comment after a row
[LONGITUDINAL_COEFFICIENTS]
PCX1                     = 1.65
PDX1                     = 1.2
PDX2                     = -0.1
PKX1                     = 21.7
[LATERAL_COEFFICIENTS]
PCY1                     = 1.3
PDY1                     = 1.0
	PKY1                 = -15.0         $ a tab before the key
PKY2                     = 1.7
"""


def test_tir_reader_handles_comments_quotes_tables_units():
    pf = read_tir(TIR_SNIPPET, source="snippet.tir")
    assert pf.get("MODEL", "TYRESIDE") == "LEFT $ not a comment"
    assert pf.comments[("VERTICAL", "FNOMIN")] == "Nominal wheel load [kN]"
    assert pf.number("LONGITUDINAL_COEFFICIENTS", "pcx1") == 1.65  # case-insensitive
    assert pf.number("LATERAL_COEFFICIENTS", "PKY1") == -15.0
    assert pf.tables["SHAPE"] == (["radial", "width"],
                                  [[1.0, 0.0], [1.0, 0.4], [0.95, 0.9]])
    assert pf.si("VERTICAL", "FNOMIN") == pytest.approx(4000.0)
    assert pf.si("VERTICAL", "VERTICAL_STIFFNESS") == pytest.approx(2.0e5)
    assert pf.si("DIMENSION", "UNLOADED_RADIUS") == pytest.approx(0.31)
    assert pf.si("TIRE_CONDITIONS", "IP") == pytest.approx(2.2e5)
    assert pf.lines[("VERTICAL", "FNOMIN")] == 16
    mf = MagicFormula.from_property_file(pf)
    assert mf.version == "5.2" and "PAC2002" in mf.notes[0]
    assert mf.fnomin == pytest.approx(4000.0)
    assert mf.pressure == pytest.approx(2.2e5) and mf.nominal_pressure == pytest.approx(2.2e5)
    assert mf.mu_x_peak(4000.0) == pytest.approx(1.2)
    assert mf.mu_x_peak(8000.0) == pytest.approx(1.2 - 0.1)


@pytest.mark.parametrize("text, message, row", [
    ("[A]\nX = 1\nX = 2\n", "given twice", 3),
    ("[A]\nX 1\n", "cannot read line", 2),
    ("X = 1\n[A]\n", "before the first", 1),
    ("[A]\n{a b}\n1 2 3\n", "has 3 values", 3),
    ("[A]\nX = 'abc\n", "unterminated", 2),
    ("[A]\nX = 1 2\n", "one number or a quoted string", 2),
    ("[A]\n[A]\n", "appears twice", 2),
    ("$ only comments\n", r"no \[SECTION\]", None),
])
def test_tir_reader_errors_name_the_line(text, message, row):
    with pytest.raises(InputError, match=message) as info:
        read_tir(text, source="bad.tir")
    assert info.value.file == "bad.tir"
    assert info.value.row == row


def test_property_file_errors(tmp_path):
    with pytest.raises(InputError, match="not found"):
        read_property_file(tmp_path / "missing.tir")
    bad = tmp_path / "bad.json"
    bad.write_text('{"A": {"X": [1, 2]}}')
    with pytest.raises(InputError, match="expected a number, a string or null"):
        read_property_file(bad)
    bad.write_text('{"A": {"X": 1,}')
    with pytest.raises(InputError, match="not valid JSON") as info:
        read_property_file(bad)
    assert info.value.row == 1
    deg = TIR_SNIPPET.replace("'radians'", "'deg'")
    with pytest.raises(InputError, match="only property files with angles in radians"):
        MagicFormula.from_property_file(read_tir(deg))
    no_fnomin = TIR_SNIPPET.replace("FNOMIN", "FNOMINX")
    with pytest.raises(InputError, match="FNOMIN"):
        MagicFormula.from_property_file(read_tir(no_fnomin))
    no_pcx1 = TIR_SNIPPET.replace("PCX1                     = 1.65\n", "")
    with pytest.raises(InputError, match="PCX1 is missing"):
        MagicFormula.from_property_file(read_tir(no_pcx1))
    with pytest.raises(InputError, match="text, expected a number"):
        read_tir(TIR_SNIPPET).number("MODEL", "TYRESIDE")


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.stem)
def test_json_and_converted_tir_agree(path):
    tir = path.with_name(path.stem + ".converted.tir")
    a, b = read_property_file(path), read_property_file(tir)
    assert a.format == "json" and b.format == "tir"
    assert a.sections == b.sections
    ma, mb = MagicFormula.from_file(path), MagicFormula.from_file(tir)
    k = np.linspace(-1, 1, 101)
    assert np.array_equal(ma.fx0(k, 5000.0), mb.fx0(k, 5000.0))
    assert np.array_equal(ma.fy0(k / 2, 5000.0), mb.fy0(k / 2, 5000.0))


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.stem)
def test_converted_tir_files_are_labelled_and_in_sync(path):
    """The packaged .tir files are exactly what the converter writes from the JSON."""
    tir = path.with_name(path.stem + ".converted.tir")
    text = tir.read_text(encoding="utf-8")
    assert text.startswith("! CONVERTED by frictionlaws from " + path.name)
    assert "7689fbc0" in text and "BSD-3-Clause" in text
    pf = read_property_file(path)
    header = converted_header(path.name, CHRONO_PROVENANCE)
    header += [f"JSON member {k}: {json.dumps(v)}" for k, v in pf.metadata.items()]
    assert text == format_tir(pf, header=header)


def test_json_metadata_kept():
    pf = read_json((EXAMPLES / "MagicFormula52_Parameters.json").read_text())
    assert pf.metadata["Name"] == "MagicFormula52_Parameters"
    assert pf.metadata["Inertia"] == [0.4, 0.7, 0.4]


def test_packaged_example_by_name():
    mf = MagicFormula.from_file("MagicFormula61")
    assert mf.version == "6.1" and mf.fnomin == 6752.0
    with pytest.raises(InputError, match="not found"):
        MagicFormula.from_file("no-such-tyre.tir")


def test_mf_curve_helper_matches():
    mf = MagicFormula.from_file(EXAMPLES / "MagicFormula62_Parameters.json")
    k = mf.longitudinal(3000.0)
    kappa = np.linspace(-0.3, 0.3, 13)
    assert np.allclose(mf.fx0(kappa, 3000.0),
                       mf_curve(kappa + k.S_H, k.B, k.C, k.D, k.E_a, k.E_b, k.S_V))


# Property files that used to give a number silently: each is refused naming line and key,
# or (an unknown, unrelated key) listed in a note.
_PF_CASES = [
    ("PCX1", "PCX1 = 1,65", "a decimal comma; write 1.65"),
    ("PCX1", "PCX1 = abc", "PCX1 = 'abc' is text, expected a number"),
    ("PCX1", "PCX9 = 1.65", "unknown key PCX9: did you mean PCX1"),
    ("PROPERTY_FILE_FORMAT", "FITTYP = 99", "FITTYP = 99: not a Magic Formula version"),
    ("PROPERTY_FILE_FORMAT", "FITTYP = 'sixty-one'",
     "FITTYP = sixty-one: not a Magic Formula version"),
]


@pytest.mark.parametrize(("key", "line", "message"), _PF_CASES)
def test_property_file_values_are_refused_with_line_and_key(key, line, message):
    lines = TIR_SNIPPET.splitlines()
    at = next(i for i, text in enumerate(lines) if text.strip().startswith(key + " "))
    lines[at] = line
    with pytest.raises(InputError, match=re.escape(message)) as info:
        MagicFormula.from_property_file(read_tir("\n".join(lines)))
    assert info.value.row == at + 1


def test_property_file_unknown_keys_are_listed(tmp_path):
    text = TIR_SNIPPET.replace("[LATERAL_COEFFICIENTS]", "[LATERAL_COEFFICIENTS]\nZZTOP = 3")
    mf = MagicFormula.from_property_file(read_tir(text))
    assert any("unknown keys" in n and "ZZTOP" in n for n in mf.notes)
    path = tmp_path / "extra.tir"
    path.write_text(text)
    assert main(["tyre", "mf", str(path)]) == 0


def test_property_file_encodings_follow_the_one_rule(tmp_path):
    """UTF-16 with BOM reads like UTF-8; a NUL byte is refused with its line."""
    utf16 = tmp_path / "utf16.tir"
    utf16.write_bytes(TIR_SNIPPET.encode("utf-16"))
    ref = MagicFormula.from_property_file(read_tir(TIR_SNIPPET))
    assert MagicFormula.from_file(utf16).fx0(0.1, 4000.0) == ref.fx0(0.1, 4000.0)
    nul = tmp_path / "nul.tir"
    nul.write_bytes(TIR_SNIPPET.encode() + b"$ padding\n" * 1000 + b"PCX2 = \x001\n")
    with pytest.raises(InputError, match="NUL byte"):
        MagicFormula.from_file(nul)


def test_pressure_outside_the_file_range_warns_and_nonsense_peaks_are_refused(tmp_path):
    """An INFLPRES outside PRESMIN..PRESMAX is extrapolation (warned); a pressure or a
    coefficient that makes the peak friction <= 0 is refused, never reported."""
    src = FILES[1].with_name(FILES[1].stem + ".converted.tir").read_text()
    lines = src.splitlines()

    def variant(key, value):
        out = [f"{key} = {value}" if ln.split("=")[0].strip() == key else ln for ln in lines]
        path = tmp_path / f"{key}_{value}.tir"
        path.write_text("\n".join(out) + "\n")
        return path

    with pytest.warns(ExtrapolationWarning, match="pressure"):
        MagicFormula.from_file(variant("INFLPRES", "1.2e5")).summary()
    with pytest.raises(InputError, match="is not a friction coefficient"):
        MagicFormula.from_file(variant("INFLPRES", "2600000")).summary()
    assert main(["tyre", "mf", str(variant("INFLPRES", "2600000"))]) == 2
    # impossible coefficients are refused when the file is read, by section and name
    for key, value, sec in (("PDX1", "-1.1632", "LONGITUDINAL"), ("LMUX", "0", "SCALING")):
        with pytest.raises(InputError, match=rf"\[{sec}_COEFFICIENTS\] {key} = .* is "
                           "impossible: expected (0 < value|> 0)"):
            MagicFormula.from_file(variant(key, value))
        assert main(["tyre", "mf", str(variant(key, value))]) == 2


def test_a_missing_section_header_and_an_inverted_range_are_refused(tmp_path):
    src = FILES[1].with_name(FILES[1].stem + ".converted.tir").read_text().splitlines()
    no_header = tmp_path / "no_header.tir"
    no_header.write_text("\n".join(ln for ln in src
                                   if ln.strip() != "[LONGITUDINAL_COEFFICIENTS]") + "\n")
    with pytest.raises(InputError, match=r"PCX1 belongs to \[LONGITUDINAL_COEFFICIENTS\]"):
        MagicFormula.from_file(no_header)
    negative = tmp_path / "negative.tir"
    negative.write_text("\n".join("FZMAX = -5" if ln.startswith("FZMAX") else ln
                                  for ln in src) + "\n")
    with pytest.raises(InputError, match=r"\[VERTICAL_FORCE_RANGE\] FZMAX = -5 is impossible"):
        MagicFormula.from_file(negative)
    inverted = tmp_path / "inverted.tir"
    inverted.write_text("\n".join("FZMIN = 20000" if ln.startswith("FZMIN") else ln
                                  for ln in src) + "\n")
    with pytest.raises(InputError, match="is not a range"):
        MagicFormula.from_file(inverted)
