"""Tyre slip laws: Pacejka, Burckhardt, Burckhardt-sqrt, Kiencke-Daiss, Germann.

The presets must reproduce the peaks printed in laws.md (to 0.01), computed here
by a dense numerical search, independently of the laws' derived quantities,
which are checked against the same search.
"""

from __future__ import annotations

import lmfit
import numpy as np
import pytest

from frictionlaws import fit, get_law
from frictionlaws.base.errors import DomainError

S = np.linspace(0.0, 1.0, 1_000_001)

# laws.md: Burckhardt derived peaks (slip, mu)
BURCKHARDT_PEAKS = {
    "asphalt-dry": (0.170, 1.17),
    "asphalt-wet": (0.131, 0.80),
    "concrete-dry": (0.160, 1.09),
    "cobblestone-dry": (0.400, 1.00),
    "cobblestone-wet": (0.140, 0.38),
    "snow": (0.060, 0.19),
}
# laws.md: Pacejka derived peaks (slip, mu)
PACEJKA_PEAKS = {"dry": (0.180, 1.00), "wet": (0.088, 0.82), "snow": (0.31, 0.30),
                 "ice": (0.39, 0.10)}


def numerical_peak(mu):
    i = int(np.argmax(mu))
    return S[i], mu[i]


@pytest.mark.parametrize("road", sorted(BURCKHARDT_PEAKS))
def test_burckhardt_presets_reproduce_the_published_peaks(road):
    law = get_law("burckhardt")
    s_pk, mu_pk = numerical_peak(law(s=S, v=0.0, preset=road))
    s_ref, mu_ref = BURCKHARDT_PEAKS[road]
    assert s_pk == pytest.approx(s_ref, abs=0.01)
    assert mu_pk == pytest.approx(mu_ref, abs=0.01)
    d = law.derived_values(law.resolve(preset=road))
    assert d["s_peak"] == pytest.approx(s_pk, abs=2e-6)
    assert d["mu_peak"] == pytest.approx(mu_pk, abs=1e-9)
    assert d["mu_locked"] == pytest.approx(law(s=1.0, v=0.0, preset=road), rel=1e-12)


def test_burckhardt_asphalt_dry_locked_wheel_and_ice():
    law = get_law("burckhardt")
    assert law(s=1.0, v=0.0, preset="asphalt-dry") == pytest.approx(0.76, abs=0.005)
    # ice: no interior peak, mu rises to c1 = 0.05
    mu = law(s=S, v=0.0, preset="ice")
    assert np.all(np.diff(mu) >= 0)
    assert mu[-1] == pytest.approx(0.05, abs=1e-9)
    d = law.derived_values(law.resolve(preset="ice"))
    assert d["s_peak"] == 1.0 and d["mu_peak"] == pytest.approx(0.05)
    # the velocity factor
    assert law(s=0.2, v=20.0, preset="asphalt-dry", c4=0.03) == pytest.approx(
        law(s=0.2, v=0.0, preset="asphalt-dry") * np.exp(-0.6))
    assert len(law.presets) == 7


@pytest.mark.parametrize("surface", sorted(PACEJKA_PEAKS))
def test_pacejka_presets_reproduce_the_published_peaks(surface):
    law = get_law("pacejka")
    mu = law(s=S, preset=surface)
    s_pk, mu_pk = numerical_peak(mu)
    s_ref, mu_ref = PACEJKA_PEAKS[surface]
    assert s_pk == pytest.approx(s_ref, abs=0.01)
    assert mu_pk == pytest.approx(mu_ref, abs=0.01)
    d = law.derived_values(law.resolve(preset=surface))
    assert d["s_peak"] == pytest.approx(s_pk, abs=2e-6)
    assert d["mu_peak"] == pytest.approx(mu_pk, abs=1e-9)
    # slope at the origin is B C D
    h = 1e-7
    slope = (law(s=h, preset=surface) - law(s=-h, preset=surface)) / (2 * h)
    assert d["BCD"] == pytest.approx(slope, rel=1e-6)


