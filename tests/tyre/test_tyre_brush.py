"""The brush tyre model with any sliding law, and Law.bind as a fast callable."""

from __future__ import annotations

import json
import math
import warnings

import numpy as np
import pytest
from scipy.integrate import trapezoid

from frictionlaws.base.errors import DomainError, ExtrapolationWarning, InputError
from frictionlaws.cli import main
from frictionlaws.law import NUMPY, Law
from frictionlaws.law.registry import get_law
from frictionlaws.tyre import BrushModel, BrushTyre
from frictionlaws.tyre.brush import DEFAULT_C_PY


def brush_parabolic(alpha, fz, mu, c, a):
    """Closed-form brush model, parabolic pressure, constant mu (Pacejka ch. 3)."""
    theta = 2 * c * a * a / (3 * mu * fz)
    t = np.minimum(theta * np.abs(np.tan(alpha)), 1.0)
    return np.sign(alpha) * mu * fz * (3 * t - 3 * t**2 + t**3)


def brush_uniform(sigma, fz, mu, c, a, w):
    """Closed-form brush model, uniform pressure, constant mu."""
    limit = mu * fz / (2 * a)  # line load N/m
    s_a = np.minimum(limit / (c * np.maximum(sigma, 1e-300)), 2 * a)
    return c * sigma * s_a**2 / 2 + limit * (2 * a - s_a)


# ------------------------------------------------------------------ Law.bind


@pytest.mark.parametrize("law_id, params, variables", [
    ("coulomb", {"mu0": 0.9}, {}),
    ("thirion", {"a": 0.147, "b": 4.7e-6}, {"p": np.linspace(0, 4e5, 50)}),
    ("exponential-decay", {"mu_s": 1.2, "mu_d": 0.8, "v_c": 0.3, "delta": 1.0},
     {"v": np.linspace(-2, 2, 50)}),
    ("thesis-poly2", None, {"p": np.linspace(3e4, 2.5e5, 50), "v": np.linspace(0, 2.7, 50)}),
])
def test_bind_gives_the_formula_without_checking(law_id, params, variables, monkeypatch):
    law = get_law(law_id)
    values = law.resolve(params, None if params else "steel")
    bound = law.bind(values)
    direct = law.formula(NUMPY, **{k: (np.abs(v) if k == "v" else v)
                                   for k, v in variables.items()}, **values)
    checked = law.evaluate(variables, values) if variables else law.evaluate({}, values)
    # once bound, the law's checking layer is not used at all
    monkeypatch.setattr(Law, "evaluate", lambda *a, **k: pytest.fail("evaluate called"))
    monkeypatch.setattr(Law, "resolve", lambda *a, **k: pytest.fail("resolve called"))
    got = bound(*[variables[v] for v in law.variables])
    assert np.array_equal(np.broadcast_to(got, np.shape(direct)), direct)
    assert np.allclose(got, checked, rtol=0, atol=0)
    assert callable(bound) and bound.__name__.endswith("_bound")


def test_brush_model_binds_once_and_never_calls_evaluate(monkeypatch):
    calls = []
    original = Law.bind

    def spy(self, values=None, preset=None):
        calls.append(self.id)
        return original(self, values, preset)

    monkeypatch.setattr(Law, "bind", spy)
    model = BrushModel("thirion", {"a": 0.2, "b": 3e-6})
    monkeypatch.setattr(Law, "evaluate", lambda *a, **k: pytest.fail("evaluate called"))
    model.fy(np.radians([1.0, 2.0]), 4000.0)
    model.fx(np.array([-0.1, 0.1]), 4000.0)
    model.cornering([3000.0])
    assert calls == ["thirion"]


# ----------------------------------------------------------- closed forms


@pytest.mark.parametrize("fz", [2000.0, 4000.0, 6500.0])
@pytest.mark.parametrize("mu", [0.5, 0.9, 1.2])
def test_constant_mu_matches_the_closed_form_parabolic(fz, mu):
    tyre = BrushTyre()
    model = BrushModel("coulomb", {"mu0": mu}, tyre=tyre)
    alpha = np.radians(np.concatenate([-np.geomspace(0.05, 20, 15), np.geomspace(0.05, 20, 15)]))
    got = model.fy(alpha, fz)
    want = brush_parabolic(alpha, fz, mu, tyre.c_py, tyre.half_length(fz))
    # relative error ~ 1/nodes at the smallest slips (trailing-edge sliding zone < ds)
    assert np.allclose(got, want, rtol=5e-4, atol=1e-6 * fz)
    # full sliding far out: |Fy| = mu Fz
    assert model.fy(np.radians(60.0), fz) == pytest.approx(mu * fz, rel=1e-9)


