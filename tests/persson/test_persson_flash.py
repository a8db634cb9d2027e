"""The flash temperature of Persson (2006): its limits, its scalings and its solution.

Persson, J. Phys.: Condens. Matter 18 (2006) 7789; the closures are stated in
frictionlaws/persson/flash.py.  What must hold:

* no heat (heat_fraction = 0) is the isothermal theory exactly, whatever else is set;
* at low speed diffusion wins: the rise grows as v and scales as 1/kappa, not with rho c;
* at high speed the heat has no time to diffuse: for a given dissipation the rise
  levels off (it grew as sqrt(v) in the surface-flux closure) and scales as 1/(rho c);
* the rise is proportional to the heat fraction;
* for the same dissipation the surface-flux closure heats at least as much at every scale
  (it is the upper bound);
* the background heating adds 2 heat_fraction mu p sqrt(L v / (pi kappa rho c));
* the quadrature grids and the iteration's tolerance are converged.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import frictionlaws as fl
from frictionlaws.base.errors import DomainError, ExtrapolationWarning
from frictionlaws.persson import (
    TREAD_THERMAL,
    Flash,
    asphalt_like,
    flash_temperature,
    friction,
    tread_compound,
)
from frictionlaws.persson.flash import background_rise, temperature_rise
from frictionlaws.persson.published import V_GRID, peak
from frictionlaws.persson.theory import q_nodes

GUIDE = Path(__file__).resolve().parents[2] / "docs" / "user-guide" / "persson.rst"

SURF = asphalt_like(1e6)
MAT = tread_compound()
V = np.logspace(-8, 2, 41)
T20, P = 293.15, 2e5


def _rise(flash, v, T=T20, p=P, **kw):
    """T_q - T (points x nodes) and the nodes, the extrapolation warning silenced."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        q, Tq = flash_temperature(MAT, SURF, v, T, p, flash=flash, **kw)
    return Tq - T, q


def _dissipation(v, T=T20, p=P):
    """The isothermal friction integrand and P(q) of the tread compound (points x nodes)."""
    from frictionlaws.persson import theory

    q, w, cum = q_nodes(SURF.q0, SURF.q1)
    grid = theory._Grid(q, w, cum, q**4 * SURF.C(q))
    v = np.asarray(v, float)
    dmu, Pq = theory._integrand(MAT, SURF, v, np.full(v.size, T), np.full(v.size, p), grid,
                                1.0)
    return q, w, cum, dmu, Pq


# ------------------------------------------------------------ the isothermal limit


@pytest.mark.parametrize("flash", [
    Flash(heat_fraction=0.0),
    Flash(heat_fraction=0.0, contact_temperature="exit", sliding_distance=1.0),
    Flash(heat_fraction=0.0, closure="surface-flux", conductivity=0.01, heat_capacity=1e5),
])
def test_no_heat_is_the_isothermal_curve_exactly(flash):
    iso = friction(MAT, SURF, V, T20, P)
    assert np.array_equal(friction(MAT, SURF, V, T20, P, flash=flash), iso)
    rise, _ = _rise(flash, V)
    assert np.all(rise == 0.0)


def test_no_heat_through_the_law_is_the_isothermal_law_exactly():
    law = fl.get_law("persson")
    kw = {"p": np.full(V.size, P), "v": V, "T": np.full(V.size, T20),
          "preset": "tread-on-asphalt"}
    assert np.array_equal(law(heat_fraction=0.0, **kw), law(**kw))


# ------------------------------------------------ the kernel: limits for a given dissipation


