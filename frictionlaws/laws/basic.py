"""Classical rubber sliding laws: Coulomb, Thirion, Schallamach, Denny,
exponential decay and the quadratic p-v law (Dorsch / Radioss Ifric 1).

Each law is declared once here; everything else (evaluation, fitting, docs,
``show``, export) is derived from these declarations.
"""

from __future__ import annotations

import math

import numpy as np

from ..law import F_MIN, Derived, Law, Param, Setting
from ..law.registry import register
from ._guess import linear_guess, linear_lstsq

__all__ = ["INF"]

INF = math.inf

# --------------------------------------------------------------------- coulomb


def _coulomb(m, mu0):
    return mu0


register(Law(
    id="coulomb",
    title="Coulomb (constant coefficient)",
    family="sliding",
    variables=(),
    params=(Param("mu0", "", 0.8, (0.0, INF), "constant friction coefficient"),),
    formula=_coulomb,
    guess=lambda d: {"mu0": float(np.mean(d["mu"]))},
    linear=True,
    presets={"thesis-fe-0.9": {"mu0": 0.9}, "thesis-fe-1.0": {"mu0": 1.0}},
    references=("C.-A. de Coulomb, Theorie des machines simples, 1785.",),
    evidence="C",
    description="The constant coefficient every comparison includes as its baseline; "
    "the thesis' tyre FE runs used mu = 0.9 and 1.0.",
))

# --------------------------------------------------------------------- thirion


def _thirion(m, p, a, b):
    return 1.0 / (a + b * p)


def _thirion_guess(d):
    a, b = linear_lstsq([np.ones_like(d["p"]), d["p"]], 1.0 / d["mu"])
    return {"a": max(a, 1e-3), "b": max(b, 0.0)}


register(Law(
    id="thirion",
    title="Thirion (pressure saturation)",
    family="sliding",
    variables=("p",),
    params=(
        Param("a", "", 1.0, (1e-9, INF), "1/a is mu as p -> 0"),
        Param("b", "1/Pa", 1e-6, (0.0, INF), "1/b is the saturation shear stress mu*p"),
    ),
    formula=_thirion,
    guess=_thirion_guess,
    derived=(
        Derived("mu_0", "", "friction coefficient as p -> 0 (1/a)", lambda m, a, **_: 1.0 / a),
        Derived("tau_sat", "Pa", "saturation shear stress mu*p as p -> inf (1/b)",
                lambda m, b, **_: 1.0 / b),
    ),
    references=(
        "P. Thirion, Les coefficients d'adherence du caoutchouc, "
        "Rev. Gen. Caoutch. 23 (1946) 101-106.",
    ),
    evidence="M (citation C)",
    description="1/mu = a + b p: the friction coefficient falls with contact pressure "
    "because the real contact area saturates; the shear stress mu p tends to 1/b.",
    notes="Fitted in mu-space; the linear fit of 1/mu against p is only the initial guess.",
))

# ------------------------------------------------------------------ schallamach


def _schallamach(m, F_N, mu_ref, n, F_ref):
    return mu_ref * m.power(F_N / F_ref, -n)


def _schallamach_guess(d):
    x = np.log(d["F_N"])
    slope, icpt = np.polyfit(x, np.log(d["mu"]), 1) if np.ptp(x) > 0 else (0.0, np.log(
        np.mean(d["mu"])))
    return {"mu_ref": float(np.exp(icpt)), "n": float(np.clip(-slope, 0.0, 1 / 3))}


register(Law(
    id="schallamach",
    title="Schallamach (load power law)",
    family="sliding",
    variables=("F_N",),
    params=(
        Param("mu_ref", "", 1.0, (1e-9, INF), "mu at the reference load F_ref"),
        Param("n", "", 1 / 3, (0.0, 1 / 3), "load exponent (Hertz 1/3; Archard 1/9, 1/27)",
              optional=True),
    ),
    settings=(Setting("F_ref", 1.0, "N", "reference load"),),
    floors={"F_N": F_MIN},
    formula=_schallamach,
    guess=_schallamach_guess,
    presets={"hertz": {"mu_ref": 1.0, "n": 1 / 3}, "archard-1/9": {"mu_ref": 1.0, "n": 1 / 9}},
    references=(
        "A. Schallamach, The load dependence of rubber friction, "
        "Proc. Phys. Soc. B 65 (1952) 657-661.",
    ),
    evidence="M",
    description="mu = mu_ref (F_N/F_ref)^(-n): a single Hertzian asperity gives n = 1/3, "
    "hierarchical asperities (Archard) 1/9 or 1/27.",
    notes="Singular at F_N -> 0 (floored at 1e-6 N). n may be held fixed (fix n = 0.3333).",
))

# ----------------------------------------------------------------------- denny


def _denny(m, p, a, b, E_v):
    return 1.0 / (a * (1.0 + b * p / E_v))


def _denny_guess(d):
    i, s = linear_lstsq([np.ones_like(d["p"]), d["p"]], 1.0 / d["mu"])
    i = max(i, 1e-3)
    return {"a": i, "b": max(s, 0.0) * 1e7 / i}


