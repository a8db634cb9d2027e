"""Column names and units: the canonical variables, their aliases, and the ``name=...``
pairs of a mapping or a unit table.
"""

from __future__ import annotations

import re
import unicodedata
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

from ..base import units as _units
from ..base.errors import Argument, InputError
from ..law import VARIABLES

if TYPE_CHECKING:  # pandas is imported where a DataFrame is made or asked for
    pass



__all__ = ["VARIABLE_COLUMNS", "CANONICAL", "TEXT_COLUMNS", "ALIASES", "MISSING_TOKENS",
           "canonical_name", "column_for", "parse_mapping", "parse_units"]


#: The canonical columns that are independent variables of a law
#: (:data:`frictionlaws.law.VARIABLES`; their units: :data:`frictionlaws.base.units.QUANTITIES`).
VARIABLE_COLUMNS: tuple[str, ...] = tuple(VARIABLES)


#: Canonical columns, in the order a dataset stores and writes them.
CANONICAL: tuple[str, ...] = ("mu", *VARIABLE_COLUMNS, "mu_std", "n", "surface",
                              "condition_id")


#: Canonical columns that hold text: the counter-surface, and the test condition each
#: row belongs to (repeats share it: the unit the bootstrap resamples).
TEXT_COLUMNS: tuple[str, ...] = ("surface", "condition_id")


_NUMERIC = tuple(c for c in CANONICAL if c not in TEXT_COLUMNS)


_DIMENSIONLESS = tuple(c for c in _NUMERIC if not _units.si_unit(c))


#: Accepted column names for each canonical column, in :data:`CANONICAL` order (the
#: one alias table; a test checks it has every canonical column and no other).  The
#: canonical names themselves match exactly (``T`` is temperature, ``t`` is not); these
#: aliases match case-insensitively, with spaces, ``_`` and ``-`` equivalent.
ALIASES: dict[str, tuple[str, ...]] = {
    "mu": ("mu", "μ", "cof", "coef", "friction", "friction coefficient",
           "coefficient of friction", "friction coef", "mu mean", "mean mu"),
    "p": ("p", "pressure", "contact pressure", "normal pressure", "nominal pressure"),
    "v": ("v", "velocity", "speed", "sliding velocity", "sliding speed", "slip velocity",
          "slip speed"),
    "T": ("temperature", "temp", "surface temperature"),
    "F_N": ("f_n", "fn", "load", "normal load", "normal force", "force normal"),
    "s": ("slip", "slip ratio", "longitudinal slip", "kappa", "κ"),
    "mu_std": ("mu_std", "mu std", "std mu", "std", "sd", "stdev", "std dev",
               "standard deviation", "mu sd", "sd mu"),
    "n": ("count", "replicates", "repeats", "n tests", "n repeats", "n replicates"),
    "surface": ("surface", "counter surface", "countersurface", "counterface", "material"),
    "condition_id": ("condition_id", "condition id", "test condition"),
}


#: Cell contents read as a missing value (the row is then dropped and reported).
MISSING_TOKENS = frozenset({"", "nan", "na", "n/a", "#n/a", "null", "none", "-", "—", "–"})


def _norm(name: str) -> str:
    # NFKC: the micro sign typed by keyboards (U+00B5) reads as the Greek mu (U+03BC)
    text = unicodedata.normalize("NFKC", name)
    return re.sub(r"[\s_\-]+", " ", text.strip().lower()).strip()


_ALIAS_LOOKUP: dict[str, str] = {}


for _canon, _names in ALIASES.items():
    for _alias in _names:
        _ALIAS_LOOKUP[_norm(_alias)] = _canon


_CANON_KEYS = {c.lower(): c for c in CANONICAL}


def column_for(name: str) -> str | None:
    """The dataset column a header name is read as: itself, or through :data:`ALIASES`.

    Case, spaces, ``_`` and ``-`` do not matter, and the micro sign reads as the Greek mu
    (``"Coefficient of friction"`` and ``"COF"`` -> ``"mu"``).

    Parameters
    ----------
    name : str
        A column's name (its header without the unit).

    Returns
    -------
    str or None
        One of :data:`CANONICAL`, or None when the name is no dataset column.
    """
    if name in CANONICAL:
        return name
    return _ALIAS_LOOKUP.get(_norm(name))


