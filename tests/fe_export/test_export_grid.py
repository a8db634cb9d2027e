"""Export grids: spacing, the solver's interpolation, error checks, adaptive refinement."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.interpolate import RegularGridInterpolator

from frictionlaws import get_law
from frictionlaws.base.errors import InputError
from frictionlaws.fe_export.grid import (
    AxisSpec,
    Grid,
    adaptive_grid,
    breakpoints,
    check_error,
    fixed_grid,
    interpolate,
    make_grid,
    tabulate,
    uniform_grid_for_tol,
)


def solver_interp(points, values, query):
    """Independent reference: scipy's linear interpolation with the query clamped."""
    keep = [i for i, p in enumerate(points) if len(p) > 1]
    vals = np.asarray(values)
    for i in reversed(range(len(points))):
        if len(points[i]) == 1:
            vals = np.take(vals, 0, axis=i)
    pts = [points[i] for i in keep]
    q = np.column_stack([np.clip(query[i], points[i][0], points[i][-1]) for i in keep])
    return RegularGridInterpolator(pts, vals, method="linear")(q)


def test_breakpoints_lin_log_and_single():
    x = breakpoints(1e-3, 10.0, 5, "log")
    assert x[0] == 1e-3 and x[-1] == 10.0
    assert np.allclose(np.diff(np.log10(x)), 1.0)
    assert np.allclose(breakpoints(0, 1, 5), [0, 0.25, 0.5, 0.75, 1])
    assert breakpoints(2.0, 2.0, 7).tolist() == [2.0]


def test_interpolate_matches_scipy_and_holds_ends():
    rng = np.random.default_rng(0)
    pts = [np.sort(rng.uniform(0, 1, 6)), np.sort(rng.uniform(-2, 3, 4)), np.array([5.0])]
    vals = rng.normal(size=(6, 4, 1))
    q = [rng.uniform(-0.5, 1.5, 500), rng.uniform(-4, 5, 500), rng.uniform(0, 9, 500)]
    ours = interpolate(pts, vals, q)
    assert np.allclose(ours, solver_interp(pts, vals, q), rtol=0, atol=1e-13)
    # beyond the ends the end values are held
    far = interpolate(pts, vals, [np.array([10.0]), np.array([-10.0]), np.array([0.0])])
    assert far[0] == pytest.approx(vals[-1, 0, 0])


def test_interpolate_is_exact_for_multilinear_functions():
    x = np.array([0.0, 0.3, 1.0])
    y = np.array([1.0, 2.0, 4.0, 8.0])

    def f(a, b):
        return 0.7 - 1.2 * a + 0.4 * b + 2.5 * a * b

    vals = f(*np.meshgrid(x, y, indexing="ij"))
    rng = np.random.default_rng(1)
    qa, qb = rng.uniform(0, 1, 200), rng.uniform(1, 8, 200)
    assert np.allclose(interpolate([x, y], vals, [qa, qb]), f(qa, qb), atol=1e-13)


def test_check_error_finds_the_known_maximum():
    def f(x):
        return x**2

    grid = Grid(("x",), (np.array([0.0, 1.0]),), ("lin",))
    err = check_error(f, grid)
    assert err.max_abs == pytest.approx(0.25, rel=1e-12)
    assert err.where["x"] == pytest.approx(0.5)
    assert err.n_checked > 1000


def test_axis_spec_validation():
    with pytest.raises(InputError, match="larger than"):
        AxisSpec("p", 2.0, 1.0)
    with pytest.raises(InputError, match="log spacing of v needs MIN > 0"):
        AxisSpec("v", 0.0, 1.0, spacing="log")
    with pytest.raises(InputError, match="finite"):
        AxisSpec("p", 0.0, float("nan"))
    with pytest.raises(InputError, match="one point"):
        AxisSpec("p", 0.0, 1.0, n=1)
    assert AxisSpec("v", 1e-3, 10).kind == "log"
    assert AxisSpec("v", 0.0, 10).kind == "lin"


def test_fixed_grid_uses_the_requested_counts():
    g = fixed_grid([AxisSpec("p", 1e4, 1e6, 7, "log"), AxisSpec("v", 0, 2, 5)])
    assert g.shape == (7, 5) and g.rows == 35
    assert g.spacing == ("log", "lin")


