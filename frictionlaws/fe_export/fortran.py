"""Abaqus user subroutines generated from a law's symbolic form.

Three interfaces are written, in fixed-form Fortran as Abaqus compiles it:

* ``abaqus-fric-coef``: ``FRIC_COEF`` (Abaqus/Standard, interface of 2017 and
  later releases: ``fCoef(nBlock,2)``, ``fCoefDeriv(nBlock,20,2)``,
  ``slipData(nBlock,6)``), returning mu and its derivatives with respect to
  slip rate, pressure and temperature (first direction only: isotropic);
* ``abaqus-vfric-coef``: ``VFRIC_COEF`` (Abaqus/Explicit general contact),
  mu and the three derivatives;
* ``abaqus-vfric``: ``VFRIC`` (Abaqus/Explicit contact pairs), returning the
  friction *force* ``-min(mu * fNormal, fStickForce)``.

Each file has two routines.  The law itself is a separate subroutine
``frl_<law>`` with ``implicit none``: every parameter a named constant
(``PARAMETER``), the floors of :attr:`Law.floors` (and ``|v|``) applied before
any power or log exactly as the Python law does, the expression and its
derivatives from :func:`sympy.diff`, common subexpressions shared
(:func:`sympy.cse`).  It works in SI.  The Abaqus routine converts the model's
units to SI, calls it, and scales the derivatives back.  Abaqus' include files
use implicit typing (a name starting with i..n is an INTEGER: an exponent
``n`` would silently become one), so the Abaqus routine declares every local
explicitly (REAL*8 or INTEGER); its real arguments keep the include's real kind
(single or double precision Explicit both work).

The header comment (and the CLI's notes) state the input-deck lines the
routine needs (:func:`input_deck`): ``*SURFACE INTERACTION`` with
``*FRICTION, USER=COEFFICIENT, PROPERTIES=0`` (``FRIC_COEF``, ``VFRIC_COEF``)
or ``*FRICTION, USER, DEPVAR=0, PROPERTIES=0`` (``VFRIC``), and the contact
that uses it; without them Abaqus never calls the routine.  ``FRIC_COEF``
defines the first direction only: for isotropic friction ``fCoef(k,2)`` and
``fCoefDeriv(k,:,2)`` are left alone, as the manual asks.

Variables other than p, v and T (the slip ratio ``s``, the normal load
``F_N``) are read from field variables, in the order the law lists them; in
``VFRIC`` the normal load is the nodal normal force.
"""

from __future__ import annotations

import math
import re
import textwrap
import zlib
from collections.abc import Mapping, Sequence
from typing import Any

from ..base.errors import InputError
from ..base.sanitize import ascii_line
from ..law import VARIABLES, Law

__all__ = ["FORTRAN_FORMATS", "fortran_source", "routine_name", "FIELD_VARIABLES",
           "input_deck", "interaction_name", "FIXED_FORM_SUFFIXES", "check_source_name"]

#: Export format -> Abaqus routine name.
FORTRAN_FORMATS = {
    "abaqus-fric-coef": "fric_coef",
    "abaqus-vfric-coef": "vfric_coef",
    "abaqus-vfric": "vfric",
}
#: File name endings compilers read as fixed-form source (the form written here, and
#: the one Abaqus' ``abaqus make``/``user=`` compile); any other Fortran ending
#: (``.f90``, ``.f95``, ``.f03``, ``.f08``...) makes gfortran and ifort read free form.
FIXED_FORM_SUFFIXES = (".f", ".for", ".ftn", ".f77", ".fpp")
#: Endings of free-form Fortran source: a fixed-form file under one of them does not compile.
_FREE_FORM = re.compile(r"\.f(90|95|03|08|18)$", re.IGNORECASE)
#: Law variables not passed by Abaqus' friction interfaces: read from field variables.
FIELD_VARIABLES = ("F_N", "s")
#: Order of the arguments of the law routine (and of its derivative array): the order
#: of the variable table.
_ORDER = tuple(VARIABLES)
_ARG = {"p": "xp", "v": "xv", "T": "xt", "F_N": "xfn", "s": "xs"}


# --------------------------------------------------------------- printing


