"""Magic Formula conventions (slip angle, friction scaling, FZMAX) and combined slip.

Each option is checked against the published equations written out by hand here
(Pacejka, Tire and Vehicle Dynamics, 3rd ed., eqs. 4.E19-4.E30 and 4.E50-4.E67),
not against another call of the code under test.
"""

from __future__ import annotations

import json
import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from frictionlaws.base.errors import ExtrapolationWarning, InputError
from frictionlaws.cli import main
from frictionlaws.tyre import MagicFormula, read_property_file
from frictionlaws.tyre.mf.tir import format_tir

EXAMPLES = Path(__file__).resolve().parents[2] / "datasets" / "mf-examples"
NAMES = ("MagicFormula52", "MagicFormula61", "MagicFormula62")


def _doc(name: str) -> dict:
    return json.loads((EXAMPLES / f"{name}_Parameters.json").read_text())


@pytest.fixture(autouse=True)
def _quiet_extrapolation():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        yield


def _fy0_mf61_by_hand(alpha_star: float, lmuy: float, a_mu: float) -> float:
    """F_y0 of the MF 6.1 example at F_z = FNOMIN, gamma = 0, dpi = 0, from the book."""
    d = _doc("MagicFormula61")
    c = d["LATERAL_COEFFICIENTS"]
    fz = fz0 = d["VERTICAL"]["FNOMIN"]
    lmu_p = a_mu * lmuy / (1 + (a_mu - 1) * lmuy)
    C = c["PCY1"]
    D = c["PDY1"] * lmuy * fz
    K = c["PKY1"] * fz0 * math.sin(c["PKY4"] * math.atan(fz / (c["PKY2"] * fz0)))
    B = K / (C * D + 1e-6)
    S_V = fz * c["PVY1"] * lmu_p
    S_H = c["PHY1"] + (0.0 - 0.0) / (K + 1e-6)
    x = alpha_star + S_H
    E = c["PEY1"] * (1 - c["PEY3"] * math.copysign(1.0, x))
    return D * math.sin(C * math.atan(B * x - E * (B * x - math.atan(B * x)))) + S_V


@pytest.mark.parametrize("deg", [-25.0, -3.0, 2.0, 12.0, 28.0])
def test_slip_angle_option_follows_its_convention(deg: float) -> None:
    a = math.radians(deg)
    fnom = _doc("MagicFormula61")["VERTICAL"]["FNOMIN"]
    tan_mf = MagicFormula.from_file("MagicFormula61")
    ang_mf = MagicFormula.from_file("MagicFormula61", slip_angle="alpha")
    assert tan_mf.slip_angle == "tan_alpha"  # the default
    assert tan_mf.fy0(a, fnom) == pytest.approx(_fy0_mf61_by_hand(math.tan(a), 1, 10), rel=1e-12)
    assert ang_mf.fy0(a, fnom) == pytest.approx(_fy0_mf61_by_hand(a, 1, 10), rel=1e-12)
    if abs(deg) >= 25:  # the two conventions differ visibly at large angles
        assert abs(tan_mf.fy0(a, fnom) - ang_mf.fy0(a, fnom)) > 1e-3 * abs(tan_mf.fy0(a, fnom))


@pytest.mark.parametrize("scaling,a_mu", [("degressive", 10.0), ("linear", 1.0)])
def test_friction_scaling_option_follows_its_convention(scaling: str, a_mu: float) -> None:
    pf = read_property_file(EXAMPLES / "MagicFormula61_Parameters.json")
    pf.sections["SCALING_COEFFICIENTS"]["LMUY"] = 0.8
    pf.sections["SCALING_COEFFICIENTS"]["LMUX"] = 0.7
    mf = MagicFormula.from_property_file(pf, friction_scaling=scaling)
    fnom = mf.fnomin
    for deg in (-8.0, 1.0, 6.0):
        a = math.radians(deg)
        assert mf.fy0(a, fnom) == pytest.approx(_fy0_mf61_by_hand(math.tan(a), 0.8, a_mu),
                                                rel=1e-12)
    # longitudinal: the force at the shifted origin is S_Vx = F_z PVX1 LMUX'
    c = pf.sections["LONGITUDINAL_COEFFICIENTS"]
    lmux_p = a_mu * 0.7 / (1 + (a_mu - 1) * 0.7)
    assert mf.fx0(-c["PHX1"], fnom) == pytest.approx(fnom * c["PVX1"] * lmux_p, rel=1e-10)


def test_friction_scaling_defaults_to_mfevals_linear_scaling() -> None:
    pf = read_property_file(EXAMPLES / "MagicFormula61_Parameters.json")
    pf.sections["SCALING_COEFFICIENTS"]["LMUX"] = 0.6
    default = MagicFormula.from_property_file(pf)
    assert default.friction_scaling == "linear"
    assert default.lmux_prime == 0.6  # MFeval 4.0: A_mu = 1
    assert MagicFormula.from_property_file(
        pf, friction_scaling="degressive").lmux_prime == pytest.approx(6 / 6.4)


