"""The packaged tread compound's predictions beside published figures.

The numbers the Persson guide states in its table ("Beside published figures") are
computed by published_comparison; the flash-temperature option puts the friction
maximum within half a decade of the 0.01 m/s of Persson (2006, abstract).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from frictionlaws.base.errors import InputError
from frictionlaws.io import datasets_dir
from frictionlaws.persson import TREAD_THERMAL, published_comparison
from frictionlaws.persson.published import PUBLISHED_FILE, peak, published_shift

GUIDE = Path(__file__).resolve().parent.parent / "docs" / "user-guide" / "persson.rst"


@pytest.fixture(scope="module")
def rows():
    return published_comparison()


def test_the_flash_maximum_is_within_half_a_decade_of_the_published_one(rows):
    flash_peak = rows[0]
    assert flash_peak.published == 0.01
    assert flash_peak.predicted == pytest.approx(0.02838, rel=0.01)
    assert abs(flash_peak.difference) < 0.5
    assert flash_peak.difference == pytest.approx(math.log10(flash_peak.predicted / 0.01))


def test_the_heating_onset_and_the_shift_are_the_stated_numbers(rows):
    onset, shift = rows[1], rows[2]
    assert onset.predicted == pytest.approx(0.005569, rel=0.01)
    assert onset.difference == pytest.approx(-0.254, abs=0.005)
    assert shift.published == pytest.approx(1.2869, abs=1e-4)
    assert shift.predicted == pytest.approx(1.4568, abs=1e-4)
    assert shift.difference == pytest.approx(13.2, abs=0.05)


@pytest.mark.parametrize(("T", "v_peak", "shift_difference"),
                         [(273.15, 2.404e-3, 6.0), (313.15, 0.2649, 18.3)])
def test_the_flash_maximum_moves_with_temperature_as_the_guide_says(T, v_peak,
                                                                    shift_difference):
    flash_peak, _, shift = published_comparison(T=T)
    assert flash_peak.predicted == pytest.approx(v_peak, rel=0.01)
    assert shift.difference == pytest.approx(shift_difference, abs=0.05)


def test_the_guide_states_the_computed_numbers(rows):
    text = GUIDE.read_text(encoding="utf-8")
    table = text[text.index("Beside published figures"):]
    flash_peak, onset, shift = rows
    for shown in (f"{flash_peak.predicted:.3g} m/s", f"+{flash_peak.difference:.2f} decades",
                  f"{onset.predicted:.3g} m/s", f"{onset.difference:.2f} decades",
                  f"{shift.published:.4g} decades", f"{shift.predicted:.4g} decades",
                  f"+{shift.difference:.1f} %"):
        assert shown in table, shown


def test_the_published_figures_carry_their_sources():
    spec = json.loads((datasets_dir() / PUBLISHED_FILE).read_text(encoding="utf-8"))
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


@pytest.mark.parametrize("T", [240.0, 330.0, math.nan, "293"])
def test_a_temperature_whose_shift_leaves_the_range_is_refused(T):
    with pytest.raises(InputError, match=r"T = .* must lie in 243.15\.\.323.15 K"):
        published_comparison(T=T)


def test_the_thermal_properties_must_be_given():
    with pytest.raises(InputError, match="flash must be a Flash"):
        published_comparison(flash=None)
    assert published_comparison(T=283.15, flash=TREAD_THERMAL)[2].published > 0
