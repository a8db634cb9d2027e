"""Cases on temperature: WLF shift sets and the master curve of the pyvisco DMA data.
"""

from __future__ import annotations

import numpy as np

from ...fitting.lsq import least_squares_solve
from ...io import datasets_dir
from ...viscoelastic.mastercurve import fit_wlf, load_dma_upstream_shifts
from ...viscoelastic.temperature import WLF_PRESETS, resolve_wlf, wlf_convert, wlf_log_aT
from ..core import CaseRun, Tol

__all__ = []


def _case_wlf_sets(run: CaseRun) -> None:
    T_g = 223.15
    g, u = WLF_PRESETS["grosch"], WLF_PRESETS["universal"]
    run.compare("Grosch C1 (thesis Eq. 2-4)", 8.86, g.C1, Tol(rel=1e-12))
    run.compare("Grosch C2", 101.6, g.C2, Tol(rel=1e-12), unit="K")
    run.compare("universal C1", 17.44, u.C1, Tol(rel=1e-12))
    run.compare("universal C2", 51.6, u.C2, Tol(rel=1e-12), unit="K")
    C1n, C2n = wlf_convert(17.44, 51.6, T_g, T_g + 50.0)
    run.compare("universal set referred to T_g + 50 K: C2' = C2 + 50 K (= Grosch C2)", 101.6,
                C2n, Tol(abs=1e-9), unit="K")
    run.compare("C1' = C1 C2 / (C2 + 50 K) (hand computation 17.44 x 51.6 / 101.6)",
                17.44 * 51.6 / 101.6, C1n, Tol(rel=1e-12))
    run.compare("C1' against Grosch's printed 8.86", 8.86, C1n, Tol(abs=0.005),
                note="8.8573 vs 8.86: the published constants are rounded; the difference "
                "(0.03 %) is within half a unit of the last printed digit")
    T = np.linspace(T_g, T_g + 100.0, 401)
    grosch = wlf_log_aT(T, preset="grosch", T_g=T_g, warn=False)
    univ = wlf_log_aT(T, preset="universal", T_g=T_g, warn=False)
    shift0 = wlf_log_aT(T_g + 50.0, preset="universal", T_g=T_g, warn=False)
    dev = float(np.max(np.abs(grosch - (univ - shift0))))
    # rounding of C1 (+/-0.005) changes log aT by at most 0.005 * 50/51.6 on T_g .. T_g + 100 K
    run.at_most("max |log aT(Grosch) - [log aT(universal) - log aT(universal, T_g + 50 K)]| "
                "on T_g .. T_g + 100 K", dev, 0.005 * 50 / 51.6 + 1e-9, unit="decades")
    run.compare("universal log aT at T_g + 50 K, hand: -17.44 x 50 / 101.6", -17.44 * 50 / 101.6,
                float(shift0), Tol(abs=1e-12), unit="decades")
    poles = {}
    for name in ("grosch", "universal"):
        _, C2_, T_ref_, _ = resolve_wlf(preset=name, T_g=T_g)
        poles[name] = T_ref_ - C2_
    run.compare("pole T_ref - C2 with T_g = 223.15 K: universal vs Grosch (both T_g - 51.6 K)",
                poles["grosch"], poles["universal"], Tol(abs=1e-9), unit="K")
    run.compare("Grosch pole = T_g - 51.6 K", T_g - 51.6, poles["grosch"], Tol(abs=1e-9),
                unit="K")


def _read_pyvisco_shifts() -> tuple[np.ndarray, np.ndarray]:
    """The upstream shift factors, parsed here independently (T in degC -> K)."""
    path = datasets_dir() / "dma-pyvisco" / "freq_user_master__shift_factors.csv"
    lines = [ln for ln in path.read_text(encoding="utf-8-sig").splitlines() if ln.strip()]
    names = [x.strip() for x in lines[0].split(",")]
    units = [x.strip() for x in lines[1].split(",")]
    if names[:2] != ["T", "log_aT"] or units[0] != "C":
        raise ValueError(f"unexpected header {names} / {units}")
    rows = np.array([[float(x) for x in ln.split(",")] for ln in lines[2:]])
    return rows[:, 0] + 273.15, rows[:, 1]


def _case_wlf_pyvisco(run: CaseRun) -> None:
    T, la = _read_pyvisco_shifts()
    up = load_dma_upstream_shifts()
    same = np.allclose(np.sort(up["T"]), np.sort(T), rtol=0, atol=1e-9) and np.allclose(
        up["log_aT"][np.argsort(up["T"])], la[np.argsort(T)], rtol=0, atol=0)
    run.require("library reader = independent parse of the upstream file (21 shift factors)",
                same, "identical", "identical" if same else "different")
    zero = np.flatnonzero(la == 0.0)
    T_ref = float(T[zero[0]])
    run.compare("reference temperature of the upstream shifts (log aT = 0)", 268.15, T_ref,
                Tol(abs=1e-9), unit="K", note="-5 degC")
    dT = T - T_ref
    use = dT != 0
    # independent least squares: start from the linearised form -dT/log aT = C2/C1 + dT/C1
    slope, icpt = np.polyfit(dT[use], -dT[use] / la[use], 1)
    start = np.array([1 / slope, icpt / slope])

    def resid(c: np.ndarray) -> np.ndarray:
        return -c[0] * dT[use] / (c[1] + dT[use]) - la[use]

    sol = least_squares_solve(resid, start, xtol=1e-15, ftol=1e-15, gtol=1e-15)
    C1_ref, C2_ref = (float(x) for x in sol.x)
    rms_ref = float(np.sqrt(np.mean(sol.fun ** 2)))
    w = fit_wlf(T, la, T_ref)
    run.compare("C1 (library fit_wlf vs independent least squares)", C1_ref, w.C1,
                Tol(rel=1e-4))
    run.compare("C2 (library fit_wlf vs independent least squares)", C2_ref, w.C2,
                Tol(rel=1e-4), unit="K")
    run.compare("rms residual of log aT", rms_ref, w.rms, Tol(rel=1e-4), unit="decades")
    run.report("C1 standard error (library)", w.C1_stderr)
    run.report("C2 standard error (library)", w.C2_stderr, unit="K")
    worst = int(np.argmax(np.abs(sol.fun)))
    run.report(f"largest |residual| (T = {T[use][worst] - 273.15:g} degC)",
               float(sol.fun[worst]), unit="decades")
    run.note(f"WLF fitted to the 21 upstream shift factors (-50..100 degC, T_ref = -5 degC): "
             f"C1 = {C1_ref:.3f}, C2 = {C2_ref:.2f} K, rms {rms_ref:.2f} decades. The "
             "residuals are systematic: 150 K is wider than the roughly 100 K over which WLF "
             "holds, so the constants describe this span only on average.")

