"""Cases on the FE exports: Abaqus, LS-DYNA and Radioss cards read back and checked against
the laws and the solvers' manuals.
"""

from __future__ import annotations

import math

import numpy as np

from ...fe_export import export
from ...law.registry import get_law
from ..core import CaseRun, Tol

__all__ = []


def _fe_grid() -> tuple[np.ndarray, ...]:
    v = np.concatenate([-np.geomspace(1e-4, 20.0, 15), [0.0], np.geomspace(1e-4, 20.0, 15)])
    return (v,)


def _data_lines(text: str, comment: str) -> list[str]:
    return [ln for ln in text.splitlines() if ln.strip() and not ln.startswith(comment)]


def _parse_abaqus_decay(text: str) -> tuple[float, float, float]:
    """The data line after ``*FRICTION, EXPONENTIAL DECAY``: mu_s, mu_k, d_c."""
    lines = _data_lines(text, "**")
    for i, ln in enumerate(lines):
        key = ln.replace(" ", "").upper()
        if key.startswith("*FRICTION,") and "EXPONENTIALDECAY" in key:
            mu_s, mu_k, d_c = (float(x) for x in lines[i + 1].split(",")[:3])
            return mu_s, mu_k, d_c
    raise ValueError("no *FRICTION, EXPONENTIAL DECAY block in the exported file")


def _parse_lsdyna_card2(text: str) -> tuple[float, float, float]:
    """FS, FD, DC: the first three 10-column fields of *CONTACT card 2 (manual layout)."""
    lines = _data_lines(text, "$")
    for i, ln in enumerate(lines):
        if ln.upper().startswith("*CONTACT"):
            card2 = lines[i + 2]
            return tuple(float(card2[k:k + 10]) for k in (0, 10, 20))  # type: ignore[return-value]
    raise ValueError("no *CONTACT keyword in the exported file")


def _parse_radioss(text: str) -> tuple[int, dict[str, float]]:
    """Ifric and the coefficients of an OpenRadioss /FRICTION block (20-column reals)."""
    lines = _data_lines(text, "#")
    i = next(k for k, ln in enumerate(lines) if ln.upper().startswith("/FRICTION"))
    ifric = int(lines[i + 2][0:10])
    c = [float(lines[i + 3][k:k + 20]) for k in range(0, 100, 20)]
    c6, fric = (float(lines[i + 4][k:k + 20]) for k in (0, 20))
    return ifric, {"Fric": fric, "C1": c[0], "C2": c[1], "C3": c[2], "C4": c[3], "C5": c[4],
                   "C6": c6}


def _case_abaqus(run: CaseRun) -> None:
    law = get_law("exponential-decay")
    (v,) = _fe_grid()
    # Abaqus *FRICTION, EXPONENTIAL DECAY: data line mu_s, mu_k, d_c;
    # mu = mu_k + (mu_s - mu_k) exp(-d_c * slip rate)
    for mu_s, mu_k, d_c in ((1.2, 0.8, 2.0), (0.5, 0.9, 20.0), (1.0, 0.3, 0.1)):
        gamma = np.abs(v)
        abaqus = np.array([mu_k + (mu_s - mu_k) * math.exp(-d_c * g) for g in gamma])
        ours = law(v=v, mu_s=mu_s, mu_d=mu_k, v_c=1.0 / d_c, delta=1.0)
        dev = float(np.max(np.abs(ours - abaqus)))
        run.at_most(f"mu_s={mu_s:g}, mu_k={mu_k:g}, d_c={d_c:g} s/m: max |law - Abaqus| "
                    f"over {v.size} slip rates", dev, 1e-13)
    run.compare("mu at zero slip rate = mu_s", 1.2,
                law(v=0.0, mu_s=1.2, mu_d=0.8, v_c=0.5, delta=1.0), Tol(abs=1e-15))
    run.compare("mu as slip rate -> inf = mu_k", 0.8,
                law(v=1e4, mu_s=1.2, mu_d=0.8, v_c=0.5, delta=1.0), Tol(abs=1e-15))
    # the exported card, read back as Abaqus reads it (mm-N-s: slip rate in mm/s)

    for units, scale in (("SI", 1.0), ("mm-N-s", 1000.0)):
        for mu_s, mu_d, v_c in ((1.2, 0.8, 0.5), (0.45, 0.7, 0.03)):
            res = export("exponential-decay", {"mu_s": mu_s, "mu_d": mu_d, "v_c": v_c,
                                               "delta": 1.0}, format="abaqus-decay",
                         units=units)
            ms, mk, dc = _parse_abaqus_decay(res.text)
            card = np.array([mk + (ms - mk) * math.exp(-dc * abs(x) * scale) for x in v])
            ours = law(v=v, mu_s=mu_s, mu_d=mu_d, v_c=v_c, delta=1.0)
            run.at_most(f"exported card ({units}) mu_s={mu_s:g}, mu_d={mu_d:g}, v_c={v_c:g} "
                        "m/s: max |Abaqus(card) - law|", float(np.max(np.abs(card - ours))),
                        1e-12)