def _real(value: float) -> str:
    """A REAL*8 literal that round-trips the double ``value`` exactly."""
    if not math.isfinite(value):
        raise InputError(f"cannot write the non-finite number {value!r} into Fortran")
    text = repr(float(value))
    if "e" in text:
        mant, exp = text.split("e")
        if "." not in mant:
            mant += ".0"
        return f"{mant}d{int(exp)}"
    if "." not in text:
        text += ".0"
    return text + "d0"


def _printer() -> Any:
    import sympy
    from sympy.printing.fortran import FCodePrinter

    class _Printer(FCodePrinter):
        """sympy's Fortran printer with exact doubles and real-typed intrinsics."""

        def _print_Float(self, expr: Any) -> str:
            return _real(float(expr))

        def _print_NumberSymbol(self, expr: Any) -> str:
            return _real(float(expr.evalf(30)))

        _print_Pi = _print_NumberSymbol
        _print_Exp1 = _print_NumberSymbol
        _print_EulerGamma = _print_NumberSymbol
        _print_GoldenRatio = _print_NumberSymbol
        _print_Catalan = _print_NumberSymbol

        def _real_arg(self, a: Any) -> str:
            if a.is_Number:
                return _real(float(a))
            return self._print(a)

        def _print_Max(self, expr: Any) -> str:
            return "max(" + ", ".join(self._real_arg(a) for a in expr.args) + ")"

        def _print_Min(self, expr: Any) -> str:
            return "min(" + ", ".join(self._real_arg(a) for a in expr.args) + ")"

        def _print_sign(self, expr: Any) -> str:
            a = self._print(expr.args[0])
            return f"merge(0.0d0, sign(1.0d0, {a}), ({a}) == 0.0d0)"

        def _print_Heaviside(self, expr: Any) -> str:
            a = self._print(expr.args[0])
            h0 = float(expr.args[1]) if len(expr.args) > 1 else 0.5
            return (f"merge(1.0d0, merge({_real(h0)}, 0.0d0, ({a}) == 0.0d0), "
                    f"({a}) > 0.0d0)")

        def _print_DiracDelta(self, expr: Any) -> str:
            return "0.0d0"

        def _print_Piecewise(self, expr: Any) -> str:
            *pairs, last = expr.args
            if last.cond != sympy.true:
                raise InputError("cannot write a Piecewise without a default branch to "
                                 "Fortran")
            out = self._real_arg(last.expr)
            for e, c in reversed(pairs):
                out = f"merge({self._real_arg(e)}, {out}, {self._print(c)})"
            return out

        def _print_Pow(self, expr: Any) -> str:
            base, exp = expr.args
            if base.is_Number and not exp.is_Integer and exp != sympy.S.Half:
                return f"{_real(float(base))}**({self._print(exp)})"
            return super()._print_Pow(expr)

    return _Printer({"source_format": "fixed", "standard": 95, "strict": True})


def _comment(lines: Sequence[str], width: int = 72) -> list[str]:
    """Fixed-form comment lines ('C' in column 1), wrapped at ``width``.

    Every line goes through :func:`~frictionlaws.base.sanitize.ascii_line` first.
    """
    out = []
    for line in map(ascii_line, lines):
        if not line:
            out.append("C")
            continue
        indent = len(line) - len(line.lstrip())
        for piece in textwrap.wrap(line, width - 2, subsequent_indent=" " * (indent + 2),
                                   break_long_words=True, break_on_hyphens=False) or [""]:
            out.append(("C " + piece).rstrip())
    return out


def _split_outside_quotes(text: str) -> list[str]:
    """Split after each ', ' that is not inside a character literal."""
    parts, cur, quote = [], "", None
    i = 0
    while i < len(text):
        ch = text[i]
        cur += ch
        if quote:
            if ch == quote:
                quote = None
        elif ch in "'\"":
            quote = ch
        elif ch == "," and text[i + 1:i + 2] == " ":
            parts.append(cur)
            cur = ""
            i += 1
        i += 1
    parts.append(cur)
    return parts


