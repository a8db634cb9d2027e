"""The correction S(q) = gamma + (1 - gamma) P(q)^2 of Persson (2006) to the 2001 theory.

Persson, J. Phys.: Condens. Matter 18 (2006) 7789.  An option whose limit is the
uncorrected theory (gamma = 1 gives S = 1); also checked against the independent
reference implementation (law_examples._persson).  The paper's other refinement,
the flash temperature, is tests/persson/test_persson_flash.py.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import frictionlaws as fl
from frictionlaws.base.errors import InputError
from frictionlaws.persson import (
    SelfAffine,
    asphalt_like,
    contact_ratio,
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
