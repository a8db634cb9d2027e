"""The brush model's local-speed march agrees with the march it replaced.

Two references: the earlier march (log-grid scan, then 45 bisection steps per
sliding node, vectorised over slips), kept as the baseline of
``benchmarks/bench_brush.py`` and loaded from there; and a plain-float march written
here one slip and one node at a time (:func:`scalar_march`).  The model solves all
nodes together by Newton sweeps and falls back to its node-by-node march when they do
not settle; the tests against the scalar reference forbid that fallback, so a wrong
sweep fails them.  Cases: laws rising with speed (one flat at v = 0), velocity
weakening, no static friction (everything slides), no sliding, longitudinal-style
per-slip rolling speeds.
"""

from __future__ import annotations

import importlib.util
import warnings
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

from frictionlaws.base.errors import DomainError
from frictionlaws.tyre.brush import BrushModel, BrushTyre
from frictionlaws.tyre.brush import tyre as brush_tyre

BENCH = Path(__file__).resolve().parents[2] / "benchmarks" / "bench_brush.py"


@pytest.fixture(scope="module")
def bench() -> ModuleType:
    if not BENCH.is_file():
        pytest.skip("benchmarks/ is not next to the tests")
    spec = importlib.util.spec_from_file_location("bench_brush", BENCH)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


MODELS = {
    "exponential-decay": lambda: BrushModel(
        "exponential-decay", {"mu_s": 0.6, "mu_d": 1.0, "v_c": 0.05, "delta": 1.0},
        sliding_speed="local"),
    "viscous function": lambda: BrushModel(lambda p, v: 0.9 * np.tanh(v / 0.01),
                                           sliding_speed="local"),
    "pressure and speed": lambda: BrushModel(
        lambda p, v: (1.2 - 1.5e-6 * p) * (1.0 + 0.2 * np.log1p(v / 0.1)),
        sliding_speed="local"),
}


@pytest.mark.parametrize("name", sorted(MODELS))
@pytest.mark.parametrize("fz", [2000.0, 4000.0, 6500.0])
def test_local_march_matches_the_bisection_march(bench: ModuleType, name: str,
                                                 fz: float) -> None:
    model = MODELS[name]()
    c = model.tyre.c_py
    s, p = model.tyre.patch(fz)
    ds = float(s[1] - s[0])
    sigma = np.tan(np.radians([0.0057, 0.5, 1.0, 2.0, 3.0, 8.0, 30.0]))
    vr = np.linspace(0.5, 1.5, sigma.size) * model.tyre.speed  # per-slip rolling speeds
    q_ref, vs_ref = bench.march_local_bisection(model, p, sigma * ds, vr, ds, c)
    q, vs = model._march_local(p, sigma * ds, vr, ds, c)
    f_ref, f = bench.forces(q_ref, c, ds), bench.forces(q, c, ds)
    assert np.allclose(f, f_ref, rtol=1e-11, atol=0.0)
    assert np.allclose(q, q_ref, rtol=1e-10, atol=1e-18)
    assert (vs is None) == (vs_ref is None)
    if vs is not None:
        assert np.allclose(vs, vs_ref, rtol=1e-8)
    assert np.any(q < np.arange(p.size) * sigma[:, None] * ds * (1 - 1e-9))  # some slide


def test_velocity_weakening_is_still_refused() -> None:
    poly = BrushModel("thesis-poly2", preset="steel", sliding_speed="local")
    with pytest.raises(DomainError, match="no steady sliding speed"):
        poly.fy(np.radians(2.0), 3000.0)


# ------------------------------------------------ against a scalar reference march


