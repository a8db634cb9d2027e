"""A law's declaration and its parameters: :class:`LawDeclaration`.

The fields a law is declared with (documented on :class:`~frictionlaws.law.Law`), their
consistency checks, and everything about parameter and setting values: names, bounds,
presets, the one validation of values (:meth:`LawDeclaration.check_values`), the
initial guess and the JSON-able summary.  Evaluation, floors and the symbolic form are
the rooms built on it (:mod:`~frictionlaws.law.domain`,
:mod:`~frictionlaws.law.evaluation`, :mod:`~frictionlaws.law.text`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, TypeVar

import numpy as np

from ..base.errors import InputError
from ..base.units import si_magnitude
from .declaration import FAMILIES, VARIABLES, Derived, Param, Setting

__all__ = ["LawDeclaration"]


@dataclass(eq=False)
class LawDeclaration:
    """The declaration of a law and its parameter values.

    The base of :class:`~frictionlaws.law.Law`, the class to build, where the fields
    are documented.
    """

    id: str
    title: str
    family: str
    variables: tuple[str, ...]
    params: tuple[Param, ...]
    formula: Callable[..., Any]
    settings: tuple[Setting, ...] = ()
    floors: Mapping[str, float] = field(default_factory=dict)
    presets: Mapping[str, Mapping[str, float]] = field(default_factory=dict)
    domain: Mapping[str, tuple[float, float]] = field(default_factory=dict)
    typical: Mapping[str, tuple[float, float]] = field(default_factory=dict)
    references: tuple[str, ...] = ()
    evidence: str = "M"
    guess: Callable[[Mapping[str, np.ndarray]], dict[str, float]] | None = None
    derived: tuple[Derived, ...] = ()
    admissible: Callable[[Mapping[str, float]], str | None] | None = None
    linear: bool = False
    aliases: tuple[str, ...] = ()
    optional_variables: Mapping[str, tuple[str, float]] = field(default_factory=dict)
    variable_meanings: Mapping[str, str] = field(default_factory=dict)
    strict_domain: bool = False
    description: str = ""
    notes: str = ""

    def __post_init__(self) -> None:
        if self.family not in FAMILIES:
            raise ValueError(f"law {self.id}: family must be one of {FAMILIES}")
        unknown = set(self.variables) - set(VARIABLES)
        if unknown:
            raise ValueError(f"law {self.id}: unknown variables {sorted(unknown)}")
        names = [p.name for p in self.params] + [s.name for s in self.settings]
        if len(set(names)) != len(names):
            raise ValueError(f"law {self.id}: duplicate parameter/setting names")
        clash = set(names) & set(VARIABLES)
        if clash:
            raise ValueError(f"law {self.id}: names clash with variables {clash}")
        self._check_optional_variables()
        for name, preset in self.presets.items():
            missing = {p.name for p in self.params if not p.optional} - set(preset)
            extra = set(preset) - set(names)
            if missing or extra:
                raise ValueError(
                    f"law {self.id}: preset {name!r} missing {sorted(missing)} "
                    f"or unknown {sorted(extra)}"
                )

    def _check_optional_variables(self) -> None:
        for var, (pname, neutral) in self.optional_variables.items():
            if var not in self.variables:
                raise ValueError(f"law {self.id}: optional variable {var!r} is not a variable")
            decl = next((p for p in self.params if p.name == pname), None)
            if decl is None:
                raise ValueError(f"law {self.id}: optional variable {var!r} names unknown "
                                 f"parameter {pname!r}")
            if not decl.bounds[0] <= neutral <= decl.bounds[1]:
                raise ValueError(f"law {self.id}: neutral value {neutral!r} of {pname!r} is "
                                 "outside its bounds")
        unknown = set(self.variable_meanings) - set(self.variables)
        if unknown:
            raise ValueError(f"law {self.id}: meanings given for unknown variables "
                             f"{sorted(unknown)}")

    def meaning(self, variable: str) -> str:
        """Return what ``variable`` is in this law (its own wording, else the generic one).

        Parameters
        ----------
        variable : str
            A variable name (``"p"``, ``"v"``, ``"T"``, ``"F_N"``, ``"s"``).

        Returns
        -------
        str
            E.g. ``"contact pressure"``; burckhardt's ``v`` is the vehicle speed.
        """
        return self.variable_meanings.get(variable, VARIABLES[variable].meaning)

    def required_variables(self, params: Mapping[str, float] | None = None) -> tuple[str, ...]:
        """The variables an evaluation needs.

        Parameters
        ----------
        params : mapping, optional
            Parameter values; an optional variable whose parameter has its
            neutral value here is not needed.  Without it, only the
            variables that are never optional.

        Returns
        -------
        tuple of str
            The variable names, in the law's order.
        """
        out = []
        for var in self.variables:
            opt = self.optional_variables.get(var)
            if opt is not None and (params is None or params.get(opt[0]) == opt[1]):
                continue
            out.append(var)
        return tuple(out)

    def neutral_fixes(self, available: set[str] | Mapping[str, Any]) -> dict[str, float]:
        """Return the parameters to fix at their neutral value (their variable is absent).

        Parameters
        ----------
        available : set of str or mapping
            The variables the data have.

        Returns
        -------
        dict
            Parameter name -> neutral value, for every optional variable not available.
        """
        return {pname: neutral for var, (pname, neutral) in self.optional_variables.items()
                if var not in available}

    def _fill_optional(self, variables: Mapping[str, Any], params: Mapping[str, float]
                       ) -> dict[str, Any]:
        """``variables`` plus absent optional variables (0) whose parameter is neutral."""
        out = dict(variables)
        for var, (pname, neutral) in self.optional_variables.items():
            if var not in out and params.get(pname) == neutral:
                out[var] = 0.0
        return out

    @property
    def param_names(self) -> tuple[str, ...]:
        """Names of the fitted parameters, in declaration order."""
        return tuple(p.name for p in self.params)

    @property
    def setting_values(self) -> dict[str, float]:
        """The default values of the fixed settings."""
        return {s.name: s.value for s in self.settings}

    def param(self, name: str) -> Param:
        """Return the :class:`Param` called ``name``.

        Parameters
        ----------
        name : str
            A parameter name.

        Returns
        -------
        Param
            Its declaration.
        """
        return _named(self.id, "parameter", self.params, name)

    def setting(self, name: str) -> Setting:
        """Return the :class:`Setting` called ``name``.

        Parameters
        ----------
        name : str
            A setting name.

        Returns
        -------
        Setting
            Its declaration.
        """
        return _named(self.id, "setting", self.settings, name)

    @property
    def defaults(self) -> dict[str, float]:
        """Default parameter values."""
        return {p.name: p.default for p in self.params}

    def typical_range(self, name: str) -> tuple[float, float]:
        """Return the default plotting/tabulation range of variable ``name`` in SI.

        Parameters
        ----------
        name : str
            A variable name.

        Returns
        -------
        tuple of float
            (low, high) in SI.
        """
        if name in self.typical:
            return self.typical[name]
        if name in self.domain:
            return self.domain[name]
        return VARIABLES[name].typical

    # ------------------------------------------------------------- parameters
    def resolve(self, values: Mapping[str, float] | None = None, preset: str | None = None
                ) -> dict[str, float]:
        """Complete parameters and settings: preset, then ``values``, then defaults.

        Parameters
        ----------
        values : mapping, optional
            Parameter and setting values by name.
        preset : str, optional
            A preset name.

        Returns
        -------
        dict
            Every parameter and setting, checked.

        Raises
        ------
        InputError
            When a required parameter is missing or a name is unknown.
        """
        out: dict[str, float] = dict(self.setting_values)
        if preset is not None:
            if preset not in self.presets:
                raise InputError(
                    f"law '{self.id}' has no preset '{preset}' "
                    f"(presets: {', '.join(self.presets) or 'none'})"
                )
            out.update(self.presets[preset])
        values = dict(values or {})
        known = set(self.param_names) | set(out)
        unknown = set(values) - known
        if unknown:
            raise InputError(
                f"law '{self.id}' does not take {', '.join(sorted(unknown))} "
                f"(parameters: {', '.join(self.param_names)}; settings: "
                f"{', '.join(s.name for s in self.settings) or 'none'})"
            )
        out.update({k: _as_float(k, si_magnitude(v, self.value_unit(k), f"law '{self.id}': {k}"),
                                  self.id) for k, v in values.items()})
        missing = []
        for p in self.params:
            if p.name not in out:
                if p.optional:
                    out[p.name] = p.default
                else:
                    missing.append(p.name)
        if missing:
            raise InputError(
                f"law '{self.id}' needs parameter(s) {', '.join(missing)} "
                "(give them, or a preset)"
            )
        self.check_values(out)
        return out

    def bounds_of(self, name: str) -> tuple[float, float]:
        """Return the declared bounds of a parameter or setting ``name``.

        Parameters
        ----------
        name : str
            A parameter or setting name.

        Returns
        -------
        tuple of float
            (lower, upper).
        """
        for p in self.params:
            if p.name == name:
                return p.bounds
        return self.setting(name).bounds

    def check_values(self, values: Mapping[str, float], *, admissible: bool = True) -> None:
        """Refuse parameter or setting values that are non-finite or outside their bounds.

        This is the one validation of parameter values: every entry point
        (evaluation, fixed values of a fit, saved results, presets, export, tyre
        models) goes through :meth:`resolve`, which calls it.  Admissibility
        (e.g. a denominator that can vanish) is checked too.

        Parameters
        ----------
        values : mapping
            Parameter and setting values by name (a complete set when
            ``admissible`` is True).
        admissible : bool
            Also check the law's admissibility rule on the complete set.

        Raises
        ------
        InputError
            Naming the law, the parameter, its value and the bounds expected.
        """
        for name, value in values.items():
            lo, hi = self.bounds_of(name)
            if not math.isfinite(value):
                raise InputError(f"law '{self.id}': {name} = {value} is not a finite number")
            if not lo <= value <= hi:
                unit = self._unit_of(name)
                raise InputError(
                    f"law '{self.id}': {name} = {value:.6g}{unit} is outside its bounds "
                    f"[{lo:.6g}, {hi:.6g}]{unit} ({self._meaning_of(name)})"
                )
        if not admissible:
            return
        message = self.check_admissible(values)
        if message:
            raise InputError(f"law '{self.id}': parameters not admissible: {message}")

    def _declared(self, name: str) -> Param | Setting | None:
        for p in self.params:
            if p.name == name:
                return p
        for s in self.settings:
            if s.name == name:
                return s
        return None

    def value_unit(self, name: str) -> str:
        """The SI unit of a parameter or setting.

        Parameters
        ----------
        name : str
            A parameter or setting of the law.

        Returns
        -------
        str
            Its unit (``""`` when dimensionless or not a name of the law).
        """
        decl = self._declared(name)
        return decl.unit if decl is not None else ""

    def _unit_of(self, name: str) -> str:
        decl = self._declared(name)
        return f" {decl.unit}" if decl is not None and decl.unit else ""

    def _meaning_of(self, name: str) -> str:
        decl = self._declared(name)
        return decl.meaning if decl is not None else ""

    def check_admissible(self, params: Mapping[str, float]) -> str | None:
        """Say why ``params`` are not admissible.

        Parameters
        ----------
        params : mapping
            A complete set of parameter and setting values.

        Returns
        -------
        str or None
            The reason, or None when they are admissible.
        """
        if self.admissible is None:
            return None
        return self.admissible(params)

    def initial_guess(self, data: Mapping[str, np.ndarray]) -> dict[str, float]:
        """Return a data-driven initial guess, clipped into the bounds.

        Parameters
        ----------
        data : mapping
            ``"mu"`` and the variables as arrays (SI).

        Returns
        -------
        dict
            Parameter name -> start value.
        """
        guess = self.defaults
        if self.guess is not None:
            try:
                with np.errstate(all="ignore"):
                    g = self.guess(data)
                guess.update({k: float(v) for k, v in g.items() if np.isfinite(v)})
            except (ValueError, np.linalg.LinAlgError, FloatingPointError, ZeroDivisionError):
                pass
        for p in self.params:
            lo, hi = p.bounds
            val = guess[p.name]
            if not lo <= val <= hi:
                span = (hi - lo) if np.isfinite(hi - lo) else max(abs(val), 1.0)
                val = min(max(val, lo + 1e-6 * span if np.isfinite(lo) else val),
                          hi - 1e-6 * span if np.isfinite(hi) else val)
            guess[p.name] = val
        return guess

    def summary(self) -> dict[str, Any]:
        """Describe the law as JSON-able data (used by ``show --json`` and the docs).

        Returns
        -------
        dict
            Declaration fields by name.
        """
        return {
            "id": self.id,
            "title": self.title,
            "aliases": list(self.aliases),
            "family": self.family,
            "variables": {v: VARIABLES[v].unit for v in self.variables},
            "variable_meanings": {v: self.meaning(v) for v in self.variables},
            "optional_variables": {v: {"parameter": p, "neutral": n}
                                   for v, (p, n) in self.optional_variables.items()},
            "params": [
                {"name": p.name, "unit": p.unit, "default": p.default,
                 "bounds": [_jsonable(b) for b in p.bounds], "meaning": p.meaning,
                 "optional": p.optional}
                for p in self.params
            ],
            "settings": [
                {"name": s.name, "value": s.value, "unit": s.unit, "meaning": s.meaning}
                for s in self.settings
            ],
            "floors": dict(self.floors),
            "presets": {k: dict(v) for k, v in self.presets.items()},
            "domain": {k: list(v) for k, v in self.domain.items()},
            "derived": [{"name": d.name, "unit": d.unit, "meaning": d.meaning}
                        for d in self.derived],
            "references": list(self.references),
            "evidence": self.evidence,
            "description": self.description,
            "notes": self.notes,
        }

    def derived_values(self, params: Mapping[str, float]) -> dict[str, float]:
        """Evaluate the derived quantities for complete ``params``.

        Parameters
        ----------
        params : mapping
            Parameter and setting values.

        Returns
        -------
        dict
            Derived quantity name -> value.
        """
        out = {}
        for d in self.derived:
            out[d.name] = d.value(params)
        return out


def _jsonable(x: float) -> float | str | None:
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return x


def _as_float(name: str, value: Any, law_id: str) -> float:
    """A parameter value as float; booleans, text and None are refused."""
    if isinstance(value, (bool, np.bool_)) or value is None or isinstance(value, str):
        raise InputError(f"law '{law_id}': {name} must be a number, got {value!r}")
    try:
        return float(value)
    except (TypeError, ValueError):
        raise InputError(f"law '{law_id}': {name} must be a number, got {value!r}") from None


_Named = TypeVar("_Named", Param, Setting)


def _named(law_id: str, kind: str, items: Sequence[_Named], name: str) -> _Named:
    """The declaration called ``name`` among ``items``, or an error listing them."""
    for item in items:
        if item.name == name:
            return item
    raise InputError(f"law '{law_id}' has no {kind} '{name}' "
                     f"({kind}s: {', '.join(i.name for i in items) or 'none'})")