def _stmt(text: str, indent: int = 6) -> list[str]:
    """A fixed-form statement, wrapped after commas (never inside a string).

    Continuation lines carry '*' in column 6, as in Abaqus' own templates.
    """
    first = " " * indent + text
    if len(first) <= 72:
        return [first]
    lines: list[str] = []
    cur = " " * indent
    for part in _split_outside_quotes(text):
        sep = "" if not cur.strip() or cur.rstrip().endswith("*") else " "
        if len(cur) + len(sep) + len(part) > 72 and cur.strip() not in ("", "*"):
            lines.append(cur.rstrip())
            cur, sep = "     *   ", ""
        cur += sep + part
    lines.append(cur.rstrip())
    too_long = [ln for ln in lines if len(ln) > 72]
    if too_long:
        raise InputError(f"cannot wrap Fortran statement within 72 columns: {too_long[0]!r}")
    return lines


def _declare(kind: str, names: Sequence[str], indent: int = 6) -> list[str]:
    """``REAL*8 a, b, c`` declarations wrapped to fixed form."""
    if not names:
        return []
    return _stmt(f"{kind} " + ", ".join(names), indent)


def check_source_name(path: str) -> None:
    """Refuse a file name a compiler would read as free-form source.

    The routines are fixed-form Fortran; under a free-form ending (``.f90``...)
    gfortran and ifort reject them, so the name must end in one of
    :data:`FIXED_FORM_SUFFIXES` (any other ending is left to the user).

    Parameters
    ----------
    path : str
        The output file name.

    Raises
    ------
    InputError
        For a free-form ending, naming the file and the endings to use.
    """
    if _FREE_FORM.search(str(path)):
        raise InputError(
            "the Abaqus user subroutine is fixed-form Fortran, which compilers refuse "
            f"under a free-form name ending '{str(path).rsplit('.', 1)[-1]}'; name the file "
            f"with one of {', '.join(FIXED_FORM_SUFFIXES)} (Abaqus compiles .f and .for)",
            file=str(path))


# ---------------------------------------------------------------- naming


def routine_name(law: Law) -> str:
    """The Fortran name of the law routine: ``frl_<id>`` (at most 31 characters)."""
    base = "frl_" + re.sub(r"[^a-z0-9]+", "_", law.id.lower()).strip("_")
    if len(base) > 31:
        base = base[:24] + f"_{zlib.crc32(law.id.encode()) % 100000:05d}"
    return base


def interaction_name(law: Law) -> str:
    """The surface-interaction name the deck instructions use: ``FRL_<ID>`` (at most 80)."""
    return routine_name(law).upper()[:80]


def input_deck(law: Law, fmt: str) -> tuple[list[str], list[str]]:
    """The Abaqus input lines a deck needs for the routine of ``fmt``, and notes.

    Without ``*FRICTION, USER=...`` in the surface interaction Abaqus never
    calls the routine and silently uses other friction.  The routines keep
    no state variables and take no properties (the law's parameters are
    compiled in), so ``PROPERTIES=0`` (no data lines follow) and, for
    ``VFRIC`` (the only one of the three with state variables),
    ``DEPVAR=0``.

    Parameters
    ----------
    law : Law
        The law.
    fmt : str
        One of :data:`FORTRAN_FORMATS`.

    Returns
    -------
    lines : list of str
        Keyword and data lines in deck order (``<...>`` marks what the user
        supplies): model data first, then the step where the contact is
        step data (Abaqus/Explicit).
    notes : list of str
        What else the deck must define (temperatures, field variables).
    """
    if fmt not in FORTRAN_FORMATS:
        raise InputError(f"unknown Fortran format '{fmt}'")
    name = interaction_name(law)
    friction = {"abaqus-fric-coef": "*FRICTION, USER=COEFFICIENT, PROPERTIES=0",
                "abaqus-vfric-coef": "*FRICTION, USER=COEFFICIENT, PROPERTIES=0",
                "abaqus-vfric": "*FRICTION, USER, DEPVAR=0, PROPERTIES=0"}[fmt]
    lines = [f"*SURFACE INTERACTION, NAME={name}", friction]
    if fmt == "abaqus-fric-coef":
        lines += [f"*CONTACT PAIR, INTERACTION={name}", "<slave surface>, <master surface>"]
    else:
        lines += ["*STEP", "*DYNAMIC, EXPLICIT", ", <time period>"]
        if fmt == "abaqus-vfric-coef":
            lines += ["*CONTACT", "*CONTACT INCLUSIONS, ALL EXTERIOR",
                      "*CONTACT PROPERTY ASSIGNMENT", f" ,  , {name}"]
        else:
            lines += [f"*CONTACT PAIR, INTERACTION={name}", "<slave surface>, <master surface>"]
        lines += ["*END STEP"]
    notes = []
    if fmt == "abaqus-fric-coef":
        notes.append(f"general contact instead of a pair: *CONTACT, *CONTACT INCLUSIONS, "
                     f"*CONTACT PROPERTY ASSIGNMENT with ' ,  , {name}'")
    if "T" in law.variables:
        notes.append("the law needs the temperature at the contact: define it "
                     "(*INITIAL CONDITIONS, TYPE=TEMPERATURE, *TEMPERATURE or a coupled "
                     "analysis), else the routine stops the analysis")
    fields = _field_index(law)
    if fmt == "abaqus-vfric":
        fields = {k: j + 1 for j, k in enumerate(k for k in fields if k != "F_N")}
    for var, i in fields.items():
        notes.append(f"field variable {i} = {var}: define it (*INITIAL CONDITIONS, "
                     f"TYPE=FIELD, VARIABLE={i} or *FIELD, VARIABLE={i}), else the routine "
                     "stops the analysis")
    return lines, notes


