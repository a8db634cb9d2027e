"""WLF shift factor, its presets and checks, and temperature-aware laws (with_wlf)."""

from __future__ import annotations

import json
import math
import warnings

import numpy as np
import pytest

from frictionlaws import fit, get_law
from frictionlaws.base.errors import DomainError, ExtrapolationWarning, InputError
from frictionlaws.law import NUMPY
from frictionlaws.viscoelastic.temperature import (
    WLF_PRESETS,
    WLFLaw,
    resolve_wlf,
    with_wlf,
    wlf_convert,
    wlf_log_aT,
    wlf_messages,
)

T_G = 223.15  # a tread compound with T_g = -50 degC


def test_wlf_value_and_sign():
    # Grosch: T_ref = T_g + 50 K; log10 a_T = -8.86 dT / (101.6 + dT)
    T_ref = T_G + 50.0
    assert wlf_log_aT(T_ref, preset="grosch", T_g=T_G) == 0.0
    T = T_ref + 20.0
    assert wlf_log_aT(T, preset="grosch", T_g=T_G) == pytest.approx(-8.86 * 20 / 121.6,
                                                                    rel=1e-14)
    # colder than the reference: positive (behaves as a higher velocity)
    assert wlf_log_aT(T_ref - 20.0, preset="grosch", T_g=T_G) > 0
    arr = wlf_log_aT(np.array([T_ref, T_ref + 10]), 8.86, 101.6, T_ref, warn=False)
    assert arr.shape == (2,)


def test_the_two_presets_agree_within_rounding():
    """Grosch (T_ref = T_g + 50 K) and universal (T_ref = T_g) are one function.

    Referred to the same reference temperature they differ only because the
    published constants are rounded: 8.86 * 101.6 / 51.6 = 17.4453, published 17.44.
    """
    T = np.linspace(T_G, T_G + 100.0, 2001)
    g = wlf_log_aT(T, preset="grosch", T_g=T_G, warn=False)
    u = wlf_log_aT(T, preset="universal", T_g=T_G, warn=False)
    # refer the universal curve to T_g + 50 K (subtract its value there)
    u_ref = u - wlf_log_aT(T_G + 50.0, preset="universal", T_g=T_G, warn=False)
    signed = g - u_ref
    diff = np.abs(signed)
    max_diff = float(diff.max())
    print(f"max |log10 a_T(grosch) - log10 a_T(universal)| over T_g..T_g+100 K: "
          f"{max_diff:.4g} decades at T - T_g = {T[np.argmax(diff)] - T_G:.1f} K")
    # the published constants are not exactly consistent: 2.6e-3 decades at T_g
    assert max_diff == pytest.approx(2.59e-3, abs=0.05e-3)
    # with the exact conversion of the constants the two agree to rounding error
    C1x, C2x = wlf_convert(8.86, 101.6, T_G + 50.0, T_G)
    assert C2x == pytest.approx(51.6) and C1x == pytest.approx(17.4453, abs=1e-4)
    ux = wlf_log_aT(T, C1x, C2x, T_G, warn=False)
    ux = ux - wlf_log_aT(T_G + 50.0, C1x, C2x, T_G, warn=False)
    assert np.max(np.abs(g - ux)) < 1e-12
    # up to an optimal constant offset the rounded sets still differ by 1.7e-3 decades
    assert (signed.max() - signed.min()) / 2 == pytest.approx(1.73e-3, abs=0.05e-3)


def test_warning_outside_validity_window_and_messages():
    with pytest.warns(ExtrapolationWarning, match="below T_g"):
        wlf_log_aT(T_G - 10.0, preset="grosch", T_g=T_G)
    with pytest.warns(ExtrapolationWarning, match="above T_g"):
        wlf_log_aT(T_G + 120.0, preset="universal", T_g=T_G)
    msgs = wlf_messages([T_G - 5, T_G + 50, T_G + 101, T_G + 150], 8.86, 101.6, T_G + 50, T_G)
    assert len(msgs) == 2 and "1 temperature(s) below" in msgs[0] and "2 temperature(s)" in msgs[1]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        wlf_log_aT(np.linspace(T_G, T_G + 100, 11), preset="grosch", T_g=T_G)
        # T_g inferred from the preset's (C1, C2) when only T_ref is given
        wlf_log_aT(T_G + 30, 8.86, 101.6, T_G + 50)
    with pytest.warns(ExtrapolationWarning):
        wlf_log_aT(T_G - 30, 8.86, 101.6, T_G + 50)