def test_pacejka_peak_with_shifts_and_without_interior_peak():
    law = get_law("pacejka")
    p = {"B": 10.0, "C": 1.9, "D": 1.0, "E": 0.97, "S_h": 0.02, "S_v": 0.05}
    d = law.derived_values(law.resolve(p))
    s_pk, mu_pk = numerical_peak(law(s=S, **p))
    assert d["s_peak"] == pytest.approx(s_pk, abs=2e-6)
    assert d["mu_peak"] == pytest.approx(1.05) and mu_pk == pytest.approx(1.05)
    # C <= 1: sin never turns over; the largest value on 0..1 is at s = 1
    p1 = {"B": 5.0, "C": 1.0, "D": 0.8, "E": 0.5}
    d1 = law.derived_values(law.resolve(p1))
    assert d1["s_peak"] == 1.0
    assert d1["mu_peak"] == pytest.approx(law(s=1.0, **p1))


def test_burckhardt_sqrt_and_kiencke_daiss_peaks():
    bs = get_law("burckhardt-sqrt")
    p = {"c1": 1.6, "c2": 1.2}
    d = bs.derived_values(bs.resolve(p))
    s_pk, mu_pk = numerical_peak(bs(s=S, **p))
    assert d["s_peak"] == pytest.approx((1.6 / 2.4) ** 2) == pytest.approx(s_pk, abs=2e-6)
    assert d["mu_peak"] == pytest.approx(1.6**2 / 4.8) == pytest.approx(mu_pk, abs=1e-9)
    # peak beyond s = 1: clipped to the domain
    d2 = bs.derived_values(bs.resolve({"c1": 3.0, "c2": 1.0}))
    assert d2["s_peak"] == 1.0 and d2["mu_peak"] == pytest.approx(2.0)

    kd = get_law("kiencke-daiss")
    p = {"k_s": 20.0, "c1": 30.0, "c2": 5.0}
    d = kd.derived_values(kd.resolve(p))
    s_pk, mu_pk = numerical_peak(kd(s=S, **p))
    assert d["s_peak"] == pytest.approx(1 / np.sqrt(30)) == pytest.approx(s_pk, abs=2e-6)
    assert d["mu_peak"] == pytest.approx(20 / (2 * np.sqrt(30) + 5))
    assert d["mu_peak"] == pytest.approx(mu_pk, abs=1e-9)
    # initial slope k_s
    assert kd(s=1e-8, **p) / 1e-8 == pytest.approx(20.0, rel=1e-6)


def test_kiencke_daiss_admissibility():
    kd = get_law("kiencke-daiss")
    assert kd.check_admissible({"k_s": 20, "c1": 30, "c2": 5}) is None
    # vertex inside (0, 1) with a negative minimum: 1 - c2^2/(4 c1) < 0
    msg = kd.check_admissible({"k_s": 20, "c1": 4.0, "c2": -5.0})
    assert msg and "pole" in msg
    s = np.linspace(0, 1, 10001)
    assert np.min(4.0 * s**2 - 5.0 * s + 1) < 0
    # the minimum at s = 1: 1 + c2 + c1 <= 0
    assert kd.check_admissible({"k_s": 20, "c1": 0.1, "c2": -1.5})
    # a negative c2 that keeps the denominator positive is fine
    assert kd.check_admissible({"k_s": 20, "c1": 30.0, "c2": -10.0}) is None


def test_germann_domain_is_pre_peak():
    law = get_law("germann")
    assert law.domain["s"] == (0.0, 0.3)
    s = np.linspace(0, 0.6, 40)
    mu = law.evaluate({"s": s}, law.resolve({"a0": 0.0, "a1": 8.0, "a2": -15.0}))
    with pytest.raises(DomainError, match="outside the law's slip domain"):
        law(s=s, a0=0.0, a1=8.0, a2=-15.0)
    res = fit(law, {"s": s, "mu": mu})
    assert any("outside the law's valid domain of s" in w for w in res.warnings)
    assert law.outside_domain({"s": s}) == {"s": int(np.sum(s > 0.3))}


def test_slip_law_without_slip_fails_clearly():
    data = {"p": np.full(10, 1e5), "v": np.linspace(0.1, 2, 10), "mu": np.full(10, 0.8)}
    for law_id in ("pacejka", "burckhardt", "burckhardt-sqrt", "kiencke-daiss", "germann"):
        with pytest.raises(DomainError, match="slip law .* needs the slip ratio s") as exc:
            fit(law_id, data)
        assert law_id in str(exc.value)
        assert "pure-sliding tribometer data cannot determine it" in str(exc.value)