def _unique(names: Mapping[str, str]) -> dict[str, str]:
    """Make Fortran names unique case-insensitively (Fortran ignores case)."""
    out: dict[str, str] = {}
    seen: set[str] = set()
    for key, name in names.items():
        cand = name.lower()[:31]
        i = 2
        while cand in seen:
            suffix = f"_{i}"
            cand = name.lower()[:31 - len(suffix)] + suffix
            i += 1
        seen.add(cand)
        out[key] = cand
    return out


# ------------------------------------------------------------ law routine


def _undefined_functions(law: Law, expr: Any = None) -> list[str]:
    from sympy.core.function import AppliedUndef

    expr = law.symbolic() if expr is None else expr
    return sorted({str(f.func) for f in expr.atoms(AppliedUndef)})


def has_closed_form(law: Law) -> bool:
    """True when the law's symbolic form holds no unevaluated function (an integral)."""
    return not _undefined_functions(law)


def require_closed_form(law: Law, expr: Any = None) -> None:
    """Refuse a law whose symbolic form holds an unevaluated function (an integral).

    Such a law (e.g. ``persson``, a double integral over wavenumber and angle)
    has no Fortran expression; its tables (Abaqus, LS-DYNA, Ansys, Radioss
    formats) are exported instead.
    """
    undefined = _undefined_functions(law, expr)
    if undefined:
        raise InputError(
            f"law '{law.id}' has no closed form ({', '.join(undefined)} is a numerical "
            "integral), so no Fortran user subroutine can be generated; export a table "
            "format instead")