def test_friction_scaling_options_agree_at_unit_scaling_and_for_mf52() -> None:
    k = np.linspace(-0.4, 0.4, 9)
    for name in NAMES:
        deg = MagicFormula.from_file(name)
        lin = MagicFormula.from_file(name, friction_scaling="linear")
        np.testing.assert_array_equal(deg.fx0(k, 4000.0), lin.fx0(k, 4000.0))
    pf = read_property_file(EXAMPLES / "MagicFormula52_Parameters.json")
    pf.sections["SCALING_COEFFICIENTS"]["LMUY"] = 0.8
    a, b = (MagicFormula.from_property_file(pf, friction_scaling=s)
            for s in ("degressive", "linear"))
    assert a.lmuy_prime == b.lmuy_prime == 0.8  # MF 5.2: LMU' = LMU always


def test_loads_above_fzmax_option() -> None:
    k = np.linspace(-0.3, 0.3, 7)
    ext = MagicFormula.from_file("MagicFormula62")
    clamp = MagicFormula.from_file("MagicFormula62", loads_above_fzmax="clamp")
    fzmax = ext.limits["fz"][1]
    assert fzmax == 18000
    np.testing.assert_array_equal(clamp.fx0(k, 25000.0), ext.fx0(k, fzmax))
    np.testing.assert_array_equal(clamp.fy0(k, 25000.0), ext.fy0(k, fzmax))
    assert not np.allclose(ext.fx0(k, 25000.0), ext.fx0(k, fzmax))
    # below FZMAX nothing changes
    np.testing.assert_array_equal(clamp.fx0(k, 5000.0), ext.fx0(k, 5000.0))
    with warnings.catch_warnings():
        warnings.simplefilter("error", ExtrapolationWarning)
        with pytest.raises(ExtrapolationWarning, match="outside"):
            ext.fx0(k, 25000.0)


def test_option_values_are_checked() -> None:
    for kw in ({"slip_angle": "tan"}, {"friction_scaling": "A10"},
               {"loads_above_fzmax": "yes"}):
        with pytest.raises(InputError, match="must be one of"):
            MagicFormula.from_file("MagicFormula61", **kw)


def test_missing_inflpres_uses_the_nominal_pressure_with_a_note(tmp_path: Path) -> None:
    pf = read_property_file(EXAMPLES / "MagicFormula61_Parameters.json")
    del pf.sections["OPERATING_CONDITIONS"]["INFLPRES"]
    path = tmp_path / "noinfl.tir"
    path.write_text(format_tir(pf))
    mf = MagicFormula.from_file(path)
    assert mf.pressure == mf.nominal_pressure == 260000
    assert any("no inflation pressure" in n and "dpi = 0" in n for n in mf.notes)
    ref = MagicFormula.from_file("MagicFormula61")
    np.testing.assert_array_equal(mf.fy0([0.05, 0.1], 5000.0), ref.fy0([0.05, 0.1], 5000.0))
    # another pressure still works when given
    assert mf.fy0(0.1, 5000.0, pressure=3e5) == ref.fy0(0.1, 5000.0, pressure=3e5)


