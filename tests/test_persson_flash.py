"""The two refinements of Persson (2006) to the 2001 theory: the flash temperature and S(q).

Persson, J. Phys.: Condens. Matter 18 (2006) 7789.  Both are options whose limits
are the isothermal, uncorrected theory: no heat or an unbounded conductivity gives
the isothermal mu; gamma = 1 gives S = 1.  The correction is also checked against
the independent reference implementation (law_examples._persson).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import frictionlaws as fl
from frictionlaws.base.errors import DomainError, InputError
from frictionlaws.persson import (
    TREAD_THERMAL,
    Flash,
    SelfAffine,
    asphalt_like,
    contact_ratio,
    flash_temperature,
    friction,
    tread_compound,
)
from frictionlaws.validation.law_examples import _persson

SURF = asphalt_like(1e6)
V = np.logspace(-8, 4, 49)
MAT = tread_compound()


# ------------------------------------------------------------------------ S(q)


def test_gamma_one_is_the_uncorrected_theory():
    assert np.array_equal(friction(MAT, SURF, V, 293.15, 2e5, gamma=1.0),
                          friction(MAT, SURF, V, 293.15, 2e5))


@pytest.mark.parametrize("v", [1e-4, 0.05])
def test_correction_matches_the_independent_reference(v):
    h = math.sqrt(math.pi * SURF.C0 * SURF.q0**2 / SURF.H)
    ref = _persson(math, 2e5, v, 293.15, 1e6, 0.0, SURF.q0, SURF.H, h, gamma=0.5,
                   material=MAT)
    assert friction(MAT, SURF, v, 293.15, 2e5, gamma=0.5) == pytest.approx(ref, rel=1e-4)


def test_correction_halves_mu_at_small_contact_and_vanishes_at_full_contact():
    # small contact (P << 1 everywhere that matters): S -> gamma
    P = contact_ratio(MAT, SURF, 0.01, 293.15, 2e4, [1e4])[0]
    assert P < 0.05
    r = friction(MAT, SURF, 0.01, 293.15, 2e4, gamma=0.5) / friction(MAT, SURF, 0.01, 293.15,
                                                                       2e4)
    assert 0.5 < r < 0.5 + P
    # full contact (P = 1): S = 1 whatever gamma
    smooth = SelfAffine.from_rms(SURF.q0, 0.8, 1e-9, 1e4)
    assert friction(MAT, smooth, 0.01, 293.15, 1e6, gamma=0.3) == pytest.approx(
        friction(MAT, smooth, 0.01, 293.15, 1e6), rel=1e-6)


@pytest.mark.parametrize("gamma", [-0.1, 1.5, math.nan])
def test_gamma_outside_zero_to_one_is_refused(gamma):
    with pytest.raises(InputError, match="gamma"):
        friction(MAT, SURF, 0.01, 293.15, 2e5, gamma=gamma)


def test_law_setting_gamma():
    law = fl.get_law("persson")
    mu = law(p=2e5, v=0.01, T=293.15, preset="tread-on-asphalt", gamma=0.5)
    assert mu == pytest.approx(friction(MAT, SURF, 0.01, 293.15, 2e5, gamma=0.5), rel=1e-12)


# ------------------------------------------------------------------ flash temperature


def test_no_heat_or_unbounded_conductivity_is_isothermal():
    iso = friction(MAT, SURF, V, 293.15, 2e5)
    cold = friction(MAT, SURF, V, 293.15, 2e5, flash=replace(TREAD_THERMAL, heat_fraction=0.0))
    assert np.array_equal(cold, iso)
    conducting = friction(MAT, SURF, V, 293.15, 2e5, flash=Flash(conductivity=1e15))
    assert np.max(np.abs(conducting / iso - 1)) < 1e-6


def test_flash_heating_grows_with_speed_and_lowers_friction():
    iso = friction(MAT, SURF, V, 293.15, 2e5)
    hot = friction(MAT, SURF, V, 293.15, 2e5, flash=TREAD_THERMAL)
    slow = V < 1e-6
    assert np.max(np.abs(hot[slow] / iso[slow] - 1)) < 1e-3
    fast = V > 0.01
    assert np.all(hot[fast] < iso[fast])
    q, Tq = flash_temperature(MAT, SURF, np.array([1e-6, 1e-3, 0.1, 10.0]), 293.15, 2e5,
                              flash=TREAD_THERMAL)
    rise = Tq.max(axis=1) - 293.15
    assert q.size == Tq.shape[1] and np.all(Tq >= 293.15 - 1e-9)
    assert np.all(np.diff(rise) > 0) and rise[0] < 0.01 and rise[-1] > 10.0
    # the peak drops and moves to lower speed
    assert hot.max() < iso.max() and V[np.argmax(hot)] < V[np.argmax(iso)]


def test_flash_temperature_scales_with_the_heat_fraction_when_small():
    _, T1 = flash_temperature(MAT, SURF, 1e-3, 293.15, 2e5, flash=Flash(heat_fraction=0.01))
    _, T2 = flash_temperature(MAT, SURF, 1e-3, 293.15, 2e5, flash=Flash(heat_fraction=0.02))
    assert (T2 - 293.15).max() / (T1 - 293.15).max() == pytest.approx(2.0, rel=0.02)


def test_non_converged_flash_temperature_is_refused():
    with pytest.raises(DomainError, match="did not converge"):
        friction(MAT, SURF, 1.0, 293.15, 2e5, flash=Flash(max_iter=1))


@pytest.mark.parametrize("kw", [{"conductivity": 0.0}, {"heat_capacity": -1.0},
                                {"heat_fraction": 1.5}, {"conductivity": math.nan}])
def test_bad_thermal_properties_are_refused(kw):
    with pytest.raises(InputError, match="flash temperature"):
        Flash(**kw)


def test_law_setting_heat_fraction():
    law = fl.get_law("persson")
    mu = law(p=2e5, v=1.0, T=293.15, preset="tread-on-asphalt", heat_fraction=1.0)
    assert mu == pytest.approx(friction(MAT, SURF, 1.0, 293.15, 2e5, flash=TREAD_THERMAL),
                               rel=1e-12)
    assert mu < law(p=2e5, v=1.0, T=293.15, preset="tread-on-asphalt")


def test_the_2006_preset_turns_both_refinements_on():
    law = fl.get_law("persson")
    mu = law(p=2e5, v=0.1, T=293.15, preset="tread-on-asphalt-2006")
    assert mu == pytest.approx(friction(MAT, SURF, 0.1, 293.15, 2e5, gamma=0.5,
                                        flash=TREAD_THERMAL), rel=1e-12)


@settings(max_examples=30, deadline=None)
@given(name=st.sampled_from(["gamma", "heat_fraction"]),
       value=st.one_of(st.floats(-1e6, -1e-9), st.floats(1.0 + 1e-9, 1e6),
                       st.just(math.nan), st.just(math.inf)))
def test_law_settings_outside_zero_to_one_are_refused(name, value):
    with pytest.raises(InputError, match=name):
        fl.get_law("persson")(p=2e5, v=0.1, T=293.15, preset="tread-on-asphalt",
                              **{name: value})


def test_flash_temperature_converges_across_the_domain():
    # cold rubber sliding fast heats itself further (the plain iteration oscillates there)
    p, T, v = np.meshgrid([1e4, 1e5, 1e6], [243.15, 253.15, 293.15, 343.15],
                          [1e-3, 0.1, 10.0, 1e3], indexing="ij")
    mu = friction(MAT, SURF, v, T, p, gamma=0.5, flash=TREAD_THERMAL)
    assert np.all(np.isfinite(mu)) and np.all(mu > 0)
    # points where a step of half the full one overshot for ever
    mu = friction(MAT, SURF, np.array([6.784, 8.724]), np.array([265.145, 268.195]),
                  np.array([2.5498e5, 5.892e4]), gamma=0.5, flash=TREAD_THERMAL)
    assert np.all(np.isfinite(mu)) and np.all(mu > 0)
    _, Tq = flash_temperature(MAT, SURF, 10.0, 253.15, 1e5, flash=TREAD_THERMAL)
    assert Tq.max() > 300.0
