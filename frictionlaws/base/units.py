"""Units at the edges: parse unit strings with pint, convert to SI, write back.

Inside frictionlaws every quantity is SI: contact pressure ``p`` in Pa,
sliding velocity ``v`` in m/s, temperature ``T`` in K, normal load ``F_N`` in
N, friction coefficient ``mu`` and slip ratio ``s`` dimensionless.  Files and
command lines may use any unit pint understands (``MPa``, ``N/mm^2``, ``psi``,
``km/h``, ``degC``, ``degF``, ``kgf``...); this module turns them into SI and
back, and says clearly when a unit is unknown or has the wrong dimension.

Two conventions need care and are handled here:

* offset temperature units (``degC``, ``degF``) are converted as absolute
  temperatures (20 degC -> 293.15 K), never as differences;
* a normal load given as a *mass* (``kg``, ``g``, ``lb``: the dead weights of a
  tribometer) is turned into a force with g = 9.8 m/s^2, the value the source
  thesis used for its tables; ``kgf`` (kilogram-force) uses standard gravity
  9.80665 m/s^2.  :func:`conversion_note` returns the sentence that a dataset
  records when the mass convention was applied.

The units this table itself declares for a quantity (no unit for a
dimensionless one, its SI unit, its display unit with :attr:`Quantity.display_si`)
are checked and converted from the table alone; any other unit goes to pint,
which is imported and its registry built once, on first use.  So importing this
module costs nothing, and data in SI or display units never load pint.
"""

from __future__ import annotations

import functools
import math
import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .errors import InputError
from .numbers import parse_number

__all__ = [
    "QUANTITIES",
    "Quantity",
    "G_THESIS",
    "G_STANDARD",
    "unit_registry",
    "parse_unit",
    "check_unit",
    "to_si",
    "from_si",
    "conversion_note",
    "parse_quantity",
    "display_unit",
    "to_display",
    "header",
    "is_no_unit",
    "UnitText",
    "parse_unit_text",
    "canonical_unit",
    "MAX_UNIT_CHARS",
    "MAX_UNIT_EXPONENT",
    "MAX_UNIT_DEPTH",
    "is_pint_quantity",
    "si_magnitude",
]

#: Gravity used to turn a dead weight in kg into a load, as the thesis did [m/s^2].
G_THESIS = 9.8
#: Standard gravity, used by pint for ``kgf`` and ``lbf`` [m/s^2].
G_STANDARD = 9.80665

#: Strings that mean "no unit" for a dimensionless column.
_NO_UNIT = {"", "-", "1", "–", "—", "dimensionless", "none"}


@dataclass(frozen=True)
class Quantity:
    """A kind of quantity a column or option can hold.

    Parameters
    ----------
    si : str
        The SI unit used inside frictionlaws (``""`` for dimensionless).
    what : str
        A phrase naming the dimension in error messages ("a pressure").
    examples : tuple of str
        Units shown in messages as examples of what is accepted.
    display : str
        Unit used when writing the quantity in outputs.
    example : str
        A value with its unit, quoted in messages (``"0.2 MPa"``); ``"1"`` when
        dimensionless.
    display_si : tuple of float
        ``(scale, offset)`` of the display unit: a value ``x`` in ``display`` is
        ``scale * x + offset`` in ``si`` (MPa: ``(1e6, 0)``; degC: ``(1, 273.15)``).
        A test checks every entry against pint.
    """

    si: str
    what: str
    examples: tuple[str, ...]
    display: str
    example: str = "1"
    display_si: tuple[float, float] = (1.0, 0.0)