def test_low_speed_diffusion_wins_rise_grows_as_v_and_scales_as_one_over_kappa():
    q, w, cum, dmu, Pq = _dissipation([1e-3])
    p = np.array([P])

    def rise(flash, v):
        return temperature_rise(flash, q, w, cum, dmu, Pq, np.array([v]), p)[0]

    base = rise(Flash(), 1e-9)
    # the diffusive limit: each band adds heat_fraction p v dmu / (P kappa q)
    band = P * 1e-9 * dmu[0] / (Pq[0] * 0.25 * q)
    assert base == pytest.approx((band / w) @ cum.T, rel=1e-4)
    assert rise(Flash(), 2e-9) == pytest.approx(2 * base, rel=1e-4)
    assert rise(Flash(conductivity=0.5), 1e-9) == pytest.approx(base / 2, rel=1e-4)
    assert rise(Flash(heat_capacity=3.6e6), 1e-9) == pytest.approx(base, rel=1e-4)
    assert rise(Flash(contact_temperature="exit"), 1e-9) == pytest.approx(base, rel=1e-4)


@pytest.mark.parametrize(("how", "share"), [("mean", 0.5), ("exit", 1.0)])
def test_high_speed_the_rise_levels_off_and_scales_as_one_over_rho_c(how, share):
    q, w, cum, dmu, Pq = _dissipation([1.0])
    p = np.array([P])

    def rise(flash, v):
        return temperature_rise(flash, q, w, cum, dmu, Pq, np.array([v]), p)[0]

    flash = Flash(contact_temperature=how)
    # no time to diffuse: each band keeps its heat, heat_fraction pi p dmu / (P rho c)
    band = share * math.pi * P * dmu[0] / (Pq[0] * 1.8e6)
    assert rise(flash, 1e6) == pytest.approx((band / w) @ cum.T, rel=1e-4)
    assert rise(flash, 1e7) == pytest.approx(rise(flash, 1e6), rel=1e-4)
    assert rise(replace(flash, heat_capacity=3.6e6), 1e6) == pytest.approx(
        rise(flash, 1e6) / 2, rel=1e-4)
    assert rise(replace(flash, conductivity=0.5), 1e6) == pytest.approx(rise(flash, 1e6),
                                                                         rel=1e-4)
    # the surface flux (a sliding disc) keeps growing, as sqrt(v)
    sf = Flash(closure="surface-flux")
    assert rise(sf, 1e7)[-1] / rise(sf, 1e6)[-1] == pytest.approx(math.sqrt(10), rel=1e-3)


@pytest.mark.parametrize(("T", "p"), [(253.15, 2e5), (293.15, 2e5), (313.15, 1e6),
                                      (293.15, 1e4)])
def test_the_surface_flux_closure_bounds_the_volume_closure_at_every_scale(T, p):
    v = np.logspace(-8, 3, 23)
    q, w, cum, dmu, Pq = _dissipation(v, T, p)
    pp = np.full(v.size, p)
    bound = temperature_rise(Flash(closure="surface-flux"), q, w, cum, dmu, Pq, v, pp)
    for how in ("mean", "exit"):
        vol = temperature_rise(Flash(contact_temperature=how), q, w, cum, dmu, Pq, v, pp)
        assert np.all(vol >= 0) and np.all(bound >= vol)
        assert np.all(np.diff(vol, axis=1) >= -1e-12 * vol.max())    # hotter at finer scales


def test_background_heating_is_constant_flux_on_a_half_space():
    mu, v, p = np.array([1.2, 0.5]), np.array([1.0, 0.01]), np.array([2e5, 1e6])
    flash = Flash(sliding_distance=0.1, heat_fraction=0.5)
    expect = 2 * 0.5 * mu * p * np.sqrt(0.1 * v / (math.pi * 0.25 * 1.8e6))
    assert background_rise(flash, mu, v, p) == pytest.approx(expect, rel=1e-12)
    assert np.all(background_rise(Flash(), mu, v, p) == 0.0)


def test_the_share_a_layer_keeps_is_its_formula_and_finite_at_the_ends():
    from frictionlaws.persson.flash import _h

    x = np.logspace(-3, 3, 25)
    assert _h(x, "exit") == pytest.approx(-np.expm1(-x) / x, rel=1e-12)
    assert _h(x, "mean") == pytest.approx((x - 1 + np.exp(-x)) / x**2, rel=1e-9)
    ends = np.array([0.0, 1e-12, 1e300])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert _h(ends, "exit") == pytest.approx([1.0, 1.0, 1e-300])
        assert _h(ends, "mean") == pytest.approx([0.5, 0.5, 1e-300])


