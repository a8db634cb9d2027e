"""The brush model's local-speed march agrees with the march it replaced (issue 15).

The reference is the pre-issue-15 march (log-grid scan, then 45 bisection steps per
sliding node), kept as the baseline of ``benchmarks/bench_brush.py`` and loaded from
there.  Both end with a bracket of the same width around the same root, so the forces
agree to round-off, for laws rising with speed, a user's function without static
friction, and longitudinal slip.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

from frictionlaws.errors import DomainError
from frictionlaws.tyre.brush import BrushModel

BENCH = Path(__file__).resolve().parents[1] / "benchmarks" / "bench_brush.py"


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
