"""The thesis' polynomial correlations (Eq. 5-1 and 5-2) with the published
coefficients of Tables 5-1 and 5-2.

The coefficients were published for P in MPa and V (disc velocity) in m/s; the
formula converts from the library's SI pressure, so the presets are used as
printed. The domain is the measured box: outside it the polynomials are
meaningless (poly2/steel gives about 30 at 0.5 MPa).
"""

from __future__ import annotations

import numpy as np

from ..law import Law, Param
from ..law.registry import register
from ._guess import linear_guess

__all__ = ["THESIS_BOX"]

#: The measured box of the thesis campaign (SI): P 0.03..0.25 MPa, V 0..2.77 m/s.
THESIS_BOX = {"p": (0.03e6, 0.25e6), "v": (0.0, 2.77)}
_MPA = 1e6
_REF = (
    "PhD thesis on rubber friction measured on a rotary pin-on-disc tribometer and its "
    "use in tyre FE analysis (source thesis of frictionlaws), chapter 5, Eq. 5-1/5-2, "
    "Tables 5-1/5-2.",
)


def _poly2(m, p, v, a0, a1, a2, a3, a4):
    P = p / _MPA
    return a0 + a1 * P + a2 * P**2 + a3 * v + a4 * v**2


def _poly3(m, p, v, a0, a1, a2, a3, a4, a5, a6):
    P = p / _MPA
    # P * P * P: numpy raises to a general power slowly; sympy still shows P**3
    return a0 + a1 * P + a2 * P**2 + a3 * (P * P * P) + a4 * v + a5 * v**2 + a6 * (v * v * v)


def _params(n_p: int, n_v: int) -> tuple[Param, ...]:
    out = [Param("a0", "", 1.0, meaning="constant")]
    for k in range(1, n_p + 1):
        out.append(Param(f"a{k}", f"MPa^-{k}", 0.0, meaning=f"coefficient of P^{k} (P in MPa)"))
    for k in range(1, n_v + 1):
        out.append(Param(f"a{n_p + k}", f"(s/m)^{k}", 0.0,
                         meaning=f"coefficient of V^{k} (V in m/s)"))
    return tuple(out)


def _basis(n_p: int, n_v: int):
    def basis(d):
        P = d["p"] / _MPA
        return ([np.ones_like(P)] + [P**k for k in range(1, n_p + 1)]
                + [d["v"] ** k for k in range(1, n_v + 1)])
    return basis


_P2 = _params(2, 2)
_P3 = _params(3, 3)

register(Law(
    id="thesis-poly2",
    title="Thesis polynomial, 2nd degree (Eq. 5-1)",
    family="sliding",
    variables=("p", "v"),
    params=_P2,
    formula=_poly2,
    guess=linear_guess([p.name for p in _P2], _basis(2, 2)),
    linear=True,
    presets={
        "steel": {"a0": 5.18, "a1": -59.2, "a2": 220.0, "a3": 1.05, "a4": -0.303},
        "sandpaper": {"a0": 4.64, "a1": -38.8, "a2": 101.0, "a3": 0.307, "a4": -0.118},
        "all": {"a0": 4.54, "a1": -38.4, "a2": 99.1, "a3": 0.827, "a4": -0.244},
    },
    domain=THESIS_BOX,
    strict_domain=True,
    references=_REF,
    evidence="C (thesis Table 5-1)",
    description="mu = a0 + a1 P + a2 P^2 + a3 V + a4 V^2 with P in MPa and V in m/s as "
    "published. Published R^2: steel 85.58 %, sandpaper 85.41 %, all 79.97 %.",
    notes="Valid only over the measured box P 0.03..0.25 MPa, V 0..2.77 m/s.",
))

register(Law(
    id="thesis-poly3",
    title="Thesis polynomial, 3rd degree (Eq. 5-2)",
    family="sliding",
    variables=("p", "v"),
    params=_P3,
    formula=_poly3,
    guess=linear_guess([p.name for p in _P3], _basis(3, 3)),
    linear=True,
    presets={
        "steel": {"a0": 6.28, "a1": -108.0, "a2": 809.0, "a3": -2090.0,
                  "a4": 0.158, "a5": 0.669, "a6": -0.235},
        "sandpaper": {"a0": 5.73, "a1": -76.5, "a2": 431.0, "a3": -818.0,
                      "a4": -0.0437, "a5": 0.284, "a6": -0.097},
        "all": {"a0": 5.73, "a1": -81.9, "a2": 505.0, "a3": -1070.0,
                "a4": 1.74, "a5": -1.22, "a6": 0.233},
    },
    domain=THESIS_BOX,
    strict_domain=True,
    references=_REF,
    evidence="C (thesis Table 5-2)",
    description="mu = a0 + a1 P + a2 P^2 + a3 P^3 + a4 V + a5 V^2 + a6 V^3 with P in MPa "
    "and V in m/s as published. Published R^2: steel 86.64 %, sandpaper 89.64 %, "
    "all 84.11 %.",
    notes="Valid only over the measured box P 0.03..0.25 MPa, V 0..2.77 m/s; the cubic in P "
    "turns sharply outside it.",
))
