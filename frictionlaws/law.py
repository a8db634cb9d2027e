"""The declaration of a friction law, and everything derived from it.

A law is declared once, as a :class:`Law` built from

* its variables (names from :data:`VARIABLES`, always in SI),
* its fitted parameters (:class:`Param`: unit, default, bounds, meaning),
* its fixed settings (:class:`Setting`: reference scales such as ``p_ref``),
* one formula, written as a Python function ``formula(m, **names)`` where ``m``
  is a math namespace.  Called with :data:`NUMPY` it is the vectorised numpy
  evaluation; called with the sympy namespace and symbols it is the symbolic
  form used by the docs, the Fortran generator and the tests.

Floors (``v_min``, ``p_min``) and the absolute value of the sliding velocity
are applied by the :class:`Law` wrapper before the formula is called, so the
formula stays smooth, and the exporters apply the same floors.
"""

from __future__ import annotations

import functools
import json
import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import SimpleNamespace
from typing import TYPE_CHECKING, Any

import numpy as np

from .errors import DomainError, InputError
from .units import QUANTITIES, si_magnitude

if TYPE_CHECKING:
    from .bound import BoundLaw

__all__ = [
    "VARIABLES",
    "Variable",
    "Param",
    "Setting",
    "Derived",
    "Law",
    "NUMPY",
    "sympy_namespace",
    "V_MIN",
    "P_MIN",
]

#: Floor applied to the sliding velocity in laws with log v or v**(-k) [m/s].
V_MIN = 1e-9
#: Multiples of a floor at which a law is probed for its limit at 0 (v = 0, p = 0):
#: ``log`` and powers are finite there (down to 1e-300), so a law with a limit reaches it.
ZERO_PROBES = (1e-20, 1e-90, 1e-290)
#: Agreement of the last two probes for a limit at 0 to count as reached (relative; for
#: |mu| below 1, absolute).
LIMIT_RTOL = 1e-9
#: Floor applied to the contact pressure in laws singular at p = 0 [Pa].
P_MIN = 1.0
#: Floor applied to the normal load in laws singular at F_N = 0 [N].
F_MIN = 1e-6
#: Largest friction coefficient the library writes (FE decks) or reports as a tyre's
#: peak.  Rubber on dry rough surfaces reaches 3 to 4; more is a unit or parameter
#: error (mu_k = 9495 from an extrapolated fit, mu0 = 1e6 typed by hand).
MU_MAX = 10.0


@dataclass(frozen=True)
class Variable:
    """An independent variable a law may use (always in SI units inside).

    Its units are not declared here: :attr:`unit` and :attr:`display_unit` are read
    from the one table of units, :data:`frictionlaws.units.QUANTITIES`.

    Parameters
    ----------
    name : str
        The variable's name (a key of :data:`~frictionlaws.units.QUANTITIES`).
    meaning : str
        What the variable is, in a few words ("contact pressure").
    typical : tuple of float
        A typical range in SI (low, high).
    """

    name: str
    meaning: str
    typical: tuple[float, float]

    @property
    def unit(self) -> str:
        """The SI unit (``""`` when dimensionless)."""
        return QUANTITIES[self.name].si

    @property
    def display_unit(self) -> str:
        """The unit outputs write the variable in (p in MPa, T in degC)."""
        return QUANTITIES[self.name].display


#: The independent variables known to frictionlaws (their units are read from
#: :data:`frictionlaws.units.QUANTITIES`).
VARIABLES: dict[str, Variable] = {
    "p": Variable("p", "contact pressure", (1e4, 1e6)),
    "v": Variable("v", "sliding velocity (magnitude)", (1e-3, 10.0)),
    "T": Variable("T", "temperature", (253.15, 373.15)),
    "F_N": Variable("F_N", "normal load", (1.0, 1000.0)),
    "s": Variable("s", "slip ratio (braking slip, 0..1)", (0.0, 1.0)),
}

FAMILIES = ("sliding", "slip")
EVIDENCE_TAGS = {
    "C": "confirmed in a public source",
    "S": "secondary support only",
    "M": "as commonly quoted, not verified against the original",
    "I": "own derivation or numerical check",
    "NF": "original not found; documented identifiable recommendation",
}


@dataclass(frozen=True)
class Param:
    """A fitted parameter of a law.

    Parameters
    ----------
    name : str
        Python identifier used in the formula and as keyword argument.
    unit : str
        Unit in SI, parsable by pint (``""`` for dimensionless).
    default : float
        A typical value; also the fallback initial guess.
    bounds : tuple of float
        Lower and upper bound used by the fitter (may be infinite).
    meaning : str
        One line saying what the parameter is.
    optional : bool
        When True the law may be called without this parameter and the
        default is used (e.g. the Schallamach exponent n = 1/3).
    """

    name: str
    unit: str
    default: float
    bounds: tuple[float, float] = (-math.inf, math.inf)
    meaning: str = ""
    optional: bool = False


@dataclass(frozen=True)
class Setting:
    """A fixed setting of a law (a reference scale), not fitted by default.

    Parameters
    ----------
    name : str
        Python identifier used in the formula.
    value : float
        The value (SI).
    unit : str
        Unit in SI, parsable by pint (``""`` for dimensionless).
    meaning : str
        One line saying what the setting is.
    bounds : tuple of float
        Lower and upper bound when the setting is fitted (``free=``).
    """

    name: str
    value: float
    unit: str
    meaning: str = ""
    bounds: tuple[float, float] = (0.0, math.inf)


