"""Fitting what Persson's theory leaves free (q1, mu_a and, freed, the roughness scale h_rms).

The law ``persson`` fits like any law: data made by the theory itself at three
temperatures and two pressures, with noise, give back the parameters they were
made with, within what the noise allows.
"""

from __future__ import annotations

import numpy as np
import pytest

import frictionlaws as fl

TRUE = {"q1": 4e5, "mu_a": 0.2, "h_rms": 0.2e-3}


def _data(seed=7, sigma=0.01):
    law = fl.get_law("persson")
    rng = np.random.default_rng(seed)
    T = np.repeat([273.15, 293.15, 313.15], 16)
    v = np.tile(np.logspace(-5, 0, 16), 3)
    p = np.tile([1e5, 4e5], 24)
    mu = law(p=p, v=v, T=T, **TRUE) + sigma * rng.standard_normal(T.size)
    return {"p": p, "v": v, "T": T, "mu": mu}


def test_fit_recovers_q1_mu_a_and_the_roughness_scale():
    res = fl.fit("persson", _data(), free=["h_rms"])
    assert res.values["q1"] == pytest.approx(TRUE["q1"], rel=0.15)
    assert res.values["mu_a"] == pytest.approx(TRUE["mu_a"], abs=0.02)
    assert res.values["h_rms"] == pytest.approx(TRUE["h_rms"], rel=0.05)
    assert res.metrics["rmse"] < 0.012


def test_fixed_roughness_scale_and_data_outside_the_domain():
    d = _data()
    res = fl.fit("persson", d, fix={"h_rms": TRUE["h_rms"]})
    assert res.values["q1"] == pytest.approx(TRUE["q1"], rel=0.1)
    d["T"][3] = 233.15  # below the compound's range
    with pytest.raises(fl.InputError, match=r"rows 4\b.*T -30..70 degC"):
        fl.fit("persson", d)
    res = fl.fit("persson", d, on_invalid="drop")
    assert res.residual.size == 47
    assert any("rows 4" in note and "dropped" in note for note in res.notes)
