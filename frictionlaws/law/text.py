"""A law's formula as text: the sympy form, LaTeX, and the shipped cache of its text.

:class:`LawText` adds the symbolic form (:meth:`LawText.symbolic`, :meth:`LawText.latex`,
:meth:`LawText.pretty`).  The plain-text form of the built-in laws is read from a cache
written by sympy (``formula_text.json``), used only while :func:`formula_check` says the
law still computes what it did when the cache was written.
"""

from __future__ import annotations

import functools
import json
import math
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from .namespace import NUMPY, sympy_namespace
from .parameters import LawDeclaration

__all__ = ["LawText", "FORMULA_TEXT_FILE", "formula_check", "formula_matches",
           "formula_text_entries", "formula_texts_current", "write_formula_texts"]


class LawText(LawDeclaration):
    """A law's declaration with its symbolic form and formula text."""

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


#: The shipped cache of formula texts (see :meth:`LawText.pretty`).
FORMULA_TEXT_FILE = Path(__file__).parent / "formula_text.json"
#: Relative agreement of :func:`formula_check` values with the cached ones.
_CHECK_RTOL = 1e-9


def formula_check(law: LawDeclaration) -> dict[str, Any] | None:
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


def _cached_text(law: LawDeclaration) -> str | None:
    """The cached text of ``law``, when it still computes what the cache recorded."""
    entry = _formula_texts().get(law.id)
    if not isinstance(entry, dict) or not isinstance(entry.get("text"), str):
        return None
    return str(entry["text"]) if formula_matches(law, entry) else None


def formula_matches(law: LawDeclaration, recorded: Mapping[str, Any]) -> bool:
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


def formula_text_entries(laws: Iterable[LawText]) -> dict[str, Any]:
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


def _formula_text_json(laws: Iterable[LawText]) -> str:
    return json.dumps(formula_text_entries(laws), indent=1, sort_keys=True) + "\n"


def formula_texts_current(laws: Iterable[LawText], path: Path | None = None) -> bool:
    """True when the formula-text cache holds what ``laws`` render to now.

    Parameters
    ----------
    laws : iterable of Law
        The laws the cache is for (the built-in ones).
    path : Path, optional
        The cache file (default :data:`FORMULA_TEXT_FILE`).

    Returns
    -------
    bool
        The same laws, each with the same text, symbols and check values (the values to
        the tolerance of :func:`formula_matches`: their last digit varies with numpy).
    """
    laws = list(laws)
    try:
        stored = json.loads(Path(path or FORMULA_TEXT_FILE).read_text(encoding="utf-8"))["laws"]
    except (OSError, ValueError, KeyError, TypeError):
        return False
    fresh = formula_text_entries(laws)["laws"]
    by_id = {law.id: law for law in laws}
    return (isinstance(stored, dict) and stored.keys() == fresh.keys()
            and all(isinstance(stored[k], dict) and stored[k].get("text") == fresh[k]["text"]
                    and formula_matches(by_id[k], stored[k]) for k in fresh))


def write_formula_texts(laws: Iterable[LawText], path: Path | None = None) -> Path:
    """Write the formula-text cache for ``laws`` (rendered with sympy).

    Parameters
    ----------
    laws : iterable of Law
        The laws to cache (the built-in ones).
    path : Path, optional
        Where to write (default :data:`FORMULA_TEXT_FILE`, which the laws then read).

    Returns
    -------
    Path
        The file written.
    """
    target = Path(path or FORMULA_TEXT_FILE)
    target.write_text(_formula_text_json(laws), encoding="utf-8")
    _formula_texts.cache_clear()
    return target
