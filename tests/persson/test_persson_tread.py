"""The packaged tread compound (datasets/tread-compound) and the law's preset on it.

What the compound must show (a tread rubber on an asphalt-like road): one bell of
mu in log v between 1e-8 and 1e4 m/s, its peak between 0.8 and 3 at 20 degC, moving
to higher speed as the rubber warms, by the WLF shift.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import frictionlaws as fl
from frictionlaws.io import datasets_dir
from frictionlaws.persson import asphalt_like, friction, havriliak_negami, tread_compound
from frictionlaws.persson.material import TREAD_FILE
from frictionlaws.viscoelastic.temperature import WLF_PRESETS

V = np.logspace(-8, 4, 100)


def _curve(T):
    law = fl.get_law("persson")
    return law(p=np.full(V.size, 2e5), v=V, T=np.full(V.size, T), preset="tread-on-asphalt")


@pytest.mark.parametrize("T", [273.15, 293.15, 313.15])
def test_one_bell_in_log_v(T):
    mu = _curve(T)
    k = int(np.argmax(mu))
    assert 0 < k < V.size - 1
    assert np.all(np.diff(mu[: k + 1]) > 0) and np.all(np.diff(mu[k:]) < 0)


def test_peak_at_20_degC_and_its_shift_with_temperature():
    peaks = {}
    for T in (273.15, 293.15, 313.15):
        mu = _curve(T)
        k = int(np.argmax(mu))
        peaks[T] = (float(mu[k]), float(V[k]))
    mu20, v20 = peaks[293.15]
    assert 0.8 <= mu20 <= 3.0
    assert peaks[273.15][1] < v20 < peaks[313.15][1]
    # the grid peak moves by the WLF shift (to the grid's resolution, 0.12 decades)
    mat = tread_compound()
    shift = float(mat.shift(293.15) - mat.shift(313.15))
    assert np.log10(peaks[313.15][1] / v20) == pytest.approx(shift, abs=0.13)


def test_the_compound_is_the_file_and_the_prony_series_fits_it():
    spec = json.loads((datasets_dir() / TREAD_FILE).read_text(encoding="utf-8"))
    assert spec["measured"] is False
    for key in ("E_r", "E_g", "alpha", "beta", "tau0"):
        assert spec["modulus"][key]["source"]
    mat = tread_compound()
    m = spec["modulus"]
    w = np.logspace(-10, 14, 97)
    E = havriliak_negami(w, *(m[k]["value"] for k in ("E_r", "E_g", "tau0", "alpha", "beta")))
    got = mat.modulus(w)
    assert np.max(np.abs(got.real / E.real - 1)) < 0.05
    assert np.max(np.abs(got.imag / E.imag - 1)) < 0.10
    assert mat.E_glassy == pytest.approx(m["E_g"]["value"], rel=0.02)
    wlf = WLF_PRESETS[spec["shift"]["wlf_preset"]]
    assert (mat.shift.C1, mat.shift.C2) == (wlf.C1, wlf.C2)
    assert mat.temperature_range() == tuple(spec["shift"]["T_range"]["value"])


def test_havriliak_negami_limits():
    E = havriliak_negami(np.array([1e-30, 1e30]), 5e6, 2e9, 100.0, 0.5, 0.5)
    assert E.real == pytest.approx([5e6, 2e9], rel=1e-6)
    assert np.all(E.imag >= 0)


def test_the_preset_is_the_theory_on_the_asphalt_like_surface():
    mu = fl.get_law("persson")(p=2e5, v=0.01, T=293.15, preset="tread-on-asphalt")
    assert mu == pytest.approx(friction(tread_compound(), asphalt_like(1e6), 0.01, 293.15,
                                        2e5), rel=1e-12)
