"""Persson's theory of rubber friction (frictionlaws.persson, law ``persson``).

Sources: Persson, J. Chem. Phys. 115 (2001) 3840; Persson et al., J. Phys.:
Condens. Matter 17 (2005) R1.  The fast implementation is checked against an
independent one (frictionlaws.validation.law_examples._persson: G and mu as an ODE
in ln q with adaptive steps, angular integrals by quadrature of the Prony sum).
"""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest
from scipy.integrate import trapezoid

import frictionlaws as fl
from frictionlaws.base.errors import InputError
from frictionlaws.persson import (
    Material,
    SelfAffine,
    Shift,
    asphalt_like,
    contact_ratio,
    default_material,
    fit_prony,
    friction,
    loss_angular,
    material_from_csv,
    psd_from_profile,
    psd_from_profile_csv,
    tread_compound,
)
from frictionlaws.validation.law_examples import _persson


def rubber(C1=8.86, C2=101.6, T_ref=293.15):
    """A rubber-like Prony series (tau 1e-9..1e-1 s, E 3 MPa -> 1.5 GPa) with WLF."""
    tau = 10.0 ** np.arange(-9.0, 0.0)
    E_i = np.array([3e8, 3e8, 3e8, 2.5e8, 1.5e8, 8e7, 4e7, 2e7, 1e7])
    return Material(3e6, E_i, tau, Shift(T_ref, C1=C1, C2=C2))


SURF = asphalt_like(1e6)


def reference(material, surface, v, T, p, q1, adaptive=False):
    M = None if adaptive else math
    return _persson(M, p, v, T, q1, 0.0, surface.q0, surface.H,
                    math.sqrt(math.pi * surface.C0 * surface.q0**2 / surface.H),
                    material=material)


# ------------------------------------------------------------------ against the reference


@pytest.mark.parametrize("material", ["rubber", "dma"])
def test_fast_agrees_with_reference_on_a_grid(material):
    mat = rubber() if material == "rubber" else default_material()
    worst = 0.0
    for v in (1e-4, 1e-2, 1.0):
        for T in (273.15, 313.15):
            for p in (5e4, 5e5):
                fast = friction(mat, SURF, v, T, p)
                ref = reference(mat, SURF, v, T, p, SURF.q1)
                worst = max(worst, abs(fast / ref - 1))
    print(f"{material}: largest relative difference on 12 points {worst:.2e}")
    assert worst < 1e-4
    assert worst < 1e-6            # what the guide states was found: a few 1e-7


def test_fast_agrees_with_adaptive_reference():
    mat = rubber()
    for v, T, p in ((1e-3, 293.15, 2e5), (0.3, 333.15, 1e6)):
        ref = reference(mat, SURF, v, T, p, SURF.q1, adaptive=True)
        assert friction(mat, SURF, v, T, p) == pytest.approx(ref, rel=1e-4)


def test_100_velocities_at_once():
    # the time is benchmarks/bench_persson.py's to measure, against a baseline
    mat = rubber()
    v = np.logspace(-8, 3, 100)
    mu = friction(mat, SURF, v, 293.15, 2e5)
    assert mu.shape == (100,) and np.all(np.isfinite(mu))


# ------------------------------------------------------------------------ limiting cases


def test_mu_vanishes_at_low_and_high_velocity_and_is_a_bell():
    mat = rubber()
    v = np.logspace(-12, 8, 81)
    mu = friction(mat, SURF, v, 293.15, 2e5)
    peak = int(np.argmax(mu))
    assert mu[0] < 1e-3 * mu[peak] and mu[-1] < 1e-2 * mu[peak]
    assert 5 < peak < 75
    # one maximum: rising before the peak, falling after it
    assert np.all(np.diff(mu[: peak + 1]) > 0) and np.all(np.diff(mu[peak:]) < 0)


def test_peak_shifts_by_the_wlf_factor():
    mat = rubber()
    from scipy.optimize import minimize_scalar

    def peak(T):
        r = minimize_scalar(lambda x: -friction(mat, SURF, 10.0**x, T, 2e5),
                            bounds=(-8, 4), method="bounded", options={"xatol": 1e-7})
        return r.x

    x0, x1 = peak(293.15), peak(313.15)
    expect = -mat.shift(313.15)  # warmer: a_T < 1, the peak moves to higher speed
    assert x1 - x0 == pytest.approx(float(expect), abs=1e-4)
    assert x1 > x0 + 1.0


def test_pressure_scaling():
    mat = rubber()
    # full contact (G << 1): P = 1 and mu ~ 1/p
    small = SelfAffine.from_rms(SURF.q0, 0.8, 1e-8, 1e4)
    mu = friction(mat, small, 0.01, 293.15, np.array([1e6, 2e6]))
    assert contact_ratio(mat, small, 0.01, 293.15, 1e6, [1e4])[0] > 0.999
    assert mu[0] / mu[1] == pytest.approx(2.0, rel=1e-3)
    # small contact (P << 1): P ~ 1/sqrt(pi G) ~ p, so P/p is constant and mu nearly not p
    P = contact_ratio(mat, SURF, 0.01, 293.15, np.array([1e4, 2e4]), [1e6])[:, 0]
    assert P[0] < 1e-2
    assert P[1] / P[0] == pytest.approx(2.0, rel=1e-3)
    mu = friction(mat, SURF, 0.01, 293.15, np.array([1e4, 2e4]))
    assert mu[1] / mu[0] == pytest.approx(1.0, abs=0.01)