LAW_BOXES = [
    ("exponential-decay", {"mu_s": 1.2, "mu_d": 0.6, "v_c": 0.3, "delta": 1.0},
     [AxisSpec("v", 0.0, 3.0)]),
    ("savkoor", {"mu_s": 0.5, "mu_m": 1.2, "h10": 0.4, "v_m": 0.01, "n": -0.1},
     [AxisSpec("p", 1e4, 1e6), AxisSpec("v", 1e-4, 10.0)]),
    ("thirion", {"a": 0.4, "b": 5e-6}, [AxisSpec("p", 1e3, 2e6)]),
    ("burckhardt", None, [AxisSpec("s", 0.0, 1.0), AxisSpec("v", 0.0, 40.0)]),
]


@pytest.mark.parametrize("law_id,values,specs", LAW_BOXES, ids=[c[0] for c in LAW_BOXES])
def test_adaptive_grid_meets_tol_with_fewer_rows_than_uniform(law_id, values, specs):
    law = get_law(law_id)
    vals = law.resolve(values, None if values else next(iter(law.presets)))
    f = law.bind(vals)
    tol = 1e-3
    grid, err = adaptive_grid(f, specs, tol)
    assert err.max_abs <= tol
    # independent check: random off-grid points, scipy interpolation, ends clamped
    rng = np.random.default_rng(11)
    q = []
    for s in specs:
        if s.kind == "log":
            q.append(np.exp(rng.uniform(np.log(s.lo), np.log(s.hi), 20000)))
        else:
            q.append(rng.uniform(s.lo, s.hi, 20000))
    values_tab = tabulate(f, grid.names, grid.points)
    approx = solver_interp(list(grid.points), values_tab, q)
    exact = np.broadcast_to(f(**dict(zip(grid.names, q, strict=True))), (20000,))
    assert np.max(np.abs(approx - exact)) <= tol
    uniform, uerr = uniform_grid_for_tol(f, specs, tol, spacing="spec")
    assert uerr.max_abs <= tol
    assert grid.rows < uniform.rows, (grid.shape, uniform.shape)


def test_adaptive_grid_refuses_more_rows_than_allowed():
    law = get_law("savkoor")
    f = law.bind({"mu_s": 0.5, "mu_m": 1.2, "h10": 0.4, "v_m": 0.01, "n": -0.1})
    with pytest.raises(InputError, match="more than 50 table rows"):
        adaptive_grid(f, [AxisSpec("p", 1e4, 1e6), AxisSpec("v", 1e-4, 10.0)], 1e-5,
                      max_rows=50)


def test_make_grid_modes():
    f = get_law("thirion").bind({"a": 0.4, "b": 5e-6})
    g, err, how = make_grid(f, [AxisSpec("p", 0, 1e6, 9)])
    assert g.shape == (9,) and how.startswith("fixed")
    g2, err2, how2 = make_grid(f, [AxisSpec("p", 0, 1e6)])
    assert "adaptive" in how2 and "default" in how2 and err2.max_abs <= 1e-3
    g3, err3, how3 = make_grid(f, [AxisSpec("p", 0, 1e6, 3)], tol=1e-4)
    assert err3.max_abs <= 1e-4 and "tol 0.0001" in how3


def test_non_finite_law_in_box_is_reported():
    def f(p):
        return 1.0 / (p - 0.5)

    with pytest.raises(InputError, match="not finite"):
        check_error(f, Grid(("p",), (np.array([0.0, 0.5, 1.0]),), ("lin",)))


def test_pole_in_the_box_is_reported_with_its_location():
    with pytest.raises(InputError, match="outside its bounds"):
        get_law("thirion").bind({"a": -0.5, "b": 1e-6})

    def f(p):  # thirion's 1/(a + b p) with a = -0.5: a pole at p = 5e5 Pa
        return 1.0 / (-0.5 + 1e-6 * np.asarray(p))
    with pytest.raises(InputError, match=r"crowd near p = 4999\d\d \(SI\)"):
        adaptive_grid(f, [AxisSpec("p", 0.0, 1e6)], 1e-3)


def test_adaptive_grid_is_never_larger_than_evenly_spaced_for_a_quadratic():
    """Even spacing is optimal for constant curvature; the adaptive mode then falls back to it."""
    law = get_law("thesis-poly2")
    f = law.bind(preset="steel")
    specs = [AxisSpec("p", 3e4, 2.5e5), AxisSpec("v", 0.0, 2.77)]
    grid, err = adaptive_grid(f, specs, 1e-3)
    uniform, _ = uniform_grid_for_tol(f, specs, 1e-3, spacing="spec")
    assert err.max_abs <= 1e-3
    assert grid.rows <= uniform.rows, (grid.shape, uniform.shape)
