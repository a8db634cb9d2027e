"""Tyre slip laws mu(s) (and vehicle speed): Pacejka's Magic Formula,
Burckhardt (with the velocity factor and the seven road presets), Burckhardt's
square-root law, Kiencke-Daiss and Germann.

These are slip-ratio laws (rolling wheel, braking slip s = 0..1); they cannot
be fitted to pure-sliding tribometer data, which has no slip.  Each law is
declared once here.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from ..fitting.derivatives import jacobian_function, model_jacobian
from ..fitting.lsq import solve
from ..law import NUMPY, Derived, Law, Param
from ..law.registry import get_law, register
from ._guess import linear_guess, linear_lstsq, subsample

__all__ = ["pacejka_peak", "BURCKHARDT_ROADS", "PACEJKA_SURFACES"]

INF = math.inf
SLIP = {"s": (0.0, 1.0)}
_MAX_GUESS_ROWS = 1500


def _subsample(d: Mapping[str, np.ndarray], n: int = _MAX_GUESS_ROWS) -> dict[str, np.ndarray]:
    return subsample(d, n)


# --------------------------------------------------------------------- pacejka


def _pacejka(m, s, B, C, D, E, S_h, S_v):
    Bx = B * (s + S_h)
    return D * m.sin(C * m.arctan(Bx - E * (Bx - m.arctan(Bx)))) + S_v


def _mf(s: Any, B: float, C: float, D: float, E: float, S_h: float, S_v: float
        ) -> np.ndarray:
    return _pacejka(NUMPY, np.asarray(s, float), B, C, D, E, S_h, S_v)


def pacejka_peak(B: float, C: float, D: float, E: float, S_h: float = 0.0, S_v: float = 0.0,
                 s_range: tuple[float, float] = (0.0, 1.0)) -> tuple[float, float]:
    """Slip and value of the maximum of the Magic Formula over ``s_range``.

    The first maximum is where the sine's argument reaches pi/2, i.e. where
    ``(1 - E) B x + E arctan(B x) = tan(pi / (2 C))`` (x = s + S_h), which is
    monotonic in x for E <= 1 and is solved with :func:`scipy.optimize.brentq`;
    its value is D + S_v.  When that point lies outside ``s_range`` (or C <= 1,
    or E = 1 with a target beyond pi/2: no interior maximum) the larger end
    value is returned.

    Returns
    -------
    (s_peak, mu_peak)
    """
    return _pacejka_peak(float(B), float(C), float(D), float(E), float(S_h), float(S_v),
                         (float(s_range[0]), float(s_range[1])))


@functools.lru_cache(maxsize=256)  # s_peak and mu_peak of one fit ask for the same point
def _pacejka_peak(B: float, C: float, D: float, E: float, S_h: float, S_v: float,
                  s_range: tuple[float, float]) -> tuple[float, float]:
    from scipy.optimize import brentq

    lo, hi = s_range
    cands = [(lo, float(_mf(lo, B, C, D, E, S_h, S_v))), (hi, float(_mf(hi, B, C, D, E, S_h,
                                                                        S_v)))]
    if C > 1.0 and B > 0 and D > 0 and E <= 1.0:
        target = math.tan(math.pi / (2.0 * C))

        def phi(x: float) -> float:
            return (1.0 - E) * B * x + E * math.atan(B * x) - target

        x_hi = 1.0 / B
        ok = True
        for _ in range(200):
            if phi(x_hi) > 0:
                break
            x_hi *= 2.0
            if x_hi > 1e12:
                ok = False
                break
        if ok:
            x_star = brentq(phi, 0.0, x_hi, xtol=1e-14, rtol=1e-14)
            s_star = x_star - S_h
            if lo <= s_star <= hi:
                cands.append((s_star, D + S_v))
    return max(cands, key=lambda t: t[1])


def _pacejka_jacobian(law: Law, s: np.ndarray) -> Any:
    """d mu / d(B, C, D, E) at S_h = S_v = 0, from the law's generated derivatives
    (None when there are none: the solver then differences)."""
    func = jacobian_function(law)
    if func is None:
        return None

    def jac(q: Mapping[str, float]) -> np.ndarray:
        return model_jacobian(func, {"s": s}, {**q, "S_h": 0.0, "S_v": 0.0},
                              _PACEJKA_SHAPE, s.size)
    return jac


_PACEJKA_SHAPE = ["B", "C", "D", "E"]
#: Grid cells the guess refines (4: on 180 synthetic datasets 3 changed which minima the
#: multi-start then reached, and ran its global stage twice as often).
_REFINED = 4


def _pacejka_grid(s: np.ndarray, mu: np.ndarray, best: int) -> list[tuple[float, ...]]:
    """(sse, B, C, D, E) of the ``best`` finite cells of the (B, C, E) grid, best first.

    D is in closed form per cell.  The sine of the grid's 1080 x N arguments runs in
    single precision, where numpy's sine is vectorised (about 8x faster here): the
    values only rank cells, whose best are then refined in double precision, and its
    rounding (1e-7) is far below the differences between cells of this coarse grid.
    One B at a time, the temporaries stay small enough to be reused rather than mapped
    afresh from the operating system (which cost more than the arithmetic).
    """
    B_grid = np.geomspace(1.0, 60.0, 15)
    C_grid = np.linspace(1.0, 2.5, 8)
    C_single = C_grid.astype(np.float32)[:, None, None]
    E_grid = np.linspace(-3.0, 1.0, 9)
    gg = np.empty((B_grid.size, C_grid.size, E_grid.size))
    gm = np.empty_like(gg)
    with np.errstate(all="ignore"):
        for i, B in enumerate(B_grid):
            Bs = B * s
            phi = Bs[None, :] - E_grid[:, None] * (Bs - np.arctan(Bs))[None, :]      # E, N
            g = np.sin(C_single * np.arctan(phi).astype(np.float32)).astype(float)  # C,E,N
            gg[i] = np.einsum("cen,cen->ce", g, g)
            gm[i] = g @ mu
        D = np.maximum(np.where(gg > 0, gm / gg, 0.0), 1e-6)
        sse = float(mu @ mu) - 2.0 * D * gm + D * D * gg  # sum((mu - D g)^2), expanded
    flat = np.where(np.isfinite(sse), sse, np.inf).ravel()
    order = np.argsort(flat, kind="stable")[:best]
    b, c, e = np.unravel_index(order[np.isfinite(flat[order])], sse.shape)
    return list(zip(sse[b, c, e].tolist(), B_grid[b].tolist(), C_grid[c].tolist(),
                    D[b, c, e].tolist(), E_grid[e].tolist()))


def _pacejka_guess(d):
    """Grid over (B, C, E) with D in closed form, then the best few cells refined.

    C and E trade off (distinct minima fit almost equally well), so the
    :data:`_REFINED` best grid cells are each refined by the fit's own local solver
    (MINPACK with the law's derivatives while inside the bounds) and the best result
    is returned; all on at most 200 rows.
    """
    d = _subsample(d, 200)
    s, mu = d["s"], d["mu"]
    cells = _pacejka_grid(s, mu, _REFINED)
    law = get_law("pacejka")
    bounds = {k: law.param(k).bounds for k in _PACEJKA_SHAPE}
    bounds["E"] = (max(bounds["E"][0], -10.0), bounds["E"][1])  # the refinements' E range
    jac = _pacejka_jacobian(law, s)

    def model(q: Mapping[str, float]) -> np.ndarray:
        return _mf(s, q["B"], q["C"], q["D"], q["E"], 0.0, 0.0)

    refined = []
    for cell in cells:
        start = {k: min(max(v, bounds[k][0] + 1e-9), bounds[k][1] - 1e-9)
                 for k, v in zip(_PACEJKA_SHAPE, cell[1:])}
        try:
            with np.errstate(all="ignore"):
                res = solve(model, mu, None, start, _PACEJKA_SHAPE, bounds, 200, jac)
        except ValueError:
            continue
        if np.isfinite(res.chisqr):
            refined.append((res.chisqr, *(res.params[k].value for k in _PACEJKA_SHAPE)))
    _, B, C, D, E = min([*refined, *cells[:1]])
    return {"B": B, "C": C, "D": D, "E": E, "S_h": 0.0, "S_v": 0.0}


#: Pacejka coefficients (B, C, D, E) for normalised longitudinal force, as
#: published by MathWorks for its generic Magic Formula tyre.
PACEJKA_SURFACES = {
    "dry": {"B": 10.0, "C": 1.9, "D": 1.0, "E": 0.97},
    "wet": {"B": 12.0, "C": 2.3, "D": 0.82, "E": 1.0},
    "snow": {"B": 5.0, "C": 2.0, "D": 0.3, "E": 1.0},
    "ice": {"B": 4.0, "C": 2.0, "D": 0.1, "E": 1.0},
}

register(Law(
    id="pacejka",
    aliases=("magic-formula",),
    title="Pacejka Magic Formula (longitudinal, normalised)",
    family="slip",
    variables=("s",),
    params=(
        Param("B", "", 10.0, (1e-6, INF), "stiffness factor"),
        Param("C", "", 1.9, (1.0, 2.5), "shape factor"),
        Param("D", "", 1.0, (1e-9, INF), "peak value (D + S_v is the peak mu)"),
        Param("E", "", 0.97, (-INF, 1.0), "curvature factor (<= 1)"),
        Param("S_h", "", 0.0, (-0.5, 0.5), "horizontal shift of the slip", optional=True),
        Param("S_v", "", 0.0, (-1.0, 1.0), "vertical shift of mu", optional=True),
    ),
    formula=_pacejka,
    guess=_pacejka_guess,
    presets=PACEJKA_SURFACES,
    domain={"s": (-1.0, 1.0)},
    derived=(
        Derived("BCD", "", "slope d mu/ds at s = -S_h (B C D: slip stiffness over load)",
                lambda m, B, C, D, **_: B * C * D),
        Derived("s_peak", "", "slip of the maximum of mu over s = 0..1 (numerical)",
                lambda m, B, C, D, E, S_h=0.0, S_v=0.0, **_: pacejka_peak(B, C, D, E, S_h,
                                                                           S_v)[0]),
        Derived("mu_peak", "", "maximum of mu over s = 0..1 (D + S_v when the peak is inside)",
                lambda m, B, C, D, E, S_h=0.0, S_v=0.0, **_: pacejka_peak(B, C, D, E, S_h,
                                                                           S_v)[1]),
    ),
    typical=SLIP,
    references=(
        "H. B. Pacejka, E. Bakker, The Magic Formula tyre model, Vehicle System Dynamics 21 "
        "(suppl.) (1993) 1-18.",
        "H. B. Pacejka, Tire and Vehicle Dynamics, 3rd ed., Butterworth-Heinemann, 2012.",
        "MathWorks, Simscape Driveline, Tire (Magic Formula) block: typical coefficients for "
        "dry tarmac, wet tarmac, snow and ice (presets).",
    ),
    evidence="C (form; dry preset), M (wet, snow, ice presets), I (derived peaks)",
    description="mu = D sin(C arctan(B x - E (B x - arctan(B x)))) + S_v with x = s + S_h: "
    "the Magic Formula for the normalised longitudinal force F_x/F_z against the slip "
    "ratio (thesis Eq. 2-29). B C D is the slope at the origin; D + S_v the peak.",
    notes="Presets (B/C/D/E): dry tarmac 10/1.9/1/0.97, wet 12/2.3/0.82/1, snow 5/2/0.3/1, "
    "ice 4/2/0.1/1; their peaks (slip/mu) are dry 0.180/1.00, wet 0.088/0.82, snow "
    "0.311/0.30, ice 0.389/0.10. E is poorly determined without data beyond the peak, and "
    "C and E trade off: with 2 % noise on s = 0..1 a second minimum near C = 1.3, E = 0 "
    "fits dry-road data as well as C = 1.9, E = 0.97, so fix E (or C) unless the data are "
    "precise. S_h and S_v default to 0 and may be fixed (fix={'S_h': 0, 'S_v': 0}).",
))

# ------------------------------------------------------------------ burckhardt


def _burckhardt(m, s, v, c1, c2, c3, c4):
    return (c1 * (1.0 - m.exp(-c2 * s)) - c3 * s) * m.exp(-c4 * v)


def _burckhardt_s_peak(m, c1, c2, c3, **_):
    # log(c1 c2) - log(c3): +inf (no interior peak) when c3 = 0, without a Python division
    return m.minimum(m.maximum((m.log(c1 * c2) - m.log(c3)) / c2, 0.0), 1.0)


def _burckhardt_mu_peak(m, c1, c2, c3, **_):
    s = _burckhardt_s_peak(m, c1, c2, c3)
    return c1 * (1.0 - m.exp(-c2 * s)) - c3 * s


def _burckhardt_guess(d):
    """Grid over (c2, c4); for each, c1 and c3 >= 0 by linear least squares (2x2, vectorised).

    With ``r = 1 - exp(-c2 s)`` and ``e = exp(-c4 v)`` the columns are ``a = r e`` and
    ``b = -s e``, so every sum the 2x2 systems need is a product of the c2-grid's
    ``r`` (and ``r^2``) with a vector of the rows, and the error of each cell follows
    from them: no grid-sized array per c4.
    """
    d = _subsample(d, 500)
    s, v, mu = d["s"], np.abs(d["v"]), d["mu"]
    c4_grid = [0.0] + (list(np.geomspace(1e-3, 0.2, 20)) if np.ptp(v) > 0 else [])
    c2_grid = np.geomspace(1.0, 1000.0, 60)
    best = None
    with np.errstate(all="ignore"):
        rise = 1.0 - np.exp(-np.outer(s, c2_grid))  # column per c2, the same for every c4
        rise2, mm = rise * rise, float(mu @ mu)
        for c4 in c4_grid:
            ev = np.exp(-c4 * v)
            b = -s * ev
            aa, ab, am = (ev * ev) @ rise2, (b * ev) @ rise, (mu * ev) @ rise
            bb, bm = float(b @ b), float(b @ mu)
            det = aa * bb - ab**2
            c1 = np.where(det > 0, (am * bb - ab * bm) / det, am / aa)
            c3 = np.where(det > 0, (aa * bm - ab * am) / det, 0.0)
            neg = c3 < 0                                  # c3 >= 0: refit c1 alone
            c1 = np.where(neg, am / aa, c1)
            c3 = np.where(neg, 0.0, c3)
            sse = (mm - 2.0 * (c1 * am + c3 * bm) + c1 * c1 * aa + 2.0 * c1 * c3 * ab
                   + c3 * c3 * bb)
            sse = np.where(np.isfinite(sse), sse, np.inf)
            j = int(np.argmin(sse))
            if best is None or sse[j] < best[0]:
                best = (float(sse[j]), dict(c1=float(c1[j]), c2=float(c2_grid[j]),
                                            c3=float(c3[j]), c4=float(c4)))
    return best[1]


#: Burckhardt's coefficients (c1, c2, c3) for seven road surfaces.
BURCKHARDT_ROADS = {
    "asphalt-dry": {"c1": 1.2801, "c2": 23.99, "c3": 0.52},
    "asphalt-wet": {"c1": 0.857, "c2": 33.822, "c3": 0.347},
    "concrete-dry": {"c1": 1.1973, "c2": 25.168, "c3": 0.5373},
    "cobblestone-dry": {"c1": 1.3713, "c2": 6.4565, "c3": 0.6691},
    "cobblestone-wet": {"c1": 0.4004, "c2": 33.708, "c3": 0.1204},
    "snow": {"c1": 0.1946, "c2": 94.129, "c3": 0.0646},
    "ice": {"c1": 0.05, "c2": 306.39, "c3": 0.0},
}

register(Law(
    id="burckhardt",
    title="Burckhardt (slip and vehicle speed)",
    family="slip",
    variables=("s", "v"),
    params=(
        Param("c1", "", 1.2, (1e-9, INF), "saturation level of the exponential rise"),
        Param("c2", "", 25.0, (1e-6, INF), "rate of the rise with slip"),
        Param("c3", "", 0.5, (0.0, INF), "linear fall-off with slip"),
        Param("c4", "s/m", 0.0, (0.0, INF), "speed decay (typical 0.02..0.04 s/m; 0 = none)",
              optional=True),
    ),
    formula=_burckhardt,
    guess=_burckhardt_guess,
    presets=BURCKHARDT_ROADS,
    optional_variables={"v": ("c4", 0.0)},
    variable_meanings={"v": "vehicle (wheel-centre) speed"},
    domain=SLIP,
    derived=(
        Derived("s_peak", "", "slip of the maximum of mu over s = 0..1 at v = 0 "
                "(ln(c1 c2/c3)/c2 clipped to 0..1; 1 means no interior peak)",
                _burckhardt_s_peak),
        Derived("mu_peak", "", "maximum of mu over s = 0..1 at v = 0 (multiply by "
                "exp(-c4 v) at speed v)", _burckhardt_mu_peak),
        Derived("mu_locked", "", "mu of the locked wheel (s = 1) at v = 0",
                lambda m, c1, c2, c3, **_: c1 * (1.0 - m.exp(-c2)) - c3),
    ),
    typical={"s": (0.0, 1.0), "v": (0.0, 40.0)},
    references=(
        "M. Burckhardt, Fahrwerktechnik: Radschlupf-Regelsysteme, Vogel, Wuerzburg, 1993.",
    ),
    evidence="S (presets, several independent sources), I (derived peaks)",
    description="mu = (c1 (1 - exp(-c2 s)) - c3 s) exp(-c4 v): an exponential rise with "
    "slip, a linear fall-off, and a decay with the vehicle speed v (thesis Eq. 2-31; with "
    "c4 = 0 it is Eq. 2-33).",
    notes="v is the vehicle (wheel-centre) speed, not the sliding velocity s v. The seven "
    "road presets have c4 = 0. Peaks (slip/mu): asphalt dry 0.170/1.17 (mu(1) = 0.76), "
    "asphalt wet 0.131/0.80, concrete dry 0.160/1.09, cobblestone dry 0.400/1.00, "
    "cobblestone wet 0.140/0.38, snow 0.060/0.19, ice no interior peak (mu rises to "
    "c1 = 0.05). With a single speed c4 cannot be determined: fix it (fix={'c4': 0}). v is "
    "optional when c4 = 0: slip-only (s, mu) data are fitted with c4 fixed at 0, and "
    "law(s=..., preset=...) needs no v.",
))

# ------------------------------------------------------------- burckhardt-sqrt


def _bsqrt(m, s, c1, c2):
    return c1 * m.sqrt(s) - c2 * s


def _bsqrt_s_peak(m, c1, c2, **_):
    return m.minimum((c1 / (2.0 * c2)) ** 2, 1.0)


register(Law(
    id="burckhardt-sqrt",
    title="Burckhardt square-root law",
    family="slip",
    variables=("s",),
    params=(
        Param("c1", "", 2.0, (0.0, INF), "coefficient of sqrt(s)"),
        Param("c2", "", 2.0, (1e-9, INF), "coefficient of the linear fall-off"),
    ),
    formula=_bsqrt,
    guess=linear_guess(("c1", "c2"), lambda d: [np.sqrt(np.maximum(d["s"], 0.0)), -d["s"]]),
    linear=True,
    domain=SLIP,
    derived=(
        Derived("s_peak", "", "slip of the maximum over s = 0..1 ((c1/(2 c2))^2, clipped)",
                _bsqrt_s_peak),
        Derived("mu_peak", "", "maximum of mu over s = 0..1 (c1^2/(4 c2) when inside)",
                lambda m, c1, c2, **_: c1 * m.sqrt(_bsqrt_s_peak(m, c1, c2))
                - c2 * _bsqrt_s_peak(m, c1, c2)),
    ),
    typical=SLIP,
    references=(
        "M. Burckhardt, Fahrwerktechnik: Radschlupf-Regelsysteme, Vogel, Wuerzburg, 1993, "
        "as quoted in the source thesis (Eq. 2-34).",
    ),
    evidence="M, I (peak)",
    description="mu = c1 sqrt(s) - c2 s: the simplest slip law, linear in its parameters "
    "(for on-line identification); peak at s* = (c1/(2 c2))^2 with mu* = c1^2/(4 c2).",
    notes="Infinite slope at s = 0. Defined for braking slip s >= 0 only (NaN below).",
))

# --------------------------------------------------------------- kiencke-daiss


def _kd(m, s, k_s, c1, c2):
    return k_s * s / (c1 * s**2 + c2 * s + 1.0)


def _kd_s_peak(m, c1, **_):
    return m.minimum(1.0 / m.sqrt(c1), 1.0)


def _kd_admissible(params: Mapping[str, float]) -> str | None:
    c1, c2 = params["c1"], params["c2"]
    # minimum of 1 + c2 s + c1 s^2 over [0, 1]
    cands = [1.0, 1.0 + c2 + c1]
    if c1 > 0:
        sv = -c2 / (2.0 * c1)
        if 0.0 < sv < 1.0:
            cands.append(1.0 - c2 * c2 / (4.0 * c1))
    low = min(cands)
    if low <= 0:
        return (f"the denominator c1 s^2 + c2 s + 1 reaches {low:.3g} <= 0 on s = 0..1 "
                f"(c1 = {c1:g}, c2 = {c2:g}): mu has a pole there")
    return None


def _kd_guess(d):
    s, mu = np.asarray(d["s"], float), np.asarray(d["mu"], float)
    # equation error: mu (c1 s^2 + c2 s + 1) = k_s s
    k_s, c1, c2 = linear_lstsq([s, -(s**2) * mu, -s * mu], mu)
    c1 = max(c1, 1e-3)
    if _kd_admissible({"c1": c1, "c2": c2}):
        c2 = max(c2, -1.9 * math.sqrt(c1))
    return {"k_s": max(k_s, 1e-3), "c1": c1, "c2": c2}


register(Law(
    id="kiencke-daiss",
    title="Kiencke-Daiss (rational slip law)",
    family="slip",
    variables=("s",),
    params=(
        Param("k_s", "", 20.0, (1e-9, INF), "initial slope d mu/ds at s = 0"),
        Param("c1", "", 30.0, (1e-9, INF), "quadratic denominator coefficient (peak at "
              "1/sqrt(c1))"),
        Param("c2", "", 5.0, meaning="linear denominator coefficient"),
    ),
    formula=_kd,
    guess=_kd_guess,
    domain=SLIP,
    derived=(
        Derived("s_peak", "", "slip of the maximum over s = 0..1 (1/sqrt(c1), clipped)",
                _kd_s_peak),
        Derived("mu_peak", "", "maximum over s = 0..1 (k_s/(2 sqrt(c1) + c2) when inside)",
                lambda m, k_s, c1, c2, **_: _kd(m, _kd_s_peak(m, c1), k_s, c1, c2)),
    ),
    admissible=_kd_admissible,
    typical=SLIP,
    references=(
        "U. Kiencke, A. Daiss, Estimation of tyre friction for enhanced ABS-systems, "
        "Proc. AVEC'94, Tsukuba, 1994.",
    ),
    evidence="C (citation AVEC'94), M (formula), I (peak)",
    description="mu = k_s s / (c1 s^2 + c2 s + 1): a rational law with initial slope k_s "
    "and its peak at s* = 1/sqrt(c1), mu* = k_s/(2 sqrt(c1) + c2).",
    notes="The denominator must stay positive on s = 0..1 (checked as admissibility).",
))

# -------------------------------------------------------------------- germann


def _germann(m, s, a0, a1, a2):
    return a0 + a1 * s + a2 * s**2


register(Law(
    id="germann",
    title="Germann (quadratic in slip, pre-peak only)",
    family="slip",
    variables=("s",),
    params=(
        Param("a0", "", 0.0, meaning="offset (about 0)"),
        Param("a1", "", 8.0, (0.0, INF), "initial slope d mu/ds"),
        Param("a2", "", -15.0, (-INF, 0.0), "curvature (< 0)"),
    ),
    formula=_germann,
    guess=linear_guess(("a0", "a1", "a2"), lambda d: [np.ones_like(d["s"]), d["s"],
                                                      d["s"] ** 2]),
    linear=True,
    domain={"s": (0.0, 0.3)},
    strict_domain=True,
    typical={"s": (0.0, 0.3)},
    derived=(
        Derived("slope_0", "", "initial slope d mu/ds at s = 0 (a1)", lambda m, a1, **_: a1),
    ),
    references=(
        "S. Germann, M. Wuertenberger, A. Daiss, Monitoring of the friction coefficient "
        "between tyre and road surface, Proc. 3rd IEEE Conf. Control Applications, "
        "Glasgow, 1994.",
    ),
    evidence="M",
    description="mu = a0 + a1 s + a2 s^2: a quadratic for the rising part of the slip "
    "curve, linear in its parameters (thesis Eq. 2-30).",
    notes="Valid only for s <= 0.3 (before the peak); never extrapolate beyond it.",
))