def scalar_march(model: BrushModel, p: np.ndarray, sigma: np.ndarray, vr: np.ndarray,
                 ds: float, c: float) -> np.ndarray:
    """The local-speed march one slip and one node at a time, in plain floats.

    A bristle sticks while its adhesion trial ``a`` stays at or below the static limit;
    otherwise it takes the slowest root of ``g(x) = a (1 - x) - limit(p, V_r a x / ds)``:
    the first point of the model's log grid of x where ``g <= 0`` closes a bracket that
    plain bisection shrinks to nothing.
    """
    w = model.tyre.width

    def limit(pk: float, v: float) -> float:
        return float(model.mu(pk, v)) * pk * w / c

    grid = [float(x) for x in brush_tyre.SLIP_SCAN]
    q = np.zeros((sigma.size, p.size))
    for j, (sig, rate) in enumerate(zip(sigma, vr / ds)):
        qn = 0.0
        for k in range(1, p.size):
            a, pk = qn + sig * ds, float(p[k])
            if a > limit(pk, 0.0):
                def g(x: float, a: float = a, pk: float = pk, rate: float = rate) -> float:
                    return a * (1.0 - x) - limit(pk, rate * a * x)
                i = next(i for i, x in enumerate(grid) if g(x) <= 0)
                lo, hi = (grid[i - 1] if i else 0.0), grid[i]
                for _ in range(80):
                    mid = 0.5 * (lo + hi)
                    lo, hi = (lo, mid) if g(mid) <= 0 else (mid, hi)
                a *= 1.0 - hi
            qn = a
            q[j, k] = qn
    return q


def _no_node_march(*args: object) -> None:
    raise AssertionError("the node-by-node march ran: the sweeps did not settle")


COARSE = BrushTyre(nodes=40)
SCALAR_CASES = {
    # rising with speed, as in the benchmark
    "rising": lambda: BrushModel("exponential-decay", {"mu_s": 0.6, "mu_d": 1.0, "v_c": 0.05,
                                                       "delta": 1.0},
                                 tyre=COARSE, sliding_speed="local"),
    # flat at v = 0 (dmu/dv = 0 there): the tip-speed Newton must not cycle
    "rising, flat start": lambda: BrushModel(
        "exponential-decay", {"mu_s": 0.6, "mu_d": 1.0, "v_c": 0.05, "delta": 2.0},
        tyre=COARSE, sliding_speed="local"),
    # velocity weakening that stays positive: a steady state exists at every node
    "weakening": lambda: BrushModel(
        "exponential-decay", {"mu_s": 1.0, "mu_d": 0.6, "v_c": 0.2, "delta": 1.0},
        tyre=COARSE, sliding_speed="local"),
    # no static friction: every loaded bristle slides from the leading edge on
    "viscous": lambda: BrushModel(lambda p, v: 0.9 * np.tanh(v / 0.01), tyre=COARSE,
                                  sliding_speed="local"),
}


@pytest.mark.parametrize("name", sorted(SCALAR_CASES))
def test_sweeps_match_a_scalar_reference(name: str,
                                         monkeypatch: pytest.MonkeyPatch) -> None:
    model = SCALAR_CASES[name]()
    monkeypatch.setattr(model, "_march_local_nodes", _no_node_march)
    c = model.tyre.c_py
    s, p = model.tyre.patch(4000.0)
    ds = float(s[1] - s[0])
    # no slip, a slip too small to slide, partial sliding, and (almost) full sliding
    sigma = np.tan(np.radians([0.0, 1e-3, 3.0, 30.0, 80.0]))
    vr = np.linspace(0.5, 1.5, sigma.size) * model.tyre.speed
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        want = scalar_march(model, p, sigma, vr, ds, c)
    q, vs = model._march_local(p, sigma * ds, vr, ds, c)
    assert np.allclose(q, want, rtol=1e-10, atol=1e-15 * want.max())
    adhesion = np.arange(p.size) * sigma[:, None] * ds
    # zero pressure at the trailing edge: the bristle lets go.  Its deflection there is
    # the difference of two numbers of the size of the deflections (the adhesion
    # displacement and the sliding correction), so rounding leaves a few units in the
    # last place of max|q| (2.2e-19 m of 5e-3 m in the viscous case), not exactly 0
    assert np.all(np.abs(q[:, -1]) <= 8 * np.finfo(float).eps * np.abs(q).max())
    if name != "viscous":  # with static friction the two smallest slips stick throughout
        assert np.allclose(q[:2, :-1], adhesion[:2, :-1], rtol=1e-14, atol=0.0)
    sliding = q[2:, 1:-1] < adhesion[2:, 1:-1] * (1 - 1e-9)
    assert sliding[0].any()
    assert sliding[0].all() == (name == "viscous")  # 3 deg: partial sliding if mu(0) > 0
    assert sliding[-1].all()  # 80 deg: every interior bristle slides
    assert vs is not None and 0.0 <= vs[0] < vs[1]


