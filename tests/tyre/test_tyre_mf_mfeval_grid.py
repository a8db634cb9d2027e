"""The Magic Formula outputs against MFeval 4.0 on the three packaged examples.

References: ``tests/tyre/data/mfeval/MF{52,61,62}_useMode{111,121}_grid.csv.gz``, written by
``tests/tyre/data/mfeval/generate_references.m`` (see the README there): per file and
slip-angle convention 25 operating conditions (loads from near FZMIN to near FZMAX,
camber -3/0/+3 deg, the inflation pressure and 0.8 / 1.2 times it, three speeds) with
pure, zero and combined slip, and a block outside the file's limits that MFeval
saturates.  useMode 111 is ``slip_angle="alpha"``, 121 ``slip_angle="tan_alpha"``; both
check limits, which is ``saturate=True`` here.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from frictionlaws.base.errors import ExtrapolationWarning
from frictionlaws.tyre.mf.model import MagicFormula
from frictionlaws.tyre.mf.outputs import steady_state

DATA = Path(__file__).parent / "data" / "mfeval"
CASES = [(v, mode) for v in ("52", "61", "62") for mode in (111, 121)]
SLIP_ANGLE = {111: "alpha", 121: "tan_alpha"}

#: Moments (and the residual torque) within 1e-4 of the file's peak |M_x|, |M_y|, |M_z|
#: over the reference: the 0.01 % of issue 28.
MOMENT_SHARE = 1e-4
MOMENTS = ("Mx", "My", "Mz", "Mzr")
#: Other outputs: tolerance as a share of the largest reference magnitude.  omega and
#: R_e: MFeval ends its fixed-point iteration for R_e when the first row of the batch
#: has converged, the others to about 1e-6; C_z = F_z / rho inherits the 1e-6 m of
#: rho below at the smallest deflections.
SHARE = {"Fx": 1e-8, "Fy": 1e-8, "mux": 1e-8, "muy": 1e-8, "Kxk": 1e-8, "Kya": 1e-8,
         "t": 1e-8, "2a": 1e-8, "2b": 1e-8, "Cx": 1e-8, "Cy": 1e-8, "sigmax": 1e-8,
         "sigmay": 1e-8, "Re": 1e-6, "omega": 1e-5, "Cz": 1e-4}
#: Loaded radius and deflection [m]: MFeval solves the MF 6.2 radius by fminsearch with
#: TolX = 1e-6 m (the MF 6.1 closed form agrees to 1e-8 m).
LENGTH_M = {"Rl": 1e-6, "rho": 1e-6}


def _reference(v: str, mode: int) -> pd.DataFrame:
    return pd.read_csv(DATA / f"MF{v}_useMode{mode}_grid.csv.gz")


@pytest.fixture(scope="module")
def evaluated() -> dict[tuple[str, int], tuple[pd.DataFrame, dict[str, np.ndarray]]]:
    out = {}
    for v, mode in CASES:
        d = _reference(v, mode)
        mf = MagicFormula.from_file(f"MagicFormula{v}", slip_angle=SLIP_ANGLE[mode])
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ExtrapolationWarning)  # the saturated block
            ours = steady_state(mf, d["kappa [-]"].to_numpy(), d["alpha [rad]"].to_numpy(),
                                d["Fz [N]"].to_numpy(), d["gamma [rad]"].to_numpy(),
                                pressure=d["P [Pa]"].to_numpy(), vx=d["Vx [m/s]"].to_numpy(),
                                saturate=True)
        out[(v, mode)] = (d, ours)
    return out


def _column(d: pd.DataFrame, name: str) -> str:
    return next(c for c in d.columns if c.split(" [")[0] == name)


def _rows(v: str, d: pd.DataFrame, name: str) -> np.ndarray:
    """Rows where MFeval's value is a solution of its equations.

    MFeval 4.0 finds the loaded radius of MF 5.2 and 6.2 files with fminsearch started
    at 0.3 m on the MF 6.2 vertical model; where the search stalls on the plateau of zero
    load (R_l above the free radius: rho = 0, C_z infinite; every row of the MF 5.2
    example) or settles on the branch above the free radius that the camber term opens,
    its R_l, rho and C_z are no loaded radius and are left out.
    """
    rows = np.ones(len(d), bool)
    if name in ("Rl", "rho", "Cz") and v != "61":
        r0 = MagicFormula.from_file(f"MagicFormula{v}").structure["UNLOADED_RADIUS"]
        rows &= (d["rho [m]"].to_numpy() > 0) & (d["Rl [m]"].to_numpy() < r0)
    return rows


@pytest.mark.parametrize(("v", "mode"), CASES)
@pytest.mark.parametrize("name", MOMENTS)
def test_moments_match_mfeval_within_a_ten_thousandth_of_the_files_peak_moment(
        evaluated: dict, v: str, mode: int, name: str) -> None:
    d, ours = evaluated[(v, mode)]
    peak = max(np.abs(d[f"{m} [N m]"]).max() for m in ("Mx", "My", "Mz"))
    err = np.abs(ours[name] - d[f"{name} [N m]"].to_numpy()).max()
    assert err <= MOMENT_SHARE * peak, f"{name}: {err / peak:.2e} of the peak moment"


@pytest.mark.parametrize(("v", "mode"), CASES)
@pytest.mark.parametrize("name", sorted(SHARE) + sorted(LENGTH_M))
def test_every_other_output_matches_mfeval(evaluated: dict, v: str, mode: int,
                                           name: str) -> None:
    d, ours = evaluated[(v, mode)]
    if name in ("Cx", "Cy") and v == "52":  # MF 5.2 files carry no carcass stiffness
        assert name not in ours
        return
    rows = _rows(v, d, name)
    if v == "52" and name in ("Rl", "rho", "Cz"):
        assert not rows.any()  # nothing of MFeval's to compare (see _rows)
        return
    ref = d[_column(d, name)].to_numpy()[rows]
    err = np.abs(ours[name][rows] - ref).max()
    if name in LENGTH_M:
        assert err <= LENGTH_M[name], f"{name}: {err:.2e} m"
    else:
        assert err <= SHARE[name] * np.abs(ref).max(), f"{name}: {err / np.abs(ref).max():.2e}"


def test_the_mf62_loaded_radius_is_compared_on_most_rows() -> None:
    for mode in (111, 121):
        d = _reference("62", mode)
        assert _rows("62", d, "Rl").sum() >= 100  # of 305


def test_the_references_cover_the_stated_grid() -> None:
    for v, mode in CASES:
        d = _reference(v, mode)
        camber = np.round(np.degrees(d["gamma [rad]"]), 6)
        assert {-3.0, 0.0, 3.0} <= set(camber)
        mf = MagicFormula.from_file(f"MagicFormula{v}")
        loads = d["Fz [N]"]
        fzmin, fzmax = mf.limits["fz"]
        assert loads.min() <= max(1.05 * fzmin, 0.03 * mf.fnomin) + 1e-9
        assert loads.max() > fzmax  # and the saturated block above FZMAX
        assert ((d["kappa [-]"] == 0) & (d["alpha [rad]"] != 0)).any()
        assert ((d["kappa [-]"] != 0) & (d["alpha [rad]"] != 0)).any()
        if mf.pressure is not None:
            assert len(set(d["P [Pa]"])) >= 3


def test_published_equations_differ_from_mfeval_where_stated() -> None:
    gamma = np.radians(3.0)
    mfe = MagicFormula.from_file("MagicFormula61")
    pub = MagicFormula.from_file("MagicFormula61", equations="published")
    c, fz = mfe.coefficients, mfe.fnomin
    # PDX3: gamma (MFeval) or sin(gamma) (eq. 4.E13)
    for mf, g in ((mfe, gamma), (pub, np.sin(gamma))):
        assert mf.mu_x_peak(fz, gamma) == pytest.approx(c["PDX1"] * (1 - c["PDX3"] * g**2),
                                                        rel=1e-12)
    # MF 5.2 with alpha* = tan(alpha): gamma* = sin(gamma) (MFeval) or gamma (MF-Tyre 5.2)
    m52 = MagicFormula.from_file("MagicFormula52")
    p52 = MagicFormula.from_file("MagicFormula52", equations="published")
    c52 = m52.coefficients
    for mf, g in ((m52, np.sin(gamma)), (p52, gamma)):
        assert mf.mu_y_peak(m52.fnomin, gamma) == pytest.approx(
            c52["PDY1"] * (1 - c52["PDY3"] * g**2), rel=1e-12)
    # LFZO multiplies the combined-slip trail in MFeval only
    kw = {"fnomin": mfe.fnomin, "version": "6.1", "structure": mfe.structure}
    coeffs = {**mfe.coefficients, "LFZO": 1.1}
    t_m = MagicFormula(coeffs, **kw).steady_state(0.02, 0.05, fz)["t"]
    t_p = MagicFormula(coeffs, equations="published", **kw).steady_state(0.02, 0.05, fz)["t"]
    assert t_m == pytest.approx(1.1 * t_p, rel=1e-12)


def test_mf52_aligning_moment_takes_the_side_force_shift_at_zero_camber_like_mfeval() -> None:
    gamma, fz = np.radians(3.0), 9000.0
    m52 = MagicFormula.from_file("MagicFormula52")
    p52 = MagicFormula.from_file("MagicFormula52", equations="published")
    kappa, alpha = 0.05, np.radians(2.0)
    diff = m52.mz(kappa, alpha, fz, gamma) - p52.mz(kappa, alpha, fz, gamma)
    assert abs(diff) > 1e-3  # the shift with mu_y at the camber or at zero camber
    assert m52.mz(kappa, alpha, fz, 0.0) == pytest.approx(p52.mz(kappa, alpha, fz, 0.0),
                                                          rel=1e-12)


def test_an_unknown_equations_choice_is_refused() -> None:
    from frictionlaws.base.errors import InputError

    with pytest.raises(InputError, match="equations must be one of mfeval, published"):
        MagicFormula.from_file("MagicFormula61", equations="book")