#: Quantity kinds by name: the canonical dataset columns plus a few used by options.
#: The one table of units: the SI unit, the unit written in outputs and the accepted
#: units of every quantity (law variables, dataset columns, rig quantities) live here
#: only; :data:`frictionlaws.law.VARIABLES` reads its variables' units from it.
QUANTITIES: dict[str, Quantity] = {
    "mu": Quantity("", "a dimensionless friction coefficient", ("-",), ""),
    "mu_std": Quantity("", "a dimensionless standard deviation of mu", ("-",), ""),
    "n": Quantity("", "a dimensionless count", ("-",), ""),
    "s": Quantity("", "a dimensionless slip ratio", ("-", "%"), ""),
    "p": Quantity("Pa", "a pressure", ("MPa", "kPa", "Pa", "bar", "psi", "N/mm^2"), "MPa",
                  "0.2 MPa", (1e6, 0.0)),
    "v": Quantity("m/s", "a velocity", ("m/s", "mm/s", "km/h"), "m/s", "1.38 m/s"),
    "T": Quantity("K", "a temperature", ("degC", "K", "degF"), "degC", "20 degC",
                  (1.0, 273.15)),
    "F_N": Quantity("N", "a force", ("N", "kN", "kgf", "lbf", "kg (dead weight)"), "N",
                    "49 N"),
    "area": Quantity("m**2", "an area", ("mm^2", "cm^2", "m^2"), "mm^2", "314.16 mm^2",
                     (1e-6, 0.0)),
    "length": Quantity("m", "a length", ("mm", "m"), "mm", "40 mm", (1e-3, 0.0)),
    "time": Quantity("s", "a time", ("s", "ms"), "s", "10 s"),
    "torque": Quantity("N*m", "a torque", ("N*m", "N*mm"), "N*m", "0.3 N*m"),
    "frequency": Quantity("Hz", "a frequency", ("Hz", "1/s"), "Hz", "1000 Hz"),
    "angular_velocity": Quantity("rad/s", "an angular velocity", ("rad/s", "rpm"), "rad/s",
                                 "331 rpm"),
    "angle": Quantity("rad", "an angle", ("deg", "rad"), "deg", "1", (math.pi / 180, 0.0)),
    "acceleration": Quantity("m/s**2", "an acceleration", ("m/s^2",), "m/s^2", "9.8 m/s^2"),
    "stiffness_per_length": Quantity("N/m**2", "a force per length per length",
                                     ("N/m^2", "N/mm^2"), "N/m^2", "8.49e6 N/m^2"),
    "curvature": Quantity("1/m", "a path curvature", ("1/m", "1/km"), "1/m", "0.5 1/m"),
}

# Names of common dimensions, for "unit 'm' is a length, expected a pressure":
# a representative unit of each, compared by dimensionality.
_DIMENSION_NAMES = (
    ("", "dimensionless"),
    ("m", "a length"),
    ("kg", "a mass"),
    ("s", "a time"),
    ("K", "a temperature"),
    ("m**2", "an area"),
    ("m**3", "a volume"),
    ("m/s", "a velocity"),
    ("m/s**2", "an acceleration"),
    ("N", "a force"),
    ("Pa", "a pressure"),
    ("J", "an energy or a torque"),
    ("1/s", "a frequency or an angular velocity"),
    ("C", "an electric charge"),
)


# --------------------------------------------------------------------------- unit grammar
#: Longest unit text read [characters]: real units are a few characters long.
MAX_UNIT_CHARS = 64
#: Largest power of one unit name (``mm^3``, ``s^-2``); pint would raise any power.
MAX_UNIT_EXPONENT = 9
#: Deepest parentheses in a unit (``N/(mm^2)``).
MAX_UNIT_DEPTH = 3

_SUPERSCRIPTS = {"\u00b9": 1, "\u00b2": 2, "\u00b3": 3}


class UnitSyntaxError(ValueError):
    """A unit text the grammar of :func:`parse_unit_text` refuses (the reason is the message)."""


@dataclass(frozen=True)
class UnitText:
    """A unit as the grammar read it: unit names with integer powers, in written order.

    Parameters
    ----------
    factors : tuple of (str, int)
        Each unit name (letters, digits after the first, ``_``, ``°``; or ``%``) with
        its power; a name appears once, powers are never 0.
    """

    factors: tuple[tuple[str, int], ...]

    def canonical(self) -> str:
        """The unit written back in one form: ``N/mm^2``, ``kg*m/s^2``, ``1/s``, ``""``."""
        def power(name: str, e: int) -> str:
            return name if e == 1 else f"{name}^{e}"

        num = "*".join(power(n, e) for n, e in self.factors if e > 0)
        den = "/".join(power(n, -e) for n, e in self.factors if e < 0)
        if not den:
            return num
        return f"{num or '1'}/{den}"

    def to_pint(self) -> Any:
        """The pint unit: each name looked up alone (never a pint expression), then raised.

        Raises
        ------
        UnitSyntaxError
            For a name pint does not know.
        """
        ureg = unit_registry()
        unit = ureg.dimensionless
        for name, e in self.factors:
            try:  # one name, never an expression; pint fails in several ways on odd ones
                found = ureg.Unit(name) if name in ureg else None
            except Exception:  # noqa: BLE001
                found = None
            if found is None:
                raise UnitSyntaxError(f"unknown unit '{name}'")
            unit = unit * found ** e
        return unit


