"""Sliding laws in p, v (and T): Savkoor, Nackenhorst, Huemer, Wriggers, Park.

The registry-wide battery (tests/laws/test_registry_laws.py) checks every law the same
way; this file checks what is particular to these laws: derived quantities
against numerical maxima, admissibility, the Nackenhorst mapping and
identifiability, limits, the temperature shift of Park, and that fits started
from the data-driven guess alone reach the truth.
"""

from __future__ import annotations

import warnings

import lmfit
import numpy as np
import pytest

from frictionlaws import fit, get_law
from frictionlaws.base.errors import DomainError, ExtrapolationWarning, InputError
from frictionlaws.laws.velocity import nackenhorst_from_thesis

V = np.geomspace(1e-10, 1e4, 200001)


def test_savkoor_derived_against_numerical_peak():
    law = get_law("savkoor")
    params = {"mu_s": 0.5, "mu_m": 1.3, "h10": 0.4, "v_m": 0.01, "n": -0.15}
    d = law.derived_values(law.resolve(params))
    mu = law(p=1e5, v=V, **params)  # p = p_ref
    i = int(np.argmax(mu))
    assert d["v_peak"] == pytest.approx(V[i], rel=1e-3)
    assert d["mu_peak"] == pytest.approx(mu[i], rel=1e-9)
    # half width at half height of the bump above mu_s, in decades
    half = params["mu_s"] + (params["mu_m"] - params["mu_s"]) / 2
    above = np.log10(V[mu >= half])
    assert (above.max() - above.min()) / 2 == pytest.approx(d["half_width_decades"], rel=1e-3)
    # the pressure factor scales the whole curve
    assert law(p=4e5, v=0.01, **params) == pytest.approx(1.3 * 4**-0.15)


def test_savkoor_admissibility():
    law = get_law("savkoor")
    ok = law.resolve({"mu_s": 0.5, "mu_m": 1.3, "h10": 0.4, "v_m": 0.01, "n": 0.0})
    assert law.check_admissible(ok) is None
    bad = dict(ok, mu_m=0.3)
    assert "mu_m" in law.check_admissible(bad)


def test_wriggers_derived_against_numerical_peak():
    law = get_law("wriggers")
    params = {"a": 2e-6, "b": 8e4, "c": 0.4, "d": 1.5e-5}
    d = law.derived_values(law.resolve(params))
    mu = law(p=1e5, v=V, **params)
    i = int(np.argmax(mu))
    assert d["vbar_pref"] == pytest.approx(V[i], rel=1e-3)
    assert d["mu_max_pref"] == pytest.approx(mu[i], rel=1e-9)
    # the peak at every pressure is mu_max(p) at v = a p, and mu_max -> b d as p -> 0
    for p in (1e3, 3e4, 1e6):
        assert law(p=p, v=params["a"] * p, **params) == pytest.approx(
            params["b"] / p * np.arctan(params["d"] * p), rel=1e-12)
    assert law(p=1.0, v=params["a"] * 1.0, **params) == pytest.approx(d["mu_max_p0"], rel=1e-6)
    # no static friction
    assert law(p=1e5, v=0.0, **params) == 0.0


def test_huemer_admissibility_and_limits():
    law = get_law("huemer")
    base = {"alpha": 0.15, "beta": 0.4, "n": 0.6, "m_v": 2.0, "b": 0.5, "c": 0.05}
    full = {**law.setting_values, **base}
    assert law.check_admissible(law.resolve(base)) is None
    assert "c = -0.1 < 0" in law.check_admissible(dict(full, c=-0.1))
    with pytest.raises(InputError, match="outside its bounds"):
        law(p=1e6, v=1.0, **dict(base, c=-0.1))
    # b < 0 is allowed while b^2 < 4c ...
    assert law.check_admissible(law.resolve(dict(base, b=-0.4, c=0.05))) is None
    # ... but not when the denominator can vanish
    msg = law.check_admissible(dict(full, b=-0.5, c=0.05))
    assert "vanishes" in msg
    # at b^2 = 4c the denominator has a double root at x = -b/(2c), i.e. v = x^(-m)
    b = -np.sqrt(4 * 0.05)
    v0 = (-b / (2 * 0.05)) ** -2.0
    assert "vanishes" in law.check_admissible(dict(full, b=b, c=0.05))
    assert abs(law.evaluate({"p": 1e6, "v": v0}, dict(full, b=b, c=0.05))) > 1e6
    with pytest.raises(InputError, match="not admissible"):
        law(p=1e6, v=v0, **dict(base, b=b, c=0.05))
    # v -> 0 gives mu -> 0 (c > 0); v -> inf gives alpha (p/p_ref)^(n-1) + beta
    assert law(p=1e6, v=0.0, **base) == pytest.approx(0.0, abs=1e-7)  # v floored at 1e-9
    assert law(p=2e6, v=1e12, **base) == pytest.approx(0.15 * 2**-0.4 + 0.4, rel=1e-5)
    assert law.derived_values(law.resolve(base))["mu_high_speed"] == pytest.approx(0.55)