def test_burckhardt_single_speed_cannot_determine_c4():
    law = get_law("burckhardt")
    s = np.linspace(0.01, 1, 40)
    mu = law(s=s, v=10.0, preset="asphalt-dry", c4=0.02)
    res = fit(law, {"s": s, "v": np.full(40, 10.0), "mu": mu})
    assert any("single value of v" in w for w in res.warnings)
    # d mu/d c4 = -v mu is a combination of d mu/d c1 and d mu/d c3 at one speed; the fitter
    # names c4 (as non-identifiable, or as poorly determined when c4 ends at its bound 0)
    named = set(res.non_identifiable) | {
        n for w in res.warnings if "poorly determined" in w
        for n in w.split(" poorly")[0].replace(",", " ").split()}
    assert "c4" in named, res.warnings
    # fixed c4 = 0 the remaining three are determined (c1 absorbs exp(-c4 v))
    res0 = fit(law, {"s": s, "v": np.full(40, 10.0), "mu": mu}, fix={"c4": 0.0})
    assert res0.non_identifiable == []
    assert res0.params["c1"].value == pytest.approx(1.2801 * np.exp(-0.2), rel=1e-6)


def test_pacejka_C_E_trade_off_is_documented_and_real():
    """With E free, a second minimum (C near 1.3, E near 0) fits noisy dry-road data.

    The fitter returns whichever has the lower chi-square; it is never worse than the
    true parameters, so the law (not the optimiser) is at fault, as its notes say.
    """
    law = get_law("pacejka")
    assert "C and E trade off" in law.notes
    s = np.linspace(0, 1, 60)
    mu_true = law(s=s, preset="dry")
    wrong_basin = 0
    for seed in range(6):
        mu = mu_true * (1 + 0.02 * np.random.default_rng(seed).standard_normal(60))
        res = fit(law, {"s": s, "mu": mu}, fix={"S_h": 0.0, "S_v": 0.0})
        assert res.metrics["chisqr"] <= np.sum((mu - mu_true) ** 2) * (1 + 1e-9)
        wrong_basin += res.params["C"].value < 1.6
    assert wrong_basin >= 1


@pytest.mark.parametrize("surface", ["dry", "wet", "snow", "ice"])
def test_pacejka_guess_alone_recovers_each_preset(surface):
    law = get_law("pacejka")
    s = np.linspace(0, 1, 80)
    mu = law(s=s, preset=surface)
    g = law.initial_guess({"s": s, "mu": mu})
    params = lmfit.Parameters()
    for p in law.params:
        if p.name in ("S_h", "S_v"):
            params.add(p.name, value=0.0, vary=False)
        else:
            params.add(p.name, value=g[p.name], min=p.bounds[0], max=p.bounds[1])
    res = lmfit.minimize(lambda q: law(s=s, **q.valuesdict()) - mu, params,
                         method="least_squares")
    for k, v in law.presets[surface].items():
        assert res.params[k].value == pytest.approx(v, rel=1e-3), (k, g[k])


@pytest.mark.parametrize("law_id,params,ranges", [
    ("burckhardt", {"c1": 1.2801, "c2": 23.99, "c3": 0.52, "c4": 0.03},
     {"s": (0.0, 1.0), "v": (2.0, 40.0)}),
    ("burckhardt-sqrt", {"c1": 1.6, "c2": 1.2}, {"s": (0.0, 1.0)}),
    ("kiencke-daiss", {"k_s": 20.0, "c1": 30.0, "c2": 5.0}, {"s": (0.0, 1.0)}),
    ("germann", {"a0": 0.0, "a1": 8.0, "a2": -15.0}, {"s": (0.0, 0.3)}),
])
def test_slip_guess_alone_recovers_the_truth(law_id, params, ranges):
    law = get_law(law_id)
    rng = np.random.default_rng(5)
    x = {k: rng.uniform(lo, hi, 100) for k, (lo, hi) in ranges.items()}
    mu = law(**x, **params)
    g = law.initial_guess({**x, "mu": mu})
    pars = lmfit.Parameters()
    for p in law.params:
        pars.add(p.name, value=g[p.name], min=p.bounds[0], max=p.bounds[1])
    res = lmfit.minimize(lambda q: law(**x, **q.valuesdict()) - mu, pars,
                         method="least_squares")
    for k, v in params.items():
        assert res.params[k].value == pytest.approx(v, rel=1e-5, abs=1e-9)