def _unit_tokens(text: str) -> list[str]:
    """The tokens of a unit text: names, ``1``, ``*``, ``/``, ``(``, ``)`` and ``^N``."""
    tokens: list[str] = []
    i, n = 0, len(text)
    while i < n:
        ch = text[i]
        if ch in " \t":  # no other white space: a line break is never part of a unit
            i += 1
            continue
        if ch.isalpha() or ch == "\u00b0":
            j = i + 1
            while j < n and (text[j].isalnum() and text[j].isascii() or text[j].isalpha()
                             or text[j] in "_\u00b0"):
                j += 1
            tokens.append(text[i:j])
            i = j
            continue
        if ch in "%()/":
            tokens.append(ch)
            i += 1
            continue
        if ch in "*\u00b7\u22c5" or ch == "^":
            if text.startswith("**", i) or ch == "^":
                i += 2 if ch == "*" else 1
                i, exponent = _exponent(text, i)
                tokens.append(f"^{exponent}")
                continue
            tokens.append("*")
            i += 1
            continue
        if ch in _SUPERSCRIPTS:
            tokens.append(f"^{_SUPERSCRIPTS[ch]}")
            i += 1
            continue
        if ch == "1" and (i + 1 == n or not text[i + 1].isdigit()):
            tokens.append("1")
            i += 1
            continue
        raise UnitSyntaxError(f"unexpected {ascii(ch)} at character {i + 1}")
    return tokens


def _exponent(text: str, i: int) -> tuple[int, int]:
    """The integer power written at ``text[i:]`` (a sign and one or two digits)."""
    while i < len(text) and text[i] in " \t":
        i += 1
    j = i + 1 if i < len(text) and text[i] in "+-" else i
    k = j
    while k < len(text) and text[k].isascii() and text[k].isdigit():
        k += 1
    if k == j:
        raise UnitSyntaxError(f"a power needs a whole number after it (character {i + 1})")
    digits = text[j:k]
    if len(digits) > 2 or int(digits) > MAX_UNIT_EXPONENT:
        raise UnitSyntaxError(f"power {text[i:k][:12]} is beyond the limit of "
                              f"{MAX_UNIT_EXPONENT}")
    return k, -int(digits) if text[i] == "-" else int(digits)


def _unit_product(tokens: list[str], i: int, depth: int
                  ) -> tuple[list[tuple[str, int]], int]:
    """Read ``factor (op factor)*`` from ``tokens[i:]`` up to ``)`` or the end."""
    factors: list[tuple[str, int]] = []
    sign = 1
    first = True
    while i < len(tokens) and tokens[i] != ")":
        tok = tokens[i]
        if tok in ("*", "/") or tok.startswith("^"):
            raise UnitSyntaxError(f"'{tok}' without a unit before it")
        if tok == "(":
            if depth >= MAX_UNIT_DEPTH:
                raise UnitSyntaxError(f"parentheses nested deeper than {MAX_UNIT_DEPTH}")
            group, i = _unit_product(tokens, i + 1, depth + 1)
            if i >= len(tokens):
                raise UnitSyntaxError("a '(' is not closed")
            i += 1
        elif tok == "1":
            if not first or i + 1 >= len(tokens) or tokens[i + 1] != "/":
                raise UnitSyntaxError("a number inside a unit (only '1/...' is read)")
            group, i = [], i + 1
        else:
            group, i = [(tok, 1)], i + 1
        power = 1
        if i < len(tokens) and tokens[i].startswith("^"):
            power, i = int(tokens[i][1:]), i + 1
        factors.extend((name, e * power * sign) for name, e in group)
        first = False
        sign = 1
        if i < len(tokens) and tokens[i] in ("*", "/"):
            sign = -1 if tokens[i] == "/" else 1
            i += 1
            if i >= len(tokens) or tokens[i] == ")":
                raise UnitSyntaxError(f"'{tokens[i - 1]}' without a unit after it")
    if not factors and first:
        raise UnitSyntaxError("empty parentheses" if depth else "no unit")
    return factors, i