def test_error_at_and_below_the_pole():
    T_ref = T_G + 50
    pole = T_ref - 101.6
    with pytest.raises(DomainError, match="pole"):
        wlf_log_aT(pole, preset="grosch", T_g=T_G)
    with pytest.raises(DomainError, match="pole"):
        wlf_log_aT([T_ref, pole - 1], preset="grosch", T_g=T_G)
    with pytest.raises(DomainError, match="non-finite"):
        wlf_messages([np.nan], 8.86, 101.6, T_ref)
    with pytest.raises(InputError, match="T_ref"):
        wlf_log_aT(300.0, preset="grosch")
    with pytest.raises(InputError, match="unknown WLF preset"):
        resolve_wlf(preset="nope", T_ref=300.0)
    with pytest.raises(InputError, match="positive"):
        resolve_wlf(C1=-1.0, C2=50.0, T_ref=300.0)


def test_presets_table():
    assert WLF_PRESETS["grosch"].C1 == 8.86 and WLF_PRESETS["grosch"].C2 == 101.6
    assert WLF_PRESETS["grosch"].T_ref(T_G) == T_G + 50
    assert WLF_PRESETS["universal"].C1 == 17.44 and WLF_PRESETS["universal"].C2 == 51.6
    assert WLF_PRESETS["universal"].T_ref(T_G) == T_G


# ------------------------------------------------------------------ with_wlf


SAVKOOR = {"mu_s": 0.5, "mu_m": 1.3, "h10": 0.4, "v_m": 0.01, "n": -0.15}


def test_with_wlf_declares_a_standard_law():
    law = with_wlf("savkoor", preset="grosch", T_g=T_G)
    assert isinstance(law, WLFLaw)
    assert law.id == "savkoor+wlf" and law.base_id == "savkoor"
    assert law.variables == ("p", "v", "T")
    assert [s.name for s in law.settings] == ["p_ref", "C1", "C2", "T_ref"]
    assert law.setting_values["T_ref"] == T_G + 50
    assert law.domain["T"] == (T_G, T_G + 100)
    assert "T_g = 223.15 K" in law.notes
    summary = law.summary()
    json.dumps(summary)
    assert "Williams" in " ".join(summary["references"])
    assert {d["name"] for d in summary["derived"]} == {"v_peak", "mu_peak", "half_width_decades"}
    assert "T_ref" in law.derived[0].meaning
    assert law.latex().startswith(r"\mu = ")
    # without T_g and without a matching preset, T_g = T_ref - 50 K is assumed and said
    law2 = with_wlf("savkoor", C1=10.0, C2=80.0, T_ref=290.0)
    assert law2.T_g == 240.0 and "assumed" in law2.notes


def test_with_wlf_evaluates_the_base_law_at_reduced_velocity():
    base = get_law("savkoor")
    law = with_wlf(base, preset="universal", T_g=T_G)
    rng = np.random.default_rng(0)
    p = rng.uniform(2e4, 1e6, 50)
    v = np.exp(rng.uniform(np.log(1e-6), np.log(10), 50))
    T = rng.uniform(T_G, T_G + 100, 50)
    log_aT = wlf_log_aT(T, preset="universal", T_g=T_G)
    # the base formula at the reduced velocity (the floor v_min applies to the measured v)
    expect = base.formula(NUMPY, p=p, v=v * 10**log_aT, **base.resolve(SAVKOOR))
    np.testing.assert_allclose(law(p=p, v=v, T=T, **SAVKOOR), expect, rtol=1e-12)
    # at T_ref the shift vanishes
    np.testing.assert_allclose(law(p=p, v=v, T=T_G, **SAVKOOR), base(p=p, v=v, **SAVKOOR),
                               rtol=1e-14)
    # higher temperature acts as a lower velocity: the peak moves to higher v
    vv = np.geomspace(1e-8, 1e4, 4001)
    v_peak_hot = vv[np.argmax(law(p=1e5, v=vv, T=T_G + 60, **SAVKOOR))]
    v_peak_ref = vv[np.argmax(law(p=1e5, v=vv, T=T_G, **SAVKOOR))]
    assert v_peak_hot > 100 * v_peak_ref


def test_with_wlf_symbolic_equals_numeric():
    import sympy

    for base_id, params in (("savkoor", SAVKOOR),
                            ("exponential-decay", {"mu_s": 1.2, "mu_d": 0.6, "v_c": 0.3,
                                                   "delta": 1.3})):
        law = with_wlf(base_id, preset="grosch", T_g=T_G)
        expr = law.symbolic()
        free = sorted(expr.free_symbols, key=str)
        assert {str(s) for s in free} <= set(law.symbols())
        f = sympy.lambdify(free, expr, modules="mpmath")
        rng = np.random.default_rng(1)
        vals = law.resolve(params)
        for _ in range(15):
            point = {"p": rng.uniform(2e4, 1e6), "v": math.exp(rng.uniform(-12, 2)),
                     "T": rng.uniform(T_G, T_G + 100)}
            num = law(**{k: point[k] for k in law.variables}, **params)
            ref = float(f(*({**point, **vals}[str(s)] for s in free)))
            assert num == pytest.approx(ref, rel=1e-9)