def canonical_name(key: str, *, what: str = "name", option: str | None = None) -> str:
    """The canonical column for a key of ``mapping``/``units`` (``"f_n"`` -> ``"F_N"``).

    ``option`` is the argument the key came from (named in the error).

    Raises
    ------
    InputError
        When ``key`` is not one of :data:`CANONICAL`.
    """
    k = key.strip()
    if k in CANONICAL:
        return k
    if k.lower() in _CANON_KEYS:
        return _CANON_KEYS[k.lower()]
    raise InputError(
        f"{what} '{k}' is not a dataset column; expected one of {', '.join(CANONICAL)}",
        option=option,
    )


def _split_pairs(text: str | Sequence[str], option: str, example: str
                 ) -> list[tuple[str, str]]:
    """``"a=1,b=2"`` (or several such strings) -> ``[("a", "1"), ("b", "2")]``."""
    parts: list[str] = []
    for chunk in ([text] if isinstance(text, str) else list(text)):
        parts.extend(str(chunk).split(","))
    items = []
    for part in parts:
        if not part.strip():
            if len(parts) > 1:
                continue
            raise InputError(["is empty; expected NAME=VALUE pairs, e.g. ",
                              Argument(option, example)], option=option)
        if "=" not in part:
            raise InputError([f"'{part.strip()}' is not NAME=VALUE; expected e.g. ",
                              Argument(option, example)], option=option)
        k, v = part.split("=", 1)
        items.append((k, v))
    return items


def _parse_pairs(text: str | Sequence[str] | Mapping[str, str] | None, option: str,
                 example: str) -> dict[str, str]:
    """``NAME=VALUE`` pairs of the argument ``option`` by canonical column name."""
    if text is None:
        return {}
    if isinstance(text, Mapping):
        items = [(str(k), str(v)) for k, v in text.items()]
    else:
        items = _split_pairs(text, option, example)
    out: dict[str, str] = {}
    for k, v in items:
        k, v = k.strip(), v.strip()
        if not k or not v:
            raise InputError([f"'{k}={v}' has an empty name or value; expected e.g. ",
                              Argument(option, example)], option=option)
        canon = canonical_name(k, option=option)
        if canon in out:
            raise InputError(f"'{canon}' is given twice", option=option)
        out[canon] = v
    return out


def parse_mapping(text: str | Sequence[str] | Mapping[str, str] | None) -> dict[str, str]:
    """Parse ``"mu=FC,p=CP,v=DV"`` into ``{"mu": "FC", "p": "CP", "v": "DV"}``.

    Keys are canonical column names (case-insensitive: ``f_n`` is ``F_N``);
    values are the user's column names.  A list of such strings or a dict is
    accepted too.

    Raises
    ------
    InputError
        On text that is not ``NAME=COLUMN`` pairs, an unknown canonical name, a
        name given twice or one column mapped twice.
    """
    out = _parse_pairs(text, "mapping", "mu=FC,p=CP,v=DV")
    seen: dict[str, str] = {}
    for canon, col in out.items():
        if col in seen:
            raise InputError(f"column '{col}' is mapped to both '{seen[col]}' and '{canon}'",
                             option="mapping")
        seen[col] = canon
    return out


def parse_units(text: str | Sequence[str] | Mapping[str, str] | None) -> dict[str, str]:
    """Parse ``"p=MPa,v=km/h"`` into ``{"p": "MPa", "v": "km/h"}``.

    Only the syntax is checked here; each unit is checked against its column
    (with pint) when the data are loaded.

    Raises
    ------
    InputError
        On text that is not ``NAME=UNIT`` pairs or an unknown canonical name.
    """
    return _parse_pairs(text, "units", "p=MPa,v=m/s")