@functools.lru_cache(maxsize=256)
def parse_unit_text(text: str) -> UnitText:
    """Read a unit text with the one unit grammar (no arithmetic, bounded powers).

    The grammar: unit names (``MPa``, ``degC``, ``°C``, ``%``), joined by ``*``, ``·``,
    a space or ``/``, each with an optional integer power ``^N``, ``**N`` or ``²``/``³``
    (``|N| <=`` :data:`MAX_UNIT_EXPONENT`), parentheses up to :data:`MAX_UNIT_DEPTH`
    deep, and ``1/...``.  No other number is read and nothing is evaluated, so no text
    can make reading a unit slow; pint only looks up each name (:meth:`UnitText.to_pint`).

    Parameters
    ----------
    text : str
        The unit as written (at most :data:`MAX_UNIT_CHARS` characters).

    Returns
    -------
    UnitText

    Raises
    ------
    UnitSyntaxError
        Naming what the grammar could not read.
    """
    if len(text) > MAX_UNIT_CHARS:
        raise UnitSyntaxError(f"longer than {MAX_UNIT_CHARS} characters")
    tokens = _unit_tokens(text)
    factors, i = _unit_product(tokens, 0, 0)
    if i < len(tokens):
        raise UnitSyntaxError("a ')' without its '('")
    merged: dict[str, int] = {}
    for name, e in factors:
        merged[name] = merged.get(name, 0) + e
    if any(abs(e) > MAX_UNIT_EXPONENT for e in merged.values()):
        raise UnitSyntaxError(f"a power beyond the limit of {MAX_UNIT_EXPONENT}")
    return UnitText(tuple((n, e) for n, e in merged.items() if e))


def _shown_unit(text: str) -> str:
    """``text`` as quoted in a message: on one line (controls escaped), at most 40 characters."""
    shown = text if text.isprintable() else ascii(text)[1:-1]
    return shown if len(shown) <= 40 else shown[:37] + "..."


def _pint_unit(text: str) -> Any:
    """The pint unit of a user's unit text, read by the grammar (:func:`parse_unit_text`)."""
    return parse_unit_text(text).to_pint()


@functools.lru_cache(maxsize=1)
def unit_registry() -> Any:
    """The shared pint ``UnitRegistry`` (built once, on first use).

    Offset units are converted to base units automatically so that a string
    such as ``"20 degC"`` parses as an absolute temperature.
    """
    import pint

    return pint.UnitRegistry(autoconvert_offset_to_baseunit=True)


def is_no_unit(unit: str | None) -> bool:
    """True when ``unit`` means "dimensionless / no unit" (``""``, ``"-"``, ``"1"``)."""
    return unit is None or unit.strip().lower() in _NO_UNIT


def _declared(unit: str | None, kind: Quantity) -> tuple[float, float] | None:
    """``(scale, offset)`` to SI of a unit the table declares for ``kind``, else None.

    The declared units are no unit for a dimensionless quantity, the SI unit and the
    display unit, written exactly as in :data:`QUANTITIES`; they need no pint.
    """
    text = "" if unit is None else str(unit).strip()
    if not kind.si:
        return (1.0, 0.0) if is_no_unit(text) else None
    if text == kind.si:
        return (1.0, 0.0)
    if text == kind.display:
        return kind.display_si
    return None


def _kind(quantity: str) -> Quantity:
    try:
        return QUANTITIES[quantity]
    except KeyError:
        raise ValueError(
            f"unknown quantity kind {quantity!r}; expected one of {', '.join(QUANTITIES)}"
        ) from None


def _describe_dimension(unit: Any) -> str:
    ureg = unit_registry()
    dim = unit.dimensionality
    for ref, name in _DIMENSION_NAMES:
        ref_unit = ureg.parse_units(ref) if ref else ureg.dimensionless
        if ref_unit.dimensionality == dim:
            return name
    return f"of dimension {dim}"