def test_with_wlf_warns_and_raises_like_wlf():
    law = with_wlf("savkoor", preset="grosch", T_g=T_G)
    with pytest.warns(ExtrapolationWarning, match="above T_g"):
        law(p=1e5, v=1e-3, T=T_G + 130, **SAVKOOR)
    with pytest.raises(DomainError, match="pole"):
        law(p=1e5, v=1e-3, T=T_G + 50 - 101.6, **SAVKOOR)
    assert law.temperature_messages([T_G + 10]) == []


def test_with_wlf_rejects_laws_it_cannot_shift():
    with pytest.raises(InputError, match="does not depend on the velocity"):
        with_wlf("thirion", preset="grosch", T_g=T_G)
    with pytest.raises(InputError, match="already depends on the temperature"):
        with_wlf("park", preset="grosch", T_g=T_G)
    with pytest.raises(InputError, match="T_ref"):
        with_wlf("savkoor", C1=8.86, C2=101.6)


def _wlf_data(law, true, C1, C2, seed=1, n=160):
    # seed 1: over seeds 1..10 the largest |fitted - true| / stderr of the 8 parameters is
    # below 2.1 except for seed 3 (3.5, a genuine least-squares optimum)
    rng = np.random.default_rng(seed)
    p = np.exp(rng.uniform(np.log(3e4), np.log(8e5), n))
    v = np.exp(rng.uniform(np.log(1e-7), np.log(1.0), n))
    T = rng.choice(T_G + np.array([20.0, 40.0, 50.0, 60.0, 80.0]), n)
    vals = law.resolve({**true, "C1": C1, "C2": C2})
    mu = law.evaluate({"p": p, "v": v, "T": T}, vals)
    mu = mu + 0.02 * np.mean(mu) * rng.standard_normal(n)
    return {"p": p, "v": v, "T": T, "mu": mu}


def test_fit_with_C1_C2_freed_recovers_them():
    law = with_wlf("savkoor", preset="grosch", T_g=T_G)
    data = _wlf_data(law, SAVKOOR, C1=10.5, C2=90.0)
    res = fit(law, data, free=["C1", "C2"])
    assert res.non_identifiable == []
    for name, true in {**SAVKOOR, "C1": 10.5, "C2": 90.0}.items():
        est = res.params[name]
        assert est.stderr is not None
        assert abs(est.value - true) <= 3 * est.stderr, (name, est.value, est.stderr, true)
    # with the WLF constants held at the (wrong) preset the fit is visibly worse
    held = fit(law, data)
    assert held.metrics["rmse"] > 1.5 * res.metrics["rmse"]
    assert "C1" not in held.params and held.settings["C1"] == 8.86
    # derived quantities still come with uncertainties
    assert res.derived["v_peak"]["stderr"] is not None


def test_wlf_law_from_single_temperature_cannot_determine_C1_C2():
    law = with_wlf("savkoor", preset="grosch", T_g=T_G)
    data = _wlf_data(law, SAVKOOR, C1=8.86, C2=101.6)
    one = {k: v[data["T"] == T_G + 60] for k, v in data.items()}
    res = fit(law, one, free=["C1", "C2"])
    # one temperature: the shift a_T(T) is one number, confounded with v_m
    assert set(res.non_identifiable) == {"v_m", "C1", "C2"}
    assert any("single value of T" in w for w in res.warnings)


def test_park_equals_savkoor_with_wlf():
    """Park's law is the Savkoor bell in reduced velocity with the pressure factor inverted."""
    park = get_law("park")
    shifted = with_wlf("savkoor", C1=8.86, C2=101.6, T_ref=273.15)
    rng = np.random.default_rng(4)
    p = np.exp(rng.uniform(np.log(3e4), np.log(1e6), 40))
    v = np.exp(rng.uniform(np.log(1e-6), np.log(1.0), 40))
    T = rng.uniform(230.0, 320.0, 40)
    pk = {"n": 1 / 9, "mu_s": 0.4, "mu_m": 1.2, "h10": 0.35, "v_m": 0.003}
    sv = {"mu_s": 0.4, "mu_m": 1.2, "h10": 0.35, "v_m": 0.003, "n": -1 / 9, "p_ref": 1.5e5}
    np.testing.assert_allclose(park(p=p, v=v, T=T, **pk), shifted(p=p, v=v, T=T, **sv),
                               rtol=1e-12)