def test_nackenhorst_mapping_from_the_thesis_form():
    thesis = get_law("nackenhorst-thesis")
    ident = get_law("nackenhorst")
    c = {"c1": 0.3, "c2": 1.2e5, "c3": -0.4, "c4": 0.06, "c5": 1e-5, "c6": 0.03, "c7": 1e-3}
    mapped = nackenhorst_from_thesis(**c)
    assert mapped["b2"] == 0.0 and mapped["n"] == -0.4
    rng = np.random.default_rng(0)
    p = np.exp(rng.uniform(np.log(1e4), np.log(1e6), 100))
    v = np.exp(rng.uniform(np.log(1e-5), np.log(10), 100))
    np.testing.assert_allclose(thesis(p=p, v=v, **c), ident(p=p, v=v, **mapped), rtol=1e-12,
                               atol=1e-14)
    # different thesis coefficient sets with the same mapping give the same law
    c_alt = dict(c, c1=0.3 * 2.0**-0.4, c2=2.4e5 / 2.0, c4=0.08, c6=0.05)
    c_alt["c2"] = c["c2"] * 2.0  # c1 c2^-c3 unchanged: c1' = c1 2^(c3)
    c_alt["c1"] = c["c1"] * 2.0 ** c["c3"]
    # choose c7 so that c6 ln c7 - c4 ln c5 is unchanged
    target = c["c6"] * np.log(c["c7"]) - c["c4"] * np.log(c["c5"])
    c_alt["c7"] = float(np.exp((target + c_alt["c4"] * np.log(c["c5"])) / c_alt["c6"]))
    np.testing.assert_allclose(thesis(p=p, v=v, **c_alt), thesis(p=p, v=v, **c), rtol=1e-10)
    assert "A = c1 (p_ref/c2)^c3" in thesis.notes
    with pytest.raises(Exception, match="positive"):
        nackenhorst_from_thesis(1, -1, 1, 1, 1, 1, 1)


def _pv_grid_data(law, params, seed=0, noise=0.02):
    """A p-v grid: 4 pressure levels x 10 velocities, 2 % noise."""
    rng = np.random.default_rng(seed)
    p, v = np.meshgrid([5e4, 1e5, 2e5, 4e5], np.geomspace(1e-3, 3.0, 10))
    p, v = p.ravel(), v.ravel()
    mu = law(p=p, v=v, **params)
    mu = mu * (1 + noise * rng.standard_normal(mu.size))
    return {"p": p, "v": v, "mu": mu}


def test_nackenhorst_thesis_names_its_non_identifiable_parameters():
    thesis = get_law("nackenhorst-thesis")
    c = {"c1": 0.3, "c2": 1.2e5, "c3": -0.4, "c4": 0.06, "c5": 1e-5, "c6": 0.03, "c7": 1e-3}
    data = _pv_grid_data(thesis, c)
    res = fit(thesis, data)
    assert set(res.non_identifiable) == {"c1", "c2", "c4", "c5", "c6", "c7"}
    assert any("cannot be told apart" in w for w in res.warnings)
    assert res.params["c3"].identifiable
    # the identifiable form fits the same data cleanly
    clean = fit("nackenhorst", data, fix={"b2": 0.0})
    assert clean.non_identifiable == []
    assert not any("cannot" in w or "poorly" in w for w in clean.warnings), clean.warnings
    mapped = nackenhorst_from_thesis(**c)
    for k in ("A", "n", "b0", "b1"):
        est = clean.params[k]
        assert abs(est.value - mapped[k]) <= 3 * est.stderr, (k, est.value, est.stderr)
    # both describe the data equally well
    assert clean.metrics["rmse"] == pytest.approx(res.metrics["rmse"], rel=1e-3)