def test_constant_mu_matches_the_closed_form_uniform():
    tyre = BrushTyre(pressure="uniform")
    fz, mu = 4000.0, 0.9
    model = BrushModel("coulomb", {"mu0": mu}, tyre=tyre)
    sigma = np.tan(np.radians(np.linspace(0.1, 15, 40)))
    got = model.fy(np.arctan(sigma), fz)
    want = brush_uniform(sigma, fz, mu, tyre.c_py, tyre.half_length(fz), tyre.width)
    assert np.allclose(got, want, rtol=5e-5)


def test_longitudinal_equals_lateral_in_theoretical_slip():
    tyre = BrushTyre(c_px=DEFAULT_C_PY, c_py=DEFAULT_C_PY)
    model = BrushModel("thirion", {"a": 0.15, "b": 4.7e-6}, tyre=tyre)
    kappa = np.array([-0.5, -0.2, -0.05, -0.01, 0.01, 0.05, 0.2, 0.5, 2.0])
    sigma = kappa / (1 + kappa)
    fx = model.fx(kappa, 4000.0)
    fy = model.fy(np.arctan(sigma), 4000.0)
    assert np.allclose(fx, fy, rtol=1e-12)
    assert model.fx(0.0, 4000.0) == 0.0


def test_locked_wheel_slides_at_road_speed():
    law = {"mu_s": 1.2, "mu_d": 0.7, "v_c": 0.5, "delta": 1.0}
    tyre = BrushTyre()
    model = BrushModel("exponential-decay", law, tyre=tyre)
    mu_v = get_law("exponential-decay")(v=tyre.speed, **law)
    assert model.fx(-1.0, 4000.0) == pytest.approx(-mu_v * 4000.0, rel=1e-9)
    coulomb = BrushModel("coulomb", {"mu0": 0.8}, tyre=tyre)
    assert coulomb.fx([-1.0, -3.0], 4000.0) == pytest.approx([-3200.0, -3200.0])


# ----------------------------------------------------- velocity-dependent laws


def test_local_speed_path_agrees_with_the_pressure_path():
    """A function of (p, v) that ignores v goes through the local-speed march."""
    fast = BrushModel("thirion", {"a": 0.147, "b": 4.7e-6})
    slow = BrushModel(lambda p, v: 1.0 / (0.147 + 4.7e-6 * p), sliding_speed="local")
    slip = BrushModel(lambda p, v: 1.0 / (0.147 + 4.7e-6 * p))
    assert slow.uses_v and not fast.uses_v
    alpha = np.radians([0.3, 1.0, 2.0, 3.0, 6.0, 12.0])
    assert np.allclose(slow.fy(alpha, 4500.0), fast.fy(alpha, 4500.0), rtol=1e-10)
    assert np.allclose(slip.fy(alpha, 4500.0), fast.fy(alpha, 4500.0), rtol=1e-12)


def test_velocity_dependent_law_slip_speed():
    tyre = BrushTyre()
    same = BrushModel("exponential-decay",
                      {"mu_s": 0.9, "mu_d": 0.9, "v_c": 0.1, "delta": 1.0}, tyre=tyre)
    const = BrushModel("coulomb", {"mu0": 0.9}, tyre=tyre)
    alpha = np.radians([0.5, 2.0, 5.0, 15.0])
    assert np.allclose(same.fy(alpha, 4000.0), const.fy(alpha, 4000.0), rtol=1e-12)
    law = {"mu_s": 1.2, "mu_d": 0.6, "v_c": 0.2, "delta": 1.0}
    weak = BrushModel("exponential-decay", law, tyre=tyre)
    # the law sees the slip speed V tan(alpha): at each angle the force equals the
    # constant-mu brush force with mu taken at that speed
    for deg in (0.5, 2.0, 8.0, 45.0):
        a = math.radians(deg)
        mu = get_law("exponential-decay")(v=tyre.speed * math.tan(a), **law)
        want = BrushModel("coulomb", {"mu0": mu}, tyre=tyre).fy(a, 4000.0)
        assert weak.fy(a, 4000.0) == pytest.approx(want, rel=1e-12)
    assert weak.fy(np.radians(45.0), 4000.0) == pytest.approx(0.6 * 4000.0, rel=1e-4)
    # longitudinal: the speed is V |kappa|; the locked wheel slides at V
    mu_v = get_law("exponential-decay")(v=tyre.speed * 0.3, **law)
    want = BrushModel("coulomb", {"mu0": mu_v}, tyre=tyre).fx(-0.3, 4000.0)
    assert weak.fx(-0.3, 4000.0) == pytest.approx(want, rel=1e-12)


