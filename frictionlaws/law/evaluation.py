"""Evaluating a law: checked calls, the fitting loop's unchecked one, bound functions.

:class:`LawEvaluation` adds to :class:`~.domain.LawDomain` the evaluation of the
formula: ``law(p=..., v=..., a=...)`` (variables and mu checked), :meth:`evaluate`
(pandas Series and xarray DataArrays keep their labels), large calls block by block,
and :meth:`bind` (a plain function with fixed parameters).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from ..base.errors import DomainError, InputError, broadcast_shape
from .declaration import VARIABLES
from .domain import LawDomain, _all_finite, _first
from .namespace import NUMPY

__all__ = ["LawEvaluation", "is_labelled", "evaluate_labelled", "BLOCK_ROWS", "BLOCKED_FROM"]

#: Values per block of a large evaluation (:meth:`LawEvaluation.evaluate_checked`): a few
#: arrays of this many doubles stay in the processor's cache.  A fit's identifiability
#: analysis builds the R factor of a large Jacobian in blocks of the same size.
BLOCK_ROWS = 1 << 16
#: Size from which a checked evaluation goes block by block.
BLOCKED_FROM = 4 * BLOCK_ROWS


def _is_series(x: Any) -> bool:
    return type(x).__name__ == "Series" and hasattr(x, "index")


class LawEvaluation(LawDomain):
    """A law's declaration and domain with the evaluation of its formula."""

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
        if any(is_labelled(x) for x in variables.values()):
            plain = {k: (v.values if is_labelled(v) else v) for k, v in variables.items()}
            self.evaluate(plain, params)  # the same checks, on the bare arrays
            return evaluate_labelled(self, variables, params)
        shape = broadcast_shape(variables, subject=f"law '{self.id}'")
        raw = self._fill_optional(variables, params)
        prepared = self.prepare_variables(raw)
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            out = self.formula(NUMPY, **prepared, **params)
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

        No checks (the fitting loop's evaluation).  From :data:`BLOCKED_FROM` values on,
        the formula runs on blocks of :data:`BLOCK_ROWS` rows, so its temporaries stay that
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
            if n < BLOCKED_FROM:
                out = np.asarray(self.formula(NUMPY, **prepared, **params), float)
                return out if out.shape == (n,) else np.broadcast_to(out, (n,)).copy()
            out = np.empty(n)
            for start in range(0, n, BLOCK_ROWS):
                part = {k: v[start:start + BLOCK_ROWS] if np.ndim(v) else v
                        for k, v in prepared.items()}
                out[start:start + BLOCK_ROWS] = self.formula(NUMPY, **part, **params)
        return out

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

        For plain float arrays of one shape, at least :data:`BLOCKED_FROM` values, the
        variables and mu of each block of :data:`BLOCK_ROWS` values are checked while the
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
        if size < BLOCKED_FROM:
            return None
        flat = {k: a.reshape(-1) for k, a in zip(names, arrays)}
        out = np.empty(size)
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            for start in range(0, size, BLOCK_ROWS):
                part = {k: a[start:start + BLOCK_ROWS] for k, a in flat.items()}
                if not all(self._variable_ok(k, a) for k, a in part.items()):
                    return None
                block = out[start:start + BLOCK_ROWS]
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


# ----------------------------------------------------------------------- xarray
def is_labelled(x: Any) -> bool:
    """True for an :class:`xarray.DataArray` (checked without importing xarray)."""
    return type(x).__name__ == "DataArray" and hasattr(x, "dims")


def evaluate_labelled(law: LawEvaluation, variables: Mapping[str, Any], params: Mapping[str, float]
                      ) -> Any:
    """Evaluate ``law`` where some variables are DataArrays; keep dims and coordinates.

    The DataArrays are aligned and broadcast by xarray; plain arrays or scalars are
    passed through.  The result is a DataArray named ``mu``.
    """
    import xarray as xr

    names = list(variables)

    def plain(*arrays: Any) -> Any:
        return np.asarray(law.evaluate(dict(zip(names, arrays)), params), dtype=float)

    out = xr.apply_ufunc(plain, *(variables[n] for n in names), dask="allowed")
    return out.rename("mu").assign_attrs(units="1", law=law.id,
                                         long_name="friction coefficient")