def _suggest(text: str, kind: Quantity) -> str:
    """A hint for a unit pint does not know (e.g. wrong capitalisation)."""
    low = text.strip().lower()
    for ex in kind.examples:
        ex_unit = ex.split(" ")[0]
        if ex_unit.lower() == low and ex_unit != text.strip():
            return f"; units are case-sensitive: did you mean '{ex_unit}'?"
    if low in {"c", "°c", "deg c", "celsius", "centigrade"} and kind.si == "K":
        return "; did you mean 'degC'?"
    if low in {"f", "°f", "deg f", "fahrenheit"} and kind.si == "K":
        return "; did you mean 'degF'?"
    return ""


def _examples(kind: Quantity) -> str:
    return ", ".join(kind.examples)


def parse_unit(
    unit: str, quantity: str, *, column: str | None = None, file: str | None = None
) -> Any:
    """Parse ``unit`` with pint and check it fits ``quantity``.

    Parameters
    ----------
    unit : str
        The unit as written by the user (``"MPa"``, ``"degC"``, ``"-"``...).
    quantity : str
        A key of :data:`QUANTITIES` (``"p"``, ``"v"``, ``"T"``, ``"F_N"``,
        ``"mu"``, ``"s"``, ``"area"``...).
    column, file : str, optional
        Where the unit came from, for the error message.

    Returns
    -------
    pint.Unit
        The parsed unit.  For ``F_N`` a mass unit is accepted (dead weight).

    Raises
    ------
    InputError
        When pint does not know the unit, or its dimension does not match.
    """
    kind = _kind(quantity)
    ureg = unit_registry()
    text = "" if unit is None else str(unit).strip()
    if is_no_unit(text):
        parsed = ureg.dimensionless
    else:
        try:
            parsed = _pint_unit(text)
        except UnitSyntaxError as exc:
            reason = str(exc)
            head = f"unknown unit '{_shown_unit(text)}'" + (
                "" if reason == f"unknown unit '{text}'" else f" ({reason})")
            raise InputError(
                f"{head}; expected {kind.what} unit such as "
                f"{_examples(kind)}{_suggest(text, kind)}",
                file=file, column=column,
            ) from None
    expected = ureg.parse_units(kind.si) if kind.si else ureg.dimensionless
    if parsed.dimensionality == expected.dimensionality:
        _check_policy(parsed, text, kind, column=column, file=file)
        return parsed
    if quantity == "F_N" and parsed.dimensionality == ureg.kilogram.dimensionality:
        return parsed  # a dead weight given as a mass: see to_si / conversion_note
    got = _describe_dimension(parsed)
    hint = _suggest(text, kind) if got == "an electric charge" else ""
    raise InputError(
        f"unit '{text}' is {got}, expected {kind.what} (e.g. {_examples(kind)}){hint}",
        file=file, column=column,
    )


def _check_policy(parsed: Any, text: str, kind: Quantity, *, column: str | None,
                  file: str | None) -> None:
    """Units pint calls compatible that still mean something else.

    An angle (``rad``, ``deg``, ``turn``) is dimensionless to pint but is not a
    friction coefficient or a slip ratio; a temperature difference (``delta_degC``)
    has the dimension of a temperature but is not one.
    """
    ureg = unit_registry()
    if not kind.si and str(ureg.get_root_units(parsed)[1]) != "dimensionless":
        raise InputError(
            f"unit '{text}' is an angle, expected {kind.what} (e.g. {_examples(kind)})",
            file=file, column=column)
    if kind.si == "Hz" and "radian" in str(ureg.get_root_units(parsed)[1]):
        raise InputError(
            f"unit '{text}' is an angular velocity (a revolution is 2 pi rad, so rpm to Hz "
            f"is ambiguous), expected {kind.what} (e.g. {_examples(kind)})",
            file=file, column=column)
    if kind.si == "rad/s" and "radian" not in str(ureg.get_root_units(parsed)[1]):
        raise InputError(
            f"unit '{text}' is a frequency (a revolution is 2 pi rad, so Hz to rad/s is "
            f"ambiguous), expected {kind.what} (e.g. {_examples(kind)})",
            file=file, column=column)
    if kind.si == "K" and "delta_" in str(parsed):
        raise InputError(
            f"unit '{text}' is a temperature difference, expected {kind.what} "
            f"(e.g. {_examples(kind)})", file=file, column=column)