def test_no_sliding_gives_the_adhesion_line() -> None:
    model = SCALAR_CASES["rising"]()
    s, p = model.tyre.patch(4000.0)
    ds = float(s[1] - s[0])
    sigma = np.array([0.0, 1e-7])
    speed = model.tyre.speed
    q, vs = model._march_local(p, sigma * ds, np.full(2, speed), ds, model.tyre.c_py)
    assert np.allclose(q[:, :-1], np.arange(p.size - 1) * sigma[:, None] * ds, rtol=1e-14,
                       atol=0.0)
    assert not q[:, -1].any()  # only the trailing-edge bristle (p = 0) slides, to zero
    assert vs == pytest.approx((1e-7 * (p.size - 1) * speed,) * 2, rel=1e-12)
    # a uniform pressure has no unloaded edge: nothing slides, no sliding speed
    flat = BrushModel("exponential-decay", {"mu_s": 0.6, "mu_d": 1.0, "v_c": 0.05,
                                            "delta": 1.0},
                      tyre=BrushTyre(nodes=40, pressure="uniform"), sliding_speed="local")
    s, p = flat.tyre.patch(4000.0)
    q, vs = flat._march_local(p, sigma * ds, np.full(2, speed), ds, flat.tyre.c_py)
    assert np.allclose(q, np.arange(p.size) * sigma[:, None] * ds, rtol=1e-14, atol=0.0)
    assert vs is None


def test_a_state_that_is_not_the_slowest_is_refused() -> None:
    """The guard that sends the sweeps back to the node march checks the root's bracket."""
    model = SCALAR_CASES["rising"]()
    c = model.tyre.c_py
    s, p = model.tyre.patch(4000.0)
    ds = float(s[1] - s[0])
    sigma = np.tan(np.radians([3.0]))
    rate = model.tyre.speed / ds
    q = scalar_march(model, p, sigma, np.array([model.tyre.speed]), ds, c)[0]
    a = q[:-1] + sigma[0] * ds
    i = np.flatnonzero(a > model._limit(p, 0.0, c)[1:])
    pk, ai, speed = p[1:][i], a[i], rate * (a[i] - q[1:][i])
    rates = np.full(i.size, rate)
    assert model._local_state_ok(pk, ai, speed, rates, c)
    assert not model._local_state_ok(pk, ai, 3.0 * speed, rates, c)  # a faster "root"
    bad_mu = BrushModel(lambda p, v: 0.9 - 2.0 * v, tyre=COARSE, sliding_speed="local")
    assert not bad_mu._local_state_ok(pk, ai, np.full(i.size, 1.0), rates, c)  # mu < 0


def test_weakening_on_a_fine_mesh_agrees_with_the_bisection_march(bench: ModuleType) -> None:
    """Strong weakening on the default mesh: whichever path decides, the result is the
    slowest steady state of the node-by-node march."""
    model = BrushModel("exponential-decay", {"mu_s": 1.0, "mu_d": 0.6, "v_c": 0.2,
                                             "delta": 1.0}, sliding_speed="local")
    c = model.tyre.c_py
    s, p = model.tyre.patch(3000.0)
    ds = float(s[1] - s[0])
    sigma = np.tan(np.radians([0.5, 2.0, 30.0]))
    vr = np.full(sigma.size, model.tyre.speed)
    q_ref, _ = bench.march_local_bisection(model, p, sigma * ds, vr, ds, c)
    q, _ = model._march_local(p, sigma * ds, vr, ds, c)
    assert np.allclose(bench.forces(q, c, ds), bench.forces(q_ref, c, ds), rtol=1e-11)
