"""The flash temperature on the packaged tread compound: the figures the Persson guide states.

On the packaged tread compound, the asphalt-like surface (q1 = 1e6 1/m) and 0.2 MPa
with the default flash settings: the 20 degC maximum of mu(v) lies at 0.1-1.5 m/s
with height 1.1-1.45, the 0 degC maximum within 0.3 decades of 0.002 m/s, and no heat
gives the isothermal curve exactly.  Every number of the guide's flash-temperature
section and of "Compared with what" is computed here and looked up in the guide.
Nothing is compared with a published figure of another rubber (the guide says why).
"""

from __future__ import annotations

import json
import math
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from frictionlaws.base.errors import ExtrapolationWarning
from frictionlaws.io import datasets_dir
from frictionlaws.persson import (
    TREAD_THERMAL,
    Flash,
    asphalt_like,
    flash_figures,
    flash_temperature,
    friction,
    tread_compound,
)
from frictionlaws.persson.published import PUBLISHED_FILE, V_GRID, peak, published_shift

GUIDE = Path(__file__).resolve().parents[2] / "docs" / "user-guide" / "persson.rst"
T0, T20, T40 = 273.15, 293.15, 313.15


def _figures(**kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        return flash_figures(**kw)


def _section(title, until):
    text = GUIDE.read_text(encoding="utf-8")
    start = text.index(title)
    return " ".join(text[start:text.index(until, start)].split())


def _shown(mu, v):
    return f"{mu:.3f} at {v:.3g} m/s"


@pytest.fixture(scope="module")
def default():
    return {T: _figures(T=T) for T in (T0, T20, T40)}


# ------------------------------------------------------------------- done when


def test_the_20_degC_maximum_lies_at_0_1_to_1_5_m_s_with_height_1_1_to_1_45(default):
    height, v = default[T20].flash_peak
    assert 0.1 <= v <= 1.5 and 1.1 <= height <= 1.45
    assert (height, v) == (pytest.approx(1.2746, abs=2e-4), pytest.approx(0.4536, rel=2e-3))


def test_the_0_degC_maximum_stays_within_0_3_decades_of_2_mm_s(default):
    height, v = default[T0].flash_peak
    assert abs(math.log10(v / 0.002)) <= 0.3
    assert v == pytest.approx(0.002154, rel=2e-3)


def test_no_heat_gives_the_isothermal_curve_exactly():
    mat, surf = tread_compound(), asphalt_like(1e6)
    iso = friction(mat, surf, V_GRID, T20, 2e5)
    assert np.array_equal(friction(mat, surf, V_GRID, T20, 2e5,
                                   flash=replace(TREAD_THERMAL, heat_fraction=0.0)), iso)
    fig = flash_figures(flash=Flash(heat_fraction=0.0))
    assert fig.flash_peak == fig.isothermal_peak and math.isnan(fig.onset)


# ---------------------------------------------------------- the guide's numbers


def test_the_guide_states_the_default_maxima_and_onsets(default):
    text = _section("**On the packaged compound.**", "Below its isothermal maximum")
    for T in (T0, T20, T40):
        assert _shown(*default[T].isothermal_peak) in text
        assert _shown(*default[T].flash_peak) in text
    assert f"{default[T20].onset:.3g} m/s" in text


@pytest.mark.slow
def test_the_guide_states_the_other_options_maxima_and_onsets():
    text = _section("**On the packaged compound.**", "Below its isothermal maximum")
    exit_ = Flash(contact_temperature="exit")
    surface = Flash(closure="surface-flux")
    for T in (T0, T20, T40):
        assert _shown(*_figures(T=T, flash=exit_).flash_peak) in text
        assert _shown(*_figures(T=T, flash=surface, v_max=10.0).flash_peak) in text
    assert f"{_figures(flash=exit_).onset:.3g} m/s" in text
    assert f"{_figures(flash=surface, v_max=10.0).onset:.3g} m/s" in text
    background = _figures(flash=Flash(sliding_distance=0.01))
    assert _shown(*background.flash_peak) in text and f"{background.onset:.3g} m/s" in text


@pytest.mark.slow
def test_the_guide_states_how_far_the_options_move_the_20_degC_maximum(default):
    text = _section("Below its isothermal maximum", ".. figure::")
    v = default[T20].flash_peak[1]
    assert math.log10(v / _figures(flash=Flash(contact_temperature="exit")).flash_peak[1]) \
        == pytest.approx(1 / 3, abs=0.03)
    assert "by a third of a decade" in text
    lower = math.log10(v / _figures(flash=Flash(closure="surface-flux"),
                                    v_max=10.0).flash_peak[1])
    assert f"{lower:.1f} decades lower" in text
    # at 40 degC the heated maximum lies above the isothermal one
    assert default[T40].flash_peak[1] > default[T40].isothermal_peak[1]


def test_the_guide_states_the_rise_per_scale_at_1_m_s():
    text = _section("At 20 °C and 1 m/s the hottest scale", "**Its checks**")
    mat, surf = tread_compound(), asphalt_like(1e6)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        rises = {name: flash_temperature(mat, surf, 1.0, T20, 2e5, flash=f)[1][0] - T20
                 for name, f in (("mean", TREAD_THERMAL),
                                 ("exit", Flash(contact_temperature="exit")),
                                 ("surface", Flash(closure="surface-flux")))}
    for name in ("mean", "exit", "surface"):
        assert f"{rises[name].max():.1f} K" in text, name
    assert rises["mean"].argmax() == rises["mean"].size - 1          # the finest is hottest
    assert abs(rises["mean"][0]) < 1e-6 and abs(rises["exit"][0]) < 1e-6
    assert f"coarsest by {rises['surface'][0]:.1f} K" in text
    slow = flash_temperature(mat, surf, 1e-6, T20, 2e5, flash=TREAD_THERMAL)[1][0] - T20
    assert f"At 1 µm/s the rise is {slow.max():.2g} K" in text


# ------------------------------------------------------------ published context


def test_the_guide_states_the_published_context_and_compares_nothing(default):
    text = _section("Compared with what", "The packaged DMA sweeps")
    assert "nothing is set beside a published figure as a check" in text
    mat = tread_compound()
    here = float(mat.shift(T20) - mat.shift(T40))
    there = float(published_shift(T20) - published_shift(T40))
    assert f"{here:.4g} decades" in text and f"{there:.4g} decades" in text
    assert f"{default[T20].flash_peak[1]:.3g} m/s at 20 °C" in text
    assert f"{default[T0].flash_peak[1]:.3g} m/s at 0 °C" in text


def test_the_published_figures_carry_their_sources_and_say_they_are_not_compared():
    spec = json.loads((datasets_dir() / PUBLISHED_FILE).read_text(encoding="utf-8"))
    assert "not compared" in spec["note"]
    for key in ("flash_peak_velocity", "heating_onset_velocity", "wlf_filled_rubber"):
        assert "abstract" in spec[key]["source"] or "Fig. 1(b)" in spec[key]["source"]
        assert spec[key]["statement"]
    # the published fit: 0 at its 70 degC, positive (slower) below it
    assert float(published_shift(343.15)) == 0.0
    assert float(published_shift(293.15)) > 0


def test_peak_is_the_vertex_of_the_parabola_in_log_v():
    v = np.logspace(-3, 1, 17)
    mu = 2.0 - 0.3 * (np.log10(v) + 0.37) ** 2
    assert peak(v, mu) == pytest.approx((2.0, 10**-0.37), rel=1e-9)
    rising = np.log10(v) + 4
    assert peak(v, rising) == (pytest.approx(5.0), pytest.approx(10.0))


def test_a_maximum_beyond_the_grid_is_not_a_figure():
    fig = _figures(T=T40, flash=Flash(closure="surface-flux"), v_max=10.0)
    assert all(math.isnan(x) for x in fig.isothermal_peak)       # isothermal: 19.9 m/s
    assert "nan" in fig.describe() and "m/s" in fig.describe()