def check_unit(
    unit: str, quantity: str, *, column: str | None = None, file: str | None = None
) -> None:
    """Raise :class:`InputError` unless ``unit`` is a valid unit for ``quantity``."""
    if _declared(unit, _kind(quantity)) is None:
        parse_unit(unit, quantity, column=column, file=file)


def canonical_unit(unit: str | None, quantity: str, *, column: str | None = None,
                   file: str | None = None) -> str:
    """``unit`` checked for ``quantity`` and written in the one form outputs use.

    Outputs never write a unit as typed: ``"N / mm**2"`` is written ``"N/mm^2"``, a
    dimensionless unit ``""`` (see :meth:`UnitText.canonical`).

    Parameters
    ----------
    unit : str or None
        The unit as given.
    quantity : str
        A key of :data:`QUANTITIES`.
    column, file : str, optional
        Where the unit came from, for the error message.

    Returns
    -------
    str

    Raises
    ------
    InputError
        As :func:`parse_unit`.
    """
    text = "" if unit is None else str(unit).strip()
    check_unit(text, quantity, column=column, file=file)
    if is_no_unit(text):
        return ""
    return parse_unit_text(text).canonical()


def _is_mass(parsed: Any) -> bool:
    ureg = unit_registry()
    return bool(parsed.dimensionality == ureg.kilogram.dimensionality)


def to_si(
    values: Any,
    unit: str,
    quantity: str,
    *,
    column: str | None = None,
    file: str | None = None,
) -> np.ndarray:
    """Convert ``values`` given in ``unit`` to the SI unit of ``quantity``.

    Parameters
    ----------
    values : array-like or float
        Numbers in ``unit``.
    unit : str
        Unit string understood by pint; ``""``, ``"-"`` or ``"1"`` for
        dimensionless.  ``"%"`` is accepted for dimensionless quantities.
    quantity : str
        Kind of quantity, a key of :data:`QUANTITIES` (``"p"`` -> Pa,
        ``"v"`` -> m/s, ``"T"`` -> K, ``"F_N"`` -> N, ``"mu"``, ``"s"`` -> 1).
    column, file : str, optional
        Where the values came from, named in error messages.

    Returns
    -------
    numpy.ndarray
        Float array in SI (0-d array for a scalar input).

    Notes
    -----
    Temperatures in ``degC``/``degF`` are absolute (20 degC -> 293.15 K).  A
    normal load in a mass unit (``kg``) is a dead weight and is multiplied by
    :data:`G_THESIS` = 9.8 m/s^2; ``kgf`` uses standard gravity.
    """
    kind = _kind(quantity)
    declared = _declared(unit, kind)
    arr = np.asarray(values, dtype=float)
    # an overflow gives inf, which the callers refuse with the row; no NumPy warning
    if declared is not None:
        scale, offset = declared
        with np.errstate(over="ignore", invalid="ignore"):
            out = arr * scale + offset if declared != (1.0, 0.0) else arr.copy()
        return np.asarray(out, dtype=float)
    parsed = parse_unit(unit, quantity, column=column, file=file)
    ureg = unit_registry()
    with np.errstate(over="ignore", invalid="ignore"):
        if quantity == "F_N" and _is_mass(parsed):
            kg = ureg.Quantity(arr, parsed).to("kg").magnitude
            return np.asarray(kg * G_THESIS, dtype=float)
        target = ureg.parse_units(kind.si) if kind.si else ureg.dimensionless
        return np.asarray(ureg.Quantity(arr, parsed).to(target).magnitude, dtype=float)