def test_at_rest_nothing_heats_and_nothing_is_warned():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        flash = Flash(sliding_distance=0.1)
        assert friction(MAT, SURF, 0.0, T20, P, flash=flash) == 0.0
        rise, _ = _rise(flash, 0.0)
    assert np.all(rise == 0.0)


# ------------------------------------------------------- the solution: scalings and limits


def test_the_rise_is_proportional_to_the_heat_fraction():
    r1, _ = _rise(Flash(heat_fraction=0.01), 1e-3)
    r2, _ = _rise(Flash(heat_fraction=0.02), 1e-3)
    assert r2[0, -1] / r1[0, -1] == pytest.approx(2.0, rel=0.01)


def test_at_low_speed_the_rise_scales_as_one_over_kappa_and_not_with_rho_c():
    base, _ = _rise(Flash(), 1e-6)
    assert 0 < base[0, -1] < 1e-3
    assert _rise(Flash(conductivity=0.5), 1e-6)[0][0, -1] == pytest.approx(base[0, -1] / 2,
                                                                           rel=1e-3)
    assert _rise(Flash(heat_capacity=3.6e6), 1e-6)[0][0, -1] == pytest.approx(base[0, -1],
                                                                              rel=1e-3)


def test_at_high_speed_the_rise_scales_as_one_over_rho_c_and_barely_with_kappa():
    weak = Flash(heat_fraction=0.01)      # small enough that mu barely changes
    base, _ = _rise(weak, 100.0)
    assert _rise(replace(weak, heat_capacity=3.6e6), 100.0)[0][0, -1] == pytest.approx(
        base[0, -1] / 2, rel=0.01)
    assert _rise(replace(weak, conductivity=0.5), 100.0)[0][0, -1] == pytest.approx(
        base[0, -1], rel=0.01)


def test_heating_grows_with_speed_is_hottest_at_the_finest_scale_and_lowers_the_peak():
    rise, q = _rise(TREAD_THERMAL, np.array([1e-6, 1e-3, 0.1, 10.0]))
    top = rise[:, -1]
    assert np.all(np.diff(top) > 0) and top[0] < 1e-3 and top[-1] > 10.0
    assert np.all(rise >= 0) and np.all(rise[:, -1] >= rise.max(axis=1) - 1e-9)
    assert rise[:, 0].max() < 0.01 * top.max()       # the coarsest scale stays cold
    iso = friction(MAT, SURF, V_GRID, T20, P)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        hot = friction(MAT, SURF, V_GRID, T20, P, flash=TREAD_THERMAL)
    rising = (V_GRID > 0.01) & (V_GRID < peak(V_GRID, iso)[1])
    assert np.all(hot[rising] < iso[rising])
    assert peak(V_GRID, hot)[0] < peak(V_GRID, iso)[0]


def test_background_heating_adds_its_rise_to_every_scale():
    weak = Flash(heat_fraction=0.01)
    v = np.array([0.01, 1.0])
    r0, _ = _rise(weak, v)
    rL, _ = _rise(replace(weak, sliding_distance=0.1), v)
    mu = friction(MAT, SURF, v, T20, P, flash=weak)
    expect = 2 * 0.01 * mu * P * np.sqrt(0.1 * v / (math.pi * 0.25 * 1.8e6))
    assert (rL - r0)[:, 0] == pytest.approx(expect, rel=0.01)
    assert np.all(rL - r0 > 0)


# ----------------------------------------------------------------------- the grids


