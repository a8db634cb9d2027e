"""Turn slip of the Magic Formula: the spin input phit, its options and its limits.

The agreement with MFeval 4.0 is in ``test_tyre_mf_mfeval_beyond.py``; here: what the
options mean, what is refused, and where MFeval gives no number.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from frictionlaws.base.errors import InputError
from frictionlaws.tyre import MagicFormula

FZ = 5000.0
SLIPS = (np.array([0.0, 0.03, -0.08])[:, None], np.radians([-6.0, 0.0, 2.0, 9.0]))


@pytest.fixture(scope="module")
def mf61() -> MagicFormula:
    return MagicFormula.from_file("MagicFormula61")


def test_without_turn_slip_phit_zero_gives_todays_outputs(mf61: MagicFormula) -> None:
    kappa, alpha = SLIPS
    base = mf61.steady_state(kappa, alpha, FZ, np.radians(2.0))
    same = mf61.steady_state(kappa, alpha, FZ, np.radians(2.0), phit=0.0, turn_slip=False,
                             limit_checks=True)
    assert set(base) == set(same)
    for name in base:
        np.testing.assert_array_equal(base[name], same[name], err_msg=name)


def test_a_spin_without_the_turn_slip_model_is_refused(mf61: MagicFormula) -> None:
    with pytest.raises(InputError, match="turn_slip=True"):
        mf61.steady_state(0.0, 0.0, FZ, phit=0.5)


def test_turn_slip_needs_the_files_turn_slip_coefficients() -> None:
    mf52 = MagicFormula.from_file("MagicFormula52")  # PAC2002 example without the section
    with pytest.raises(InputError, match="TURNSLIP_COEFFICIENTS"):
        mf52.steady_state(0.0, 0.0, FZ, phit=0.5, turn_slip=True)


def test_the_spin_moment_takes_the_sign_of_the_spin(mf61: MagicFormula) -> None:
    # straight ahead, no camber: the path curvature phit adds a moment of its sign, largest
    # at small curvature (the peak of the spin torque D_rp) and fading towards parking
    phit = np.array([-2.0, -0.5, -0.1, 0.1, 0.5, 2.0])
    out = mf61.steady_state(0.0, 0.0, FZ, phit=phit, turn_slip=True)
    mz = out["Mz"] - mf61.steady_state(0.0, 0.0, FZ, phit=0.0, turn_slip=True)["Mz"]
    assert np.all(np.sign(mz) == np.sign(phit))
    assert np.abs(mz[3]) > np.abs(mz[4]) > np.abs(mz[5]) > 0


def test_turn_slip_reduces_the_peak_side_force(mf61: MagicFormula) -> None:
    alpha = np.radians(np.linspace(-15, 15, 61))
    peak = [np.abs(mf61.steady_state(0.0, alpha, FZ, phit=p, turn_slip=True)["Fy"]).max()
            for p in (0.0, 0.5, 2.0)]
    assert peak[0] > peak[1] > peak[2]


@pytest.mark.parametrize("gamma_deg", [0.0, 3.0])
def test_the_residual_torque_is_continuous_at_zero_spin(mf61: MagicFormula,
                                                         gamma_deg: float) -> None:
    # MFeval 4.0 gives NaN at phit = 0 exactly (0/0 in its zeta_7); here the limit.  The
    # spin moment rises steeply from 0 (about 1.7e3 N m per 1/m here): 1e-9 1/m away the
    # outputs differ by less than 1e-5
    kappa, alpha = SLIPS
    g = np.radians(gamma_deg)
    at0 = mf61.steady_state(kappa, alpha, FZ, g, phit=0.0, turn_slip=True)
    for name in ("Mz", "Mzr", "Fy", "Fx"):
        assert np.isfinite(at0[name]).all(), name
        for p in (-1e-9, 1e-9):
            near = mf61.steady_state(kappa, alpha, FZ, g, phit=p, turn_slip=True)[name]
            np.testing.assert_allclose(near, at0[name], rtol=0, atol=1e-5, err_msg=name)


def test_camber_acts_as_spin_in_the_turn_slip_model(mf61: MagicFormula) -> None:
    # with turn slip the camber's side force goes through the spin (1 - PECP1 of it): a
    # side force unlike the one without turn slip (MFeval 4.0: +306 N against -414 N at
    # 4 degrees, 5 kN, zero slip for this tyre)
    g = np.radians(4.0)
    plain = mf61.steady_state(0.0, 0.0, FZ, g)["Fy"]
    spin = mf61.steady_state(0.0, 0.0, FZ, g, phit=0.0, turn_slip=True)["Fy"]
    assert abs(plain - spin) > 100.0


def test_a_standing_wheel_has_no_turn_slip_shift(mf61: MagicFormula) -> None:
    # MFeval 4.0 gives NaN for F_y at vx = 0 with limit checks (0 times an infinite slope)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        out = mf61.steady_state(0.02, np.radians(3.0), FZ, np.radians(1.0), vx=0.0,
                                phit=0.4, turn_slip=True)
    assert all(np.isfinite(out[n]) for n in ("Fx", "Fy", "Mz", "Mx", "My"))


@pytest.mark.parametrize("phit", [np.nan, np.inf])
def test_a_spin_that_is_no_number_is_refused(mf61: MagicFormula, phit: float) -> None:
    with pytest.raises(InputError, match="phit"):
        mf61.steady_state(0.0, 0.0, FZ, phit=[0.1, phit], turn_slip=True)


def test_phit_broadcasts_like_the_other_inputs(mf61: MagicFormula) -> None:
    out = mf61.steady_state(0.0, np.radians([1.0, 2.0, 3.0]), FZ,
                            phit=np.array([[0.0], [0.5]]), turn_slip=True)
    assert out["Fy"].shape == (2, 3)
    with pytest.raises(InputError, match="phit"):
        mf61.steady_state(0.0, np.radians([1.0, 2.0, 3.0]), FZ, phit=[0.1, 0.2],
                          turn_slip=True)