@dataclass(frozen=True)
class Derived:
    """A quantity derived from the parameters (peak, slope at origin...).

    Parameters
    ----------
    name : str
        Name of the quantity.
    unit : str
        Its SI unit.
    meaning : str
        One line saying what it is.
    func : callable
        ``func(m, **params_and_settings)`` returns the value; it is written with
        the same math namespace as the formula so uncertainties can be propagated
        numerically by the fitter.
    """

    name: str
    unit: str
    meaning: str
    func: Callable[..., Any]

    def value(self, params: Mapping[str, float], ns: Any = None) -> float:
        """Evaluate at ``params``: a division by zero gives inf or nan, never an error.

        Parameters
        ----------
        params : mapping
            Parameter and setting values (SI).
        ns : namespace, optional
            The math namespace (default: NumPy's).

        Returns
        -------
        float
            The value; ``inf``/``nan`` where the formula has a pole (e.g. 1/b at b = 0).
        """
        vals = {k: np.float64(v) for k, v in params.items()}
        with np.errstate(all="ignore"):
            try:
                return float(self.func(NUMPY if ns is None else ns, **vals))
            except (ZeroDivisionError, OverflowError):
                return math.nan


def _sympy_log10(x: Any) -> Any:
    import sympy

    return sympy.log(x, 10)


#: The numpy math namespace passed to formulas for numeric evaluation.
NUMPY = SimpleNamespace(
    exp=np.exp,
    log=np.log,
    log10=np.log10,
    sqrt=np.sqrt,
    sin=np.sin,
    cos=np.cos,
    tanh=np.tanh,
    cosh=np.cosh,
    arctan=np.arctan,
    abs=np.abs,
    sign=np.sign,
    maximum=np.maximum,
    minimum=np.minimum,
    power=lambda x, a: np.exp(a * np.log(x)),  # x > 0; numpy's general power is slower
    pi=np.pi,
    is_symbolic=False,
)


@functools.lru_cache(maxsize=1)
def sympy_namespace() -> SimpleNamespace:
    """The sympy math namespace passed to formulas for the symbolic form."""
    import sympy

    return SimpleNamespace(
        exp=sympy.exp,
        log=sympy.log,
        log10=_sympy_log10,
        sqrt=sympy.sqrt,
        sin=sympy.sin,
        cos=sympy.cos,
        tanh=sympy.tanh,
        cosh=sympy.cosh,
        arctan=sympy.atan,
        abs=sympy.Abs,
        sign=sympy.sign,
        maximum=sympy.Max,
        minimum=sympy.Min,
        power=sympy.Pow,
        pi=sympy.pi,
        is_symbolic=True,
    )


def _is_series(x: Any) -> bool:
    return type(x).__name__ == "Series" and hasattr(x, "index")