def test_velocity_dependent_law_local_speed():
    tyre = BrushTyre()
    # friction rising with speed: unique local solution between the mu_s and mu_d curves
    law = {"mu_s": 0.6, "mu_d": 1.0, "v_c": 0.05, "delta": 1.0}
    local = BrushModel("exponential-decay", law, tyre=tyre, sliding_speed="local")
    alpha = np.radians([1.0, 3.0, 8.0, 30.0])
    f = local.fy(alpha, 4000.0)
    lo = BrushModel("coulomb", {"mu0": 0.6}, tyre=tyre).fy(alpha, 4000.0)
    hi = BrushModel("coulomb", {"mu0": 1.0}, tyre=tyre).fy(alpha, 4000.0)
    assert np.all(lo < f) and np.all(f < hi)
    # far in full sliding the tips slide at about V tan(alpha) >> v_c: mu -> mu_d
    assert f[-1] == pytest.approx(hi[-1], rel=1e-3)
    # the thesis polynomial falls with v beyond 1.7 m/s and turns negative: near the
    # trailing edge no steady local sliding speed exists, and the model says so
    poly = BrushModel("thesis-poly2", preset="steel", sliding_speed="local")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        with pytest.raises(DomainError, match="no steady sliding speed"):
            poly.fy(np.radians(2.0), 3000.0)
        # with the slip speed (default) the same law is usable
        slip = BrushModel("thesis-poly2", preset="steel")
        assert np.isfinite(slip.fy(np.radians(2.0), 3000.0))
    with pytest.raises(InputError, match="sliding_speed"):
        BrushModel("coulomb", {"mu0": 1.0}, sliding_speed="tip")


def test_origin_slope():
    tyre = BrushTyre()
    for law, params in (("coulomb", {"mu0": 0.9}), ("thirion", {"a": 0.15, "b": 4.7e-6})):
        res = BrushModel(law, params, tyre=tyre).cornering([2000.0, 5000.0])
        a = np.array([tyre.half_length(2000.0), tyre.half_length(5000.0)])
        assert np.allclose(res.cs_origin, 2 * tyre.c_py * a**2, rtol=1e-12)
        # the numerical slope at small alpha agrees (fine mesh: the trailing-edge
        # sliding zone is shorter than one interval of the default mesh)
        fine = BrushModel(law, params, tyre=BrushTyre(nodes=4000))
        f = fine.fy(1e-4, 5000.0)
        assert f / math.tan(1e-4) == pytest.approx(res.cs_origin[1], rel=2e-3)
    # a law without static friction (mu(v = 0) = 0) is handled numerically
    viscous = BrushModel(lambda p, v: 0.9 * np.tanh(v / 0.01), tyre=tyre,
                         sliding_speed="local")
    res = viscous.cornering([4000.0])
    assert 0 < res.cs_origin[0] < 2 * tyre.c_py * tyre.half_length(4000.0) ** 2


def test_converges_with_nodes():
    law = ("thirion", {"a": 0.147, "b": 4.7e-6})
    coarse = BrushModel(*law, tyre=BrushTyre(nodes=400)).fy(np.radians([1, 2, 3]), 4000.0)
    fine = BrushModel(*law, tyre=BrushTyre(nodes=3200)).fy(np.radians([1, 2, 3]), 4000.0)
    assert np.allclose(coarse, fine, rtol=2e-4)


# ----------------------------------------------------- cornering against load


def test_constant_mu_cornering_stiffness_is_proportional_to_load():
    loads = np.arange(2000.0, 6501.0, 500.0)
    res = BrushModel("coulomb", preset="thesis-fe-0.9").cornering(loads)
    assert np.allclose(res.cs / loads, res.cs[0] / loads[0], rtol=1e-3)
    assert res.ratio() == pytest.approx(3.25, rel=1e-3)
    # default tread stiffness: calibrated on the thesis' mu = 0.9 value at 4 kN
    assert res.cs_kN_per_deg[4] == pytest.approx(0.890, abs=0.002)
    # the secant is well below the origin slope: part of the patch slides at 1-3 deg
    assert np.all(res.cs < 0.8 * res.cs_origin)
    assert res.secants_kN_per_deg.shape == (10, 3)
    assert np.all(np.diff(res.secants_kN_per_deg, axis=1) < 0)


