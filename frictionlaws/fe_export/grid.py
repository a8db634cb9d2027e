"""Tabulation grids and the solver's own interpolation.

FE codes that take mu as a table (Abaqus ``*FRICTION``, LS-DYNA
``*DEFINE_TABLE``, Ansys ``TB,FRIC``) interpolate it *multilinearly* between
the tabulated points, linearly in each variable itself (not in its log), and
hold the end values outside the table.  This module builds tensor grids with
linear or log spacing per variable, reproduces that interpolation
(:func:`interpolate`), measures how far it strays from the law on a dense
off-grid sample (:func:`check_error`), and refines a grid until the error is
within a tolerance (:func:`adaptive_grid`).

All values here are SI; unit conversion happens in the writers.  Conversions
between unit systems are affine, so the interpolation error does not depend on
the units the table is written in.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from ..base.errors import Argument, InputError

__all__ = [
    "AxisSpec",
    "Grid",
    "GridError",
    "breakpoints",
    "interpolate",
    "tabulate",
    "check_error",
    "fixed_grid",
    "adaptive_grid",
    "uniform_grid_for_tol",
    "make_grid",
    "DEFAULT_N",
    "MAX_ROWS",
]

#: Points per variable when neither N nor a tolerance is given (see :func:`make_grid`).
DEFAULT_N = 11
#: Largest table :func:`adaptive_grid` may build unless told otherwise.
MAX_ROWS = 200_000
#: Most breakpoints one variable may get from the adaptive grid.
MAX_AXIS_POINTS = 5_000
#: Points evaluated at once when tabulating (keeps memory bounded).
_CHUNK = 250_000
#: Size budget of the structured error sample while refining / for the final check.
_BUDGET_REFINE = 400_000
_BUDGET_FINAL = 1_500_000
#: Random points added to the final check.
_N_RANDOM = 20_000
#: Relative margin below the tolerance that the adaptive grid aims at.
_MARGIN = 0.01

Func = Callable[..., np.ndarray]


@dataclass(frozen=True)
class AxisSpec:
    """The range requested for one variable (SI).

    Parameters
    ----------
    name : str
        Variable name (``"p"``, ``"v"``, ``"T"``, ``"F_N"``, ``"s"``).
    lo, hi : float
        Range in SI, ``lo <= hi`` (equal: a single value).
    n : int, optional
        Number of points (the starting number in adaptive mode).
    spacing : {"auto", "lin", "log"}
        Point spacing; ``"auto"`` is log when ``lo > 0`` and ``hi / lo >= 100``.
    """

    name: str
    lo: float
    hi: float
    n: int | None = None
    spacing: str = "auto"

    def __post_init__(self) -> None:
        if not (math.isfinite(self.lo) and math.isfinite(self.hi)):
            raise InputError(f"range of {self.name} must be finite, got "
                             f"{self.lo!r}..{self.hi!r}")
        if self.lo > self.hi:
            raise InputError(f"range of {self.name}: MIN {self.lo:g} is larger than "
                             f"MAX {self.hi:g} (SI)")
        if self.spacing not in ("auto", "lin", "log"):
            raise InputError(f"spacing of {self.name} must be lin or log, got "
                             f"'{self.spacing}'")
        if self.spacing == "log" and self.lo <= 0:
            raise InputError(f"log spacing of {self.name} needs MIN > 0 (got {self.lo:g} SI); "
                             "use lin spacing or a positive MIN")
        if self.n is not None:
            if self.n < 1:
                raise InputError(f"number of points of {self.name} must be >= 1, got {self.n}")
            if self.n == 1 and self.lo != self.hi:
                raise InputError(f"{self.name}: one point cannot span {self.lo:g}..{self.hi:g}; "
                                 "give N >= 2 or MIN = MAX")

    @property
    def kind(self) -> str:
        """The resolved spacing, ``"lin"`` or ``"log"``."""
        if self.spacing != "auto":
            return self.spacing
        return "log" if self.lo > 0 and self.hi >= 100 * self.lo else "lin"

    @property
    def single(self) -> bool:
        """True when the range is a single value."""
        return self.lo == self.hi


def breakpoints(lo: float, hi: float, n: int, spacing: str = "lin") -> np.ndarray:
    """``n`` ascending points from ``lo`` to ``hi`` (ends exact)."""
    if lo == hi:
        return np.array([float(lo)])
    n = max(int(n), 2)
    pts = np.geomspace(lo, hi, n) if spacing == "log" else np.linspace(lo, hi, n)
    pts[0], pts[-1] = lo, hi
    return pts


@dataclass
class Grid:
    """A tensor grid: the breakpoints of each variable (SI, ascending)."""

    names: tuple[str, ...]
    points: tuple[np.ndarray, ...]
    spacing: tuple[str, ...]

    @property
    def shape(self) -> tuple[int, ...]:
        """Number of points per variable."""
        return tuple(len(p) for p in self.points)

    @property
    def rows(self) -> int:
        """Number of table rows (grid points)."""
        return int(np.prod(self.shape)) if self.points else 1

    def axis(self, name: str) -> np.ndarray:
        """The breakpoints of variable ``name``."""
        return self.points[self.names.index(name)]


@dataclass
class GridError:
    """How far the solver's interpolation of a table strays from the law.

    Attributes
    ----------
    max_abs : float
        Largest ``|mu_table - mu_law|`` found.
    where : dict
        Variable -> SI value where it occurs.
    rms : float
        Root mean square over the structured sample.
    n_checked : int
        Number of points checked.
    per_interval : int
        Points checked inside every grid interval along each variable.
    n_random : int
        Random points (uniform, log-uniform on log axes) among them.
    """

    max_abs: float
    where: dict[str, float] = field(default_factory=dict)
    rms: float = 0.0
    n_checked: int = 0
    per_interval: int = 0
    n_random: int = 0


# --------------------------------------------------------------- interpolation


def _locate(pts: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Interval index and weight of ``x`` on ``pts``, clamped to the ends."""
    xc = np.clip(x, pts[0], pts[-1])
    i = np.clip(np.searchsorted(pts, xc, side="right") - 1, 0, len(pts) - 2)
    t = (xc - pts[i]) / (pts[i + 1] - pts[i])
    return i, t