@dataclass(eq=False)
class Law:
    """One friction law, declared once.

    Parameters
    ----------
    id : str
        Registry id (lower case, hyphenated), e.g. ``"thirion"``.
    title : str
        Human name, e.g. ``"Thirion (pressure saturation)"``.
    family : {"sliding", "slip"}
        Sliding-velocity laws (tribometer, rubber) or slip-ratio laws (tyre).
    variables : tuple of str
        Variables the formula uses, keys of :data:`VARIABLES`.
    params : tuple of Param
        Fitted parameters, in formula order.
    formula : callable
        ``formula(m, **kw)`` with ``m`` a math namespace and ``kw`` the
        variables, parameters and settings by name.
    settings : tuple of Setting
        Fixed reference scales.
    floors : dict
        Variable name -> floor value applied before the formula (``v`` is also
        taken as ``|v|``).
    presets : dict
        Preset name -> parameter dict.
    domain : dict
        Variable name -> (low, high) in SI where the law is valid or was
        measured; outside it the law is an extrapolation.
    typical : dict
        Variable name -> (low, high) in SI: the range to plot or tabulate by
        default (falls back to the domain, then to :data:`VARIABLES`).
    references : tuple of str
        Bibliographic references.
    evidence : str
        Evidence tag(s), e.g. ``"C"`` or ``"S, I"`` (see ``laws.md``).
    guess : callable, optional
        ``guess(data) -> dict`` returning initial values from a mapping with
        ``"mu"`` and the variables as numpy arrays.
    derived : tuple of Derived
        Derived quantities.
    admissible : callable, optional
        ``admissible(params) -> str | None``: a message when a parameter set is
        not admissible (e.g. a denominator that can vanish).
    linear : bool
        True when the law is linear in its parameters (closed-form fit).
    aliases : tuple of str
        Other names the registry accepts.
    optional_variables : dict
        Variable name -> (parameter name, neutral value): the variable may be
        left out when that parameter has its neutral value, where the variable
        drops out of the formula (Burckhardt's vehicle speed ``v`` with
        ``c4 = 0``).  Evaluation without it, fits to data without it (the
        parameter is then fixed at its neutral value), comparison and export
        follow from this one entry.
    variable_meanings : dict
        Variable name -> what the variable is *in this law* when it differs
        from the generic meaning in :data:`VARIABLES` (Burckhardt's ``v`` is the
        vehicle speed, not the sliding velocity).
    strict_domain : bool
        The law means nothing outside :attr:`domain` (a polynomial valid only over
        its measured box, a pre-peak slip law): ``law(...)`` refuses variables outside
        it, fits and exports say so.  Otherwise the domain only marks extrapolation.
    description : str
        A paragraph shown by ``show`` and the docs.
    notes : str
        Caveats and traps.
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

    # ------------------------------------------------------------------ names
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
        for p in self.params:
            if p.name == name:
                return p
        raise InputError(
            f"law '{self.id}' has no parameter '{name}' "
            f"(parameters: {', '.join(self.param_names)})"
        )

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
        for s in self.settings:
            if s.name == name:
                return s
        raise InputError(
            f"law '{self.id}' has no setting '{name}' "
            f"(settings: {', '.join(s.name for s in self.settings) or 'none'})"
        )

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

    # ------------------------------------------------------------ evaluation
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

    def si_variables(self, variables: Mapping[str, Any]) -> dict[str, Any]:
        """The variables with any pint ``Quantity`` converted to its SI magnitude.

        Parameters
        ----------
        variables : mapping
            Variable name -> values (SI numbers, or pint Quantities in any unit of
            the variable's kind).

        Returns
        -------
        dict
            The same mapping with plain numbers in SI.

        Raises
        ------
        InputError
            A Quantity whose unit is not one of the variable's kind.
        """
        return {k: si_magnitude(x, VARIABLES[k].unit, f"law '{self.id}': {k}")
                if k in VARIABLES else x for k, x in variables.items()}

    def _unit_of(self, name: str) -> str:
        decl = self._declared(name)
        return f" {decl.unit}" if decl is not None and decl.unit else ""

    def _meaning_of(self, name: str) -> str:
        decl = self._declared(name)
        return decl.meaning if decl is not None else ""

    def prepare_variables(self, variables: Mapping[str, Any]) -> dict[str, Any]:
        """The law's variables as its formula takes them: floats, ``|v|``, floors applied.

        Parameters
        ----------
        variables : mapping
            Every variable of the law (SI), array-like.

        Returns
        -------
        dict
            Variable name -> float array (or float), ready for :attr:`formula`.
        """
        out = {}
        for name in self.variables:
            x = np.asarray(variables[name], dtype=float)
            if name == "v":
                x = np.abs(x)
            floor = self.floors.get(name)
            if floor is not None:
                x = np.maximum(x, floor)
            out[name] = x
        return out

    def evaluate(self, variables: Mapping[str, Any], params: Mapping[str, float]) -> Any:
        """Evaluate with explicit mappings of variables and complete parameters.

        Parameters
        ----------
        variables : mapping
            Variable name -> array-like in SI.  Variables the law does not use
            are allowed and only set the output shape.
        params : mapping
            Parameters and settings, as returned by :meth:`resolve`.

        Returns
        -------
        float or numpy.ndarray or pandas.Series
            A float when every input is a scalar, a Series when a Series came in.
        """
        variables = self.si_variables(variables)
        missing = [v for v in self.variables if v not in variables]
        if missing:
            self._refuse_missing(missing, params)
        unknown = set(variables) - set(VARIABLES)
        if unknown:
            raise InputError(f"unknown variable(s) {sorted(unknown)}; known: {list(VARIABLES)}")
        if any(type(x).__name__ == "DataArray" for x in variables.values()):
            from .interop import evaluate_labelled

            plain = {k: (v.values if type(v).__name__ == "DataArray" else v)
                     for k, v in variables.items()}
            self.evaluate(plain, params)  # the same checks, on the bare arrays
            return evaluate_labelled(self, variables, params)
        raw = self._fill_optional(variables, params)
        prepared = self.prepare_variables(raw)
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            out = self.formula(NUMPY, **prepared, **params)
        shapes = [np.shape(x) for x in variables.values()]
        shape = np.broadcast_shapes(*shapes) if shapes else ()
        if np.shape(out) != shape:
            out = (np.full(shape, float(out)) if np.ndim(out) == 0
                   else np.broadcast_to(out, shape).copy())
        out = self.below_floors(raw, prepared, params, out)
        if shape == ():
            return float(out)
        for x in variables.values():
            if _is_series(x):
                return type(x)(out, index=x.index, name="mu")
        return out

    def evaluate_prepared(self, prepared: Mapping[str, Any], params: Mapping[str, float],
                          n: int) -> np.ndarray:
        """The formula on prepared variables (:meth:`prepare_variables`), as ``n`` values.

        No checks (the fitting loop's evaluation).  From :data:`_BLOCKED_FROM` values on,
        the formula runs on blocks of :data:`_BLOCK` rows, so its temporaries stay that
        size; the numbers are the same as in one call (the formulas act element by element).

        Parameters
        ----------
        prepared : mapping
            The variables as the formula takes them (arrays of ``n`` values, or scalars).
        params : mapping
            Every parameter and setting.
        n : int
            The number of rows.

        Returns
        -------
        numpy.ndarray
            The friction coefficient at every row (NaN or infinity where the formula
            gives them).
        """
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            if n < _BLOCKED_FROM:
                out = np.asarray(self.formula(NUMPY, **prepared, **params), float)
                return out if out.shape == (n,) else np.broadcast_to(out, (n,)).copy()
            out = np.empty(n)
            for start in range(0, n, _BLOCK):
                part = {k: v[start:start + _BLOCK] if np.ndim(v) else v
                        for k, v in prepared.items()}
                out[start:start + _BLOCK] = self.formula(NUMPY, **part, **params)
        return out

    def below_floors(self, raw: Mapping[str, Any], prepared: Mapping[str, Any],
                     params: Mapping[str, float], out: Any, *, strict: bool = False) -> Any:
        """The law's own values where a variable lies below its floor.

        A floor keeps the formula smooth where it is used; it is no value of the law.
        Where ``0 < x < floor`` the formula is evaluated at ``x`` itself; at ``x = 0``
        the law's limit is taken, found by evaluating it at :data:`ZERO_PROBES` times
        the floor: where the last two probes agree within :data:`LIMIT_RTOL` that is the
        limit, else (the law grows without bound or keeps changing as ``x -> 0``) there
        is none: such a point is NaN (refused with ``strict``).

        Parameters
        ----------
        raw : mapping
            The variables as given (before ``|v|`` and the floors).
        prepared : mapping
            The same after :meth:`prepare_variables`.
        params : mapping
            Every parameter and setting.
        out : float or ndarray
            The formula at ``prepared``.
        strict : bool
            Raise where the law has no value instead of giving NaN there.

        Returns
        -------
        float or ndarray
            ``out`` with the points below a floor replaced (``out`` itself when none is).

        Raises
        ------
        DomainError
            With ``strict``, where the law has no finite value or limit, naming the
            variable and point.
        """
        low = {}
        for name, floor in self.floors.items():
            if name in raw:
                x = np.abs(np.asarray(raw[name], float))
                if x.size and not float(np.min(x)) >= floor:
                    low[name] = x
        if not low:
            return out
        shape = np.broadcast_shapes(np.shape(out), *(np.shape(x) for x in low.values()))
        rows = np.zeros(shape, dtype=bool)
        for name, x in low.items():
            rows |= np.broadcast_to(x < self.floors[name], shape)
        pts = {k: np.broadcast_to(np.asarray(v, float), shape)[rows].copy()
               for k, v in prepared.items() if k in self.variables}
        zero = {k: np.broadcast_to(x, shape)[rows] for k, x in low.items()}
        for name, x in zero.items():
            pts[name] = np.where(x < self.floors[name], x, pts[name])
        probes = []
        with np.errstate(all="ignore"):
            for f in ZERO_PROBES:
                trial = {k: (np.where(zero[k] == 0, self.floors[k] * f, v) if k in zero else v)
                         for k, v in pts.items()}
                probes.append(np.broadcast_to(np.asarray(
                    self.formula(NUMPY, **trial, **params), float), (int(rows.sum()),)))
        at_zero = np.zeros(int(rows.sum()), dtype=bool)
        for x in zero.values():
            at_zero |= x == 0
        last, prev = probes[-1], probes[-2]
        ok = np.isfinite(last) & (~at_zero | (np.abs(last - prev) <= LIMIT_RTOL * np.maximum(
            np.abs(last), 1.0)))
        if strict and not ok.all():
            self._refuse_below_floor(zero, at_zero, ok, shape, rows)
        full = np.array(np.broadcast_to(np.asarray(out, float), shape))
        full[rows] = np.where(ok, last, np.nan)
        return float(full) if full.ndim == 0 else full

    def _refuse_below_floor(self, zero: Mapping[str, np.ndarray], at_zero: np.ndarray,
                            ok: np.ndarray, shape: tuple[int, ...], rows: np.ndarray) -> None:
        """Raise for the first point :meth:`below_floors` cannot give a value at."""
        i = int(np.flatnonzero(~ok)[0])
        where = [int(j) for j in np.argwhere(rows)[i]] if rows.ndim else []
        at = (f" at index {where[0]}" if len(where) == 1 else
              f" at index {tuple(where)}" if where else "")
        name = next((k for k, x in zero.items() if x[i] < self.floors[k]), next(iter(zero)))
        unit = VARIABLES[name].unit
        if at_zero[i]:
            names = [k for k, x in zero.items() if x[i] == 0]
            what = " and ".join(f"{k} ({self.meaning(k)})" for k in names)
            raise DomainError(
                f"law '{self.id}' has no finite limit as {', '.join(names)} -> 0{at} (it grows "
                f"without bound or keeps changing as {what} go{'es' if len(names) == 1 else ''}"
                f" to 0): it cannot be evaluated at "
                f"{', '.join(f'{k} = 0 {VARIABLES[k].unit}'.rstrip() for k in names)}")
        raise DomainError(f"law '{self.id}' gives a non-finite mu at {name} = "
                          f"{zero[name][i]:g} {unit}{at}, below its floor "
                          f"{self.floors[name]:g} {unit}")

    def _refuse_missing(self, missing: list[str], params: Mapping[str, float]) -> None:
        """Raise for absent variables, unless each is optional with a neutral parameter."""
        needed = [m for m in missing if m in self.required_variables(params)]
        if not needed:
            return
        parts = []
        for m in needed:
            text = f"{m} ({self.meaning(m)} [{VARIABLES[m].unit or '-'}])"
            if m in self.optional_variables:
                pname, neutral = self.optional_variables[m]
                text += (f", optional only when {pname} = {neutral:g} (here {pname} = "
                         f"{params.get(pname, math.nan):g})")
            parts.append(text)
        raise InputError(f"law '{self.id}' needs variable(s) {'; '.join(parts)}")

    def __call__(self, **kwargs: Any) -> Any:
        """Evaluate the law: ``law(p=p, v=v, a=1.0, b=2e-6)``.

        Variables and parameters are given by keyword; settings may be
        overridden by keyword too; ``preset=`` takes a named preset.
        """
        preset = kwargs.pop("preset", None)
        if preset is not None and not isinstance(preset, str):
            raise InputError(f"law '{self.id}': preset must be a name, got {preset!r}")
        variables = {k: v for k, v in kwargs.items() if k in VARIABLES}
        values = {k: v for k, v in kwargs.items() if k not in VARIABLES}
        return self.evaluate_checked(variables, self.resolve(values, preset))

    def evaluate_checked(self, variables: Mapping[str, Any], params: Mapping[str, float]
                         ) -> Any:
        """Evaluate with the checks of a call: the variables and mu.

        The variables are checked by :meth:`check_variables`; mu must be finite and,
        for a sliding law, not negative.

        Parameters
        ----------
        variables : mapping
            Variable name -> array-like in SI.
        params : mapping
            Complete, checked parameters and settings (:meth:`resolve`).

        Returns
        -------
        float or numpy.ndarray or pandas.Series
            As :meth:`evaluate`.

        Raises
        ------
        InputError, DomainError
            A variable the law cannot take, or a mu that means nothing.
        """
        variables = self.si_variables(variables)
        fast = self._evaluate_blocks(variables, params)
        if fast is not None:
            return fast
        self.check_variables(variables)
        out = self.evaluate(variables, params)
        mu = np.asarray(out, dtype=float)
        if not self._mu_ok(mu):
            if self.floors:  # a point without a value below a floor: say which
                raw = self._fill_optional(variables, params)
                self.below_floors(raw, self.prepare_variables(raw), params, mu, strict=True)
            self._refuse_mu(mu, params)
        return out

    def _mu_ok(self, mu: np.ndarray) -> bool:
        """Cheap test (reductions only) that mu is finite and, if sliding, not negative."""
        if mu.ndim == 0:  # one value (a constant law): no array machinery
            m = float(mu)
            return math.isfinite(m) and (self.family != "sliding" or m >= 0)
        if not _all_finite(mu):
            return False
        return self.family != "sliding" or mu.size == 0 or float(mu.min()) >= 0

    def _refuse_mu(self, mu: np.ndarray, params: Mapping[str, float]) -> None:
        """Raise for the first mu :meth:`_mu_ok` refuses."""
        if not np.isfinite(mu).all():
            raise DomainError(f"law '{self.id}' gives a non-finite mu for these inputs "
                              f"and parameters {params}")
        bad = mu < 0
        if self.family == "sliding" and bad.any():
            raise DomainError(f"law '{self.id}' gives a negative mu ({mu[bad].flat[0]:.4g}) "
                              f"at index {_first(np.atleast_1d(bad))}: outside the range where "
                              "the law means anything (a sliding friction coefficient is >= 0)")

    def _evaluate_blocks(self, variables: Mapping[str, Any], params: Mapping[str, float]
                         ) -> np.ndarray | None:
        """A large checked call, evaluated and checked block by block; None when not apt.

        For plain float arrays of one shape, at least :data:`_BLOCKED_FROM` values, the
        variables and mu of each block of :data:`_BLOCK` values are checked while the
        block is in the processor's cache, so the checks cost almost nothing.  Any block
        that fails a check returns None: the whole-array path then names the value.
        """
        names = self.variables
        if not names:
            return self._constant_array(variables, params)
        if set(variables) != set(names):
            return None
        arrays: list[np.ndarray] = [variables[k] for k in names]
        shape = np.shape(arrays[0])
        if not all(type(a) is np.ndarray and a.dtype == np.float64 and a.flags.c_contiguous
                   and a.shape == shape for a in arrays):
            return None
        size = int(np.prod(shape))
        if size < _BLOCKED_FROM:
            return None
        flat = {k: a.reshape(-1) for k, a in zip(names, arrays)}
        out = np.empty(size)
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            for start in range(0, size, _BLOCK):
                part = {k: a[start:start + _BLOCK] for k, a in flat.items()}
                if not all(self._variable_ok(k, a) for k, a in part.items()):
                    return None
                block = out[start:start + _BLOCK]
                block[...] = self.formula(NUMPY, **self.prepare_variables(part), **params)
                if not self._mu_ok(block):
                    return None
        return out.reshape(shape)

    def _constant_array(self, variables: Mapping[str, Any], params: Mapping[str, float]
                        ) -> np.ndarray | None:
        """A law of no variable on arrays: mu checked once, then repeated to their shape."""
        if not variables or not set(variables) <= set(VARIABLES) or not all(
                type(a) is np.ndarray and a.ndim for a in variables.values()):
            return None
        mu = np.asarray(self.formula(NUMPY, **params), dtype=float)
        if mu.ndim or not self._mu_ok(mu):
            return None
        return np.full(np.broadcast_shapes(*(a.shape for a in variables.values())), float(mu))

    def check_variables(self, variables: Mapping[str, Any]) -> None:
        """Refuse variable values the law cannot take.

        Missing, non-numeric, non-finite, a negative pressure or load, a temperature at
        or below 0 K, or a slip ratio outside [0, 1] or outside a slip law's declared
        domain.

        Parameters
        ----------
        variables : mapping
            Variable name -> values (SI).

        Raises
        ------
        InputError, DomainError
            Naming the variable and the offending value.
        """
        for name in self.variables:
            if name not in variables:
                continue
            x = _float_array(name, variables[name], self.id)
            if not self._variable_ok(name, x):
                self._refuse_variable(name, x)

    def _variable_ok(self, name: str, x: np.ndarray) -> bool:
        """Cheap test (reductions only) that ``x`` passes :meth:`check_variables`.

        Values below a floor also fail it: :meth:`below_floors` handles them.
        """
        if x.size == 0:
            return True
        floor = self.floors.get(name)
        if floor is not None and not float(np.min(np.abs(x))) >= floor:
            return False
        if name == "s" or (self.strict_domain and name in self.domain):
            lo, hi = float(x.min()), float(x.max())  # NaN and infinities show in these
            if not (math.isfinite(lo) and math.isfinite(hi)):
                return False
        elif _all_finite(x):
            lo = hi = float(x.min())
        else:
            return False
        low = _LOWER_LIMITS.get(name)
        if low is not None and (lo < low[0] if low[1] else lo <= low[0]):
            return False
        if name == "s":
            s_lo, s_hi = self.domain.get("s", (0.0, 1.0))
            return lo >= s_lo - 1e-12 and hi <= s_hi + 1e-12
        if self.strict_domain and name in self.domain:
            d_lo, d_hi = self.domain[name]
            if name == "v":  # the magnitude of the velocity counts
                lo, hi = (0.0 if lo <= 0.0 <= hi else min(abs(lo), abs(hi)),
                          max(abs(lo), abs(hi)))
            return lo >= d_lo * (1 - 1e-9) - 1e-300 and hi <= d_hi * (1 + 1e-9)
        return True

    def _refuse_variable(self, name: str, x: np.ndarray) -> None:
        """Raise for the first value of ``x`` that :meth:`_variable_ok` refuses."""
        bad = ~np.isfinite(x)
        if bad.any():
            raise InputError(f"law '{self.id}': {name} has a non-finite value "
                             f"({x[bad].flat[0]}) at index {_first(bad)}")
        low = _LOWER_LIMITS.get(name)
        if low is not None:
            below = x < low[0] if low[1] else x <= low[0]
            if below.any():
                raise DomainError(
                    f"law '{self.id}': {name} = {x[below].flat[0]:g} at index "
                    f"{_first(below)} is not allowed ({VARIABLES[name].meaning} must be "
                    f"{'>=' if low[1] else '>'} {low[0]:g} {VARIABLES[name].unit})")
        self._check_strict_domain(name, x)
        if name == "s":
            s_lo, s_hi = self.domain.get("s", (0.0, 1.0))
            out = (x < s_lo - 1e-12) | (x > s_hi + 1e-12)
            if out.any():
                raise DomainError(
                    f"law '{self.id}': s = {x[out].flat[0]:g} at index {_first(out)} is "
                    f"outside the law's slip domain [{s_lo:g}, {s_hi:g}]")

    def bind(self, values: Mapping[str, float] | None = None, preset: str | None = None
             ) -> Callable[..., Any]:
        """Return a plain vectorised function of the law's variables with fixed parameters.

        The returned callable takes the variables positionally in the order
        of :attr:`variables` (or by keyword; an optional variable whose
        parameter is neutral may be left out), applies the floors and calls the
        formula directly: no checking, negligible overhead.

        Parameters
        ----------
        values : mapping, optional
            Parameter and setting values.
        preset : str, optional
            A preset name.

        Returns
        -------
        callable
            ``f(*variables) -> mu``.
        """
        params = self.resolve(values, preset)
        formula = self.formula
        names = self.variables
        floors = dict(self.floors)

        fill = self._fill_optional

        below = self.below_floors

        def bound(*args: Any, **kwargs: Any) -> Any:
            kw = dict(zip(names, args))
            kw.update(kwargs)
            kw = fill(kw, params)
            raw = {k: kw[k] for k in floors if k in kw}
            if "v" in kw:
                kw["v"] = np.abs(kw["v"])
            for k, f in floors.items():
                kw[k] = np.maximum(kw[k], f)
            out = formula(NUMPY, **kw, **params)
            return below(raw, kw, params, out) if raw else out

        bound.__name__ = f"{self.id.replace('-', '_')}_bound"
        bound.__doc__ = f"{self.title} with fixed parameters {params}; arguments {names} (SI)."
        return bound

    def freeze(self, values: Mapping[str, float] | None = None, preset: str | None = None,
               *, source: Any = None) -> BoundLaw:
        """Bind this law to a preset and/or values, like a frozen scipy distribution.

        Parameters
        ----------
        values : mapping, optional
            Parameter (or setting) values in SI, over the preset.
        preset : str, optional
            A named preset of the law.
        source : Source or str, optional
            Where the values came from (a string names a parameters file); see
            :func:`frictionlaws.bound.freeze`.

        Returns
        -------
        BoundLaw
            E.g. ``law.freeze(preset="x")(p=1e5)``.
        """
        from .bound import freeze

        return freeze(self, values, preset=preset, source=source)

    def _check_strict_domain(self, name: str, x: np.ndarray) -> None:
        if not self.strict_domain or name not in self.domain or name == "s":
            return
        lo, hi = self.domain[name]
        xv = np.abs(x) if name == "v" else x
        out = (xv < lo * (1 - 1e-9) - 1e-300) | (xv > hi * (1 + 1e-9))
        if out.any():
            unit = VARIABLES[name].unit
            raise DomainError(
                f"law '{self.id}': {name} = {x[out].flat[0]:g} {unit} at index {_first(out)} "
                f"is outside the range the law is valid for, {lo:g}..{hi:g} {unit} "
                "(it must not be extrapolated)")

    # -------------------------------------------------------------- symbolic
    def symbols(self) -> dict[str, Any]:
        """Return sympy symbols for variables, parameters and settings.

        Returns
        -------
        dict
            Name -> symbol (positive where natural).
        """
        import sympy

        syms: dict[str, Any] = {}
        for v in self.variables:
            syms[v] = sympy.Symbol(v, positive=v in ("p", "v", "T", "F_N") or v in self.floors)
        for p in self.params:
            syms[p.name] = sympy.Symbol(p.name, real=True)
        for s in self.settings:
            syms[s.name] = sympy.Symbol(s.name, positive=True)
        return syms

    def symbolic(self, substitute_settings: bool = False) -> Any:
        """The formula as a sympy expression (floors not included).

        Parameters
        ----------
        substitute_settings : bool
            Replace the settings by their numeric values.

        Returns
        -------
        sympy.Expr
            The expression of mu.
        """
        syms = self.symbols()
        expr = self.formula(sympy_namespace(), **syms)
        if substitute_settings:
            expr = expr.subs({syms[s.name]: s.value for s in self.settings})
        return expr

    def latex(self) -> str:
        """Return the LaTeX of the formula, ``\\mu = ...``.

        Returns
        -------
        str
            The LaTeX text.
        """
        import sympy

        return r"\mu = " + sympy.latex(self.symbolic())

    def pretty(self) -> str:
        """Return a one-line plain-text rendering of the formula.

        The text is sympy's rendering of :meth:`symbolic`.  For the built-in laws it
        is read from a shipped cache of those renderings (``formula_text.json``), used
        only while the law still computes the same numbers as when the cache was
        written (:func:`formula_check`); otherwise, and for other laws, sympy renders
        it.  So printing a formula does not load sympy, and never shows a stale one.

        Returns
        -------
        str
            ``"mu = ..."``.
        """
        cached = _cached_text(self)
        if cached is not None:
            return cached
        return self.rendered_text()

    def rendered_text(self) -> str:
        """Return the plain-text formula as sympy renders it now (no cache).

        Returns
        -------
        str
            ``"mu = ..."``, what :meth:`pretty` shows.
        """
        import sympy

        return "mu = " + sympy.sstr(self.symbolic())

    # ----------------------------------------------------------------- misc
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

    def outside_domain(self, variables: Mapping[str, Any]) -> dict[str, int]:
        """Count, per variable, how many values lie outside :attr:`domain`.

        Parameters
        ----------
        variables : mapping
            Variable name -> values (SI).

        Returns
        -------
        dict
            Variable name -> count (only variables with values outside).
        """
        out = {}
        for name, (lo, hi) in self.domain.items():
            if name in variables:
                x = np.asarray(variables[name], dtype=float)
                if name == "v":
                    x = np.abs(x)
                n = int(np.count_nonzero((x < lo * (1 - 1e-9)) | (x > hi * (1 + 1e-9))))
                if n:
                    out[name] = n
        return out

    def require_variables(self, available: set[str], what: str = "the data") -> None:
        """Raise a clear error when ``available`` lacks a variable this law needs.

        Parameters
        ----------
        available : set of str
            The variables at hand.
        what : str
            What holds them, for the message.

        Raises
        ------
        DomainError
            Naming the missing variables.
        """
        missing = [v for v in self.required_variables() if v not in available]
        if missing:
            fam = ("a slip law (tyre, rolling wheel) needs the slip ratio s; "
                   "pure-sliding tribometer data cannot determine it"
                   if self.family == "slip" and "s" in missing else
                   f"{self.family} law needs " + ", ".join(
                       f"{m} ({self.meaning(m)})" for m in missing))
            raise DomainError(
                f"law '{self.id}' cannot be fitted to {what}: {fam}; "
                f"available: {', '.join(sorted(available)) or 'none'}"
            )

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

    def __repr__(self) -> str:
        return f"<Law {self.id!r}: {self.title}>"

    def __reduce__(self) -> tuple[Any, tuple[str]]:
        """Pickle a registered law by its id (formulas need not be picklable)."""
        lookup = _LOOKUP.get("law")
        try:
            registered = lookup(self.id) if lookup is not None else None
        except InputError:
            registered = None
        if lookup is None or registered is not self:
            raise TypeError(f"law '{self.id}' is not registered: register it to pickle it")
        return (lookup, (self.id,))

    def _repr_html_(self) -> str:
        from .interop import law_html

        return law_html(self)

    def lmfit_model(self, values: Mapping[str, float] | None = None) -> Any:
        """Return the law as an :class:`lmfit.Model`.

        See :func:`frictionlaws.interop.lmfit_model`.

        Parameters
        ----------
        values : mapping, optional
            Start values (defaults: the declared ones).

        Returns
        -------
        lmfit.Model
            The model with the declared bounds as parameter hints.
        """
        from .interop import lmfit_model

        return lmfit_model(self, values=values)


#: The shipped cache of formula texts (see :meth:`Law.pretty`).
FORMULA_TEXT_FILE = Path(__file__).with_name("formula_text.json")
#: Relative agreement of :func:`formula_check` values with the cached ones.
_CHECK_RTOL = 1e-9


def formula_check(law: Law) -> dict[str, Any] | None:
    """What a cached formula text of ``law`` must agree with to be used.

    The names of the formula's symbols (with the variables that are floored,
    which sympy takes as positive) and mu computed by the numpy formula at two
    fixed points where every symbol has a value of order one (so that every term
    counts).  A change of the formula changes these numbers.

    Parameters
    ----------
    law : Law
        The law.

    Returns
    -------
    dict or None
        ``{"symbols": str, "mu": [float, float]}``; None when the formula cannot
        be computed at those points (then no cached text is used for it).
    """
    names = [*law.variables, *law.param_names, *(st.name for st in law.settings)]
    symbols = "|".join([",".join(law.variables), ",".join(law.param_names),
                        ",".join(st.name for st in law.settings), ",".join(sorted(law.floors))])
    mu = []
    for j in (0, 1):
        values = {n: 1.0 + 0.137 * (k + 1) + 0.291 * j for k, n in enumerate(names)}
        try:
            with np.errstate(all="ignore"):
                mu.append(float(law.formula(NUMPY, **values)))
        except Exception:  # noqa: BLE001 - a formula that cannot run here is not cached
            return None
    if not all(math.isfinite(m) for m in mu):
        return None
    return {"symbols": symbols, "mu": mu}


@functools.lru_cache(maxsize=1)
def _formula_texts() -> dict[str, Any]:
    try:
        doc = json.loads(FORMULA_TEXT_FILE.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    laws = doc.get("laws") if isinstance(doc, dict) else None
    return laws if isinstance(laws, dict) else {}


def _cached_text(law: Law) -> str | None:
    """The cached text of ``law``, when it still computes what the cache recorded."""
    entry = _formula_texts().get(law.id)
    if not isinstance(entry, dict) or not isinstance(entry.get("text"), str):
        return None
    return str(entry["text"]) if formula_matches(law, entry) else None


def formula_matches(law: Law, recorded: Mapping[str, Any]) -> bool:
    """True when ``law`` still computes what :func:`formula_check` recorded for it.

    Parameters
    ----------
    law : Law
        The law now.
    recorded : mapping
        A :func:`formula_check` result stored earlier (with code or text derived from
        the formula then).

    Returns
    -------
    bool
        Same symbols and the same mu at the check points (to 1e-9).
    """
    check = formula_check(law)
    if check is None or check["symbols"] != recorded.get("symbols"):
        return False
    mu = recorded.get("mu")
    if not isinstance(mu, list) or len(mu) != len(check["mu"]):
        return False
    return all(isinstance(r, (int, float)) and math.isclose(m, r, rel_tol=_CHECK_RTOL)
               for m, r in zip(check["mu"], mu))


def formula_text_entries(laws: Iterable[Law]) -> dict[str, Any]:
    """The content of the formula-text cache for ``laws`` (rendered with sympy).

    Parameters
    ----------
    laws : iterable of Law
        The laws to cache (the built-in ones).

    Returns
    -------
    dict
        ``{"format": 1, "laws": {id: {"text", "symbols", "mu"}}}``, what
        ``formula_text.json`` holds; laws without a :func:`formula_check` are left out.
    """
    out: dict[str, Any] = {}
    for law in laws:
        check = formula_check(law)
        if check is not None:
            out[law.id] = {"text": law.rendered_text(), **check}
    return {"format": 1, "laws": out}


#: How a law id is looked up again (set by :mod:`frictionlaws.registry` when it loads,
#: so that this module does not import the registry).
_LOOKUP: dict[str, Callable[[str], Law]] = {}


def set_lookup(lookup: Callable[[str], Law]) -> None:
    """Install the function that finds a registered law by id (for pickling)."""
    _LOOKUP["law"] = lookup


def _jsonable(x: float) -> float | str | None:
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return x


#: Physical lower limits of variables: (limit, inclusive).
#: Values per block of a large checked evaluation (:meth:`Law.evaluate_checked`): a few
#: arrays of this many doubles stay in the processor's cache.
_BLOCK = 1 << 16
#: Size from which a checked evaluation goes block by block.
_BLOCKED_FROM = 4 * _BLOCK

_LOWER_LIMITS: dict[str, tuple[float, bool]] = {"p": (0.0, True), "F_N": (0.0, True),
                                                 "T": (0.0, False)}


def _all_finite(x: np.ndarray) -> bool:
    """True when no value is NaN or infinite, tested cheaply.

    The sum of squares (one BLAS pass, no temporary array) is finite exactly when every
    value is, unless a value beyond 1e154 overflows it: only then are the values
    tested one by one.
    """
    flat = np.ravel(x)
    if flat.size == 0 or math.isfinite(float(np.dot(flat, flat))):
        return True
    return bool(np.isfinite(flat).all())


def _first(mask: np.ndarray) -> int | tuple[int, ...]:
    idx = np.argwhere(mask)[0]
    return int(idx[0]) if idx.size == 1 else tuple(int(i) for i in idx)


def _float_array(name: str, value: Any, law_id: str) -> np.ndarray:
    try:
        x = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"law '{law_id}': {name} must be numbers, got {value!r:.60}") from None
    return np.atleast_1d(x)


def _as_float(name: str, value: Any, law_id: str) -> float:
    """A parameter value as float; booleans, text and None are refused."""
    if isinstance(value, (bool, np.bool_)) or value is None or isinstance(value, str):
        raise InputError(f"law '{law_id}': {name} must be a number, got {value!r}")
    try:
        return float(value)
    except (TypeError, ValueError):
        raise InputError(f"law '{law_id}': {name} must be a number, got {value!r}") from None