def test_sliding_laws_need_their_variables():
    data = {"v": np.geomspace(1e-3, 1, 10), "mu": np.full(10, 0.8)}
    with pytest.raises(DomainError, match=r"p \(contact pressure\)"):
        fit("savkoor", data)
    with pytest.raises(DomainError, match=r"T \(temperature\)"):
        fit("park", {**data, "p": np.full(10, 1e5)})
    law = get_law("wriggers")
    with pytest.raises(DomainError, match="sliding law needs p"):
        law.require_variables({"s", "v"}, "slip data")


def test_single_pressure_level_says_what_it_cannot_determine():
    law = get_law("savkoor")
    params = {"mu_s": 0.5, "mu_m": 1.3, "h10": 0.4, "v_m": 0.01, "n": -0.15}
    v = np.geomspace(1e-6, 10, 40)
    data = {"p": np.full(40, 2e5), "v": v, "mu": law(p=2e5, v=v, **params)}
    res = fit(law, data)
    assert any("single value of p" in w for w in res.warnings)
    assert "n" in res.non_identifiable


def test_park_temperature_shift_and_checks():
    park = get_law("park")
    pk = {"n": 1 / 9, "mu_s": 0.4, "mu_m": 1.2, "h10": 0.35, "v_m": 0.003}
    s = park.setting_values
    # at T_ref and p0 the law is the bell itself, peak mu_m at v_m
    assert park(p=s["p0"], v=pk["v_m"], T=s["T_ref"], **pk) == pytest.approx(1.2)
    # 20 K warmer: the peak moves to v_m / a_T
    T = s["T_ref"] + 20
    log_aT = -s["C1"] * 20 / (s["C2"] + 20)
    assert park(p=s["p0"], v=pk["v_m"] / 10**log_aT, T=T, **pk) == pytest.approx(1.2)
    # pressure power law with exponent -n
    assert park(p=8 * s["p0"], v=pk["v_m"], T=s["T_ref"], **pk) == pytest.approx(
        1.2 * 8 ** (-1 / 9))
    with pytest.warns(ExtrapolationWarning, match="above T_g"):
        park(p=1e5, v=1e-3, T=s["T_ref"] + 60, **pk)
    with pytest.raises(DomainError, match="pole"):
        park(p=1e5, v=1e-3, T=s["T_ref"] - s["C2"] - 1, **pk)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        park(p=1e5, v=1e-3, T=np.linspace(s["T_ref"] - 50, s["T_ref"] + 50, 5), **pk)
    assert park.derived_values(park.resolve(pk)) == {"v_peak": 0.003, "mu_peak": 1.2}


def test_park_fit_with_wlf_constants_freed():
    park = get_law("park")
    pk = {"n": 1 / 9, "mu_s": 0.4, "mu_m": 1.2, "h10": 0.35, "v_m": 0.003}
    rng = np.random.default_rng(2)
    n = 200
    p = np.exp(rng.uniform(np.log(5e4), np.log(5e5), n))
    v = np.exp(rng.uniform(np.log(1e-6), np.log(1.0), n))
    T = rng.choice([243.15, 263.15, 283.15, 303.15, 318.15], n)
    vals = park.resolve({**pk, "C1": 11.0, "C2": 120.0})
    mu = park.evaluate({"p": p, "v": v, "T": T}, vals)
    mu = mu + 0.02 * mu.mean() * rng.standard_normal(n)
    res = fit(park, {"p": p, "v": v, "T": T, "mu": mu}, free=["C1", "C2"])
    assert res.non_identifiable == []
    for k, true in {**pk, "C1": 11.0, "C2": 120.0}.items():
        est = res.params[k]
        assert abs(est.value - true) <= 3 * est.stderr, (k, est.value, est.stderr, true)


# -------------------------------------------------- fits from the guess alone