def interpolate(points: Sequence[np.ndarray], values: np.ndarray,
                query: Sequence[np.ndarray]) -> np.ndarray:
    """Multilinear interpolation with ends held, as FE solvers do.

    Parameters
    ----------
    points : sequence of ndarray
        Ascending breakpoints per variable (a single point: constant).
    values : ndarray
        Tabulated values, shape ``tuple(len(p) for p in points)``.
    query : sequence of ndarray
        Coordinates per variable (broadcastable to one shape).

    Returns
    -------
    ndarray
        Interpolated values; outside the grid the nearest end value is held.
    """
    values = np.asarray(values, dtype=float)
    if not points:
        q = np.broadcast_arrays(*query) if query else [np.zeros(())]
        return np.full(np.shape(q[0]), float(values.reshape(-1)[0]))
    q = np.broadcast_arrays(*[np.asarray(x, dtype=float) for x in query])
    loc: list[tuple[np.ndarray, np.ndarray] | None] = []
    for pts, x in zip(points, q):
        if len(pts) == 1:
            loc.append(None)
        else:
            loc.append(_locate(np.asarray(pts, float), x))
    out = np.zeros(q[0].shape)
    for corner in itertools.product((0, 1), repeat=len(points)):
        weight = np.ones(q[0].shape)
        index = []
        skip = False
        for c, lc in zip(corner, loc):
            if lc is None:
                if c:
                    skip = True
                    break
                index.append(np.zeros(q[0].shape, dtype=int))
                continue
            i, t = lc
            weight = weight * (t if c else 1.0 - t)
            index.append(i + c)
        if not skip:
            out += weight * values[tuple(index)]
    return out


def _interp_axis(values: np.ndarray, axis: int, pts: np.ndarray, x: np.ndarray) -> np.ndarray:
    """1D clamped linear interpolation of ``values`` along ``axis`` onto ``x``."""
    if len(pts) == 1:
        return np.repeat(values, len(x), axis=axis)
    i, t = _locate(pts, x)
    shape = [1] * values.ndim
    shape[axis] = -1
    t = t.reshape(shape)
    return np.take(values, i, axis=axis) * (1.0 - t) + np.take(values, i + 1, axis=axis) * t


def _interp_tensor(points: Sequence[np.ndarray], values: np.ndarray,
                   sample: Sequence[np.ndarray]) -> np.ndarray:
    """Multilinear interpolation onto a tensor sample (separable, fast)."""
    out = values
    for axis, (pts, x) in enumerate(zip(points, sample)):
        out = _interp_axis(out, axis, pts, x)
    return out


# ------------------------------------------------------------------ tabulation


