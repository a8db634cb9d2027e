"""Where Persson's theory is defined: temperature, pressure and velocity limits, and P(q).

The theory refuses temperatures outside the material's data and pressures <= 0,
in calls, fits and exported boxes alike; at v = 0 it gives the true static
limit (the viscoelastic part vanishes), not the value at a velocity floor;
contact_ratio(q) is P at q itself.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad
from scipy.special import erf

import frictionlaws as fl
from frictionlaws.base.errors import DomainError, InputError
from frictionlaws.persson import (
    asphalt_like,
    check_conditions,
    contact_ratio,
    friction,
    modulus_sq_angular,
    tread_compound,
)

SURF = asphalt_like(1e6)
LAW = fl.get_law("persson")
T_LO, T_HI = tread_compound().temperature_range()


@settings(max_examples=40, deadline=None)
@given(T=st.one_of(st.floats(0.0, T_LO * (1 - 1e-9)), st.floats(T_HI * (1 + 1e-9), 1e4)))
def test_temperature_outside_the_data_is_refused(T):
    with pytest.raises(DomainError, match="outside|must be > 0 K"):
        LAW(p=2e5, v=0.01, T=T, preset="tread-on-asphalt")
    with pytest.raises(DomainError, match="outside the temperatures"):
        friction(tread_compound(), SURF, 0.01, T, 2e5)


@settings(max_examples=40, deadline=None)
@given(p=st.floats(-1e9, 0.0))
def test_pressure_at_or_below_zero_is_refused(p):
    with pytest.raises(DomainError):
        LAW(p=p, v=0.01, T=293.15, preset="tread-on-asphalt")
    with pytest.raises(DomainError, match="must be > 0"):
        friction(tread_compound(), SURF, 0.01, 293.15, p)


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
@pytest.mark.parametrize("name", ["v", "T", "p"])
def test_non_finite_conditions_are_refused(name, bad):
    kw = {"v": 0.01, "T": 293.15, "p": 2e5}
    kw[name] = np.array([kw[name], bad])
    with pytest.raises(InputError, match=f"{name} has a non-finite value"):
        check_conditions(tread_compound(), **kw)


def test_the_material_range_is_the_laws_domain():
    assert LAW.strict_domain
    assert LAW.domain["T"] == pytest.approx((243.15, 343.15))
    # the edges themselves are inside
    mu = LAW(p=2e5, v=np.array([0.01, 0.01]), T=np.array([T_LO, T_HI]),
             preset="tread-on-asphalt")
    assert np.all(np.isfinite(mu))


def test_zero_velocity_is_the_static_limit_not_the_maximum():
    v = np.concatenate([[0.0], np.logspace(-12, 4, 161)])
    mu = LAW(p=np.full(v.size, 2e5), v=v, T=np.full(v.size, 293.15), q1=1e6, mu_a=0.25)
    assert mu[0] == 0.25
    assert mu[0] < mu[1:].max() - 1.0
    # the viscoelastic part falls linearly in v towards the limit
    small = friction(tread_compound(), SURF, np.array([1e-14, 2e-14]), 293.15, 2e5)
    assert small[1] / small[0] == pytest.approx(2.0, rel=1e-3)
    assert friction(tread_compound(), SURF, -0.0, 293.15, 2e5) == 0.0
    # negative velocities are magnitudes
    assert friction(tread_compound(), SURF, -0.3, 293.15, 2e5) == pytest.approx(
        friction(tread_compound(), SURF, 0.3, 293.15, 2e5))


def _G_by_quad(mat, surf, v, T, p, q):
    e = (1 - mat.nu**2) * p
    aT = 10.0 ** float(mat.shift(T))

    def f(s):
        qq = math.exp(s)
        F = float(modulus_sq_angular(mat, qq * v * aT))
        return qq**4 * float(surf.C(qq)) * F / (8 * e * e)

    return quad(f, math.log(surf.q0), math.log(q), epsabs=0, epsrel=1e-10, limit=200)[0]


@pytest.mark.parametrize("q", [2e3, 5e4, 1e6, 3.7e6])
def test_contact_ratio_is_P_at_q_itself(q):
    mat = tread_compound()
    P = float(contact_ratio(mat, SURF, 0.01, 293.15, 2e5, [q])[0])
    expect = erf(1 / (2 * math.sqrt(_G_by_quad(mat, SURF, 0.01, 293.15, 2e5, q))))
    assert P == pytest.approx(expect, rel=1e-6)


def test_contact_ratio_at_and_below_q0_is_one():
    P = contact_ratio(tread_compound(), SURF, 0.01, 293.15, 2e5, [SURF.q0 / 2, SURF.q0])
    assert np.all(P == 1.0)


def _csv(tmp_path, rows):
    path = tmp_path / "d.csv"
    path.write_text("p [MPa],v [m/s],T [degC],mu\n" + "".join(
        f"{p},{v},{T},{mu}\n" for p, v, T, mu in rows))
    return path


def test_fit_refuses_rows_outside_the_domain_naming_them(tmp_path):
    good = [(0.2, 10.0 ** k, 20.0, 1.0 + 0.1 * k) for k in range(-4, 1)]
    for bad in [(0.2, 0.01, -253.0, 1.0), (0.0, 0.01, 20.0, 1.0)]:
        path = _csv(tmp_path, good + [bad])
        with pytest.raises(InputError, match=r"rows 7\b.*outside"):
            fl.fit("persson", path)


def test_cli_refuses_out_of_domain_exports_and_fits(tmp_path, capsys):
    from frictionlaws.cli import main

    out = tmp_path / "t.csv"
    for box in (["--T", "20K:300K:3", "--p", "0.2MPa:0.2MPa:1"],
                ["--T", "0degC:30degC:3", "--p", "0MPa:0.2MPa:2"]):
        rc = main(["export", "--law", "persson", "--preset", "tread-on-asphalt", "--format",
                   "csv", "--v", "0:1:3", *box, "-o", str(out)])
        err = capsys.readouterr().err
        assert rc == 2 and not out.exists(), err
        assert err.count("\n") == 1 and "Traceback" not in err
    path = _csv(tmp_path, [(0.2, 0.01, -253.0, 1.0), (0.2, 0.1, 20, 1.1),
                           (0.2, 1.0, 20, 1.2)])
    assert main(["fit", "--law", "persson", str(path)]) == 2
    assert "T -30..70 degC" in capsys.readouterr().err


@pytest.mark.slow
def test_export_from_zero_velocity_writes_the_static_limit(tmp_path):
    from frictionlaws.cli import main

    out = tmp_path / "t.csv"
    assert main(["export", "--law", "persson", "--set", "q1=1e6,mu_a=0.2", "--format",
                 "csv", "--v", "0:1:3", "--T", "20degC:20degC:1", "--p", "0.2MPa:0.2MPa:1",
                 "-o", str(out)]) == 0
    rows = [ln.split(",") for ln in out.read_text().splitlines()
            if ln and not ln.startswith("#") and not ln.startswith("p")]
    assert float(rows[0][1]) == 0.0 and float(rows[0][3]) == pytest.approx(0.2)


def test_a_temperature_in_degC_is_named_as_such():
    with pytest.raises(DomainError, match="if it is in degC, 20 degC is 293.15 K"):
        friction(tread_compound(), SURF, 0.01, 20.0, 2e5)


@pytest.mark.parametrize("T_range", [(300.0, 290.0), (0.0, 300.0), (math.nan, 300.0),
                                     (300.0,), "warm"])
def test_a_bad_declared_range_is_refused(T_range):
    from dataclasses import replace

    mat = replace(tread_compound(), T_range=T_range)
    with pytest.raises(InputError, match="T_range"):
        friction(mat, SURF, 0.01, 293.15, 2e5)


def test_a_one_temperature_material_is_held_to_that_temperature():
    from dataclasses import replace

    from frictionlaws.laws.persson import persson_law

    mat = replace(tread_compound(), T_range=(373.15, 373.15))
    law = persson_law(mat, id="persson-hot")
    assert law.domain["T"] == (373.15, 373.15) and law.typical["T"] == (373.15, 373.15)
    assert np.isfinite(law(p=2e5, v=0.01, T=373.15, q1=1e6, mu_a=0.0))
    with pytest.raises(DomainError):
        law(p=2e5, v=0.01, T=372.0, q1=1e6, mu_a=0.0)


@pytest.mark.parametrize("q", [math.nan, math.inf])
def test_contact_ratio_refuses_a_non_finite_wavenumber(q):
    with pytest.raises(InputError, match="finite wavenumbers"):
        contact_ratio(tread_compound(), SURF, 0.01, 293.15, 2e5, [1e4, q])


def test_sliding_that_excites_only_unmeasured_frequencies_is_warned():
    import warnings

    from frictionlaws.base.errors import ExtrapolationWarning
    from frictionlaws.persson import default_material

    mat = default_material()  # measured sweeps: a finite band of reduced frequencies
    lo, hi = mat.omega_range
    with pytest.warns(ExtrapolationWarning, match=r"1 of 2 conditions.*v = 1e\+04 m/s"):
        friction(mat, SURF, np.array([0.01, 1e4]), 293.15, 2e5)
    assert SURF.q0 * 1e4 * 10 ** float(mat.shift(293.15)) > hi
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        friction(mat, SURF, np.array([0.0, 1e-6, 0.01]), 293.15, 2e5)
        # the packaged compound is a function of frequency: nothing is extrapolated
        assert tread_compound().omega_range is None
        friction(tread_compound(), SURF, np.array([1e-8, 1e4]), 293.15, 2e5)


@settings(max_examples=20, deadline=None, derandomize=True)
@given(q1=st.one_of(st.floats(1.0, SURF.q0), st.just(math.inf), st.just(math.nan)))
def test_a_cut_off_at_or_below_q0_or_unbounded_is_refused_not_zero(q1):
    with pytest.raises(InputError, match="q1 = .* must be finite and exceed"):
        friction(tread_compound(), SURF, 0.01, 293.15, 2e5, q1=q1)


def test_a_surface_without_a_cut_off_needs_one_from_the_call():
    from frictionlaws.persson import SelfAffine

    open_ended = SelfAffine.from_rms(SURF.q0, SURF.H, 3e-4)  # q1 = inf
    with pytest.raises(InputError, match="give q1"):
        friction(tread_compound(), open_ended, 0.01, 293.15, 2e5)
    assert friction(tread_compound(), open_ended, 0.01, 293.15, 2e5, q1=1e6) == pytest.approx(
        friction(tread_compound(), SURF, 0.01, 293.15, 2e5), rel=1e-12)


@pytest.mark.parametrize("q0", [0.0, -1.0, 1e-300, math.inf, math.nan])
def test_a_surface_from_its_rms_height_refuses_a_bad_q0(q0):
    from frictionlaws.persson import SelfAffine

    with pytest.raises(InputError, match="q0 = .* positive wavenumber"):
        SelfAffine.from_rms(q0, 0.8, 3e-4)


@pytest.mark.parametrize(("order", "panels"), [(0, 2.0), (2.5, 2.0), (True, 2.0), (10, 0.0),
                                               (10, -1.0), (10, 1e9), (10, math.nan)])
def test_a_quadrature_rule_that_is_none_or_unbounded_is_refused(order, panels):
    with pytest.raises(InputError, match="order|panels_per_decade"):
        friction(tread_compound(), SURF, 0.01, 293.15, 2e5, order=order,
                 panels_per_decade=panels)


@pytest.mark.slow
@settings(max_examples=3, deadline=None, derandomize=True)
@given(edge=st.sampled_from(["low", "high", "both"]))
def test_compare_scans_a_strict_domain_law_only_inside_its_domain(edge, tmp_path_factory):
    from frictionlaws.comparison import compare

    temps = {"low": (T_LO, T_LO + 20.0), "high": (T_HI - 20.0, T_HI), "both": (T_LO, T_HI)}[edge]
    v = np.logspace(-4, 1, 5)
    rows = {"p": [], "v": [], "T": [], "mu": []}
    for T in temps:
        for p in (1e5, 3e5):
            mu = LAW(p=p, v=v, T=T, q1=3e5, mu_a=0.1)
            rows["p"] += [p] * v.size
            rows["v"] += list(v)
            rows["T"] += [T] * v.size
            rows["mu"] += list(mu + 0.005 * np.sin(np.arange(v.size) + p / 1e5))
    data = {k: np.asarray(x, float) for k, x in rows.items()}
    cmp = compare(["persson", "coulomb"], data, folds=3)
    assert cmp.box["T"][0] < T_LO or cmp.box["T"][1] > T_HI  # the data's box leaves it
    scan = cmp["persson"].plausibility
    assert math.isfinite(scan.mu_min) and math.isfinite(scan.mu_max)