CASES = {
    "savkoor": ({"mu_s": 0.5, "mu_m": 1.3, "h10": 0.4, "v_m": 0.01, "n": -0.15},
                {"p": (2e4, 1e6), "v": (1e-6, 10.0)}),
    "nackenhorst": ({"A": 0.3, "n": -0.4, "b0": 0.7, "b1": 0.03, "b2": -0.004},
                    {"p": (2e4, 1e6), "v": (1e-4, 10.0)}),
    "huemer": ({"alpha": 0.15, "beta": 0.4, "n": 0.6, "m_v": 2.0, "b": 0.5, "c": 0.05},
               {"p": (1e5, 3e6), "v": (1e-3, 10.0)}),
    "wriggers": ({"a": 2e-6, "b": 8e4, "c": 0.4, "d": 1.5e-5},
                 {"p": (2e4, 1e6), "v": (1e-3, 10.0)}),
    "park": ({"n": 1 / 9, "mu_s": 0.4, "mu_m": 1.2, "h10": 0.35, "v_m": 0.003},
             {"p": (5e4, 5e5), "v": (1e-5, 1.0), "T": (243.15, 313.15)}),
}


def fit_from_guess(law, data):
    """A plain lmfit least-squares fit started only from ``law.initial_guess``."""
    settings = law.setting_values
    guess = law.initial_guess(data)
    params = lmfit.Parameters()
    for p in law.params:
        lo, hi = p.bounds
        params.add(p.name, value=guess[p.name], min=lo, max=hi)

    def resid(pars):
        vals = {**settings, **{k: pars[k].value for k in law.param_names}}
        return law.evaluate({v: data[v] for v in law.variables}, vals) - data["mu"]

    return guess, lmfit.minimize(resid, params, method="least_squares")


@pytest.mark.parametrize("law_id", sorted(CASES))
@pytest.mark.parametrize("seed", [11, 12])
def test_fit_from_the_guess_alone_recovers_the_truth(law_id, seed):
    law = get_law(law_id)
    params, ranges = CASES[law_id]
    rng = np.random.default_rng(seed)
    x = {}
    for var, (lo, hi) in ranges.items():
        x[var] = (rng.uniform(lo, hi, 150) if var == "T"
                  else np.exp(rng.uniform(np.log(lo), np.log(hi), 150)))
    mu = law(**x, **params)
    guess, res = fit_from_guess(law, {**x, "mu": mu})
    true = law.resolve(params)
    for k in law.param_names:
        assert res.params[k].value == pytest.approx(true[k], rel=1e-5, abs=1e-9), (
            k, guess[k], res.params[k].value, true[k])


def test_guess_of_nackenhorst_thesis_is_an_equivalent_coefficient_set():
    thesis = get_law("nackenhorst-thesis")
    c = {"c1": 0.3, "c2": 1.2e5, "c3": -0.4, "c4": 0.06, "c5": 1e-5, "c6": 0.03, "c7": 1e-3}
    data = _pv_grid_data(thesis, c, noise=0.0)
    g = thesis.initial_guess(data)
    pred = thesis(p=data["p"], v=data["v"], **g)
    np.testing.assert_allclose(pred, data["mu"], atol=2e-3)


def test_cli_fit_names_non_identifiable_nackenhorst_parameters(tmp_path, capsys):
    from frictionlaws.cli import main

    thesis = get_law("nackenhorst-thesis")
    c = {"c1": 0.3, "c2": 1.2e5, "c3": -0.4, "c4": 0.06, "c5": 1e-5, "c6": 0.03, "c7": 1e-3}
    data = _pv_grid_data(thesis, c)
    path = tmp_path / "pv.csv"
    lines = ["mu,p [MPa],v [m/s]"] + [f"{m:.6f},{p / 1e6:g},{v:.6g}"
                                      for m, p, v in zip(data["mu"], data["p"], data["v"])]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    assert main(["fit", "--law", "nackenhorst-thesis", str(path)]) == 0
    out = capsys.readouterr().out
    assert "the data cannot determine c1, c2, c4, c5, c6, c7" in out
    assert main(["fit", "--law", "nackenhorst", str(path), "--fix", "b2=0"]) == 0
    out = capsys.readouterr().out
    assert "cannot" not in out and "not identifiable" not in out
    # a slip law on the same sliding data: exit code 2 and a one-line reason
    assert main(["fit", "--law", "pacejka", str(path)]) == 2
    err = capsys.readouterr().err
    assert "needs the slip ratio s" in err and "Traceback" not in err