def tabulate(func: Func, names: Sequence[str], axes: Sequence[np.ndarray]) -> np.ndarray:
    """Evaluate ``func(**{name: x})`` on the tensor grid of ``axes`` (chunked)."""
    shape = tuple(len(a) for a in axes)
    if not names:
        return np.asarray(func(), dtype=float).reshape(())
    out = np.empty(shape)
    inner = int(np.prod(shape[1:])) if len(shape) > 1 else 1
    step = max(1, _CHUNK // max(inner, 1))
    for start in range(0, shape[0], step):
        sl = slice(start, min(start + step, shape[0]))
        sub = [axes[0][sl]] + list(axes[1:])
        mesh = np.ix_(*sub)
        with np.errstate(all="ignore"):
            val = func(**dict(zip(names, mesh)))
        out[sl] = np.broadcast_to(np.asarray(val, dtype=float), out[sl].shape)
    return out


def _sample_axis(pts: np.ndarray, f: int) -> tuple[np.ndarray, np.ndarray]:
    """Breakpoints plus ``f`` evenly placed points inside each interval.

    Returns the sample and, for every sample point, the interval it lies
    inside (-1 for the breakpoints themselves).
    """
    if len(pts) == 1:
        return pts.copy(), np.array([-1])
    fr = np.arange(1, f + 1) / (f + 1)
    inner = pts[:-1, None] + (pts[1:] - pts[:-1])[:, None] * fr[None, :]
    interval = np.repeat(np.arange(len(pts) - 1), f)
    x = np.concatenate([pts, inner.ravel()])
    owner = np.concatenate([np.full(len(pts), -1), interval])
    order = np.argsort(x, kind="stable")
    return x[order], owner[order]


def _fractions(grid_shape: Sequence[int], budget: int, choices=(15, 11, 7, 5, 3)) -> int:
    for f in choices:
        size = np.prod([n + f * (n - 1) for n in grid_shape]) if grid_shape else 1
        if size <= budget:
            return f
    return choices[-1]


def _check_structured(func: Func, grid: Grid, values: np.ndarray, f: int
                      ) -> tuple[np.ndarray, list[np.ndarray], list[np.ndarray], np.ndarray]:
    samples, owners = zip(*(_sample_axis(p, f) for p in grid.points))
    exact = tabulate(func, grid.names, samples)
    with np.errstate(invalid="ignore", over="ignore"):
        approx = _interp_tensor(grid.points, values, samples)
        return exact, list(samples), list(owners), np.abs(approx - exact)


def _random_points(grid: Grid, n: int, seed: int = 12345) -> list[np.ndarray]:
    rng = np.random.default_rng(seed)
    out = []
    for pts, sp in zip(grid.points, grid.spacing):
        lo, hi = float(pts[0]), float(pts[-1])
        if lo == hi:
            out.append(np.full(n, lo))
        elif sp == "log" and lo > 0:
            out.append(np.exp(rng.uniform(np.log(lo), np.log(hi), n)))
        else:
            out.append(rng.uniform(lo, hi, n))
    return out


def check_error(func: Func, grid: Grid, values: np.ndarray | None = None, *,
                budget: int = _BUDGET_FINAL, n_random: int = _N_RANDOM) -> GridError:
    """The solver-interpolation error of ``grid`` against ``func``.

    The law is compared with the multilinear, end-held interpolation of the
    table on a dense structured sample (the breakpoints plus up to 15 points
    inside every interval along each variable, all combinations) and on
    ``n_random`` random points in the box.
    """
    if values is None:
        values = tabulate(func, grid.names, grid.points)
    if not grid.names:
        return GridError(0.0, {}, 0.0, 1, 0, 0)
    f = _fractions(grid.shape, budget)
    exact, samples, _, err = _check_structured(func, grid, values, f)
    bad = ~np.isfinite(err)
    if bad.any():
        idx = np.unravel_index(int(np.argmax(bad)), err.shape)
        where = {n: float(s[i]) for n, s, i in zip(grid.names, samples, idx)}
        raise InputError("the law is not finite at "
                         + ", ".join(f"{k}={v:g}" for k, v in where.items())
                         + " (SI) inside the box; shrink the box or check the parameters")
    k = int(np.argmax(err))
    idx = np.unravel_index(k, err.shape)
    max_abs = float(err[idx])
    where = {n: float(s[i]) for n, s, i in zip(grid.names, samples, idx)}
    rms = float(np.sqrt(np.mean(err**2)))
    n_checked = int(err.size)
    if n_random:
        q = _random_points(grid, n_random)
        with np.errstate(all="ignore"):
            ex = np.broadcast_to(np.asarray(func(**dict(zip(grid.names, q))), float), (n_random,))
        er = np.abs(interpolate(grid.points, values, q) - ex)
        if np.isfinite(er).all() and er.max() > max_abs:
            j = int(np.argmax(er))
            max_abs = float(er[j])
            where = {n: float(x[j]) for n, x in zip(grid.names, q)}
        n_checked += n_random
    return GridError(max_abs, where, rms, n_checked, f, n_random)


# ------------------------------------------------------------------ building


def _axis_points(spec: AxisSpec, n: int | None) -> np.ndarray:
    if spec.single:
        return np.array([spec.lo])
    return breakpoints(spec.lo, spec.hi, n or 2, spec.kind)


def fixed_grid(specs: Sequence[AxisSpec], n_default: int = DEFAULT_N) -> Grid:
    """The grid with the requested number of points per variable."""
    return Grid(tuple(s.name for s in specs),
                tuple(_axis_points(s, s.n or n_default) for s in specs),
                tuple(s.kind for s in specs))


def _directional(func: Func, grid: Grid, exact: np.ndarray, samples: list[np.ndarray],
                 owners: list[np.ndarray], axis: int) -> np.ndarray:
    """Largest 1D interpolation error along ``axis`` inside each of its intervals."""
    pts = grid.points[axis]
    if len(pts) == 1:
        return np.zeros(0)
    axes = list(samples)
    axes[axis] = pts
    at_bp = tabulate(func, grid.names, axes)
    d = np.abs(_interp_axis(at_bp, axis, pts, samples[axis]) - exact)
    d = np.moveaxis(d, axis, 0).reshape(len(samples[axis]), -1).max(axis=1)
    out = np.zeros(len(pts) - 1)
    inside = owners[axis] >= 0
    np.maximum.at(out, owners[axis][inside], d[inside])
    return out


def _interval_errors(func: Func, names: Sequence[str], a: int, x0: float, ends: np.ndarray,
                     context: Sequence[np.ndarray]) -> np.ndarray:
    """Largest 1D interpolation error along ``a`` on ``[x0, e]`` for each end ``e``.

    Measured at 7 evenly placed points inside each interval, with the other
    variables on the ``context`` points (largest over them).
    """
    fr = np.arange(1, 8) / 8.0
    inner = x0 + (ends - x0)[:, None] * fr[None, :]
    axes = list(context)
    axes[a] = np.concatenate([[x0], ends, inner.ravel()])
    vals = np.moveaxis(tabulate(func, names, axes), a, 0)
    n = len(ends)
    f0, fe = vals[0], vals[1:n + 1]
    fin = vals[n + 1:].reshape((n, len(fr)) + vals.shape[1:])
    frs = fr.reshape((1, -1) + (1,) * (vals.ndim - 1))
    lin = f0[None, None] * (1.0 - frs) + fe[:, None] * frs
    err = np.abs(fin - lin).reshape(n, -1)
    with np.errstate(invalid="ignore"):
        return np.where(np.isfinite(err).all(axis=1), err.max(axis=1), np.inf)


def _march_axis(func: Func, names: Sequence[str], a: int, lo: float, hi: float,
                context: Sequence[np.ndarray], tol_a: float, max_points: int) -> np.ndarray:
    """A 1D grid for variable ``a`` whose interpolation error is at most ``tol_a``.

    Marches from ``lo`` to ``hi`` taking, at each step, the longest interval
    (among candidates spaced by a factor 2^(1/4)) whose 1D error stays within
    ``tol_a``: the points gather where the law curves (error equidistribution).
    """
    if lo == hi:
        return np.array([lo])
    steps = 2.0 ** (np.arange(-16, 25) / 4.0)
    pts = [lo]
    x = lo
    h = (hi - lo) / 64.0
    h_min = (hi - lo) * 1e-9
    while x < hi:
        if len(pts) > max_points:
            break  # the caller only wants to know that it takes more than max_points
        if len(pts) > MAX_AXIS_POINTS:
            d = np.diff(pts)
            j = int(np.argmin(d))
            raise InputError(
                f"{names[a]} needs more than {MAX_AXIS_POINTS} breakpoints to meet the "
                f"tolerance; they crowd near {names[a]} = {pts[j]:.6g} (SI), where the law "
                "changes fastest (a pole or a step?); shrink the box, relax the tolerance "
                "or check the parameters")
        remaining = hi - x
        cand = np.unique(np.minimum(h * steps, remaining))
        err = _interval_errors(func, names, a, x, x + cand, context)
        if np.isinf(err).all():
            break  # the law is not finite here: the full check reports where
        ok = np.nonzero(err <= tol_a)[0]
        if len(ok) == 0:
            if cand[0] <= h_min:
                raise InputError(
                    f"the law changes by more than {tol_a:.2g} in mu within 1e-9 of the range "
                    f"of {names[a]} near {names[a]} = {x:.6g} (SI): a pole or a step; "
                    "shrink the box or check the parameters")
            h = cand[0] / 16.0
            continue
        step = _refined_step(func, names, a, x, cand, int(ok[-1]), context, tol_a)
        x_new = hi if step >= remaining * (1 - 1e-12) else x + step
        pts.append(x_new)
        h = step
        x = x_new
    if pts[-1] < hi:
        pts.append(hi)
    return np.unique(np.asarray(pts, dtype=float))


def _refined_step(func: Func, names: Sequence[str], a: int, x: float, cand: np.ndarray,
                  j: int, context: Sequence[np.ndarray], tol_a: float) -> float:
    """The longest step from ``x`` within ``tol_a``: candidate ``j`` passes, ``j + 1`` fails.

    Seven steps between the two candidates are tried; the longest that passes wins.
    """
    step = cand[j]
    if j + 1 < len(cand):  # refine between the last passing and the next candidate
        fine = np.linspace(cand[j], cand[j + 1], 9)[1:-1]
        e_fine = _interval_errors(func, names, a, x, x + fine, context)
        ok_fine = np.nonzero(e_fine <= tol_a)[0]
        if len(ok_fine):
            step = fine[ok_fine[-1]]
    return step


def adaptive_grid(func: Func, specs: Sequence[AxisSpec], tol: float, *,
                  max_rows: int = MAX_ROWS, max_iter: int = 200) -> tuple[Grid, GridError]:
    """A small grid whose solver interpolation is within ``tol`` of ``func``.

    1. Each variable gets its own non-uniform 1D grid whose one-dimensional
       interpolation error (largest over a context sample of the other
       variables) is at most ``s * tol / k`` (``k`` variables): intervals are
       split where the error is large, so points gather where the law curves.
    2. The multilinear error of the tensor grid is checked (:func:`check_error`)
       and the budget factor ``s`` is searched (bracketing) for the smallest
       table that meets ``tol``: errors along different variables rarely peak
       at the same point and may have opposite signs.
    3. Should no budget succeed, the cells where the error exceeds ``tol`` are
       split until it is met (repair phase).

    The grid stays a full tensor grid, as the solvers require.  Requested
    counts are not used: the tolerance decides the points.

    Raises
    ------
    InputError
        When ``tol`` is not positive or the table would exceed ``max_rows``.
    """
    if not tol > 0:
        raise InputError(f"tolerance must be positive, got {tol!r}")
    # aim 1 % below tol: the check samples the box densely but not continuously
    asked = tol
    tol = tol * (1.0 - _MARGIN)
    names = tuple(s.name for s in specs)
    spacing = tuple(s.kind for s in specs)
    start = [_axis_points(s, s.n) for s in specs]
    if not names:
        grid = Grid(names, (), spacing)
        return grid, check_error(func, grid)
    k = max(1, sum(1 for p in start if len(p) > 1))
    n_ctx = max(5, min(65, int(500 ** (1.0 / max(k - 1, 1)))))
    context = [breakpoints(s.lo, s.hi, n_ctx, s.kind) if not s.single else np.array([s.lo])
               for s in specs]

    best: tuple[Grid, GridError] | None = None
    best_s = 1.0
    s_ok, s_bad, s = 0.0, math.inf, 1.0
    last = start
    for _ in range(8):
        pts = [_march_axis(func, names, a, specs[a].lo, specs[a].hi, context, s * tol / k,
                           max_rows) for a in range(len(specs))]
        grid = Grid(names, tuple(pts), spacing)
        if grid.rows > max_rows:
            s_bad = min(s_bad, s)
            if s_ok == 0.0 and s <= 1.0:
                raise _too_many(grid, asked, max_rows)
        else:
            last = pts
            values = tabulate(func, names, grid.points)
            err = check_error(func, grid, values)
            if err.max_abs <= tol:
                if best is None or grid.rows < best[0].rows:
                    best, best_s = (grid, err), s
                s_ok = max(s_ok, s)
            else:
                s_bad = min(s_bad, s)
        if best is not None and s_bad / max(s_ok, 1e-300) < 1.15:
            break
        s = _next_budget(s_ok, s_bad, best[1].max_abs if best is not None else tol, tol)
    if best is None:
        return _repair(func, names, spacing, last, tol, max_rows, max_iter)
    if k > 1:
        best = _coordinate_pass(func, names, specs, context, best, best_s * tol / k, tol)
    return _evenly_spaced_if_smaller(func, names, specs, best, tol)


def _next_budget(s_ok: float, s_bad: float, err_now: float, tol: float) -> float:
    """The next error-budget factor of :func:`adaptive_grid`'s bracketing search.

    ``s_ok`` is the largest factor that met ``tol`` (0 if none yet), ``s_bad`` the
    smallest that did not (inf if none yet); ``err_now`` the best grid's error.
    """
    if s_bad == math.inf:
        return s_ok * min(4.0, max(1.2, tol / max(err_now, 1e-300)))
    if s_ok == 0.0:
        return s_bad * 0.6
    return math.sqrt(s_ok * s_bad)


def _evenly_spaced_if_smaller(func: Func, names: tuple[str, ...], specs: Sequence[AxisSpec],
                              best: tuple[Grid, GridError], tol: float
                              ) -> tuple[Grid, GridError]:
    """Keep the adaptive grid unless evenly spaced breakpoints do as well with fewer rows.

    Where a law's curvature is the same everywhere (a quadratic), even spacing
    is already optimal and the adaptive split of the tolerance between the
    variables can cost a few rows.  Starting from the adaptive grid's counts,
    each variable's count is lowered (bisection) while an evenly spaced grid
    (each variable's own lin/log spacing) still meets ``tol``.
    """
    grid = best[0]
    counts = [len(p) for p in grid.points]

    def build(c: Sequence[int]) -> Grid:
        return Grid(names, tuple(breakpoints(s.lo, s.hi, n, s.kind) if not s.single
                                 else np.array([s.lo]) for s, n in zip(specs, c)),
                    grid.spacing)

    def meets(c: Sequence[int]) -> bool:
        return check_error(func, build(c), budget=_BUDGET_REFINE, n_random=2000).max_abs <= tol

    if not meets(counts):
        return best
    for a, spec in enumerate(specs):
        lo, hi = (1 if spec.single else 2), counts[a]
        while lo < hi:
            mid = (lo + hi) // 2
            trial = list(counts)
            trial[a] = mid
            if meets(trial):
                hi = mid
            else:
                lo = mid + 1
        counts[a] = hi
    even = build(counts)
    if even.rows >= grid.rows:
        return best
    err = check_error(func, even)
    return (even, err) if err.max_abs <= tol else best


def _coordinate_pass(func: Func, names: tuple[str, ...], specs: Sequence[AxisSpec],
                     context: Sequence[np.ndarray], best: tuple[Grid, GridError],
                     tol_a: float, tol: float) -> tuple[Grid, GridError]:
    """Loosen one variable's budget at a time while the grid still meets ``tol``.

    Errors along different variables may offset each other (opposite signs) or
    peak in different places; a common budget cannot exploit that, this pass can.
    """
    grid, err = best
    for a in range(len(specs)):
        if len(grid.points[a]) <= 2:
            continue
        for factor in (1.6, 2.5, 4.0):
            pts = list(grid.points)
            pts[a] = _march_axis(func, names, a, specs[a].lo, specs[a].hi, context,
                                 factor * tol_a, len(grid.points[a]))
            if len(pts[a]) >= len(grid.points[a]):
                continue
            trial = Grid(names, tuple(pts), grid.spacing)
            e = check_error(func, trial)
            if e.max_abs > tol:
                break
            grid, err = trial, e
    return grid, err


def _repair(func: Func, names: tuple[str, ...], spacing: tuple[str, ...],
            pts: list[np.ndarray], tol: float, max_rows: int, max_iter: int
            ) -> tuple[Grid, GridError]:
    """Split the cells where the multilinear error exceeds ``tol`` until it is met."""
    for _ in range(max_iter):
        grid = Grid(names, tuple(pts), spacing)
        if grid.rows > max_rows:
            raise _too_many(grid, tol, max_rows)
        values = tabulate(func, names, grid.points)
        f = _fractions(grid.shape, _BUDGET_REFINE, choices=(7, 5, 3))
        exact, samples, owners, err = _check_structured(func, grid, values, f)
        if not np.isfinite(err).all():
            check_error(func, grid, values)  # raises with the location
        if err.max() <= tol:
            final = check_error(func, grid, values)
            if final.max_abs <= tol:
                return grid, final
            marks = _cell_marks(grid, final.where)
        else:
            marks = _error_marks(func, grid, exact, samples, owners, err, tol)
            if not marks:
                worst = np.unravel_index(int(np.argmax(err)), err.shape)
                marks = _cell_marks(grid, {n: s[i] for n, s, i in
                                           zip(names, samples, worst, strict=True)})
        pts = _split(pts, spacing, marks)
    raise InputError(f"adaptive grid did not reach tol {tol:g} in {max_iter} refinements "
                     f"({Grid(names, tuple(pts), spacing).rows} rows); relax the tolerance "
                     "or shrink the box")


def _too_many(grid: Grid, tol: float, max_rows: int) -> InputError:
    where = []
    for name, pts in zip(grid.names, grid.points, strict=True):
        if len(pts) > 2:
            j = int(np.argmin(np.diff(pts)))
            where.append(f"{name} = {0.5 * (pts[j] + pts[j + 1]):.6g}")
    near = (f"; the points crowd near {', '.join(where)} (SI), where the law changes "
            "fastest (a pole or a step?)" if where else "")
    return InputError([
        f"meeting tol {tol:.3g} needs more than {max_rows} table rows "
        f"(reached {_shape_text(grid)}){near}; relax the tolerance, shrink the box, or "
        "raise the row limit (", Argument("max_rows"), ")"])


def _shape_text(grid: Grid) -> str:
    """``12 x 9 = 108`` rows; ``7`` for one variable."""
    dims = " x ".join(map(str, grid.shape))
    return dims if len(grid.shape) == 1 else f"{dims} = {grid.rows}"


def _error_marks(func: Func, grid: Grid, exact: np.ndarray, samples: list[np.ndarray],
                 owners: list[np.ndarray], err: np.ndarray, tol: float
                 ) -> list[tuple[int, int, int]]:
    """Intervals to split where the multilinear error exceeds ``tol``.

    At every sample point with error ``E > tol``, the variables whose
    one-dimensional error is at least 30 % of the largest one are held
    responsible; their interval there is split into ``m = ceil(1.05 sqrt(E /
    tol))`` parts (linear interpolation error falls as the square of the
    spacing).  Driving the refinement by the total error, not by the sum of
    the one-dimensional errors, lets errors of opposite sign offset each other
    as they do in the solver.
    """
    dirs = []
    for a, pts in enumerate(grid.points):
        if len(pts) == 1:
            dirs.append(np.zeros_like(err))
            continue
        axes = list(samples)
        axes[a] = pts
        at_bp = tabulate(func, grid.names, axes)
        dirs.append(np.abs(_interp_axis(at_bp, a, pts, samples[a]) - exact))
    dmax = np.maximum.reduce(dirs) if dirs else np.zeros_like(err)
    over = err > tol
    need = np.where(over, np.minimum(64, np.ceil(1.05 * np.sqrt(err / tol))), 0.0)
    marks = []
    for a, d in enumerate(dirs):
        if len(grid.points[a]) == 1:
            continue
        m_a = np.where(over & (d >= 0.3 * dmax), need, 0.0)
        per_sample = np.moveaxis(m_a, a, 0).reshape(len(samples[a]), -1).max(axis=1)
        per_interval = np.zeros(len(grid.points[a]) - 1)
        inside = owners[a] >= 0
        np.maximum.at(per_interval, owners[a][inside], per_sample[inside])
        marks += [(a, int(j), max(2, int(m))) for j, m in enumerate(per_interval) if m > 0]
    return marks


def _cell_marks(grid: Grid, where: Mapping[str, float]) -> list[tuple[int, int, int]]:
    """Bisect the intervals (on every variable) of the cell containing ``where``."""
    marks = []
    for a, (name, pts) in enumerate(zip(grid.names, grid.points)):
        if len(pts) > 1:
            i, _ = _locate(pts, np.array([where[name]]))
            marks.append((a, int(i[0]), 2))
    return marks


def _split(pts: list[np.ndarray], spacing: Sequence[str], marks: list[tuple[int, int, int]]
           ) -> list[np.ndarray]:
    """Split interval ``j`` of axis ``a`` into ``m`` equal parts (geometric on log axes)."""
    new = [list(p) for p in pts]
    for a, j, m in marks:
        lo, hi = float(pts[a][j]), float(pts[a][j + 1])
        inner = breakpoints(lo, hi, m + 1, spacing[a] if lo > 0 else "lin")[1:-1]
        new[a].extend(inner.tolist())
    return [np.unique(np.asarray(p, dtype=float)) for p in new]


def uniform_grid_for_tol(func: Func, specs: Sequence[AxisSpec], tol: float, *,
                         spacing: str = "lin", max_rows: int = 2_000_000
                         ) -> tuple[Grid, GridError]:
    """The smallest evenly spaced grid (per-variable counts) meeting ``tol``.

    The baseline the adaptive grid is compared with.  ``spacing`` is
    ``"lin"``, ``"log"`` (where the range is positive) or ``"spec"`` (each
    variable's own spacing).  Counts grow on the
    variable with the largest one-dimensional error until the multilinear
    error is within ``tol``, then each count is lowered as far as the
    tolerance allows (bisection).
    """
    names = tuple(s.name for s in specs)
    if spacing not in ("lin", "log", "spec"):
        raise ValueError(f"spacing must be lin, log or spec, got {spacing!r}")
    kinds = tuple(s.kind if spacing == "spec" else
                  ("log" if spacing == "log" and s.lo > 0 else "lin") for s in specs)
    counts = [1 if s.single else 2 for s in specs]

    def build(c: Sequence[int]) -> Grid:
        return Grid(names, tuple(breakpoints(s.lo, s.hi, n, k) if not s.single
                                 else np.array([s.lo]) for s, n, k in zip(specs, c, kinds)),
                    kinds)

    def error(c: Sequence[int]) -> float:
        g = build(c)
        return check_error(func, g, budget=_BUDGET_REFINE, n_random=2000).max_abs

    while error(counts) > tol:
        g = build(counts)
        if g.rows > max_rows:
            raise _too_many(g, tol, max_rows)
        values = tabulate(func, names, g.points)
        f = _fractions(g.shape, _BUDGET_REFINE, choices=(7, 5, 3))
        exact, samples, owners, _ = _check_structured(func, g, values, f)
        d = [(_directional(func, g, exact, samples, owners, a).max(initial=0.0), a)
             for a in range(len(specs)) if not specs[a].single]
        a = max(d)[1]
        counts[a] = counts[a] + 1 if counts[a] < 16 else int(math.ceil(counts[a] * 1.15))
    for a in range(len(specs)):
        lo, hi = (1 if specs[a].single else 2), counts[a]
        while lo < hi:
            mid = (lo + hi) // 2
            trial = list(counts)
            trial[a] = mid
            if error(trial) <= tol:
                hi = mid
            else:
                lo = mid + 1
        counts[a] = hi
    g = build(counts)
    return g, check_error(func, g)


def make_grid(func: Func, specs: Sequence[AxisSpec], tol: float | None = None, *,
              max_rows: int = MAX_ROWS, default_tol: float = 1e-3
              ) -> tuple[Grid, GridError, str]:
    """The grid an export uses, with its error and a one-line description.

    * ``tol`` given: :func:`adaptive_grid` (requested counts are ignored);
    * no ``tol`` and every variable has a count: :func:`fixed_grid`;
    * otherwise adaptive with ``default_tol``.
    """
    if tol is None and all(s.n is not None or s.single for s in specs):
        rows = math.prod(1 if s.single else int(s.n or DEFAULT_N) for s in specs)
        if rows > max_rows:  # counted before a single point is allocated
            raise InputError(f"the requested grid has {rows} rows, more than the limit "
                             f"{max_rows}; use fewer points or raise the row limit")
        grid = fixed_grid(specs)
        err = check_error(func, grid)
        return grid, err, "fixed (points per variable as requested)"
    used = default_tol if tol is None else float(tol)
    if not specs:
        grid = Grid((), (), ())
        return grid, check_error(func, grid), "none (mu is constant)"
    grid, err = adaptive_grid(func, specs, used, max_rows=max_rows)
    how = (f"adaptive, tol {used:g}" + ("" if tol is not None else " (default)")
           + ": breakpoints added until the solver's interpolation is within tol")
    return grid, err, how