def test_loss_angular_small_frequency_limit():
    mat = rubber()
    w = np.array([1e-6])
    # Im E ~ w sum(E_i tau_i); int cos^2 = pi
    assert loss_angular(mat, w)[0] == pytest.approx(math.pi * w[0] * np.sum(mat.E_i * mat.tau),
                                                    rel=1e-6)


# ------------------------------------------------------------------------------- material


def test_prony_fit_recovers_a_known_series():
    true = rubber()
    w = np.logspace(-3, 11, 60)
    E = true.modulus(w)
    E_inf, E_i, tau, rms = fit_prony(w, E.real, E.imag, per_decade=1.0, extend=1.0)
    assert np.all(E_i > 0) and E_inf >= 0 and rms < 1e-3
    fitted = Material(E_inf, E_i, tau, true.shift)
    np.testing.assert_allclose(fitted.modulus(w), E, rtol=5e-3)


def test_default_material_from_the_packaged_dma():
    mat = default_material()
    assert mat.E_inf > 0 and np.all(mat.E_i >= 0) and mat.rms_rel < 0.1
    assert mat.shift(mat.shift.T_ref) == pytest.approx(0.0, abs=1e-12)
    assert mat.shift(253.15) > 0 > mat.shift(333.15)
    assert "dma-pyvisco" in mat.summary()["source"]


def test_material_from_csv_with_units(tmp_path):
    d = fl.viscoelastic.mastercurve.load_dma_example()
    keep = np.isin(d["set"], np.arange(8, 14))
    lines = ["f [Hz],E_stor [MPa],E_loss [MPa],T [degC]"]
    for f, s, l_, T in zip(d["f"][keep], d["E_stor"][keep], d["E_loss"][keep], d["T"][keep]):
        lines.append(f"{float(f)!r},{float(s) / 1e6!r},{float(l_) / 1e6!r},{float(T) - 273.15!r}")
    path = tmp_path / "dma.csv"
    path.write_text("\n".join(lines) + "\n")
    mat = material_from_csv(path)
    assert mat.E_i.size > 3 and mat.rms_rel < 0.1 and mat.E_glassy > 1e9
    lines[5] = lines[5].replace(lines[5].split(",")[1], "abc")
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(InputError) as err:
        material_from_csv(path)
    assert err.value.column == "E_stor" and err.value.row is not None


def test_one_temperature_csv_needs_T_ref(tmp_path):
    path = tmp_path / "one.csv"
    w = np.logspace(-2, 3, 12)
    E = rubber().modulus(2 * np.pi * w)
    path.write_text("f [Hz],E_stor [Pa],E_loss [Pa]\n" + "".join(
        f"{float(f)!r},{float(e.real)!r},{float(e.imag)!r}\n" for f, e in zip(w, E)))
    with pytest.raises(InputError, match="T_ref"):
        material_from_csv(path)
    mat = material_from_csv(path, T_ref=293.15)
    assert mat.shift.C1 == 17.44


# -------------------------------------------------------------------------------- surface


def test_self_affine_rms():
    s = SelfAffine.from_rms(1e3, 0.8, 1e-4)
    assert s.rms() == pytest.approx(1e-4, rel=1e-12)
    q = np.logspace(3, 9, 20001)
    numeric = math.sqrt(2 * math.pi * trapezoid(q**2 * s.C(q), np.log(q)))
    assert numeric == pytest.approx(s.rms(1e9), rel=1e-4)
    with pytest.raises(InputError):
        SelfAffine(1e3, 1.2, 1e-10)


def synthetic_profile(H=0.8, n=2**16, dx=1e-5, C0=1e-15, q0=2e3, seed=0):
    """A random-phase line scan with the 1-D spectrum of a self-affine 2-D one (rms height
    about 0.12 mm, rms slope 1.3 over the scan's band: a road-like surface)."""
    from scipy.special import gamma

    rng = np.random.default_rng(seed)
    q = 2 * np.pi * np.fft.rfftfreq(n, dx)
    k1 = math.sqrt(math.pi) * gamma(H + 0.5) / gamma(H + 1)
    C1 = np.where(q >= q0, C0 * k1 * q0 ** (2 + 2 * H) * np.maximum(q, q0) ** (-1 - 2 * H), 0.0)
    C1[0] = 0
    amp = np.sqrt(C1 * 2 * np.pi * n / dx)
    spec = amp * np.exp(2j * np.pi * rng.random(q.size))
    h = np.fft.irfft(spec, n)
    return np.arange(n) * dx, h, SelfAffine(q0, H, C0)


