"""What one export needs: the law, its values, units, box, and the common header.

Writers (one module per solver) receive a :class:`Job` and return a
:class:`Written`; the header every file carries (law, parameters with units,
unit system, box, grid, maximum interpolation error and where it occurs, what
the solver does outside the box) is composed here so all formats say the same
things the same way.
"""

from __future__ import annotations

import functools
import itertools
import math
import textwrap
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .. import __version__
from ..base.errors import Argument, DomainError, InputError
from ..base.sanitize import ascii_line
from ..law import MU_MAX, VARIABLES, Law
from .grid import AxisSpec, Grid, GridError, make_grid, tabulate
from .systems import UnitSystem

#: Points at which the law is checked in the box before export (spread over the axes).
_BOX_SAMPLES = 200_000

__all__ = ["Job", "Written", "commented", "fmt_num"]


def fmt_num(x: float, digits: int = 6) -> str:
    """A compact number for headers and messages."""
    return f"{float(x):.{digits}g}"


@dataclass
class Written:
    """What a writer produced.

    Attributes
    ----------
    text : str
        The file content.
    rows : int or None
        Table rows (grid points), None for formula exports.
    error : GridError or None
        Interpolation (or approximation) error, SI locations.
    exact : bool
        True when the file reproduces the law exactly (a formula, not a table).
    summary : list of str
        Lines to show the user (also in the header).
    grid : Grid or None
        The grid written, when there is one.
    details : dict
        Format-specific facts (fitted coefficients, ids...).
    """

    text: str
    rows: int | None = None
    error: GridError | None = None
    exact: bool = False
    summary: list[str] = field(default_factory=list)
    grid: Grid | None = None
    details: dict[str, Any] = field(default_factory=dict)


