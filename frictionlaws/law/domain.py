"""Where a law can be evaluated: the variables it takes, its floors and its domain.

:class:`LawDomain` adds to the declaration the checks of the variables (finite, a
pressure or load not negative, a temperature above 0 K, a slip ratio in its domain, a
strict domain kept), the floors (:meth:`LawDomain.prepare_variables`) and the law's own
values below them (:meth:`LawDomain.below_floors`: the limit at 0 where it exists).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from ..base.errors import DomainError, InputError
from ..base.units import si_magnitude
from .declaration import VARIABLES
from .namespace import NUMPY
from .parameters import LawDeclaration

__all__ = ["LawDomain", "ZERO_PROBES", "LIMIT_RTOL"]

#: Multiples of a floor at which a law is probed for its limit at 0 (v = 0, p = 0):
#: ``log`` and powers are finite there (down to 1e-300), so a law with a limit reaches it.
ZERO_PROBES = (1e-20, 1e-90, 1e-290)
#: Agreement of the last two probes for a limit at 0 to count as reached (relative; for
#: ``|mu|`` below 1, absolute).
LIMIT_RTOL = 1e-9
#: Physical lower limits of variables: (limit, inclusive).
_LOWER_LIMITS: dict[str, tuple[float, bool]] = {"p": (0.0, True), "F_N": (0.0, True),
                                                 "T": (0.0, False)}


class LawDomain(LawDeclaration):
    """A law's declaration with the checks of its variables, floors and domain."""

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