def law_routine(law: Law, values: Mapping[str, float]) -> list[str]:
    """The ``frl_<law>`` subroutine: mu and d(mu)/d(p, v, T, F_N, s) in SI."""
    import sympy

    syms = law.symbols()
    expr = law.symbolic()
    require_closed_form(law, expr)
    params = [p.name for p in law.params]
    settings = [s.name for s in law.settings]
    missing = [n for n in params + settings if n not in values]
    if missing:
        raise InputError(f"law '{law.id}': no value for {', '.join(missing)}")
    fnames = _unique({**{n: f"c_{n}" for n in params}, **{n: f"s_{n}" for n in settings},
                      **{v: f"x_{v}" for v in law.variables},
                      **{f"g:{v}": f"g_{v}" for v in law.variables}})
    derivs = [sympy.diff(expr, syms[v]) for v in law.variables]
    temp = sympy.numbered_symbols("w_")
    repl, reduced = sympy.cse([expr, *derivs], symbols=temp, optimizations="basic")
    rename = {syms[n]: sympy.Symbol(fnames[n]) for n in params + settings + list(law.variables)}
    printer = _printer()
    name = routine_name(law)

    lines = _stmt(f"subroutine {name}(xp, xv, xt, xfn, xs, fmu, dmu)")
    lines += _comment([
        f"Law '{law.id}' ({law.title}) and its derivatives, in SI:",
        "in: xp [Pa], xv [m/s], xt [K], xfn [N], xs [-] (unused ones ignored)",
        "out: fmu = mu; dmu(1..5) = d(mu)/d(xp, xv, xt, xfn, xs)",
    ])
    lines.append("      implicit none")
    lines += _declare("real*8", ["xp", "xv", "xt", "xfn", "xs", "fmu", "dmu(5)"])
    lines += _constant_lines([fnames[n] for n in params + settings],
                             [float(values[n]) for n in params + settings])
    locals_ = [fnames[v] for v in law.variables] + [fnames[f"g:{v}"] for v in law.variables]
    temps = [str(t) for t, _ in repl]
    lines += _declare("real*8", locals_ + temps)
    lines += _variable_lines(law, fnames)
    for t, e in repl:
        lines += printer.doprint(e.xreplace(rename), assign_to=str(t)).splitlines()
    lines += printer.doprint(reduced[0].xreplace(rename), assign_to="fmu").splitlines()
    for i, v in enumerate(_ORDER):
        target = f"dmu({i + 1})"
        if v in law.variables:
            k = law.variables.index(v)
            d = reduced[1 + k].xreplace(rename) * sympy.Symbol(fnames[f"g:{v}"])
            lines += printer.doprint(d, assign_to=target).splitlines()
        else:
            lines.append(f"      {target} = 0.0d0")
    lines += ["      return", "      end"]
    return lines


def _constant_lines(names: Sequence[str], values: Sequence[float]) -> list[str]:
    """Declarations of the parameters and settings as Fortran named constants."""
    if not names:
        return []
    lines = _comment(["parameters and settings (named constants, SI):"])
    lines += _declare("real*8", list(names))
    for fname, val in zip(names, values, strict=True):
        lines += _stmt(f"parameter ({fname} = {_real(val)})")
    return lines


def _variable_lines(law: Law, fnames: Mapping[str, str]) -> list[str]:
    """The law's variables from the arguments: |v|, the floors, and their chain factors."""
    lines = []
    if law.variables:
        lines += _comment(["floors and |v| before any power or log (as the Python law)"])
    for v in law.variables:
        x, g, arg = fnames[v], fnames[f"g:{v}"], _ARG[v]
        if v == "v":
            lines += [f"      {x} = abs({arg})", f"      {g} = sign(1.0d0, {arg})"]
        else:
            lines += [f"      {x} = {arg}", f"      {g} = 1.0d0"]
        floor = law.floors.get(v)
        if floor is not None:
            lines += [f"      if ({x} .lt. {_real(floor)}) then",
                      f"         {x} = {_real(floor)}",
                      f"         {g} = 0.0d0",
                      "      end if"]
    return lines


# --------------------------------------------------------- Abaqus routines


def _conversions(law: Law, units: Any) -> tuple[list[str], list[str]]:
    """Declarations of the unit constants u_<var> (scale) and o_<var> (offset)."""
    names, stmts = [], []
    for v in _ORDER:
        if v in law.variables or v in ("p", "v", "T"):
            scale, offset = units.affine(v)
            names += [f"u_{v.lower()}", f"o_{v.lower()}"]
            stmts += _stmt(f"parameter (u_{v.lower()} = {_real(scale)}, "
                           f"o_{v.lower()} = {_real(offset)})")
    return _declare("real*8", names) + stmts, names


def _field_index(law: Law) -> dict[str, int]:
    return {v: i + 1 for i, v in enumerate(x for x in law.variables if x in FIELD_VARIABLES)}