def test_psd_from_profile_recovers_the_2d_spectrum():
    x, h, true = synthetic_profile()
    psd = psd_from_profile(x, h)
    mid = (psd.q > 2e4) & (psd.q < 1e5)
    ratio = psd.C_values[mid] / true.C(psd.q[mid])
    assert np.all(np.abs(np.log(ratio)) < math.log(1.3)), ratio


def test_psd_from_profile_csv(tmp_path):
    x, h, true = synthetic_profile(n=2**12)
    path = tmp_path / "profile.csv"
    path.write_text("x [mm],h [um]\n" + "".join(f"{float(a) * 1e3!r},{float(b) * 1e6!r}\n"
                                                for a, b in zip(x, h)))
    psd = psd_from_profile_csv(path)
    np.testing.assert_allclose(psd.C_values, psd_from_profile(x, h).C_values, rtol=1e-9)
    assert friction(rubber(), psd, 0.01, 293.15, 2e5) > 0
    bad = tmp_path / "uneven.csv"
    xs = np.concatenate([x[:100], x[101:]])
    bad.write_text("x [m],h [m]\n" + "".join(f"{float(a)!r},0.0\n" for a in xs))
    with pytest.raises(InputError, match="constant step"):
        psd_from_profile_csv(bad)


# ------------------------------------------------------------------------ the registry law


def test_law_matches_theory_and_has_a_symbolic_form():
    law = fl.get_law("persson")
    mu = law(p=2e5, v=0.01, T=293.15, preset="tread-on-asphalt")
    assert mu == pytest.approx(friction(tread_compound(), SURF, 0.01, 293.15, 2e5))
    assert r"\mu_{P}" in law.latex()


def test_fortran_export_is_refused():
    from frictionlaws.fe_export.fortran import require_closed_form

    with pytest.raises(InputError, match="no closed form"):
        require_closed_form(fl.get_law("persson"))
    require_closed_form(fl.get_law("savkoor"))


def _data_csv(tmp_path):
    law = fl.get_law("persson")
    rng = np.random.default_rng(3)
    n = 60
    p = np.exp(rng.uniform(np.log(5e4), np.log(5e5), n))
    v = np.exp(rng.uniform(np.log(1e-4), np.log(3.0), n))
    T = rng.uniform(273.15, 323.15, n)
    mu = law(p=p, v=v, T=T, q1=3e5, mu_a=0.3) + 0.003 * rng.standard_normal(n)
    path = tmp_path / "persson.csv"
    path.write_text("p [MPa],v [m/s],T [degC],mu\n" + "".join(
        f"{a / 1e6:.17g},{b:.17g},{c - 273.15:.17g},{d:.17g}\n" for a, b, c, d in zip(p, v, T, mu)))
    return path


@pytest.mark.slow
def test_cli_show_fit_export(tmp_path, capsys):
    from frictionlaws.cli import main

    assert main(["show", "persson"]) == 0
    out = capsys.readouterr().out
    assert "q1" in out and "mu_P" in out
    data = _data_csv(tmp_path)
    saved = tmp_path / "fit.json"
    assert main(["fit", "--law", "persson", str(data), "--json", "--save", str(saved)]) == 0
    res = json.loads(capsys.readouterr().out)
    params = res["params"]
    assert params["q1"]["value"] == pytest.approx(3e5, rel=0.1)
    assert params["mu_a"]["value"] == pytest.approx(0.3, abs=0.01)
    table = tmp_path / "table.csv"
    assert main(["export", "--params", str(saved), "--format", "csv", "--p", "0.1MPa:0.3MPa:3",
                 "--v", "0.001:1:4", "--T", "20degC:40degC:3", "-o", str(table)]) == 0
    assert table.exists()
    capsys.readouterr()
    sub = tmp_path / "sub.f"
    assert main(["export", "--law", "persson", "--preset", "tread-on-asphalt", "--format",
                 "abaqus-fric-coef", "--v", "0:10", "-o", str(sub)]) == 2
    err = capsys.readouterr().err
    assert "export a table" in err and not sub.exists()


def test_the_report_keeps_its_columns_with_long_setting_names():
    law = fl.get_law("persson")
    v = np.logspace(-3, 0, 6)
    mu = law(p=2e5, v=v, T=293.15, q1=3e5, mu_a=0.1) + 0.005 * np.cos(7 * v)
    res = fl.fit("persson", {"p": np.full(6, 2e5), "v": v, "T": np.full(6, 293.15), "mu": mu})
    lines = res.report().splitlines()
    start = next(i for i, ln in enumerate(lines) if ln.startswith("parameter"))
    table = lines[start:start + 1 + len(res.params) + len(res.settings)]
    assert any(ln.startswith("heat_fraction ") for ln in table)
    ends = {re.match(r"\S+\s+\S+", ln).end() for ln in table}  # name, then value
    assert len(ends) == 1  # every value ends under the header's "value"