@dataclass
class Job:
    """Everything a writer needs for one export.

    Attributes
    ----------
    law : Law
        The law.
    values : dict
        Complete parameters and settings in SI (``law.resolve`` output).
    fmt : str
        Export format.
    units : UnitSystem
        The units the file is written in.
    specs : dict
        Variable -> :class:`AxisSpec` (SI) for the ranges the user gave.
    tol : float or None
        Interpolation tolerance (adaptive grid) or None.
    max_rows : int
        Largest table allowed.
    source : str
        Where the parameter values came from.
    fit : BoundLaw, optional
        The :class:`~frictionlaws.law.bound.BoundLaw` the values came from (standard
        errors, fixed parameters, fitted ranges).
    options : dict
        The format's options, checked, with their defaults (:mod:`frictionlaws.fe_export.formats`).
    warnings : list of str
        Warnings collected on the way (written in the header and returned).
    """

    law: Law
    values: dict[str, float]
    fmt: str
    units: UnitSystem
    specs: dict[str, AxisSpec]
    tol: float | None
    max_rows: int
    source: str
    fit: Any = None
    options: dict[str, Any] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)

    @functools.cached_property
    def variables(self) -> tuple[str, ...]:
        """The law's variables the export depends on: an optional variable whose
        parameter has its neutral value (Burckhardt's ``v`` with ``c4 = 0``) is left out."""
        return self.law.required_variables(self.values)

    @functools.cached_property
    def func(self) -> Callable[..., Any]:
        """The law as a fast vectorised function of its variables (SI)."""
        return self.law.bind(self.values)

    def require_box(self, names: Sequence[str], what: str) -> list[AxisSpec]:
        """The ranges of ``names``; InputError naming the option when one is missing."""
        missing = [n for n in names if n not in self.specs]
        if missing:
            hints: list[str | Argument] = []
            for m in missing:  # each range as the front end sets it (the CLI: --p MIN:MAX)
                hints += [" " if hints else "", Argument(f"box.{m}", "MIN:MAX[:N]")]
            raise InputError(
                [f"{what}: law '{self.law.id}' depends on "
                 + ", ".join(f"{m} ({self.law.meaning(m)})" for m in missing)
                 + "; give its range: ", *hints])
        return [self.specs[n] for n in names]

    def make_grid(self, names: Sequence[str], what: str) -> tuple[Grid, GridError, str]:
        """The grid over ``names`` (the order of the table's axes) and its error.

        Before any grid is built, the law is checked on a dense sampling of the box
        and on its corners: a non-finite or negative mu anywhere is refused.
        """
        specs = self.require_box(names, what)
        self.check_box(specs)
        grid, err, how = make_grid(self.func, specs, self.tol, max_rows=self.max_rows)
        self._refuse_bad_mu(grid.names, np.meshgrid(*grid.points, indexing="ij"))
        return grid, err, how

    def check_box(self, specs: Sequence[AxisSpec]) -> None:
        """Refuse a law whose mu is non-finite or negative somewhere in the box, and a box
        beyond a strict domain (a law that must not be extrapolated)."""
        if self.law.strict_domain:
            for spec in specs:
                lo, hi = self.law.domain.get(spec.name, (-np.inf, np.inf))
                if spec.lo < lo * (1 - 1e-9) or spec.hi > hi * (1 + 1e-9):
                    raise InputError(
                        f"law '{self.law.id}' is valid only for {spec.name} in "
                        f"{self.model(spec.name, lo)} .. {self.model(spec.name, hi)} and must "
                        f"not be extrapolated; the box asks for {self.model(spec.name, spec.lo)}"
                        f" .. {self.model(spec.name, spec.hi)}")
        per_axis = max(2, int(round(_BOX_SAMPLES ** (1.0 / max(len(specs), 1)))))
        axes = []
        for spec in specs:
            lo, hi = spec.lo, spec.hi
            log = lo > 0 and hi / lo >= 100 and spec.spacing != "lin"
            pts = np.geomspace(lo, hi, per_axis) if log else np.linspace(lo, hi, per_axis)
            axes.append(pts)
        mesh = np.meshgrid(*axes, indexing="ij") if axes else []
        self._refuse_bad_mu(tuple(s.name for s in specs), mesh)

    def _refuse_bad_mu(self, names: Sequence[str], mesh: Sequence[np.ndarray]) -> None:
        with np.errstate(all="ignore"):
            mu = np.asarray(self.func(**dict(zip(names, mesh))), dtype=float)
        mu = np.broadcast_to(mu, mesh[0].shape) if mesh else np.atleast_1d(mu)
        bad = ~np.isfinite(mu) | (mu < 0) | (mu > MU_MAX)
        if not bad.any():
            return
        idx = tuple(int(i) for i in np.argwhere(bad)[0])
        where = ", ".join(f"{n} = {self.model(n, float(m[idx]))}" for n, m in zip(names, mesh))
        value = mu[idx] if mu.ndim else float(mu)
        raise InputError(
            f"law '{self.law.id}' gives mu = {value:.4g} at {where or 'every point'}: "
            f"a friction coefficient must be finite and in 0..{MU_MAX:g} everywhere in "
            "the exported box; nothing was written (narrow the box or check the parameters)")

    def check_levels(self, levels: Mapping[str, float]) -> None:
        """Refuse friction levels of a formula card (``mu_s``, ``mu_k``...) outside
        0..:data:`frictionlaws.law.MU_MAX`: the solver reaches them at some slip rate."""
        for name, value in levels.items():
            if not (math.isfinite(value) and 0 <= value <= MU_MAX):
                raise InputError(
                    [f"law '{self.law.id}': {name} = {value:.6g} in the {self.fmt} card is not "
                     f"a friction coefficient in 0..{MU_MAX:g}; nothing was written "
                     "(check the parameters; a fit that cannot determine them needs ",
                     Argument("fix"), ")"])

    def check_corners(self, needs_box: bool) -> None:
        """Refuse a box reaching where the law itself is undefined (before any output).

        The law is evaluated, with the checks of its evaluation (a WLF pole) and of its
        floors (no limit at v = 0 or p = 0), at each corner of the box (a variable
        without a range at the ends of its typical range): the exporters evaluate the
        law through :meth:`Law.bind`, which gives NaN there and names no cause.
        A table (``needs_box``) missing a range is left to the writer, which names it.

        Raises
        ------
        DomainError
            Naming the box and what the law says there.
        """
        names = list(self.variables)
        if not names or (needs_box and any(v not in self.specs for v in names)):
            return
        ends = [(self.specs[v].lo, self.specs[v].hi) if v in self.specs
                else self.law.typical_range(v) for v in names]
        corners = np.array(list(itertools.product(*ends)), float)
        try:
            point = {v: corners[:, j] for j, v in enumerate(names)}
            mu = np.asarray(self.law.evaluate(point, self.values), float)
            if self.law.floors and not np.all(np.isfinite(mu)):  # no limit at 0: say so
                self.law.below_floors(point, self.law.prepare_variables(point), self.values,
                                      mu, strict=True)
        except DomainError as exc:
            box = ", ".join(f"{v} {self.model(v, lo)} .. {self.model(v, hi)}"
                            for v, (lo, hi) in zip(names, ends))
            raise DomainError(f"the export box ({box}) reaches where law '{self.law.id}' is "
                              f"undefined: {exc.bare_message}") from None

    def floor_warnings(self) -> None:
        """Warn where generated code, which floors its variables, departs from the law at 0.

        A user subroutine is called wherever the simulation goes, v = 0 (sticking)
        included, and applies the floors of :attr:`Law.floors` as the formula needs
        them; the law's value at 0 is its limit (:meth:`Law.below_floors`).  Where the
        two differ by more than the export's tolerance (or the law has no limit there),
        the export says so, with both numbers, at the corners of the box.
        """
        tol = self.tol if self.tol is not None else 1e-3
        names = list(self.variables)
        ends = [(self.specs[v].lo, self.specs[v].hi) if v in self.specs
                else self.law.typical_range(v) for v in names]
        corners = np.array(list(itertools.product(*ends)), float)
        for var, floor in self.law.floors.items():
            if var not in names:
                continue
            j = names.index(var)
            point = {v: corners[:, i] for i, v in enumerate(names)}
            at_zero = np.asarray(self.law.evaluate({**point, var: 0.0 * corners[:, j]},
                                                   self.values), float)
            at_floor = np.asarray(self.func(**{**point, var: floor + 0.0 * corners[:, j]}),
                                  float)
            gap = np.abs(at_floor - at_zero)
            if np.all(np.isfinite(at_zero)) and float(np.max(gap)) <= tol:
                continue
            k = int(np.nanargmax(np.where(np.isfinite(gap), gap, np.inf)))
            law_says = (f"the law's limit is {at_zero[k]:.6g}" if np.isfinite(at_zero[k])
                        else "the law has no limit there")
            self.warnings.append(
                f"the routine floors {var} at {self.model(var, floor)}: at {var} = 0 it "
                f"gives mu = {at_floor[k]:.6g} where {law_says} (at "
                + ", ".join(f"{v} = {self.model(v, corners[k, i])}" for i, v in
                            enumerate(names) if v != var) + ")")

    def check_formula_box(self, *, code: bool = False) -> None:
        """Check a formula export (no table) where the solver will evaluate it.

        The box given for a variable, else the law's typical range, is sampled as for
        tables: mu must be finite and in 0..:data:`frictionlaws.law.MU_MAX` there.  With ``code``
        (a user subroutine, evaluated wherever the simulation goes) a law with a strict
        domain is refused: only a table holds its ends.
        """
        if self.law.strict_domain and code:
            raise InputError(
                f"law '{self.law.id}' is valid only inside its measured box and must not be "
                f"extrapolated; an export to {self.fmt} would evaluate it anywhere: export a "
                "table (csv, abaqus, ansys, lsdyna) over the box instead")
        specs = [self.specs[v] if v in self.specs
                 else AxisSpec(v, *self.law.typical_range(v))
                 for v in self.law.variables]
        self.check_box(specs)

    # ------------------------------------------------------------- header
    def model(self, var: str, x_si: float) -> str:
        """``"0.25 MPa"``: an SI value written in the model's unit."""
        unit = self.units.unit(var)
        val = float(self.units.to_model(var, x_si))
        return f"{fmt_num(val)} {unit}".rstrip()

    def param_lines(self) -> list[str]:
        """Parameter and setting lines with units (and standard errors from a fit)."""
        out = ["parameters (SI, as the law is defined):"]
        stderr = getattr(self.fit, "stderr", None) or {}
        fixed = getattr(self.fit, "fixed", None) or ()
        for p in self.law.params:
            unit = p.unit or "-"
            line = f"  {p.name} = {self.values[p.name]!r} [{unit}]"
            if stderr.get(p.name) is not None:
                line += f" +/- {fmt_num(stderr[p.name], 3)} (standard error)"
            elif p.name in fixed:
                line += " (fixed)"
            out.append(line + (f"  {p.meaning}" if p.meaning else ""))
        for s in self.law.settings:
            unit = s.unit or "-"
            out.append(f"  {s.name} = {self.values[s.name]!r} [{unit}] (setting)"
                       + (f"  {s.meaning}" if s.meaning else ""))
        if self.law.floors:
            out.append("floors (applied before the formula, as the Python law does): "
                       + ", ".join(f"{k} >= {fmt_num(v)} {VARIABLES[k].unit}".rstrip()
                                   for k, v in self.law.floors.items()))
        return out

    def box_lines(self, grid: Grid | None = None) -> list[str]:
        """The box in model units, with the grid when there is one."""
        if grid is None:
            if not self.specs:
                return []
            return ["box: " + "; ".join(
                f"{n} {self.model(n, s.lo)} .. {self.model(n, s.hi)}"
                for n, s in self.specs.items() if n in self.variables)]
        parts = []
        for name, pts in zip(grid.names, grid.points, strict=True):
            sp = _spacing_label(pts)
            if len(pts) == 1:
                parts.append(f"{name} {self.model(name, pts[0])} (a single value)")
            else:
                parts.append(f"{name} {self.model(name, pts[0])} .. "
                             f"{self.model(name, pts[-1])} ({len(pts)} points, {sp})")
        return ["box: " + "; ".join(parts) if parts else "box: none (mu is constant)",
                f"table rows: {grid.rows}"]

    def error_lines(self, err: GridError | None, how: str, kind: str = "interpolation"
                    ) -> list[str]:
        """Maximum error, where it occurs, rms and how it was checked."""
        if err is None:
            return []
        where = ", ".join(f"{k} = {self.model(k, v)}" for k, v in err.where.items())
        out = [f"grid: {how}"] if how else []
        out.append(f"max {kind} error |mu_file - mu_law| = {err.max_abs:.3g}"
                   + (f" at {where}" if where else "")
                   + f"; rms {err.rms:.3g}")
        if err.n_checked > 1:
            out.append(f"checked on {err.n_checked} points: every breakpoint and "
                       f"{err.per_interval} points inside every interval along each "
                       f"variable (all combinations), plus {err.n_random} random points")
        return out

    def domain_warnings(self) -> None:
        """Warn when the box leaves the law's domain or the fitted data's range."""
        for name, spec in self.specs.items():
            if name not in self.variables:
                continue
            dom = self.law.domain.get(name)
            if dom and (spec.lo < dom[0] * (1 - 1e-9) - 1e-300 or spec.hi > dom[1] * (1 + 1e-9)):
                self.warnings.append(
                    f"the box of {name} ({self.model(name, spec.lo)} .. "
                    f"{self.model(name, spec.hi)}) leaves the law's domain "
                    f"({self.model(name, dom[0])} .. {self.model(name, dom[1])}): "
                    "the exported values there are an extrapolation of the law")
            rng = (getattr(self.fit, "fitted_ranges", None) or {}).get(name)
            if rng and (spec.lo < rng[0] * (1 - 1e-9) - 1e-300 or spec.hi > rng[1] * (1 + 1e-9)):
                self.warnings.append(
                    f"the box of {name} extends beyond the fitted data "
                    f"({self.model(name, rng[0])} .. {self.model(name, rng[1])}): "
                    "extrapolation of the fit")
        for name, spec in self.specs.items():
            if name in self.variables and spec.single:
                self.warnings.append(
                    f"{name} has a single value ({self.model(name, spec.lo)}): the file holds mu "
                    f"at that {name} for every {name} the model reaches")
        for name in self.specs:
            if name not in self.variables:
                self.warnings.append(f"law '{self.law.id}' does not depend on {name}: "
                                     "its range is ignored")

    def _dropped_lines(self) -> list[str]:
        """Optional variables the export leaves out, and why (their parameter is neutral)."""
        out = []
        for var in self.law.variables:
            if var not in self.variables:
                pname, neutral = self.law.optional_variables[var]
                out.append(f"{var} ({self.law.meaning(var)}) left out: it drops out of the law "
                           f"at {pname} = {neutral:g}")
        return out

    def header(self, title: str, body: Sequence[str], outside: str | None) -> list[str]:
        """The header lines every exported file starts with."""
        law = self.law
        try:
            formula = law.pretty()
        except Exception:  # noqa: BLE001 - a plugin law's symbolic form may fail
            formula = "(symbolic form unavailable)"
        lines = [
            f"frictionlaws {__version__} export: {title}",
            f"law: {law.id} - {law.title} (evidence {law.evidence})",
            f"formula: {formula}",
            *self.param_lines(),
            f"parameters from: {self.source}",
            f"units: {self.units.describe(self.variables)}",
            *self._dropped_lines(),
            *body,
        ]
        if outside:
            lines.append(f"outside the box: {outside}")
        for w in self.warnings:
            lines.append(f"WARNING: {w}")
        return lines