def _checks(law: Law, errcall: str, temp_count: str, field_count: str,
            fields_from_force: bool = False) -> list[str]:
    """Stop the analysis with a message when a variable the law needs is missing."""
    out = []
    fields = _field_index(law)
    if fields_from_force:
        fields = {k: i for k, i in fields.items() if k != "F_N"}
        fields = {k: j + 1 for j, k in enumerate(fields)}

    def stop(what: str) -> list[str]:
        # the message must fit one continuation line (column 10 to 72)
        room = 60 - len(what) - len("frictionlaws : ")
        text = f"frictionlaws {law.id[:max(room, 4)]}: {what}".replace("'", "")
        return _stmt(f"call {errcall}(-3, '{text}', kerr, rerr, cerr)", 9)

    if "T" in law.variables:
        out += [f"      if ({temp_count} .lt. 1) then", *stop("the law needs a temperature"),
                "      end if"]
    if fields:
        need = max(fields.values())
        names = " ".join(f"{v}={i}" for v, i in fields.items())
        out += [f"      if ({field_count} .lt. {need}) then",
                *stop(f"needs field(s) {names}"), "      end if"]
    if out:
        out = ["      kerr(1) = 0", "      rerr(1) = 0.0d0", "      cerr(1) = ' '"] + out
    return out


_ERR_DECL = ["      integer kerr(1)", "      real*8 rerr(1)", "      character*8 cerr(1)"]


def _inputs(law: Law, src: Mapping[str, str]) -> list[str]:
    """Assign zp, zv, zt, zfn, zs (SI) from the interface's arrays."""
    out = []
    for v, z in (("p", "zp"), ("v", "zv"), ("T", "zt"), ("F_N", "zfn"), ("s", "zs")):
        if v in law.variables or v in ("p", "v", "T"):
            if v in src:
                out += _stmt(f"   {z} = {src[v]} * u_{v.lower()} + o_{v.lower()}", 6)
            else:
                out.append(f"         {z} = 0.0d0")
        else:
            out.append(f"         {z} = 0.0d0")
    return out


def _sources(law: Law, slip_rate: str) -> dict[str, str]:
    """Where each variable comes from in the coefficient interfaces (kk: the contact point)."""
    src = {"p": "pressure(kk)", "v": slip_rate,
           "T": "tempAvg(kk)" if "T" in law.variables else "0.0d0"}
    src.update({v: f"fieldAvg(kk,{i})" for v, i in _field_index(law).items()})
    return src


def _fric_coef(law: Law, units: Any, name: str) -> list[str]:
    src = _sources(law, "slipData(kk,1)")
    conv, _ = _conversions(law, units)
    lines = [
        "      subroutine fric_coef (",
        "C Write only -",
        "     *   fCoef, fCoefDeriv,",
        "C Read only -",
        "     *   nBlock, nProps, nTemp, nFields,",
        "     *   jFlags, rData,",
        "     *   surfInt, surfSlv, surfMst,",
        "     *   props, slipData, pressure,",
        "     *   tempAvg, fieldAvg )",
        "C",
        "      include 'aba_param.inc'",
        "C",
        "C     arguments (Abaqus/Standard is double precision)",
        "      integer nBlock, nProps, nTemp, nFields",
        "      integer iKStep, iKInc, nFlags, iTimStep, iTimGlb, iDTimCur, nData",
        "      parameter (iKStep = 1, iKInc = 2, nFlags = 2)",
        "      parameter (iTimStep = 1, iTimGlb = 2, iDTimCur = 3, nData = 3)",
        "      integer jFlags(nFlags)",
        "      real*8 fCoef(nBlock,2), fCoefDeriv(nBlock,20,2), props(nProps)",
        "      real*8 slipData(nBlock,6), pressure(nBlock), tempAvg(nBlock)",
        "      real*8 fieldAvg(nBlock,nFields), rData(nData)",
        "      character*(*) surfInt, surfSlv, surfMst",
        "C     locals, all declared (no implicit typing)",
        "      integer kk, jj",
        "      real*8 zp, zv, zt, zfn, zs, zmu, zdmu(5)",
        *_ERR_DECL,
        *conv,
        *_checks(law, "stdb_abqerr", "nTemp", "nFields"),
        "      do kk = 1, nBlock",
        *_inputs(law, src),
        *_stmt(f"call {name}(zp, zv, zt, zfn, zs, zmu, zdmu)", 9),
        "C        isotropic friction: only the first direction is defined;",
        "C        fCoef(kk,2) and fCoefDeriv(kk,:,2) are left alone (manual)",
        "         fCoef(kk,1) = zmu",
        "         do jj = 4, 20",
        "            fCoefDeriv(kk,jj,1) = 0.0d0",
        "         end do",
        "C        d mu / d slip rate, d pressure, d temperature (model units)",
        "         fCoefDeriv(kk,1,1) = zdmu(2) * u_v",
        "         fCoefDeriv(kk,2,1) = zdmu(1) * u_p",
        "         fCoefDeriv(kk,3,1) = zdmu(3) * u_t",
        "      end do",
        "      return",
        "      end",
    ]
    return lines