def test_cli_options_reach_the_model(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["tyre", "mf", "MagicFormula61", "--json", "--slip-angle", "alpha",
                 "--friction-scaling", "linear", "--loads-above-fzmax", "clamp",
                 "--equations", "published", "--loads", "10,20"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["conventions"] == {"slip_angle": "alpha", "friction_scaling": "linear",
                                  "loads_above_fzmax": "clamp", "equations": "published"}
    assert out["mu_x_peak"][1] == pytest.approx(
        MagicFormula.from_file("MagicFormula61").mu_x_peak(18000.0))
    assert main(["tyre", "reduce", "MagicFormula61", "--load", "25", "--json",
                 "--loads-above-fzmax", "clamp"]) == 0
    red = json.loads(capsys.readouterr().out)
    assert red["load_N"] == 25000.0
    assert main(["tyre", "mf", "MagicFormula61", "--slip-angle", "tan"]) == 2
    assert "invalid choice" in capsys.readouterr().err


# ---------------------------------------------------------------- combined slip


@pytest.mark.parametrize("name", NAMES)
def test_combined_slip_recovers_pure_slip(name: str) -> None:
    mf = MagicFormula.from_file(name)
    k = np.linspace(-0.6, 0.6, 25)
    a = np.radians(np.linspace(-20, 20, 25))
    for fz in (2000.0, 4500.0, 8000.0):
        for g in (0.0, 0.04):
            np.testing.assert_array_equal(mf.fx(k, 0.0, fz, g), mf.fx0(k, fz, g))
            np.testing.assert_array_equal(mf.fy(0.0, a, fz, g), mf.fy0(a, fz, g))
            np.testing.assert_array_equal(mf.weight_x(k, 0.0, fz, g), 1.0)
            G, S_V = mf.weight_y(0.0, a, fz, g)
            np.testing.assert_array_equal(G, 1.0)
            np.testing.assert_array_equal(S_V, 0.0)


def test_weighting_functions_by_hand_mf61() -> None:
    d = _doc("MagicFormula61")
    cx, cy = d["LONGITUDINAL_COEFFICIENTS"], d["LATERAL_COEFFICIENTS"]
    fz0 = d["VERTICAL"]["FNOMIN"]
    fz, kappa, alpha, gamma = 5000.0, -0.08, math.radians(6.0), 0.03
    dfz, g, a_s = (fz - fz0) / fz0, math.sin(gamma), math.tan(alpha)

    def cosw(x: float, B: float, C: float, E: float) -> float:
        return math.cos(C * math.atan(B * x - E * (B * x - math.atan(B * x))))

    B = (cx["RBX1"] + cx["RBX3"] * g**2) * math.cos(math.atan(cx["RBX2"] * kappa))
    E = cx["REX1"] + cx["REX2"] * dfz
    G_xa = cosw(a_s + cx["RHX1"], B, cx["RCX1"], E) / cosw(cx["RHX1"], B, cx["RCX1"], E)
    B = (cy["RBY1"] + cy["RBY4"] * g**2) * math.cos(math.atan(cy["RBY2"] * (a_s - cy["RBY3"])))
    E = cy["REY1"] + cy["REY2"] * dfz
    S_H = cy["RHY1"] + cy["RHY2"] * dfz
    G_yk = cosw(kappa + S_H, B, cy["RCY1"], E) / cosw(S_H, B, cy["RCY1"], E)
    mu_y = (cy["PDY1"] + cy["PDY2"] * dfz) * (1 - cy["PDY3"] * g**2)
    D_V = mu_y * fz * (cy["RVY1"] + cy["RVY2"] * dfz + cy["RVY3"] * g) * math.cos(
        math.atan(cy["RVY4"] * a_s))
    S_Vyk = D_V * math.sin(cy["RVY5"] * math.atan(cy["RVY6"] * kappa))
    mf = MagicFormula.from_file("MagicFormula61")
    assert mf.weight_x(kappa, alpha, fz, gamma) == pytest.approx(G_xa, rel=1e-12)
    G, S_V = mf.weight_y(kappa, alpha, fz, gamma)
    assert (float(G), float(S_V)) == pytest.approx((G_yk, S_Vyk), rel=1e-12)
    assert mf.fx(kappa, alpha, fz, gamma) == pytest.approx(
        G_xa * mf.fx0(kappa, fz, gamma), rel=1e-12)
    assert mf.fy(kappa, alpha, fz, gamma) == pytest.approx(
        G_yk * mf.fy0(alpha, fz, gamma) + S_Vyk, rel=1e-12)


@pytest.mark.parametrize("name", NAMES)
def test_friction_ellipse(name: str) -> None:
    """Combined forces stay inside the pure-slip peaks' ellipse; slip in one direction
    takes force from the other."""
    mf = MagicFormula.from_file(name)
    k = np.linspace(-0.5, 0.5, 101)[:, None]
    a = np.radians(np.linspace(-20, 20, 81))[None, :]
    for fz in (2000.0, 4500.0, 8000.0):
        dx = np.max(np.abs(mf.fx0(k, fz)))
        dy = np.max(np.abs(mf.fy0(a, fz)))
        gx = mf.weight_x(k, a, fz)
        gy, s_v = mf.weight_y(k, a, fz)
        assert np.all((gx > 0) & (gx <= 1.01)) and np.all((gy > 0) & (gy <= 1.03))
        # the weighted pure forces lie within the ellipse of the pure-slip peaks
        # (within 5 % for the MF 6.x examples; the MF 5.2 example's weighting is weaker,
        # RBX1 = 9.5 against 18.3, and its combined force reaches 1.17 x the ellipse)
        r = np.hypot(gx * mf.fx0(k, fz) / dx, gy * mf.fy0(a, fz) / dy)
        assert r.max() <= (1.2 if name.endswith("52") else 1.05)
        # with the kappa-induced side force S_Vyk (large in the MF 5.2 example)
        r_full = np.hypot(mf.fx(k, a, fz) / dx, mf.fy(k, a, fz) / dy)
        assert r_full.max() <= 1.2
        # at the peak of the pure curves, cross slip lowers the force monotonically
        k_pk = float(k.ravel()[np.argmax(np.abs(mf.fx0(k.ravel(), fz)))])
        fx_line = np.abs(mf.fx(k_pk, np.radians(np.linspace(0, 15, 16)), fz))
        assert np.all(np.diff(fx_line) <= 1e-9 * dx) and fx_line[-1] < 0.95 * fx_line[0]
        a_pk = float(a.ravel()[np.argmax(np.abs(mf.fy0(a.ravel(), fz)))])
        fy_line = np.abs(mf.fy(np.linspace(0, -0.3, 16), a_pk, fz))
        assert fy_line[-1] < 0.9 * fy_line[0]