def commented(lines: Sequence[str], prefix: str, width: int = 78) -> list[str]:
    """Header lines as comments, wrapped to ``width`` columns.

    Every line goes through :func:`~frictionlaws.base.sanitize.ascii_line` first: a name or
    source with a line break or a control character stays inside its comment.
    """
    out = []
    for line in map(ascii_line, lines):
        if not line:
            out.append(prefix.rstrip())
            continue
        indent = len(line) - len(line.lstrip())
        wrapped = textwrap.wrap(line, max(20, width - len(prefix)),
                                subsequent_indent=" " * (indent + 2),
                                break_long_words=False, break_on_hyphens=False)
        out += [(prefix + w).rstrip() for w in wrapped or [""]]
    return out


def model_axes(job: Job, grid: Grid) -> list[np.ndarray]:
    """The grid's breakpoints converted to the model's units."""
    return [np.asarray(job.units.to_model(n, p), float)
            for n, p in zip(grid.names, grid.points, strict=True)]


def tabulated(job: Job, grid: Grid) -> np.ndarray:
    """mu on the grid (SI evaluation)."""
    return tabulate(job.func, grid.names, grid.points)


def _spacing_label(pts: np.ndarray) -> str:
    """How the breakpoints are spaced, read off the points themselves."""
    pts = np.asarray(pts, float)
    if len(pts) < 3:
        return "ends only"
    if np.allclose(np.diff(pts), (pts[-1] - pts[0]) / (len(pts) - 1), rtol=1e-6, atol=0):
        return "evenly spaced"
    if pts[0] > 0:
        lp = np.log(pts)
        if np.allclose(np.diff(lp), (lp[-1] - lp[0]) / (len(pts) - 1), rtol=1e-6, atol=0):
            return "log-spaced"
    return "uneven: refined where mu curves"
