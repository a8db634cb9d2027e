"""Persson's theory of rubber friction as a registry law (``persson``).

The viscoelastic friction of the packaged tread compound
(``datasets/tread-compound``: a Havriliak-Negami master curve with the universal
WLF shift, as a Prony series) sliding on a self-affine surface (settings q0, H,
h_rms; asphalt-like by default), computed by :func:`frictionlaws.persson.friction`,
plus an additive contribution ``mu_a`` (adhesion, other mechanisms).  The fitted parameters are the
short-wavelength cut-off ``q1`` and ``mu_a``.  The symbolic form is
``mu_a + mu_P(p, v, T, q1, q0, H, h_rms)`` with ``mu_P`` an unevaluated function
carrying its numerical implementation (sympy ``implemented_function``), so the
docs render it, ``lambdify`` evaluates it, and the Fortran generator refuses it
(no closed form).  :func:`persson_law` builds the same law for another material
or surface.
"""

from __future__ import annotations

import functools
import math
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from ..law import Law, Param, Setting
from ..law.registry import register

if TYPE_CHECKING:
    from ..persson.flash import Flash
    from ..persson.material import Material

__all__ = ["persson_law", "Q0_ASPHALT", "H_ASPHALT", "H_RMS_ASPHALT"]

#: Roll-off wavenumber of the asphalt-like default surface [1/m] (2 pi / 1 cm).
Q0_ASPHALT = 2 * math.pi / 0.01
#: Hurst exponent of the asphalt-like default surface.
H_ASPHALT = 0.8
#: rms height of the asphalt-like default surface over q >= q0 [m].
H_RMS_ASPHALT = 0.3e-3

#: Pressures the law takes [Pa]: above 0 (the theory divides by p; at p = 0 there is no
#: contact), from 1 Pa to 100 MPa, beyond any pressure a rubber contact carries.
_P_DOMAIN = (1.0, 1e8)

_REFERENCES = (
    "B. N. J. Persson, Theory of rubber friction and contact mechanics, J. Chem. Phys. 115 "
    "(2001) 3840-3861.",
    "B. N. J. Persson, O. Albohr, U. Tartaglino, A. I. Volokitin, E. Tosatti, On the nature "
    "of surface roughness with application to contact mechanics, sealing, rubber friction "
    "and adhesion, J. Phys.: Condens. Matter 17 (2005) R1-R62.",
    "B. N. J. Persson, Rubber friction: role of the flash temperature, J. Phys.: Condens. "
    "Matter 18 (2006) 7789-7823.",
)


def _numeric(material: Material | None, thermal: Flash | None, p: Any, v: Any, T: Any,
             q1: Any, q0: Any, H: Any, h_rms: Any, gamma: Any, heat_fraction: Any) -> Any:
    # imported here: registering the law (every get_law) must not load the theory
    from ..persson.flash import TREAD_THERMAL
    from ..persson.material import tread_compound
    from ..persson.surface import SelfAffine
    from ..persson.theory import friction

    mat = tread_compound() if material is None else material
    surface = SelfAffine.from_rms(float(q0), float(H), float(h_rms), float(q1))
    hf = float(heat_fraction)
    flash = (replace(TREAD_THERMAL if thermal is None else thermal, heat_fraction=hf)
             if hf > 0 else None)
    return friction(mat, surface, v, T, p, q1=float(q1), gamma=float(gamma), flash=flash)


@functools.lru_cache(maxsize=8)
def _symbolic_function(name: str, material: Material | None, thermal: Flash | None) -> Any:
    from sympy.utilities.lambdify import implemented_function

    def impl(p: Any, v: Any, T: Any, q1: Any, q0: Any, H: Any, h_rms: Any, gamma: Any,
             heat_fraction: Any) -> float:
        return float(_numeric(material, thermal, *(float(x) for x in (
            p, v, T, q1, q0, H, h_rms, gamma, heat_fraction))))

    return implemented_function(name, impl)


def _material_domain(material: Material | None) -> tuple[tuple[float, float], str]:
    """The material's temperature range [K] and how the description names it."""
    if material is None:
        from ..persson.material import tread_temperature_range

        return tread_temperature_range(), (
            "the packaged tread compound (datasets/tread-compound: a Havriliak-Negami master "
            "curve at T_g = -30 degC with the universal WLF shift, constructed from published "
            "forms and representative values, not measured)")
    return material.temperature_range(), f"the material {material.source or '(user-built)'}"


def _settings(q0: float, H: float, h_rms: float) -> tuple[Setting, ...]:
    return (
        Setting("q0", q0, "1/m", "roll-off wavenumber of the self-affine surface", (1.0, 1e6)),
        Setting("H", H, "", "Hurst exponent of the surface (fractal dimension 3 - H)",
                (0.05, 0.99)),
        Setting("h_rms", h_rms, "m", "rms height of the surface over q >= q0 (at most 1 cm; "
                "the theory also refuses a band q0..q1 of rms slope above 10)", (1e-9, 0.01)),
        Setting("gamma", 1.0, "", "gamma of the correction S(q) = gamma + (1 - gamma) "
                "P(q)^2 (Persson 2006 suggests about 0.5; 1 = uncorrected, as in 2001)",
                (0.0, 1.0)),
        Setting("heat_fraction", 0.0, "", "fraction of the friction heat flowing into the "
                "rubber, for the flash temperature (0 = isothermal)", (0.0, 1.0)),
    )