def from_si(values: Any, unit: str, quantity: str) -> np.ndarray:
    """Convert SI ``values`` of ``quantity`` into ``unit`` (the inverse of :func:`to_si`)."""
    kind = _kind(quantity)
    arr = np.asarray(values, dtype=float)
    declared = _declared(unit, kind)
    if declared is not None:
        scale, offset = declared
        out = (arr - offset) * (1.0 / scale) if declared != (1.0, 0.0) else arr.copy()
        return np.asarray(out, dtype=float)
    parsed = parse_unit(unit, quantity)
    ureg = unit_registry()
    if quantity == "F_N" and _is_mass(parsed):
        return np.asarray(
            ureg.Quantity(arr / G_THESIS, "kg").to(parsed).magnitude, dtype=float
        )
    source = ureg.parse_units(kind.si) if kind.si else ureg.dimensionless
    return np.asarray(ureg.Quantity(arr, source).to(parsed).magnitude, dtype=float)


def conversion_note(unit: str, quantity: str, column: str | None = None) -> str | None:
    """The sentence a dataset records when a conversion needs a convention.

    Returns a note for a normal load given as a mass (converted with
    g = 9.8 m/s^2 as in the thesis), ``None`` otherwise.
    """
    if quantity != "F_N" or is_no_unit(unit) or _declared(unit, _kind(quantity)) is not None:
        return None
    parsed = parse_unit(unit, quantity, column=column)
    if not _is_mass(parsed):
        return None
    where = f"column '{column}'" if column else "F_N"
    return (
        f"{where}: normal load given as a mass in '{parse_unit_text(unit).canonical()}' "
        "(dead weight), converted to "
        f"newtons with g = {G_THESIS} m/s^2 as the thesis did; write the unit as 'kgf' to "
        f"use standard gravity {G_STANDARD} m/s^2 instead"
    )


_NUMBER_START = re.compile(r"^\s*[-+]?([0-9]|\.[0-9])")
#: The number written before the unit (checked by the one number parser: no ``4_0``, no
#: ``4,0``, no full-width digits, no overflow).
_NUMBER_TOKEN = re.compile(r"^\s*([-+]?[0-9_.,]*(?:[eE][-+]?[0-9_]+)?)", re.ASCII)


def parse_quantity(
    text: str | float,
    expected: str,
    *,
    what: str | None = None,
    file: str | None = None,
    column: str | None = None,
) -> float:
    """Parse a quantity such as ``"314.16 mm^2"`` into a float in SI.

    Parameters
    ----------
    text : str or float
        A number followed by a unit.  A plain float is taken as already SI.
    expected : str
        The kind of quantity, a key of :data:`QUANTITIES` (``"area"``,
        ``"p"``, ``"T"``...).
    what : str, optional
        How to name the value in messages (e.g. ``"--area"``).
    file, column : str, optional
        Passed on to :class:`InputError`.

    Returns
    -------
    float
        The value in the SI unit of ``expected`` (m^2 for an area).

    Raises
    ------
    InputError
        When the text has no number, no unit where one is needed, an unknown
        unit or the wrong dimension.
    """
    kind = _kind(expected)
    label = what or expected
    if isinstance(text, (int, float, np.integer, np.floating)) and not isinstance(text, bool):
        value = float(text)
        if not np.isfinite(value):
            raise InputError(f"{label} must be a finite number, got {text}",
                             file=file, column=column)
        return value
    raw = str(text).strip()
    if not _NUMBER_START.match(raw):
        raise InputError(
            f"{label} '{raw}' is not a number with a unit; expected e.g. "
            f"'{_example_quantity(expected)}'",
            file=file, column=column,
        )
    number, unit_text = _split_quantity(raw, label, file, column)
    ureg = unit_registry()
    try:
        unit = _pint_unit(unit_text) if unit_text.strip() else ureg.dimensionless
    except UnitSyntaxError as exc:
        raise InputError(
            f"{label} '{_shown_unit(raw)}' could not be read ({exc}); expected {kind.what} "
            f"such as '{_example_quantity(expected)}'",
            file=file, column=column,
        ) from None
    q = ureg.Quantity(number, unit)
    target = ureg.parse_units(kind.si) if kind.si else ureg.dimensionless
    if q.dimensionality != target.dimensionality:
        if kind.si and q.dimensionless:
            raise InputError(
                f"{label} '{raw}' has no unit; give {kind.what} with its unit, e.g. "
                f"'{_example_quantity(expected)}'",
                file=file, column=column,
            )
        raise InputError(
            f"{label} '{raw}' is {_describe_dimension(q.units)}, expected {kind.what} "
            f"(e.g. '{_example_quantity(expected)}')",
            file=file, column=column,
        )
    if unit_text.strip():
        _check_policy(unit, unit_text.strip(), kind, column=column, file=file)
    value = float(q.to(target).magnitude)
    if not np.isfinite(value):
        raise InputError(f"{label} '{raw}' is not finite", file=file, column=column)
    return value