def test_cornering_result_reporting():
    res = BrushModel("coulomb", {"mu0": 1.0}).cornering([2000.0, 4000.0], angles_deg=(1, 3))
    d = json.loads(json.dumps(res.to_dict()))
    assert d["loads_kN"] == [2.0, 4.0]
    assert d["angles_deg"] == [1.0, 3.0]
    assert len(d["cornering_stiffness_kN_per_deg"]) == 2
    assert d["tyre"]["units"]["c_py"] == "N/m^2"
    text = res.table()
    assert "CS [kN/deg]" in text and "load [kN]" in text and "p_mean [MPa]" in text
    assert res.ratio(2000.0, 4000.0) == pytest.approx(2.0, rel=1e-3)
    with pytest.raises(InputError, match="not among the computed loads"):
        res.ratio(3000.0)


def test_fit_result_and_extrapolation_warning(tmp_path):
    path = tmp_path / "thirion.json"
    path.write_text(json.dumps({"law": "thirion", "params": {"a": 0.147, "b": 4.7e-6}}))
    from frictionlaws.fitting import load_result

    loaded = load_result(path)
    model = BrushModel(loaded)
    assert model.values["a"] == 0.147
    # a fit result carries its data range: pressures beyond it are flagged
    loaded.data = {"ranges": {"p": [3.1e4, 2.5e5]}}
    with pytest.warns(ExtrapolationWarning, match="outside the fitted data range of p"):
        BrushModel(loaded).fy(np.radians(2.0), 6500.0)
    res = BrushModel(loaded).cornering([2000.0, 6500.0])
    assert any("6.5 kN" in w for w in res.warnings)
    # the thesis polynomial outside its measured box is flagged from the law's domain
    with pytest.warns(ExtrapolationWarning, match="valid domain of the law"):
        BrushModel("thesis-poly2", preset="steel").fy(np.radians(2.0), 6500.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ExtrapolationWarning)
        BrushModel("coulomb", {"mu0": 0.9}).fy(np.radians(2.0), 6500.0)


# ------------------------------------------------------------- patch, tyre


def test_patch_pressure_and_contact_models():
    tyre = BrushTyre()
    for fz in (2000.0, 6500.0):
        s, p = tyre.patch(fz)
        assert trapezoid(p, s) * tyre.width == pytest.approx(fz, rel=1e-12)
        assert p[0] == 0 and p[-1] == 0
        assert p.max() == pytest.approx(1.5 * tyre.mean_pressure(fz), rel=1e-4)
    assert tyre.half_length(3000.0) == pytest.approx(0.055)
    assert tyre.half_length(12000.0) == pytest.approx(0.11)
    # thesis sizing: 3 kN on 16 500 mm^2 -> 0.18 MPa
    assert tyre.mean_pressure(3000.0) == pytest.approx(3000.0 / 16500e-6, rel=1e-12)
    defl = BrushTyre(contact="deflection")
    delta = 3000.0 / defl.vertical_stiffness
    assert defl.half_length(3000.0) == pytest.approx(0.6 * math.sqrt(0.31 * delta) + 0.8 * delta)
    assert BrushTyre(contact=lambda fz: 0.05).half_length(1234.0) == 0.05
    shaped = BrushTyre(pressure=lambda xi: (1 - xi**2) ** 2)
    s, p = shaped.patch(4000.0)
    assert trapezoid(p, s) * shaped.width == pytest.approx(4000.0, rel=1e-12)
    assert BrushModel("coulomb", {"mu0": 0.9}, tyre=shaped).fy(np.radians(60), 4000.0) == (
        pytest.approx(3600.0, rel=1e-9))


def test_patch_state_profiles():
    model = BrushModel("thirion", {"a": 0.147, "b": 4.7e-6})
    st = model.patch_state(np.radians(3.0), 4000.0)
    limit = model.mu(st["p"]) * st["p"] * model.tyre.width
    assert np.all(st["line_load"] <= limit * (1 + 1e-12) + 1e-9)
    assert st["sliding"][-5:].all() and not st["sliding"][:50].any()
    assert trapezoid(st["line_load"], st["s"]) == pytest.approx(
        model.fy(np.radians(3.0), 4000.0), rel=1e-12)
    stx = model.patch_state(-0.05, 4000.0, direction="x")
    assert stx["sliding"].any()
    with pytest.raises(InputError):
        model.patch_state(0.1, 4000.0, direction="z")


# ------------------------------------------------------------------ errors


@pytest.mark.parametrize("law, needs", [("schallamach", "F_N"), ("park", "T"),
                                        ("pacejka", "slip"), ("burckhardt", "s")])