@pytest.mark.slow
def test_the_quadrature_grids_and_the_tolerance_are_converged_as_the_guide_says():
    """The default grid (10 nodes a panel, 2 panels a decade) against 20 and 6."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        mu = friction(MAT, SURF, V_GRID, T20, P, flash=TREAD_THERMAL)
        fine = friction(MAT, SURF, V_GRID, T20, P, flash=TREAD_THERMAL, order=20,
                        panels_per_decade=6.0)
        tight = friction(MAT, SURF, V_GRID, T20, P, flash=replace(TREAD_THERMAL, tol=1e-8))
    (h0, v0), (h1, v1) = peak(V_GRID, mu), peak(V_GRID, fine)
    # the temperature at one scale, interpolated in ln q between the nodes
    r0, q0 = _rise(TREAD_THERMAL, 1.0)
    r1, q1 = _rise(TREAD_THERMAL, 1.0, order=20, panels_per_decade=6.0)
    at = np.log(3e5)
    rise = np.interp(at, np.log(q0), r0[0]) / np.interp(at, np.log(q1), r1[0]) - 1
    grid, velocity, tol = (np.max(np.abs(mu / fine - 1)), abs(v0 / v1 - 1),
                           np.max(np.abs(mu / tight - 1)))
    assert grid < 1e-6 and tol < 1e-6 and velocity < 1e-4 and abs(h0 / h1 - 1) < 1e-6
    assert abs(rise) < 1e-3
    text = " ".join(GUIDE.read_text(encoding="utf-8").split())
    text = text[text.index("**Convergence:**"):]
    for x in (grid, velocity, tol, abs(rise)):
        assert f"{x:.2g}" in text[:600], x


# ------------------------------------------------------- refusals and warnings


def test_a_rubber_hotter_than_300_degC_is_refused():
    with pytest.raises(DomainError, match=r"reaches .* K, above 573.15 K \(300 degC\)"):
        friction(MAT, SURF, 1e3, T20, 1e5, flash=Flash(closure="surface-flux"))


def test_temperatures_above_the_material_data_are_warned_about():
    with pytest.warns(ExtrapolationWarning, match="flash temperature reaches"):
        friction(MAT, SURF, 30.0, T20, P, flash=TREAD_THERMAL)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        friction(MAT, SURF, 0.1, T20, P, flash=TREAD_THERMAL)


def test_non_converged_flash_temperature_is_refused():
    with pytest.raises(DomainError, match="did not converge"):
        friction(MAT, SURF, 1.0, T20, P, flash=Flash(max_iter=1))


def test_the_solution_converges_across_the_domain():
    p, T, v = np.meshgrid([1e4, 1e5, 1e6], [243.15, 253.15, 293.15, 343.15],
                          [1e-3, 0.1, 10.0, 1e3], indexing="ij")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        mu = friction(MAT, SURF, v, T, p, gamma=0.5, flash=TREAD_THERMAL)
        assert np.all(np.isfinite(mu)) and np.all(mu > 0)
        sf = friction(MAT, SURF, v[..., :3], T[..., :3], p[..., :3], gamma=0.5,
                      flash=Flash(closure="surface-flux"))
    assert np.all(np.isfinite(sf)) and np.all(sf > 0)


# ------------------------------------------------------------------------ the law


def test_law_setting_heat_fraction_is_the_default_closure():
    law = fl.get_law("persson")
    mu = law(p=P, v=1.0, T=T20, preset="tread-on-asphalt", heat_fraction=1.0)
    assert mu == pytest.approx(friction(MAT, SURF, 1.0, T20, P, flash=TREAD_THERMAL),
                               rel=1e-12)
    assert mu < law(p=P, v=1.0, T=T20, preset="tread-on-asphalt")
    assert "volume closure" in law.notes


def test_the_2006_preset_turns_both_refinements_on():
    law = fl.get_law("persson")
    mu = law(p=P, v=0.1, T=T20, preset="tread-on-asphalt-2006")
    assert mu == pytest.approx(friction(MAT, SURF, 0.1, T20, P, gamma=0.5,
                                        flash=TREAD_THERMAL), rel=1e-12)