def _vfric_coef(law: Law, units: Any, name: str) -> list[str]:
    src = _sources(law, "slipRate(kk)")
    conv, _ = _conversions(law, units)
    return [
        "      subroutine vfric_coef (",
        "C Write only -",
        "     *   fCoef, fCoefDeriv,",
        "C Read only -",
        "     *   nBlock, nProps, nTemp, nFields,",
        "     *   jFlags, rData,",
        "     *   surfInt, surfSlv, surfMst,",
        "     *   props, slipRate, pressure,",
        "     *   tempAvg, fieldAvg )",
        "C",
        "      include 'vaba_param.inc'",
        "C",
        "C     arguments: integers declared; reals take the include's kind",
        "      integer nBlock, nProps, nTemp, nFields",
        "      integer iKStep, iKInc, nFlags, iTimStep, iTimGlb, iDTimCur, nData",
        "      parameter (iKStep = 1, iKInc = 2, nFlags = 2)",
        "      parameter (iTimStep = 1, iTimGlb = 2, iDTimCur = 3, nData = 3)",
        "      integer jFlags(nFlags)",
        "      dimension fCoef(nBlock), fCoefDeriv(nBlock,3), props(nProps),",
        "     *   slipRate(nBlock), pressure(nBlock), tempAvg(nBlock),",
        "     *   fieldAvg(nBlock,nFields), rData(nData)",
        "      character*(*) surfInt, surfSlv, surfMst",
        "C     locals, all declared (no implicit typing)",
        "      integer kk",
        "      real*8 zp, zv, zt, zfn, zs, zmu, zdmu(5)",
        *_ERR_DECL,
        *conv,
        *_checks(law, "xplb_abqerr", "nTemp", "nFields"),
        "      do kk = 1, nBlock",
        *_inputs(law, src),
        *_stmt(f"call {name}(zp, zv, zt, zfn, zs, zmu, zdmu)", 9),
        "         fCoef(kk) = zmu",
        "C        d mu / d slip rate, d pressure, d temperature (model units)",
        "         fCoefDeriv(kk,1) = zdmu(2) * u_v",
        "         fCoefDeriv(kk,2) = zdmu(1) * u_p",
        "         fCoefDeriv(kk,3) = zdmu(3) * u_t",
        "      end do",
        "      return",
        "      end",
    ]


