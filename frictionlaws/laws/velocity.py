"""Rubber sliding laws in pressure and velocity (and temperature): Savkoor,
Nackenhorst (identifiable form and the published 7-parameter form), Huemer,
Wriggers-Reinelt and Park.

The forms follow the corrected catalogue (``laws.md``): log10 where the
literature means a decimal log, reference scales as fixed settings, one
redundant constant removed from each over-parametrised published form.
Each law is declared once here.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from ..base.errors import InputError
from ..law import NUMPY, P_MIN, V_MIN, Derived, Law, Param, Setting
from ..law.registry import register
from ..viscoelastic.temperature import WLF_PRESETS, WLFLaw, wlf_formula, wlf_settings
from ._guess import spread, subsample

__all__ = ["nackenhorst_from_thesis", "P_REF_SAVKOOR", "P_REF_NACKENHORST", "P_REF_HUEMER",
           "P0_PARK", "T_REF_PARK", "P_REF_WRIGGERS_DERIVED"]

INF = math.inf

#: Reference pressure of the Savkoor pressure factor [Pa] (0.1 MPa).
P_REF_SAVKOOR = 1e5
#: Reference pressure of the Nackenhorst pressure term [Pa] (0.1 MPa).
P_REF_NACKENHORST = 1e5
#: Reference pressure of the Huemer law [Pa] (1 MPa).
P_REF_HUEMER = 1e6
#: Park's reference pressure p0 [Pa] (1.5e5 Pa as quoted: friction is about
#: independent of pressure near it).
P0_PARK = 1.5e5
#: Default WLF reference temperature of the Park law [K]: T_g + 50 K for a
#: tread compound with T_g = -50 degC (set it for your compound).
T_REF_PARK = 273.15
#: Pressure at which the Wriggers peak (mu_max, vbar) is reported [Pa].
P_REF_WRIGGERS_DERIVED = 1e5

_MAX_GUESS_ROWS = 3000


def _subsample(d: Mapping[str, np.ndarray], n: int = _MAX_GUESS_ROWS) -> dict[str, np.ndarray]:
    return subsample(d, n)


def _bell_fit(x: np.ndarray, y: np.ndarray) -> tuple[float, float, float, float]:
    """Best ``y ~ a + b exp(-h^2 (x - xm)^2)`` with b >= 0 on a grid of (xm, h).

    Variable projection: for each (xm, h) the linear coefficients (a, b) are
    solved in closed form.  Returns (a, a + b, h, xm).
    """
    lo, hi = float(np.min(x)), float(np.max(x))
    xm_grid = np.linspace(lo - 1.0, hi + 1.0, 49)
    h_grid = np.geomspace(0.05, 2.0, 32)
    dx2 = (x[None, :] - xm_grid[:, None]) ** 2
    gc = np.exp(-(h_grid**2)[None, :, None] * dx2[:, None, :])      # (xm, h, row)
    gm = gc.mean(axis=2)
    gc -= gm[..., None]  # centred in place: one grid-sized array in all
    yc = y - y.mean()
    var = np.einsum("ijk,ijk->ij", gc, gc)
    cov = gc @ yc
    with np.errstate(all="ignore"):
        b = np.where(var > 1e-12, cov / var, 0.0)
    b = np.maximum(b, 0.0)
    a = y.mean() - b * gm
    sse = float(yc @ yc) - 2.0 * b * cov + b * b * var  # sum((yc - b gc)^2), expanded
    i, j = np.unravel_index(np.argmin(sse), sse.shape)
    return float(a[i, j]), float(a[i, j] + b[i, j]), float(h_grid[j]), float(xm_grid[i])


def _pressure_exponent(lp: np.ndarray, x: np.ndarray, mu: np.ndarray,
                       lo: float, hi: float) -> float:
    """Slope of log(mu) against log(p) with a quadratic in x as nuisance, clipped."""
    if np.ptp(lp) < 0.05:
        return 0.0
    cols = [np.ones_like(lp), lp]
    if np.ptp(x) > 0:
        cols += [x, x**2]
    coef, *_ = np.linalg.lstsq(np.column_stack(cols), np.log(np.maximum(mu, 1e-9)), rcond=None)
    return float(np.clip(coef[1], lo, hi))


def _bell_guess(x: np.ndarray, lp: np.ndarray, mu: np.ndarray, n_lo: float, n_hi: float
                ) -> dict[str, float]:
    """Initial values for mu = exp(n lp) [mu_s + (mu_m - mu_s) exp(-h10^2 (x - xm)^2)]."""
    n = _pressure_exponent(lp, x, mu, n_lo, n_hi)
    y = mu / np.exp(n * lp)
    mu_s, mu_m, h10, xm = _bell_fit(x, y)
    return {"n": n, "mu_s": max(mu_s, 0.0), "mu_m": max(mu_m, mu_s + 1e-3, 1e-3),
            "h10": h10, "v_m": 10.0**xm}


def _bell_admissible(params: Mapping[str, float]) -> str | None:
    if params["mu_m"] < params["mu_s"]:
        return (f"mu_m = {params['mu_m']:g} is below mu_s = {params['mu_s']:g}: the curve "
                "then has a dip, not a peak, at v_m (mu_m must exceed mu_s)")
    return None


# --------------------------------------------------------------------- savkoor


def _savkoor(m, p, v, mu_s, mu_m, h10, v_m, n, p_ref):
    bell = mu_s + (mu_m - mu_s) * m.exp(-(h10**2) * m.log10(v / v_m) ** 2)
    return (p / p_ref) ** n * bell


def _savkoor_guess(d):
    d = _subsample(d, 500)  # the bell grid has 1568 cells: its cost grows with the rows
    g = _bell_guess(np.log10(d["v"]), np.log(d["p"] / P_REF_SAVKOOR), d["mu"], -1.0, 0.0)
    return g


register(Law(
    id="savkoor",
    title="Savkoor (log-velocity bell times pressure power)",
    family="sliding",
    variables=("p", "v"),
    params=(
        Param("mu_s", "", 0.5, (0.0, INF), "plateau far from the peak (low and high v)"),
        Param("mu_m", "", 1.2, (0.0, INF), "peak friction at v = v_m and p = p_ref"),
        Param("h10", "", 0.3, (0.05, 2.0),
              "width factor per decade of velocity (h_ln = h10 / ln 10)"),
        Param("v_m", "m/s", 0.01, (1e-12, INF), "velocity of the peak"),
        Param("n", "", 0.0, (-1.0, 0.0), "pressure exponent (0 = no pressure effect)"),
    ),
    settings=(Setting("p_ref", P_REF_SAVKOOR, "Pa", "reference pressure of the pressure factor"),),
    floors={"v": V_MIN, "p": P_MIN},
    formula=_savkoor,
    guess=_savkoor_guess,
    derived=(
        Derived("v_peak", "m/s", "sliding velocity of the friction peak",
                lambda m, v_m, **_: v_m),
        Derived("mu_peak", "", "peak friction coefficient at p = p_ref",
                lambda m, mu_m, **_: mu_m),
        Derived("half_width_decades", "", "half width of the bell at half height, in "
                "decades of velocity (sqrt(ln 2)/h10)",
                lambda m, h10, **_: m.sqrt(m.log(2.0)) / h10),
    ),
    admissible=_bell_admissible,
    typical={"v": (1e-6, 10.0), "p": (1e4, 1e6)},
    references=(
        "A. R. Savkoor, On the friction of rubber, Wear 8 (1965) 222-237.",
        "K. A. Grosch, The relation between the friction and visco-elastic properties of "
        "rubber, Proc. R. Soc. Lond. A 274 (1963) 21-39 (the master curves the bell "
        "describes).",
    ),
    evidence="S (log10 form), I (combination with the pressure factor)",
    description="mu = (p/p_ref)^n [mu_s + (mu_m - mu_s) exp(-h10^2 log10^2(v/v_m))]: a "
    "Gaussian bell in log10 of the velocity with its peak mu_m at v_m, the shape of "
    "Grosch's master curves, times a pressure power law.",
    notes="h depends on the base of the log: this is h10 (log10); h_ln = h10/ln 10. The "
    "thesis' separate mu(p) = mu0 (P/E)^n is merged as the pressure factor; mu0 is then "
    "redundant and dropped. p_ref = 0.1 MPa is fixed. With data on one side of v_m, v_m, "
    "mu_m and h10 are strongly correlated (the fitter says so). v is floored at 1e-9 m/s, "
    "p at 1 Pa.",
))

# ----------------------------------------------------------------- nackenhorst


def _nackenhorst(m, p, v, A, n, b0, b1, b2, p_ref, v_ref):
    L = m.log(v / v_ref)
    return A * (p / p_ref) ** n + b0 + b1 * L + b2 * L**2


def _nack_linear(P: np.ndarray, L: np.ndarray, mu: np.ndarray, n: float
                 ) -> tuple[float, np.ndarray]:
    """Least squares of mu ~ A P^n + b0 + b1 L + b2 L^2 with b2 <= 0 (returns SSE, coef)."""
    cols = [P**n, np.ones_like(P), L, L**2]
    a = np.column_stack(cols)
    coef, *_ = np.linalg.lstsq(a, mu, rcond=None)
    if coef[3] > 0:
        c3, *_ = np.linalg.lstsq(a[:, :3], mu, rcond=None)
        coef = np.append(c3, 0.0)
    sse = float(np.sum((a @ coef - mu) ** 2))
    return sse, coef


def _nackenhorst_guess(d):
    d = _subsample(d)
    P, L, mu = d["p"] / P_REF_NACKENHORST, np.log(d["v"] / 1.0), d["mu"]
    if spread(d["p"]) < 1.05:
        # one pressure level: the pressure term is a constant; keep A = 0
        a = np.column_stack([np.ones_like(L), L, L**2])
        c, *_ = np.linalg.lstsq(a, mu, rcond=None)
        return {"A": 0.0, "n": -0.3, "b0": c[0], "b1": c[1], "b2": min(c[2], 0.0)}
    best = None
    for n in np.linspace(-2.0, 2.0, 81):
        if abs(n) < 0.02:
            continue
        sse, coef = _nack_linear(P, L, mu, n)
        if best is None or sse < best[0]:
            best = (sse, n, coef)
    _, n, (A, b0, b1, b2) = best
    return {"A": A, "n": n, "b0": b0, "b1": b1, "b2": b2}


register(Law(
    id="nackenhorst",
    title="Nackenhorst (identifiable 5-parameter form)",
    family="sliding",
    variables=("p", "v"),
    params=(
        Param("A", "", 0.3, meaning="amplitude of the pressure term at p = p_ref"),
        Param("n", "", -0.3, (-3.0, 3.0), "pressure exponent"),
        Param("b0", "", 0.6, meaning="constant (mu - A at p = p_ref, v = v_ref)"),
        Param("b1", "", 0.02, meaning="slope against ln(v/v_ref)"),
        Param("b2", "", -0.002, (-INF, 0.0), "curvature against ln(v/v_ref) (<= 0)"),
    ),
    settings=(
        Setting("p_ref", P_REF_NACKENHORST, "Pa", "reference pressure"),
        Setting("v_ref", 1.0, "m/s", "reference velocity"),
    ),
    floors={"v": V_MIN, "p": P_MIN},
    formula=_nackenhorst,
    guess=_nackenhorst_guess,
    typical={"v": (1e-3, 10.0), "p": (1e4, 1e6)},
    references=(
        "U. Nackenhorst, as quoted in the source thesis (Eq. 2-16); original not found.",
    ),
    evidence="NF (original), I (identifiable form, rank 5/5 on a p-v grid)",
    description="mu = A (p/p_ref)^n + b0 + b1 ln(v/v_ref) + b2 ln^2(v/v_ref): a pressure "
    "power term plus a quadratic in the log of the velocity.",
    notes="The published form c1 (p/c2)^c3 + c4 ln(v/c5) - c6 ln(v/c7) (law "
    "'nackenhorst-thesis') has only 4 identifiable parameters out of 7; this form has 5 and "
    "all are identifiable with >= 3 pressure levels and several velocities. Mapping from the "
    "thesis coefficients (nackenhorst_from_thesis): A = c1 (p_ref/c2)^c3, n = c3, "
    "b1 = c4 - c6, b0 = c6 ln(c7/v_ref) - c4 ln(c5/v_ref), b2 = 0. With n near 0, A and b0 "
    "cannot be told apart. v is floored at 1e-9 m/s, p at 1 Pa.",
))

# ----------------------------------------------------------- nackenhorst-thesis


def _nackenhorst_thesis(m, p, v, c1, c2, c3, c4, c5, c6, c7):
    return c1 * (p / c2) ** c3 + c4 * m.log(v / c5) - c6 * m.log(v / c7)


def nackenhorst_from_thesis(c1: float, c2: float, c3: float, c4: float, c5: float, c6: float,
                            c7: float, *, p_ref: float = P_REF_NACKENHORST,
                            v_ref: float = 1.0) -> dict[str, float]:
    """Map the published Nackenhorst coefficients to the identifiable form.

    ``c1 (p/c2)^c3 + c4 ln(v/c5) - c6 ln(v/c7)`` equals
    ``A (p/p_ref)^n + b0 + b1 ln(v/v_ref)`` (law ``nackenhorst`` with b2 = 0) for

    * ``A = c1 (p_ref/c2)^c3``, ``n = c3``
    * ``b1 = c4 - c6``
    * ``b0 = c6 ln(c7/v_ref) - c4 ln(c5/v_ref)``

    so only (c1 c2^-c3, c3, c4 - c6, c6 ln c7 - c4 ln c5) can be determined
    from data: 4 of the 7 published coefficients.

    Parameters
    ----------
    c1..c7 : float
        Published coefficients (c2 in Pa, c5 and c7 in m/s).
    p_ref, v_ref : float
        Reference scales of the identifiable form [Pa, m/s].

    Returns
    -------
    dict
        ``{"A", "n", "b0", "b1", "b2"}`` for law ``nackenhorst``.
    """
    if c2 <= 0 or c5 <= 0 or c7 <= 0:
        raise InputError("c2, c5 and c7 are scales and must be positive")
    return {
        "A": float(c1 * (p_ref / c2) ** c3),
        "n": float(c3),
        "b0": float(c6 * math.log(c7 / v_ref) - c4 * math.log(c5 / v_ref)),
        "b1": float(c4 - c6),
        "b2": 0.0,
    }


def _nackenhorst_thesis_guess(d):
    g = _nackenhorst_guess(d)
    b0, b1 = g["b0"], g["b1"]
    # one representative of the 3-dimensional family of equivalent coefficient sets
    c6 = max(abs(b0), 0.01)
    return {"c1": g["A"], "c2": P_REF_NACKENHORST, "c3": g["n"], "c4": b1 + c6, "c5": 1.0,
            "c6": c6, "c7": math.exp(b0 / c6)}


register(Law(
    id="nackenhorst-thesis",
    title="Nackenhorst (published 7-parameter form, not identifiable)",
    family="sliding",
    variables=("p", "v"),
    params=(
        Param("c1", "", 0.3, meaning="amplitude of the pressure term"),
        Param("c2", "Pa", 1e5, (1e-12, INF), "pressure scale (not separable from c1)"),
        Param("c3", "", -0.3, (-3.0, 3.0), "pressure exponent"),
        Param("c4", "", 0.05, meaning="coefficient of ln(v/c5)"),
        Param("c5", "m/s", 1.0, (1e-12, INF), "velocity scale of the first log term"),
        Param("c6", "", 0.03, meaning="coefficient of -ln(v/c7)"),
        Param("c7", "m/s", 0.1, (1e-12, INF), "velocity scale of the second log term"),
    ),
    floors={"v": V_MIN, "p": P_MIN},
    formula=_nackenhorst_thesis,
    guess=_nackenhorst_thesis_guess,
    typical={"v": (1e-3, 10.0), "p": (1e4, 1e6)},
    references=(
        "U. Nackenhorst, as quoted in the source thesis (Eq. 2-16); original not found.",
    ),
    evidence="M (as quoted), I (identifiability)",
    description="mu = c1 (p/c2)^c3 + c4 ln(v/c5) - c6 ln(v/c7), the form as published; "
    "kept so that users can see why it cannot be fitted.",
    notes="Only 4 of the 7 coefficients are identifiable: c1 and c2 enter only as "
    "c1 c2^-c3, and the two log terms collapse to (c4 - c6) ln v + (c6 ln c7 - c4 ln c5). "
    "A fit names the parameters it cannot determine. Use law 'nackenhorst' instead; "
    "nackenhorst_from_thesis() maps published coefficients to it: A = c1 (p_ref/c2)^c3, "
    "n = c3, b1 = c4 - c6, b0 = c6 ln(c7/v_ref) - c4 ln(c5/v_ref), b2 = 0.",
))

# ---------------------------------------------------------------------- huemer


def _huemer(m, p, v, alpha, beta, n, m_v, b, c, p_ref, v_ref):
    x = (v / v_ref) ** (-1.0 / m_v)
    return (alpha * (p / p_ref) ** (n - 1.0) + beta) / (1.0 + b * x + c * x**2)


def _huemer_admissible(params: Mapping[str, float]) -> str | None:
    b, c = params["b"], params["c"]
    if c < 0:
        return f"c = {c:g} < 0: the denominator 1 + b x + c x^2 turns negative at low velocity"
    if b < 0 and b * b >= 4 * c * (1 - 1e-9):  # (tolerance: b^2 = 4c up to rounding)
        return (f"b = {b:g}, c = {c:g}: b^2 >= 4c with b < 0, so the denominator "
                "1 + b x + c x^2 vanishes at some velocity (need b >= 0 or b^2 < 4c)")
    if params["m_v"] <= 0:
        return "m_v must be positive"
    return None


def _huemer_model(P, V, alpha, beta, n, m_v, b, c):
    x = V ** (-1.0 / m_v)
    return (alpha * P ** (n - 1.0) + beta) / (1.0 + b * x + c * x**2)


def _huemer_guess(d):
    d = _subsample(d)
    P, V, mu = d["p"] / P_REF_HUEMER, d["v"] / 1.0, d["mu"]
    best = None
    n_grid = np.linspace(0.05, 0.95, 19) if spread(d["p"]) > 1.05 else np.array([0.5])
    with np.errstate(all="ignore"):
        for m_v in np.geomspace(0.2, 10.0, 25):
            x = V ** (-1.0 / m_v)
            if not np.all(np.isfinite(x * x)):
                continue
            for n in n_grid:
                # equation error: mu (1 + b x + c x^2) = alpha P^(n-1) + beta
                cols = np.column_stack([P ** (n - 1.0), np.ones_like(P), -x * mu, -(x**2) * mu])
                scale = np.linalg.norm(cols, axis=0)
                scale[scale == 0] = 1.0
                coef, *_ = np.linalg.lstsq(cols / scale, mu, rcond=None)
                alpha, beta, b, c = coef / scale
                alpha, beta, c = max(alpha, 0.0), max(beta, 0.0), max(c, 0.0)
                if b < 0 and b * b >= 4 * c:
                    b = -1.9 * math.sqrt(c)
                pred = _huemer_model(P, V, alpha, beta, n, m_v, b, c)
                sse = float(np.sum((pred - mu) ** 2))
                if np.isfinite(sse) and (best is None or sse < best[0]):
                    best = (sse, dict(alpha=alpha, beta=beta, n=n, m_v=m_v, b=b, c=c))
    return best[1] if best else {}


register(Law(
    id="huemer",
    title="Huemer (pressure and velocity, rubber on ice and concrete)",
    family="sliding",
    variables=("p", "v"),
    params=(
        Param("alpha", "", 0.1, (0.0, INF), "amplitude of the pressure term at p = p_ref"),
        Param("beta", "", 0.5, (0.0, INF), "pressure-independent part of the numerator"),
        Param("n", "", 0.5, (0.0, 1.0), "pressure exponent (the term is p^(n-1))"),
        Param("m_v", "", 2.0, (0.05, 50.0), "velocity exponent m (terms v^(-1/m), v^(-2/m))"),
        Param("b", "", 0.1, meaning="coefficient of (v/v_ref)^(-1/m) in the denominator"),
        Param("c", "", 0.01, (0.0, INF), "coefficient of (v/v_ref)^(-2/m) in the denominator"),
    ),
    settings=(
        Setting("p_ref", P_REF_HUEMER, "Pa", "reference pressure"),
        Setting("v_ref", 1.0, "m/s", "reference velocity"),
    ),
    floors={"v": V_MIN, "p": P_MIN},
    formula=_huemer,
    guess=_huemer_guess,
    derived=(
        Derived("mu_high_speed", "", "friction at p = p_ref as v -> infinity (alpha + beta)",
                lambda m, alpha, beta, **_: alpha + beta),
    ),
    admissible=_huemer_admissible,
    typical={"v": (1e-3, 10.0), "p": (1e4, 1e7)},
    references=(
        "T. Huemer, W. N. Liu, J. Eberhardsteiner, H. A. Mang, A 3D finite element "
        "formulation describing the frictional behavior of rubber on ice and concrete "
        "surfaces, Engineering Computations 18 (2001) 417-437.",
    ),
    evidence="M (form), C (abstract: friction depends on p, v, T)",
    description="mu = (alpha (p/p_ref)^(n-1) + beta) / (1 + b x + c x^2) with "
    "x = (v/v_ref)^(-1/m): a pressure term over a velocity denominator that takes the "
    "friction to zero as v -> 0 (when c > 0) and to alpha (p/p_ref)^(n-1) + beta at high "
    "velocity.",
    notes="The thesis' denominator constant a is fixed to 1: numerator and denominator scale "
    "together, so with a free only 6 of 7 parameters are identifiable. The exponent m is "
    "called m_v here. The denominator must stay positive for every v: c >= 0 and (b >= 0 or "
    "b^2 < 4c) (checked as admissibility). p_ref = 1 MPa and v_ref = 1 m/s are fixed. "
    "v is floored at 1e-9 m/s, p at 1 Pa.",
))

# -------------------------------------------------------------------- wriggers


def _wriggers(m, p, v, a, b, c, d):
    vbar = a * p
    return (b / p) * m.arctan(d * p) * (2.0 * v * vbar / (v**2 + vbar**2)) ** c


def _wriggers_guess(dd):
    dd = _subsample(dd, 1500)
    p, v, mu = dd["p"], np.abs(dd["v"]), dd["mu"]
    vpos = v[v > 0]
    if vpos.size == 0:
        return {}
    pmin, pmax = float(np.min(p)), float(np.max(p))
    pmed = float(np.median(p))
    a_grid = np.geomspace(vpos.min() / pmax / 10.0, vpos.max() / pmin * 10.0, 31)
    c_grid = np.geomspace(0.05, 5.0, 16)
    d_grid = np.geomspace(0.01, 100.0, 15) / pmed
    best = None
    with np.errstate(all="ignore"):
        atan = np.arctan(d_grid[:, None] * p[None, :]) / p[None, :]          # (nd, N)
        for a in a_grid:
            vbar = a * p
            s = 2.0 * v * vbar / (v**2 + vbar**2)                             # (N,)
            sc = s[None, :] ** c_grid[:, None]                                # (nc, N)
            g = atan[:, None, :] * sc[None, :, :]                             # (nd, nc, N)
            gg = np.sum(g * g, axis=2)
            bb = np.where(gg > 0, np.sum(g * mu, axis=2) / gg, 0.0)
            bb = np.maximum(bb, 0.0)
            sse = np.sum((mu - bb[..., None] * g) ** 2, axis=2)
            i, j = np.unravel_index(np.nanargmin(sse), sse.shape)
            if best is None or sse[i, j] < best[0]:
                best = (float(sse[i, j]), a, float(bb[i, j]), float(c_grid[j]),
                        float(d_grid[i]))
    if best is None:
        return {}
    _, a, b, c, d = best
    return {"a": a, "b": b, "c": c, "d": d}


register(Law(
    id="wriggers",
    title="Wriggers-Reinelt (pressure-dependent peak in log velocity)",
    family="sliding",
    variables=("p", "v"),
    params=(
        Param("a", "m/(s*Pa)", 1e-6, (1e-30, INF), "peak velocity per unit pressure, vbar = a p"),
        Param("b", "Pa", 1e5, (1e-30, INF), "mu_max = (b/p) arctan(d p); pi b /(2 p) at high p"),
        Param("c", "", 0.5, (0.0, 5.0), "width exponent of the velocity bell"),
        Param("d", "1/Pa", 1e-5, (1e-30, INF), "mu_max -> b d as p -> 0"),
    ),
    floors={"p": P_MIN},
    formula=_wriggers,
    guess=_wriggers_guess,
    derived=(
        Derived("mu_max_pref", "", "peak friction (at v = vbar) at p = 0.1 MPa",
                lambda m, b, d, **_: (b / P_REF_WRIGGERS_DERIVED)
                * m.arctan(d * P_REF_WRIGGERS_DERIVED)),
        Derived("vbar_pref", "m/s", "velocity of the peak at p = 0.1 MPa (a p)",
                lambda m, a, **_: a * P_REF_WRIGGERS_DERIVED),
        Derived("mu_max_p0", "", "peak friction as p -> 0 (b d)", lambda m, b, d, **_: b * d),
    ),
    typical={"v": (1e-4, 10.0), "p": (1e4, 1e6)},
    references=(
        "P. Wriggers, J. Reinelt, Multi-scale approach for frictional contact of elastomers "
        "on rough rigid surfaces, Comput. Methods Appl. Mech. Eng. 198 (2009) 1996-2008.",
    ),
    evidence="NF (original not read; form internally consistent, I)",
    description="mu = mu_max(p) (2 v vbar / (v^2 + vbar^2))^c with mu_max = (b/p) "
    "arctan(d p) and vbar = a p. The velocity factor is sech(ln(v/vbar))^c: a bell in "
    "log v with maximum 1 at vbar, so mu_max(p) is the peak at each pressure.",
    notes="mu(v = 0) = 0: no static friction. mu_max -> b d as p -> 0 and ~ pi b/(2p) at "
    "high p. Needs >= 3 pressure levels to be identifiable. The parameters span many "
    "orders of magnitude in SI (a ~ 1e-6 m/(s Pa), d ~ 1e-5 1/Pa). p is floored at 1 Pa.",
))

# ------------------------------------------------------------------------ park


def _park(m, p, v, T, n, mu_s, mu_m, h10, v_m, p0, C1, C2, T_ref):
    x = m.log10(v / v_m) + wlf_formula(m, T, C1, C2, T_ref)
    return (p / p0) ** (-n) * (mu_s + (mu_m - mu_s) * m.exp(-(h10**2) * x**2))


_GROSCH = WLF_PRESETS["grosch"]


def _park_guess(d):
    d = _subsample(d, 1000)
    shift = wlf_formula(NUMPY, d["T"], _GROSCH.C1, _GROSCH.C2, T_REF_PARK)
    with np.errstate(all="ignore"):
        shift = np.where(np.isfinite(shift) & (d["T"] > T_REF_PARK - _GROSCH.C2), shift, 0.0)
    x = np.log10(d["v"]) + shift
    g = _bell_guess(x, np.log(d["p"] / P0_PARK), d["mu"], -1.0, 0.0)
    g["n"] = -g["n"]
    return g


register(WLFLaw(
    id="park",
    title="Park (pressure power law times a WLF master curve)",
    family="sliding",
    variables=("p", "v", "T"),
    params=(
        Param("n", "", 1 / 9, (0.0, 1.0), "pressure exponent (1/9 rough, 1/3 smooth quoted)"),
        Param("mu_s", "", 0.5, (0.0, INF), "master-curve plateau far from the peak"),
        Param("mu_m", "", 1.2, (0.0, INF), "master-curve peak at p = p0"),
        Param("h10", "", 0.3, (0.05, 2.0), "width factor per decade of reduced velocity"),
        Param("v_m", "m/s", 0.01, (1e-12, INF), "reduced velocity of the peak (at T_ref)"),
    ),
    settings=(Setting("p0", P0_PARK, "Pa", "reference pressure (1.5e5 Pa quoted)"),
              *wlf_settings(_GROSCH.C1, _GROSCH.C2, T_REF_PARK)),
    floors={"v": V_MIN, "p": P_MIN},
    formula=_park,
    guess=_park_guess,
    derived=(
        Derived("v_peak", "m/s", "reduced velocity a_T v of the friction peak (the sliding "
                "velocity of the peak at T_ref)", lambda m, v_m, **_: v_m),
        Derived("mu_peak", "", "peak friction coefficient at p = p0",
                lambda m, mu_m, **_: mu_m),
    ),
    admissible=_bell_admissible,
    domain={"T": (T_REF_PARK - 50.0, T_REF_PARK + 50.0)},
    typical={"v": (1e-6, 10.0), "p": (1e4, 1e6), "T": (T_REF_PARK - 50.0, T_REF_PARK + 50.0)},
    references=(
        "Park (2006), friction model implemented as an Abaqus/Explicit VFRIC subroutine, as "
        "quoted in the source thesis (Eq. 2-18); original not found.",
        "K. A. Grosch, Proc. R. Soc. Lond. A 274 (1963) 21-39 (master curve, WLF constants).",
        "M. L. Williams, R. F. Landel, J. D. Ferry, J. Am. Chem. Soc. 77 (1955) 3701-3707.",
    ),
    evidence="NF (coherent: n = 1/3 Hertz, 1/9 Archard)",
    description="mu = (p/p0)^(-n) f(log10(a_T v)), with the master curve f the Savkoor bell "
    "f = mu_s + (mu_m - mu_s) exp(-h10^2 log10^2(a_T v / v_m)) and the WLF shift "
    "log10 a_T = -C1 (T - T_ref)/(C2 + T - T_ref).",
    notes="The thesis prints '(P/P_o) - n f(...)': the minus sign is the exponent. The WLF "
    "constants are settings with Grosch's values C1 = 8.86, C2 = 101.6 K and T_ref = "
    "273.15 K (= T_g + 50 K for T_g = -50 degC); set T_ref (and T_g) for your compound, or "
    "fit them with free=['C1', 'C2'] when the data span several temperatures. The "
    "universal set is C1 = 17.44, C2 = 51.6 K with T_ref = T_g. Valid roughly T_g .. "
    "T_g + 100 K (warns outside), undefined at or below T_ref - C2 (raises). v is floored "
    "at 1e-9 m/s, p at 1 Pa.",
    base_id="park",
    T_g=T_REF_PARK - 50.0,
))