def _flash_note(thermal: Flash | None) -> str:
    """How the setting heat_fraction heats the rubber (the law's thermal properties)."""
    from ..persson.flash import TREAD_THERMAL

    f = TREAD_THERMAL if thermal is None else thermal
    how = ("the heat of each scale made in the rubber's volume down to the depth 1/q, "
           f"its {f.contact_temperature} temperature over the contact time"
           if f.closure == "volume" else "the heat of each scale a flux through sliding "
           "discs (an upper bound)")
    background = (f", background heating over a sliding distance of {f.sliding_distance:g} m"
                  if f.sliding_distance > 0 else ", no background heating")
    return (f"flash temperature, Persson 2006, in the {f.closure} closure of "
            f"frictionlaws.persson.flash: {how}; conductivity {f.conductivity:g} W/(m K), "
            f"heat capacity {f.heat_capacity:g} J/(m^3 K){background}; mu_a makes no heat")


def _notes(T_domain: tuple[float, float], thermal: Flash | None) -> str:
    return ("No closed form: the Fortran user-subroutine formats are refused, tables are "
            "exported. By default isothermal and uncorrected (gamma = 1, heat_fraction = 0, "
            "the 2001 theory); the settings gamma (S(q) correction) and heat_fraction ("
            f"{_flash_note(thermal)}) turn the 2006 refinements on. T is held to the "
            f"material's range {T_domain[0]:.2f}..{T_domain[1]:.2f} K and p to 1 Pa..100 MPa "
            "(refused outside them, in calls, fits and exported boxes); v = 0 gives the static "
            "limit mu = mu_a (the viscoelastic part vanishes linearly in v). Build another "
            "material with frictionlaws.persson (material_from_csv, persson_law).")


def _typical_T(domain: tuple[float, float]) -> tuple[float, float]:
    """-20..60 degC where the material's range allows, else its whole range."""
    lo, hi = max(domain[0], 253.15), min(domain[1], 333.15)
    return (lo, hi) if lo < hi else domain


def persson_law(material: Material | None = None, *, id: str = "persson",
                title: str = "Persson (viscoelastic friction on a rough surface)",
                q0: float = Q0_ASPHALT, H: float = H_ASPHALT, h_rms: float = H_RMS_ASPHALT,
                thermal: Flash | None = None, register_law: bool = False) -> Law:
    """The Persson law for ``material`` (default: the packaged tread compound).

    Its temperature domain is the material's
    (:meth:`~frictionlaws.persson.Material.temperature_range`), held strictly:
    calls, fits and exported boxes outside it are refused, as are pressures
    <= 0; v = 0 gives the static limit mu = mu_a.

    Parameters
    ----------
    material : Material, optional
        The rubber; default :func:`frictionlaws.persson.tread_compound`.
    id, title : str
        Registry id and title of the law.
    q0, H, h_rms : float
        Default values of the surface settings [1/m], [-], [m].
    thermal : Flash, optional
        Thermal properties of the rubber for the flash temperature (setting
        ``heat_fraction`` > 0); default
        :data:`frictionlaws.persson.flash.TREAD_THERMAL`.
    register_law : bool
        Register the law (ids must be unique).
    """

    def formula(m: Any, p: Any, v: Any, T: Any, q1: Any, mu_a: Any, q0: Any, H: Any,
                h_rms: Any, gamma: Any, heat_fraction: Any) -> Any:
        if m.is_symbolic:
            return mu_a + _symbolic_function("mu_P", material, thermal)(
                p, v, T, q1, q0, H, h_rms, gamma, heat_fraction)
        return mu_a + _numeric(material, thermal, p, v, T, q1, q0, H, h_rms, gamma,
                               heat_fraction)

    T_domain, what = _material_domain(material)
    law = Law(
        id=id, title=title, family="sliding", variables=("p", "v", "T"),
        params=(
            Param("q1", "1/m", 1e6, (1e4, 1e8), "short-wavelength cut-off of the roughness "
                  "spectrum (smallest wavelength 2 pi/q1 that the rubber feels)"),
            Param("mu_a", "", 0.0, (0.0, math.inf),
                  "additive contribution (adhesion and other mechanisms)"),
        ),
        settings=_settings(q0, H, h_rms),
        formula=formula,
        presets={"tread-on-asphalt": {"q1": 1e6, "mu_a": 0.0},
                 "tread-on-asphalt-2006": {"q1": 1e6, "mu_a": 0.0, "gamma": 0.5,
                                           "heat_fraction": 1.0}},
        domain={"T": T_domain, "p": _P_DOMAIN},
        strict_domain=True,
        typical={"v": (1e-6, 10.0), "p": (1e4, 1e6), "T": _typical_T(T_domain)},
        references=_REFERENCES,
        evidence="C (theory, as published), I (numerical implementation checked against "
        "adaptive quadrature)",
        description="mu = mu_a + mu_P(p, v, T; q1): the viscoelastic friction of Persson's "
        "theory, 1/2 int q^3 C(q) P(q) int cos(phi) Im E(q v cos(phi), T) dphi dq / "
        "((1 - nu^2) p), with the contact ratio P(q) = erf(1/(2 sqrt(G(q)))), for "
        f"{what}, on a self-affine surface C(q) = C0 (q/q0)^(-2(1+H)) with the rms height "
        "h_rms (asphalt-like: q0 = 2 pi/1 cm, H = 0.8, h_rms = 0.3 mm), plus an additive "
        "contribution mu_a.",
        notes=_notes(T_domain, thermal),
    )
    if register_law:
        register(law)
    return law


persson_law(register_law=True)