def _split_quantity(raw: str, label: str, file: str | None, column: str | None
                    ) -> tuple[float, str]:
    """The number of ``raw`` (read by the one number parser) and the unit text after it.

    pint would read ``4_0 mm`` and ``4,0 mm`` as 40 mm and ``008011 mm`` as 0 mm, and
    evaluate ``2**9**9 m``; the number is parsed here (refusing what
    :func:`~frictionlaws.base.numbers.parse_number` refuses) and the rest by the unit grammar.
    """
    m = _NUMBER_TOKEN.match(raw)
    token = m.group(1) if m else ""
    try:
        value = parse_number(token)
    except ValueError as exc:
        raise InputError(f"{label} '{_shown_unit(raw)}': {exc}", file=file,
                         column=column) from None
    return value, raw[m.end():] if m else ""


def _example_quantity(expected: str) -> str:
    return _kind(expected).example


def display_unit(quantity: str) -> str:
    """The unit frictionlaws writes ``quantity`` in (p MPa, v m/s, T degC, F_N N)."""
    return _kind(quantity).display


def to_display(values: Any, quantity: str) -> np.ndarray:
    """SI ``values`` of ``quantity`` in its display unit (:func:`display_unit`).

    Parameters
    ----------
    values : array_like
        Values in SI (Pa, m/s, K, N).
    quantity : str
        A quantity of :data:`QUANTITIES` (``"p"``, ``"T"``, ``"mu"``...).

    Returns
    -------
    numpy.ndarray
        The values in the display unit (MPa, degC...); a copy as floats when the
        display unit is the SI one.
    """
    kind = _kind(quantity)
    if kind.display == kind.si:
        return np.asarray(values, dtype=float)
    return from_si(values, kind.display, quantity)


def header(column: str, unit: str | None = None) -> str:
    """A CSV/table header with its unit: ``header("p")`` -> ``"p [MPa]"``; ``"mu"`` stays."""
    unit = display_unit(column) if unit is None and column in QUANTITIES else unit
    return f"{column} [{unit}]" if unit else column


def si_unit(quantity: str) -> str:
    """The SI unit of ``quantity`` as a string (``""`` when dimensionless)."""
    return _kind(quantity).si


def examples(quantity: str) -> Sequence[str]:
    """Example units accepted for ``quantity`` (used in messages and docs)."""
    return _kind(quantity).examples


def is_pint_quantity(value: Any) -> bool:
    """True for a pint ``Quantity`` (of any registry), without importing pint."""
    return any(c.__name__ == "Quantity" and c.__module__.split(".")[0] == "pint"
               for c in type(value).__mro__)


def si_magnitude(value: Any, si: str, what: str) -> Any:
    """A pint ``Quantity`` as its magnitude in the SI unit ``si``; anything else unchanged.

    The one conversion of quantities handed to the API (a law call, ``fit``,
    ``predict``, an export's values): numpy would strip the unit and read
    ``0.1 MPa`` as 0.1 Pa.

    Parameters
    ----------
    value : Any
        A pint Quantity (scalar or array), or a plain value (returned as it is).
    si : str
        The SI unit the value is wanted in (``""`` for a dimensionless one).
    what : str
        How to name the value in messages (``"law 'thirion': p"``).

    Returns
    -------
    Any
        The magnitude in ``si``, or ``value`` when it is not a Quantity.

    Raises
    ------
    InputError
        When the Quantity's unit is not one of a quantity of unit ``si``.
    """
    if not is_pint_quantity(value):
        return value
    try:
        return value.to(si or "dimensionless").magnitude
    except Exception:  # noqa: BLE001 - pint raises several types for incompatible units
        raise InputError(f"{what} is given in '{value.units}', which cannot be converted "
                         f"to {si or 'a dimensionless number'}") from None
