"""Temperature: the WLF shift factor and temperature-aware laws.

Rubber friction follows the rubber's viscoelasticity: raising the temperature
has the same effect as lowering the sliding velocity.  The Williams-Landel-Ferry
(WLF) equation gives the shift factor

.. math::

    \\log_{10} a_T = -\\frac{C_1 (T - T_\\mathrm{ref})}{C_2 + T - T_\\mathrm{ref}},

and a law measured (or fitted) at the reference temperature is evaluated at
another temperature at the *reduced velocity* ``a_T(T) v``.  :func:`with_wlf`
turns any velocity-dependent law into such a temperature-aware law.

Two preset sets of constants are in use (:data:`WLF_PRESETS`): Grosch's
``C1 = 8.86, C2 = 101.6 K`` with ``T_ref = T_g + 50 K``, and the "universal"
``C1 = 17.44, C2 = 51.6 K`` with ``T_ref = T_g``.  They are the same function
referred to different reference temperatures (``C2`` shifts by 50 K and
``C1 C2`` is conserved), up to the rounding of the published constants.

WLF holds roughly from ``T_g`` to ``T_g + 100 K``; outside that window an
:class:`~frictionlaws.base.errors.ExtrapolationWarning` is issued.  At and below the
pole ``T = T_ref - C2`` the equation is meaningless and a
:class:`~frictionlaws.base.errors.DomainError` is raised.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..base.errors import DomainError, ExtrapolationWarning, InputError
from ..law import NUMPY, Derived, Law, Setting
from ..law.registry import REGISTRY, get_law

__all__ = [
    "WLFPreset",
    "WLF_PRESETS",
    "WLF_WINDOW",
    "wlf_log_aT",
    "wlf_messages",
    "wlf_formula",
    "wlf_convert",
    "resolve_wlf",
    "with_wlf",
    "WLFLaw",
]

#: Width of the window above T_g where WLF is valid [K].
WLF_WINDOW = 100.0

_WLF_REFERENCE = (
    "M. L. Williams, R. F. Landel, J. D. Ferry, The temperature dependence of relaxation "
    "mechanisms in amorphous polymers and other glass-forming liquids, "
    "J. Am. Chem. Soc. 77 (1955) 3701-3707."
)
_GROSCH_REFERENCE = (
    "K. A. Grosch, The relation between the friction and visco-elastic properties of "
    "rubber, Proc. R. Soc. Lond. A 274 (1963) 21-39."
)


@dataclass(frozen=True)
class WLFPreset:
    """A published set of WLF constants.

    Attributes
    ----------
    name : str
        Preset name.
    C1 : float
        Dimensionless constant C1.
    C2 : float
        Constant C2 [K].
    offset : float
        Reference temperature above the glass transition, ``T_ref - T_g`` [K].
    reference : str
        Where the constants come from.
    """

    name: str
    C1: float
    C2: float
    offset: float
    reference: str

    def T_ref(self, T_g: float) -> float:
        """The reference temperature for a material with glass transition ``T_g`` [K]."""
        return float(T_g) + self.offset


#: The published WLF constant sets: Grosch (T_ref = T_g + 50 K) and the
#: "universal" set (T_ref = T_g).
WLF_PRESETS: dict[str, WLFPreset] = {
    "grosch": WLFPreset("grosch", 8.86, 101.6, 50.0,
                        _GROSCH_REFERENCE + " (constants as quoted in the source thesis, "
                        "Eq. 2-4); " + _WLF_REFERENCE),
    "universal": WLFPreset("universal", 17.44, 51.6, 0.0, _WLF_REFERENCE),
}


def wlf_formula(m: Any, T: Any, C1: Any, C2: Any, T_ref: Any) -> Any:
    """log10 a_T written with the math namespace ``m`` (numpy or sympy)."""
    dT = T - T_ref
    return -C1 * dT / (C2 + dT)


def _preset(name: str) -> WLFPreset:
    try:
        return WLF_PRESETS[str(name).lower()]
    except KeyError:
        raise InputError(f"unknown WLF preset '{name}' (presets: "
                         f"{', '.join(WLF_PRESETS)})") from None


def _infer_T_g(C1: float, C2: float, T_ref: float) -> float | None:
    """T_g when (C1, C2) match a preset to 1 %, else None."""
    for p in WLF_PRESETS.values():
        if abs(C1 / p.C1 - 1) < 0.01 and abs(C2 / p.C2 - 1) < 0.01:
            return T_ref - p.offset
    return None


def wlf_messages(T: Any, C1: float, C2: float, T_ref: float,
                 T_g: float | None = None) -> list[str]:
    """Check temperatures against the WLF pole and validity window.

    Parameters
    ----------
    T : array-like
        Temperatures [K].
    C1, C2, T_ref : float
        WLF constants (C2 and T_ref in K).
    T_g : float, optional
        Glass transition temperature [K]; the validity window is
        ``T_g .. T_g + 100 K``.  When None it is inferred from a matching
        preset; when no preset matches only the pole is checked.

    Returns
    -------
    list of str
        One message per kind of extrapolation (empty when all is well).

    Raises
    ------
    DomainError
        When a temperature lies at or below the pole ``T_ref - C2`` (or is not finite).
    """
    T = np.asarray(T, dtype=float)
    if T.size and not np.all(np.isfinite(T)):
        raise DomainError("temperature T has non-finite values")
    pole = T_ref - C2
    if T.size and np.min(T) <= pole:
        n = int(np.count_nonzero(T <= pole))
        raise DomainError(
            f"{n} temperature(s) at or below the WLF pole T_ref - C2 = {pole:.2f} K "
            f"({pole - 273.15:.2f} degC; lowest T = {np.min(T):.2f} K): the WLF shift is "
            f"undefined there (C1 = {C1:g}, C2 = {C2:g} K, T_ref = {T_ref:.2f} K)")
    if T_g is None:
        T_g = _infer_T_g(C1, C2, T_ref)
    msgs = []
    if T_g is not None and T.size:
        lo, hi = T_g, T_g + WLF_WINDOW
        below = int(np.count_nonzero(T < lo - 1e-9))
        above = int(np.count_nonzero(T > hi + 1e-9))
        if below:
            msgs.append(f"{below} temperature(s) below T_g = {lo:.2f} K ({lo - 273.15:.1f} degC): "
                        "WLF is an extrapolation there (valid roughly T_g .. T_g + 100 K)")
        if above:
            msgs.append(f"{above} temperature(s) above T_g + 100 K = {hi:.2f} K "
                        f"({hi - 273.15:.1f} degC): WLF is an extrapolation there")
    return msgs


def wlf_log_aT(T: Any, C1: float | None = None, C2: float | None = None,
               T_ref: float | None = None, *, T_g: float | None = None,
               preset: str | None = None, warn: bool = True) -> Any:
    """The WLF shift factor log10 a_T.

    Parameters
    ----------
    T : array-like
        Temperatures [K].
    C1, C2 : float, optional
        WLF constants (C2 in K); taken from ``preset`` when not given.
    T_ref : float, optional
        Reference temperature [K], where log10 a_T = 0; with a preset it may
        be omitted when ``T_g`` is given (``T_ref = T_g + offset``).
    T_g : float, optional
        Glass transition temperature [K], for the validity window.
    preset : {"grosch", "universal"}, optional
        Published constants (:data:`WLF_PRESETS`).
    warn : bool
        Issue an :class:`~frictionlaws.base.errors.ExtrapolationWarning` outside
        ``T_g .. T_g + 100 K``.

    Returns
    -------
    float or numpy.ndarray
        The decimal logarithm of the shift factor, log10 a_T, per temperature
        (a float for a scalar ``T``); positive below T_ref: the material behaves
        as at a higher velocity or frequency.

    Raises
    ------
    DomainError
        At or below the pole ``T_ref - C2``.
    InputError
        When the constants cannot be resolved.

    Examples
    --------
    >>> round(wlf_log_aT(273.15, preset="grosch", T_g=223.15), 6)
    0.0
    """
    C1, C2, T_ref, T_g = resolve_wlf(C1=C1, C2=C2, T_ref=T_ref, T_g=T_g, preset=preset)
    msgs = wlf_messages(T, C1, C2, T_ref, T_g)
    if warn and msgs:
        warnings.warn("; ".join(msgs), ExtrapolationWarning, stacklevel=2)
    out = wlf_formula(NUMPY, np.asarray(T, dtype=float), C1, C2, T_ref)
    return float(out) if np.ndim(out) == 0 else out


def wlf_convert(C1: float, C2: float, T_ref: float, T_ref_new: float) -> tuple[float, float]:
    """Refer the WLF constants to another reference temperature.

    The same shift function (up to the additive constant that makes
    log10 a_T(T_ref_new) = 0) has ``C2' = C2 + (T_ref_new - T_ref)`` and
    ``C1' = C1 C2 / C2'``.

    Returns
    -------
    (C1', C2')
    """
    C2n = C2 + (T_ref_new - T_ref)
    if C2n <= 0:
        raise DomainError(f"new reference {T_ref_new:.2f} K is at or below the WLF pole "
                          f"{T_ref - C2:.2f} K")
    return C1 * C2 / C2n, C2n


def resolve_wlf(*, C1: float | None = None, C2: float | None = None,
                T_ref: float | None = None, T_g: float | None = None,
                preset: str | None = None) -> tuple[float, float, float, float | None]:
    """Complete (C1, C2, T_ref, T_g) from explicit values and/or a preset.

    Explicit values win over the preset's.  With a preset, ``T_ref`` and
    ``T_g`` determine each other (``T_ref = T_g + offset``).  Without a
    preset, ``T_g`` is inferred when (C1, C2) match a preset, else left None.
    """
    p = _preset(preset) if preset is not None else None
    if p is not None:
        C1 = p.C1 if C1 is None else C1
        C2 = p.C2 if C2 is None else C2
        if T_ref is None and T_g is not None:
            T_ref = p.T_ref(T_g)
        if T_g is None and T_ref is not None:
            T_g = T_ref - p.offset
    if C1 is None or C2 is None:
        raise InputError("WLF needs C1 and C2 (or preset='grosch' / 'universal')")
    if T_ref is None:
        raise InputError("WLF needs the reference temperature T_ref [K] "
                         "(or T_g [K] with a preset)")
    C1, C2, T_ref = float(C1), float(C2), float(T_ref)
    for name, val in (("C1", C1), ("C2", C2), ("T_ref", T_ref)):
        if not math.isfinite(val) or val <= 0:
            raise InputError(f"WLF constant {name} must be positive and finite, got {val!r}")
    if T_g is None:
        T_g = _infer_T_g(C1, C2, T_ref)
    return C1, C2, T_ref, (None if T_g is None else float(T_g))


# ------------------------------------------------------------ temperature-aware laws


@dataclass(eq=False, repr=False)
class WLFLaw(Law):
    """A law whose velocity is reduced with the WLF shift factor.

    It behaves as any :class:`~frictionlaws.law.Law`; :meth:`evaluate` also
    checks the temperatures against the WLF pole (error) and the validity
    window ``T_g .. T_g + 100 K`` (:class:`~frictionlaws.base.errors.ExtrapolationWarning`).
    The WLF constants are the settings ``C1``, ``C2`` and ``T_ref`` (free them
    in a fit with ``fit(..., free=["C1", "C2"])``).
    """

    base_id: str = ""
    T_g: float | None = None

    def temperature_messages(self, T: Any, params: Mapping[str, float] | None = None
                             ) -> list[str]:
        """Extrapolation messages for temperatures ``T`` (raises at the pole)."""
        vals = {**self.setting_values, **(params or {})}
        return wlf_messages(T, vals["C1"], vals["C2"], vals["T_ref"], self.T_g)

    def evaluate(self, variables: Mapping[str, Any], params: Mapping[str, float]) -> Any:
        if "T" in variables and all(k in params for k in ("C1", "C2", "T_ref")):
            msgs = wlf_messages(variables["T"], params["C1"], params["C2"], params["T_ref"],
                                self.T_g)
            if msgs:
                warnings.warn(f"law '{self.id}': " + "; ".join(msgs), ExtrapolationWarning,
                              stacklevel=2)
        return super().evaluate(variables, params)


def wlf_settings(C1: float, C2: float, T_ref: float) -> tuple[Setting, Setting, Setting]:
    """The three WLF settings (with bounds used when they are freed in a fit)."""
    return (
        Setting("C1", C1, "", "WLF constant C1 (Grosch 8.86 at T_g + 50 K; 17.44 at T_g)",
                (0.1, 100.0)),
        Setting("C2", C2, "K", "WLF constant C2 (Grosch 101.6 K; 51.6 K at T_g)",
                (1.0, 1000.0)),
        Setting("T_ref", T_ref, "K", "WLF reference temperature (log10 a_T = 0)",
                (1.0, 1000.0)),
    )


def with_wlf(law: Law | str, *, C1: float | None = None, C2: float | None = None,
             T_ref: float | None = None, T_g: float | None = None,
             preset: str | None = None) -> WLFLaw:
    """A temperature-aware version of a velocity-dependent law.

    The new law, id ``"<law>+wlf"``, has the extra variable ``T`` and
    evaluates the base law at the reduced velocity ``a_T(T) v`` with
    ``log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref)``.  Its symbolic form,
    evaluation, fitting (C1, C2, T_ref are settings that may be freed) and
    ``show`` all work through the standard :class:`~frictionlaws.law.Law`
    interface.  The base law's parameters keep their meaning *at T_ref*.  The
    base law's floors (``v_min``) apply to the measured velocity, before the
    shift, as for every law.

    Parameters
    ----------
    law : Law or str
        The base law (or its id); it must use the velocity ``v`` and not ``T``.
    C1, C2 : float, optional
        WLF constants (C2 in K); default from ``preset`` (``"grosch"`` when
        neither constants nor preset are given).
    T_ref : float, optional
        Reference temperature [K]: the temperature at which the base law's
        parameters hold.
    T_g : float, optional
        Glass transition temperature [K]: sets the validity window
        ``T_g .. T_g + 100 K`` and, with a preset, ``T_ref``.  When neither
        ``T_g`` nor a matching preset is known, ``T_g = T_ref - 50 K`` is
        assumed (Grosch's convention) and stated in the law's notes.
    preset : {"grosch", "universal"}, optional
        Published constants.

    Returns
    -------
    WLFLaw
        The new law (not registered; pass it to :func:`frictionlaws.law.registry.register`
        to make it available by name).

    Raises
    ------
    InputError
        When the base law does not use the velocity, already uses T, or the
        WLF constants cannot be resolved.
    """
    base = get_law(law)
    _check_wlf_base(base)
    if preset is None and C1 is None and C2 is None:
        preset = "grosch"
    C1, C2, T_ref, T_g_known = resolve_wlf(C1=C1, C2=C2, T_ref=T_ref, T_g=T_g, preset=preset)
    T_g_res = T_ref - 50.0 if T_g_known is None else T_g_known
    window = (T_g_res, T_g_res + WLF_WINDOW)
    return WLFLaw(
        id=f"{base.id}+wlf",
        title=f"{base.title} with WLF temperature shift",
        family=base.family,
        variables=tuple(base.variables) + ("T",),
        params=base.params,
        formula=_shifted_formula(base),
        settings=tuple(base.settings) + wlf_settings(C1, C2, T_ref),
        floors=dict(base.floors),
        presets=base.presets,
        domain={**base.domain, "T": window},
        typical={**base.typical, "T": window},
        references=tuple(base.references) + (_WLF_REFERENCE,),
        evidence=f"{base.evidence}; WLF: C (Williams-Landel-Ferry), I (combination)",
        guess=_shifted_guess(base, C1, C2, T_ref),
        derived=tuple(_derived_at_ref(dv) for dv in base.derived),
        admissible=base.admissible,
        linear=False,
        aliases=(),
        description=(f"{base.description} Evaluated at the reduced velocity a_T(T) v, "
                     "log10 a_T = -C1 (T - T_ref)/(C2 + T - T_ref) (WLF): a higher "
                     "temperature acts as a lower velocity.").strip(),
        notes=_wlf_notes(base, preset, (C1, C2, T_ref), T_g_res, assumed=T_g_known is None),
        base_id=base.id,
        T_g=T_g_res,
    )


def _check_wlf_base(base: Law) -> None:
    """Refuse a base law a WLF shift cannot act on (no v, already T, or name clash)."""
    if "v" not in base.variables:
        raise InputError(f"law '{base.id}' does not depend on the velocity v: a WLF shift "
                         "acts through the reduced velocity a_T v and has no effect on it")
    if "T" in base.variables:
        raise InputError(f"law '{base.id}' already depends on the temperature T")
    clash = {"C1", "C2", "T_ref"} & ({p.name for p in base.params}
                                     | {s.name for s in base.settings})
    if clash:
        raise InputError(f"law '{base.id}' already has {sorted(clash)}: cannot add WLF")


def _shifted_formula(base: Law) -> Callable[..., Any]:
    """The base law's formula evaluated at the reduced velocity ``a_T(T) v``."""
    base_formula = base.formula

    def formula(m: Any, *, v: Any, T: Any, C1: Any, C2: Any, T_ref: Any, **kw: Any) -> Any:
        v_red = v * 10 ** wlf_formula(m, T, C1, C2, T_ref)
        return base_formula(m, v=v_red, **kw)

    return formula


def _shifted_guess(base: Law, C1: float, C2: float,
                   T_ref: float) -> Callable[[Mapping[str, np.ndarray]], dict[str, float]]:
    """The base law's starting guess, applied to the data shifted to ``T_ref``."""
    base_guess = base.guess

    def guess(data: Mapping[str, np.ndarray]) -> dict[str, float]:
        if base_guess is None:
            return {}
        d = dict(data)
        if "T" in d:
            with np.errstate(all="ignore"):
                shift = wlf_formula(NUMPY, np.asarray(d["T"], float), C1, C2, T_ref)
            d["v"] = np.abs(np.asarray(d["v"], float)) * 10 ** np.where(
                np.isfinite(shift), shift, 0.0)
        return base_guess(d)

    return guess


def _derived_at_ref(dv: Derived) -> Derived:
    """A derived quantity of the base law, stated to hold at ``T = T_ref``."""
    extra = (" (at T = T_ref; at another T divide by a_T(T))" if dv.unit == "m/s"
             else " (at T = T_ref)")
    return Derived(dv.name, dv.unit, dv.meaning + extra, dv.func)


def _wlf_notes(base: Law, preset: str | None, constants: tuple[float, float, float],
               T_g: float, *, assumed: bool) -> str:
    """The notes of a ``<law>+wlf`` law: constants, their source, T_g and the window."""
    C1, C2, T_ref = constants
    window = (T_g, T_g + WLF_WINDOW)
    source = (f"preset '{preset}'" if preset is not None else "user constants")
    tg_note = (f"T_g = {T_g:.2f} K assumed as T_ref - 50 K (Grosch's convention): "
               "pass T_g= to with_wlf to set the validity window" if assumed
               else f"T_g = {T_g:.2f} K")
    return (
        f"WLF shift ({source}: C1 = {C1:g}, C2 = {C2:g} K, T_ref = {T_ref:.2f} K; {tg_note}). "
        f"Valid roughly T_g .. T_g + 100 K = {window[0]:.2f} .. {window[1]:.2f} K; outside it "
        "evaluation warns (ExtrapolationWarning), at or below the pole T_ref - C2 it raises. "
        "Free C1, C2 (and T_ref) in a fit with free=['C1', 'C2']; T_ref and C1 are not "
        "separable from a shift of v alone unless the data span several temperatures. "
        + (f"Base law notes: {base.notes}" if base.notes else "")
    ).strip()


#: Reference temperature of ``<law>+wlf`` laws looked up by name [K] (20 degC).
DEFAULT_T_REF = 293.15


def _grosch_wlf(base: Law) -> Law:
    """``<law>+wlf``: the base law at reduced velocity a_T(T) v.

    Grosch's constants (C1 = 8.86, C2 = 101.6 K) with T_ref = :data:`DEFAULT_T_REF`
    (20 degC, so T_g is taken as -30 degC).  C1, C2 and T_ref are settings: change
    them with ``fix`` or fit them with ``free``.
    """
    return with_wlf(base, preset="grosch", T_ref=DEFAULT_T_REF)


REGISTRY.add_derivation("wlf", _grosch_wlf)