def _vfric(law: Law, units: Any, name: str) -> list[str]:
    fields = {k: i for k, i in _field_index(law).items() if k != "F_N"}
    fields = {k: j + 1 for j, k in enumerate(fields)}
    src = {"p": "zpm", "v": "zvm", "T": "tempSlv(kk)" if "T" in law.variables else "0.0d0",
           "F_N": "zfm"}
    src.update({v: f"preDefSlv(kk,{i})" for v, i in fields.items()})
    conv, _ = _conversions(law, units)
    return [
        "      subroutine vfric (",
        "C Write only -",
        "     *   fTangential,",
        "C Read/Write -",
        "     *   statev,",
        "C Read only -",
        "     *   kStep, kInc, nContact, nFacNod, nSlvNod, nMstNod,",
        "     *   nFricDir, nDir, nStateVar, nProps, nTemp, nPred, numDefTfv,",
        "     *   jSlvUid, jMstUid, jConSlvid, jConMstid, timStep, timGlb,",
        "     *   dTimPrev, surfInt, surfSlv, surfMst, lContType,",
        "     *   dSlipFric, fStickForce, fTangPrev, fNormal, frictionWork,",
        "     *   shape, coordSlv, coordMst, dircosSl, dircosN, props,",
        "     *   areaSlv, tempSlv, preDefSlv, tempMst, preDefMst )",
        "C",
        "      include 'vaba_param.inc'",
        "C",
        "C     arguments: integers declared; reals take the include's kind",
        "      integer kStep, kInc, nContact, nFacNod, nSlvNod, nMstNod",
        "      integer nFricDir, nDir, nStateVar, nProps, nTemp, nPred",
        "      integer numDefTfv, lContType",
        "      integer jSlvUid(nSlvNod), jMstUid(nMstNod), jConSlvid(nContact)",
        "      integer jConMstid(nFacNod,nContact)",
        "      dimension props(nProps), statev(nStateVar,nSlvNod),",
        "     *   dSlipFric(nDir,nContact), fTangential(nFricDir,nContact),",
        "     *   fTangPrev(nDir,nContact), fStickForce(nContact),",
        "     *   areaSlv(nSlvNod), fNormal(nContact), shape(nFacNod,nContact),",
        "     *   coordSlv(nDir,nSlvNod), coordMst(nDir,nMstNod),",
        "     *   dircosSl(nDir,nContact), dircosN(nDir,nContact),",
        "     *   tempSlv(nContact), tempMst(numDefTfv),",
        "     *   preDefSlv(nContact,nPred), preDefMst(numDefTfv,nPred)",
        "      character*(*) surfInt, surfSlv, surfMst",
        "C     locals, all declared (no implicit typing)",
        "      integer kk, jj",
        "      real*8 zp, zv, zt, zfn, zs, zmu, zdmu(5)",
        "      real*8 zpm, zvm, zfm, zarea, zslip, zft",
        *_ERR_DECL,
        *conv,
        *_checks(law, "xplb_abqerr", "nTemp", "nPred", fields_from_force=True),
        "      do kk = 1, nContact",
        "C        slip rate = |slip increment| / time increment",
        "         zslip = 0.0d0",
        "         do jj = 1, nDir",
        "            zslip = zslip + dSlipFric(jj,kk)**2",
        "         end do",
        "         zvm = 0.0d0",
        "         if (dTimPrev .gt. 0.0d0) zvm = sqrt(zslip) / dTimPrev",
        "C        pressure = normal force / slave nodal area",
        "         zfm = abs(fNormal(kk))",
        "         zarea = areaSlv(jConSlvid(kk))",
        "         zpm = 0.0d0",
        "         if (zarea .gt. 0.0d0) zpm = zfm / zarea",
        *_inputs(law, src),
        *_stmt(f"call {name}(zp, zv, zt, zfn, zs, zmu, zdmu)", 9),
        "C        friction force, opposing slip, at most the sticking force",
        "         zft = zmu * zfm",
        "         if (zft .gt. fStickForce(kk)) zft = fStickForce(kk)",
        "         fTangential(1,kk) = -zft",
        "         do jj = 2, nFricDir",
        "            fTangential(jj,kk) = 0.0d0",
        "         end do",
        "      end do",
        "      return",
        "      end",
    ]


def fortran_source(law: Law, values: Mapping[str, float], fmt: str, units: Any,
                   header: Sequence[str]) -> str:
    """The complete fixed-form source for export format ``fmt``.

    Parameters
    ----------
    law : Law
        The law.
    values : mapping
        Complete parameters and settings (SI), as from :meth:`Law.resolve`.
    fmt : str
        One of :data:`FORTRAN_FORMATS`.
    units : UnitSystem
        The model's units (the routine converts them to SI).
    header : sequence of str
        Header lines written as comments at the top.
    """
    if fmt not in FORTRAN_FORMATS:
        raise InputError(f"unknown Fortran format '{fmt}'")
    name = routine_name(law)
    build = {"abaqus-fric-coef": _fric_coef, "abaqus-vfric-coef": _vfric_coef,
             "abaqus-vfric": _vfric}[fmt]
    lines = _comment(header)
    lines += ["C"] + build(law, units, name) + ["C"] + law_routine(law, values)
    for ln in lines:
        if not ln.startswith("C") and len(ln) > 72:
            raise AssertionError(f"generated Fortran line longer than 72 columns: {ln!r}")
    return "\n".join(lines) + "\n"