def test_laws_that_need_more_than_p_and_v_are_rejected(law, needs):
    with pytest.raises(DomainError, match=needs) as info:
        BrushModel(law, preset=next(iter(get_law(law).presets), None)
                   if get_law(law).presets else None,
                   params=None if get_law(law).presets else get_law(law).defaults)
    assert "bristle" in str(info.value)


def test_bad_inputs():
    with pytest.raises(InputError, match="width must be a positive"):
        BrushTyre(width=-0.1)
    with pytest.raises(InputError, match="pressure must be one of"):
        BrushTyre(pressure="triangular")
    with pytest.raises(InputError, match="contact must be one of"):
        BrushTyre(contact="hertz")
    with pytest.raises(InputError, match="nodes"):
        BrushTyre(nodes=5)
    with pytest.raises(InputError, match="pressure shape"):
        BrushTyre(pressure=lambda xi: xi).patch(3000.0)
    with pytest.raises(InputError, match="contact-length function"):
        BrushTyre(contact=lambda fz: -1.0).half_length(3000.0)
    model = BrushModel("coulomb", {"mu0": 0.9})
    with pytest.raises(InputError, match="vertical load must be positive"):
        model.fy(0.01, -5.0)
    with pytest.raises(InputError, match="vertical load must be positive"):
        model.cornering([2000.0, float("nan")])
    with pytest.raises(InputError, match="between -90 and 90"):
        model.fy(2.0, 3000.0)
    with pytest.raises(InputError, match="slip angles must be in"):
        model.cornering([3000.0], angles_deg=(0.0, 1.0))
    with pytest.raises(InputError, match="needs parameter"):
        BrushModel("thirion")
    with pytest.raises(InputError, match="unknown law"):
        BrushModel("no-such-law", {})
    with pytest.raises(InputError, match="law must be"):
        BrushModel(42)
    # a law that turns negative inside the patch is refused where it happens
    neg = BrushModel("quadratic-pv", {"c0": 1.0, "c1": -1e-5, "c2": 0.0, "c3": 0.0,
                                      "c4": 0.0, "c5": 0.0})
    with pytest.raises(DomainError, match=r"mu = .* at p = .* MPa"):
        neg.fy(np.radians(2.0), 6000.0)


@pytest.mark.parametrize(("kwargs", "message"), [
    ({"width": 150e3}, "width = 150000 m is outside"),
    ({"width": 1e-4}, "width = 0.0001 m is outside"),
    ({"radius": 40.0}, "radius = 40 m is outside"),
    ({"speed": 1e4}, "speed = 10000 m/s is outside"),
])
def test_brush_tyre_refuses_geometry_no_tyre_has(kwargs, message):
    with pytest.raises(InputError, match=message):
        BrushTyre(**kwargs)


@pytest.mark.parametrize("contact", ["sqrt", "deflection"])
def test_brush_tyre_refuses_a_load_whose_patch_outgrows_the_wheel(contact):
    tyre = BrushTyre(contact=contact)
    assert tyre.half_length(6.5e3) < tyre.radius
    with pytest.raises(InputError, match="more than the tyre radius"):
        tyre.half_length(1e12)
    assert main(["tyre", "cornering", "--law", "coulomb", "--set", "mu0=0.9",
                 "--loads", "1e9:1e9:1"]) == 2


def test_zero_friction_gives_no_stiffness_and_an_undefined_ratio(capsys):
    import warnings as _w

    with _w.catch_warnings():
        _w.simplefilter("error")
        res = BrushModel("coulomb", {"mu0": 0.0}).cornering([2000.0, 6500.0])
    assert np.all(res.cs_kN_per_deg == 0) and math.isnan(res.ratio())
    assert "n/a" in res.table()


@pytest.mark.parametrize("n,usable", [(-0.2, True), (-0.9, True), (-1.0, False)])
def test_edges_of_the_patch_take_the_limit_of_mu_p(n, usable):
    # savkoor's mu grows as p^n when p -> 0: no mu at the patch's edges, but the
    # friction limit mu p goes to 0 for n > -1 (and not for n = -1)

    values = {"mu_s": 0.4, "mu_m": 1.2, "h10": 0.35, "v_m": 1e-3, "n": n}
    model = BrushModel("savkoor", values)
    if not usable:
        with pytest.raises(DomainError, match="p = 0 MPa"):
            model.cornering(np.array([3000.0]), [1.0])
        return
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        res = model.cornering(np.array([2000.0, 6000.0]), [1.0, 2.0])
    assert np.all(np.isfinite(res.cs_kN_per_deg)) and np.all(res.cs_kN_per_deg > 0)