def _case_lsdyna(run: CaseRun) -> None:
    law = get_law("exponential-decay")
    (v,) = _fe_grid()
    # LS-DYNA *CONTACT card 2: mu = FD + (FS - FD) exp(-DC |v_rel|)
    for fs, fd, dc in ((1.2, 0.8, 2.0), (0.2, 0.6, 50.0), (0.9, 0.45, 0.5)):
        dyna = np.array([fd + (fs - fd) * math.exp(-dc * abs(x)) for x in v])
        ours = law(v=v, mu_s=fs, mu_d=fd, v_c=1.0 / dc, delta=1.0)
        run.at_most(f"FS={fs:g}, FD={fd:g}, DC={dc:g} s/m: max |law - LS-DYNA| over "
                    f"{v.size} velocities (both signs)", float(np.max(np.abs(ours - dyna))),
                    1e-13)
    run.require("delta = 1 is the default (the manuals' law without a shape exponent)",
                law.param("delta").default == 1.0, "1", law.param("delta").default)

    for units, scale in (("SI", 1.0), ("mm-N-s", 1000.0)):
        for mu_s, mu_d, v_c in ((1.2, 0.8, 0.5), (0.45, 0.7, 0.03)):
            res = export("exponential-decay", {"mu_s": mu_s, "mu_d": mu_d, "v_c": v_c,
                                               "delta": 1.0}, format="lsdyna",
                         box={"v": (0.0, 10.0)}, units=units)
            fs, fd, dc = _parse_lsdyna_card2(res.text)
            card = np.array([fd + (fs - fd) * math.exp(-dc * abs(x) * scale) for x in v])
            ours = law(v=v, mu_s=mu_s, mu_d=mu_d, v_c=v_c, delta=1.0)
            run.at_most(f"exported card 2 ({units}) mu_s={mu_s:g}, mu_d={mu_d:g}, "
                        f"v_c={v_c:g} m/s: max |LS-DYNA(card) - law|",
                        float(np.max(np.abs(card - ours))), 1e-7,
                        note="" if units != "SI" or mu_s != 1.2 else
                        "10-column fields round DC to about 8 significant digits")


def _case_radioss(run: CaseRun) -> None:
    law = get_law("quadratic-pv")
    run.require("alias 'radioss-ifric1' and 'dorsch' resolve to quadratic-pv",
                get_law("radioss-ifric1") is law and get_law("dorsch") is law, "yes",
                "yes" if get_law("radioss-ifric1") is law and get_law("dorsch") is law else "no")
    p = np.geomspace(1e3, 2e6, 13)
    v = np.concatenate([np.geomspace(1e-3, 30.0, 9), [0.0]])
    P, V = np.meshgrid(p, v)
    # OpenRadioss Ifric = 1: mu = Fric + C1 p + C2 v + C3 p v + C4 p^2 + C5 v^2
    for fric, c1, c2, c3, c4, c5 in ((0.9, -1.5e-6, 0.08, 2e-7, 8e-13, -0.015),
                                     (0.3, 2e-7, -0.01, -3e-8, -1e-14, 0.002)):
        radioss = np.array([[fric + c1 * pp + c2 * vv + c3 * pp * vv + c4 * pp * pp
                             + c5 * vv * vv for pp, vv in zip(rp, rv)] for rp, rv in zip(P, V)])
        # the formula itself (law.evaluate: the grid reaches where mu < 0, which law(...)
        # and the exports refuse)
        ours = law.evaluate({"p": P, "v": V}, law.resolve(
            {"c0": fric, "c1": c1, "c2": c2, "c3": c3, "c4": c4, "c5": c5}))
        scale = np.maximum(np.abs(radioss), 1.0)
        run.at_most(f"Fric={fric:g}, C1..C5 = {c1:g}, {c2:g}, {c3:g}, {c4:g}, {c5:g}: "
                    f"max rel. |law - Ifric 1| over {P.size} (p, v)",
                    float(np.max(np.abs(ours - radioss) / scale)), 1e-12)

    c = {"c0": 0.9, "c1": -1.5e-6, "c2": 0.08, "c3": 2e-7, "c4": 8e-13, "c5": -0.015}
    for units, sp, sv in (("SI", 1.0, 1.0), ("mm-N-s", 1e-6, 1e3)):
        res = export("quadratic-pv", c, format="radioss", box={"p": (1e3, 2e6), "v": (0, 5)},
                     units=units)
        ifric, k = _parse_radioss(res.text)
        P, V = np.meshgrid(p, np.linspace(0.0, 5.0, 11))  # the box, where mu >= 0
        Pm, Vm = P * sp, V * sv          # the model's units (MPa, mm/s in mm-N-s)
        card = (k["Fric"] + k["C1"] * Pm + k["C2"] * Vm + k["C3"] * Pm * Vm + k["C4"] * Pm ** 2
                + k["C5"] * Vm ** 2)
        ours = law(p=P, v=V, **c)
        run.require(f"exported /FRICTION ({units}) is Ifric 1", ifric == 1, "1", ifric)
        run.at_most(f"exported /FRICTION ({units}): max rel. |Radioss(card) - law|",
                    float(np.max(np.abs(card - ours) / np.maximum(np.abs(ours), 1.0))), 1e-9)
    ed = get_law("exponential-decay")
    res = export("exponential-decay", {"mu_s": 1.1, "mu_d": 0.7, "v_c": 0.2, "delta": 1.0},
                 format="radioss", box={"v": (0.0, 10.0)})
    ifric, k = _parse_radioss(res.text)
    vv = np.linspace(0.0, 10.0, 41)
    card = k["C1"] + (k["Fric"] - k["C1"]) * np.exp(-k["C2"] * vv)
    run.require("exponential-decay exports as Ifric 4", ifric == 4, "4", ifric)
    run.at_most("Ifric 4 card, mu = C1 + (Fric - C1) exp(-C2 v), vs exponential-decay",
                float(np.max(np.abs(card - ed(v=vv, mu_s=1.1, mu_d=0.7, v_c=0.2, delta=1.0)))),
                1e-12)

