"""Recognise laws that a solver's built-in friction model reproduces exactly.

Solvers have a few closed-form friction laws:

* ``mu = mu_k + (mu_s - mu_k) exp(-d_c v)``: Abaqus ``*FRICTION, EXPONENTIAL
  DECAY``, LS-DYNA ``FS/FD/DC``, Radioss ``Ifric = 4``;
* ``mu = Fric + C1 p + C2 v + C3 p v + C4 p^2 + C5 v^2``: Radioss ``Ifric = 1``.

Rather than trusting law names, the law's symbolic form with the parameter
values substituted is matched against these forms (so ``exponential-decay``
with ``delta = 1``, ``coulomb``, ``quadratic-pv`` and ``thesis-poly2`` are all
recognised, and a third-party law of the same form would be too), and the
match is verified numerically against the law.  Coefficients are returned in
the model's units.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..law import Law

__all__ = ["ExpDecay", "exp_decay_form", "quadratic_pv_form", "numeric_expr"]


def numeric_expr(law: Law, values: Mapping[str, float]) -> Any:
    """The law's sympy form with every parameter and setting replaced by its value.

    Integral values become sympy integers so that, e.g., ``(v/v_c)**delta``
    with ``delta = 1`` collapses to ``v/v_c``.
    """
    import sympy

    syms = law.symbols()
    expr = law.symbolic()
    sub = {}
    for name in [p.name for p in law.params] + [s.name for s in law.settings]:
        val = float(values[name])
        sub[syms[name]] = sympy.Integer(int(val)) if val.is_integer() else sympy.Float(val)
    return sympy.expand(expr.subs(sub))


@dataclass(frozen=True)
class ExpDecay:
    """``mu = mu_k + (mu_s - mu_k) exp(-d_c v)``, ``d_c`` in 1/(m/s) (SI)."""

    mu_s: float
    mu_k: float
    d_c: float

    def __call__(self, v: Any) -> Any:
        return self.mu_k + (self.mu_s - self.mu_k) * np.exp(-self.d_c * np.abs(v))


def exp_decay_form(law: Law, values: Mapping[str, float]) -> tuple[ExpDecay | None, str]:
    """Match ``mu = A + B exp(C v)`` (C < 0), or a constant.

    Returns
    -------
    (ExpDecay or None, str)
        The exact form, or None and the reason it does not match.
    """
    import sympy

    others = [v for v in law.variables if v != "v"]
    if others:
        return None, (f"law '{law.id}' depends on {', '.join(others)}; the exponential-decay "
                      "model depends on the slip rate only")
    expr = numeric_expr(law, values)
    syms = law.symbols()
    if "v" not in law.variables or syms["v"] not in expr.free_symbols:
        c = float(expr)
        return ExpDecay(c, c, 0.0), ""
    v = syms["v"]
    A, B, C = (sympy.Wild(n, exclude=[v]) for n in "ABC")
    m = expr.match(A + B * sympy.exp(C * v))
    reason = (f"law '{law.id}' with these parameters is not of the form "
              "mu_k + (mu_s - mu_k) exp(-d_c v)")
    if law.id == "exponential-decay" and "delta" in values and values["delta"] != 1:
        reason += f" (delta = {values['delta']:g}; the solver's model needs delta = 1)"
    if not m or any(k not in m for k in (A, B, C)):
        return None, reason
    try:
        a, b, c = (float(m[k]) for k in (A, B, C))
    except (TypeError, ValueError):
        return None, reason
    if c > 0 and b != 0:
        return None, (f"law '{law.id}' grows exponentially with v (rate {c:g} s/m): "
                      "not a decay")
    form = ExpDecay(a + b, a, -c if b != 0 else 0.0)
    vv = np.concatenate([[0.0], np.geomspace(1e-6, 1e3, 60)])
    if form.d_c > 0:
        vv = np.concatenate([vv, np.linspace(0, 10 / form.d_c, 41)])
    ref = np.asarray(law.evaluate({"v": vv}, values), float)
    if not np.allclose(form(vv), ref, rtol=1e-12, atol=1e-13):
        return None, reason + " (numerical check failed)"
    return form, ""


def quadratic_pv_form(law: Law, values: Mapping[str, float], units: Any
                      ) -> tuple[dict[str, float] | None, str]:
    """Match Radioss Ifric 1, ``Fric + C1 p + C2 v + C3 p v + C4 p^2 + C5 v^2``.

    The coefficients are returned in the model's units (``p``, ``v`` as
    ``units`` defines them), under the keys ``Fric, C1 .. C5``.
    """
    import sympy

    others = [v for v in law.variables if v not in ("p", "v")]
    if others:
        return None, (f"law '{law.id}' depends on {', '.join(others)}; Radioss friction "
                      "models depend on pressure and velocity only")
    expr = numeric_expr(law, values)
    syms = law.symbols()
    P, V = sympy.symbols("P V", positive=True)
    sub = {}
    for name, new in (("p", P), ("v", V)):
        if name in syms:
            scale, offset = units.affine(name)
            sub[syms[name]] = sympy.Float(scale) * new + sympy.Float(offset)
    expr = sympy.expand(expr.subs(sub))
    reason = (f"law '{law.id}' with these parameters is not a polynomial of degree 2 in "
              "(p, v) without p^2 v, p v^2 terms")
    try:
        poly = sympy.Poly(expr, P, V)
    except sympy.PolynomialError:
        return None, reason
    allowed = {(0, 0): "Fric", (1, 0): "C1", (0, 1): "C2", (1, 1): "C3", (2, 0): "C4",
               (0, 2): "C5"}
    coeffs = {k: 0.0 for k in allowed.values()}
    for monom, coef in poly.terms():
        if monom not in allowed:
            return None, reason
        try:
            coeffs[allowed[monom]] = float(coef)
        except (TypeError, ValueError):
            return None, reason
    # numerical check in SI
    rng = np.random.default_rng(1)
    pp = rng.uniform(0, 2e6, 50) if "p" in law.variables else np.zeros(50)
    vv = rng.uniform(0, 20, 50) if "v" in law.variables else np.zeros(50)
    Pm, Vm = units.to_model("p", pp), units.to_model("v", vv)
    approx = (coeffs["Fric"] + coeffs["C1"] * Pm + coeffs["C2"] * Vm + coeffs["C3"] * Pm * Vm
              + coeffs["C4"] * Pm**2 + coeffs["C5"] * Vm**2)
    ref = np.asarray(law.evaluate({k: x for k, x in (("p", pp), ("v", vv))
                                   if k in law.variables} or {"p": pp}, values), float)
    if not np.allclose(approx, ref, rtol=1e-9, atol=1e-12 * max(1.0, np.abs(ref).max())):
        return None, reason + " (numerical check failed)"
    return coeffs, ""