register(Law(
    id="denny",
    title="Denny (pressure over compression modulus)",
    family="sliding",
    variables=("p",),
    params=(
        Param("a", "", 2.0, (1e-9, INF), "1/a is mu as p -> 0 (1..8 quoted)"),
        Param("b", "", 15.0, (0.0, INF), "pressure sensitivity relative to E_v (~15 quoted)"),
    ),
    settings=(Setting("E_v", 1e7, "Pa", "compression modulus of the rubber (fixed)"),),
    formula=_denny,
    guess=_denny_guess,
    references=(
        "D. F. Denny, The influence of load and surface roughness on the friction of "
        "rubber-like materials, Proc. Phys. Soc. B 66 (1953) 721-727.",
    ),
    evidence="NF (quoted ranges), I (identifiability)",
    description="1/mu = a (1 + b p / E_v): Thirion's law with the pressure scaled by the "
    "rubber's compression modulus.",
    notes="E_v is a fixed setting: with E_v free the law is Thirion and b, E_v cannot be "
    "told apart (the fitter reports them as non-identifiable).",
))

# ------------------------------------------------------------ exponential decay


def _expdecay(m, v, mu_s, mu_d, v_c, delta):
    return mu_d + (mu_s - mu_d) * m.exp(-((v / v_c) ** delta))


def _expdecay_guess(d):
    v, mu = d["v"], d["mu"]
    order = np.argsort(v)
    n = max(1, len(v) // 4)
    mu_s, mu_d = float(np.mean(mu[order[:n]])), float(np.mean(mu[order[-n:]]))
    vpos = v[v > 0]
    v_c = float(np.exp(np.mean(np.log(vpos)))) if vpos.size else 1.0
    return {"mu_s": mu_s, "mu_d": mu_d, "v_c": v_c, "delta": 1.0}


register(Law(
    id="exponential-decay",
    title="Exponential decay (static to kinetic)",
    family="sliding",
    variables=("v",),
    params=(
        Param("mu_s", "", 1.0, (0.0, INF), "static coefficient, mu at v = 0"),
        Param("mu_d", "", 0.6, (0.0, INF), "kinetic coefficient, mu as v -> inf"),
        Param("v_c", "m/s", 1.0, (1e-12, INF), "decay velocity (Abaqus d_c = 1/v_c)"),
        Param("delta", "", 1.0, (0.05, 3.0), "shape exponent; 1 is the Abaqus/LS-DYNA law",
              optional=True),
    ),
    formula=_expdecay,
    guess=_expdecay_guess,
    presets={"rubber-steel": {"mu_s": 1.2, "mu_d": 0.8, "v_c": 0.5, "delta": 1.0}},
    references=(
        "Abaqus Analysis User's Guide, *FRICTION, EXPONENTIAL DECAY.",
        "LS-DYNA Keyword User's Manual, *CONTACT card 2 (FS, FD, DC).",
    ),
    evidence="C",
    description="mu = mu_d + (mu_s - mu_d) exp(-(v/v_c)^delta). With delta = 1 this is "
    "exactly Abaqus' EXPONENTIAL DECAY and LS-DYNA's FS/FD/DC law (d_c = 1/v_c).",
    notes="The thesis swaps mu_s and mu_D; this is the corrected form with mu(0) = mu_s. "
    "mu_d > mu_s (friction rising with speed) is allowed.",
))

# ----------------------------------------------------------------- quadratic-pv

_QPV = ("c0", "c1", "c2", "c3", "c4", "c5")


def _qpv(m, p, v, c0, c1, c2, c3, c4, c5):
    return c0 + c1 * p + c2 * v + c3 * p * v + c4 * p**2 + c5 * v**2


register(Law(
    id="quadratic-pv",
    aliases=("dorsch", "radioss-ifric1"),
    title="Quadratic p-v law (Dorsch / Radioss Ifric 1)",
    family="sliding",
    variables=("p", "v"),
    params=(
        Param("c0", "", 1.0, meaning="constant (Radioss Fric)"),
        Param("c1", "1/Pa", 0.0, meaning="linear pressure coefficient"),
        Param("c2", "s/m", 0.0, meaning="linear velocity coefficient"),
        Param("c3", "s/(Pa*m)", 0.0, meaning="pressure-velocity cross term"),
        Param("c4", "1/Pa^2", 0.0, meaning="quadratic pressure coefficient"),
        Param("c5", "s^2/m^2", 0.0, meaning="quadratic velocity coefficient"),
    ),
    formula=_qpv,
    guess=linear_guess(_QPV, lambda d: [np.ones_like(d["p"]), d["p"], d["v"],
                                        d["p"] * d["v"], d["p"] ** 2, d["v"] ** 2]),
    linear=True,
    references=(
        "V. Dorsch, Reibung von Elastomeren, as quoted in the source thesis.",
        "OpenRadioss /INTER/TYPE7 and /FRICTION, Ifric = 1 (generalized viscous friction).",
    ),
    evidence="C (Radioss form), NF (Dorsch original)",
    description="mu = c0 + c1 p + c2 v + c3 p v + c4 p^2 + c5 v^2: the full bivariate "
    "quadratic, exactly OpenRadioss' Ifric = 1 law.",
    notes="The thesis' Dorsch formula is garbled (p^2 and v twice, no constant, no cross "
    "term); this is its most likely intent. Meaningless far outside the fitted box.",
))
