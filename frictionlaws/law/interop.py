"""A law in other tools' terms: an :class:`lmfit.Model`, and the HTML Jupyter shows.

:mod:`frictionlaws.fitting.views` gathers these with the other integrations (pandas, xarray,
plots); they live here, beside the law, because :class:`~frictionlaws.law.Law` hands its
:meth:`~frictionlaws.law.Law.lmfit_model` and ``_repr_html_`` to them.  Heavy libraries
are imported inside the functions that need them.
"""

from __future__ import annotations

import html
import inspect
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from .evaluation import LawEvaluation

__all__ = ["lmfit_model", "law_html", "table_html"]


# ------------------------------------------------------------------------ lmfit
def lmfit_model(law: LawEvaluation, *, values: Mapping[str, float] | None = None) -> Any:
    """The law as an :class:`lmfit.Model`.

    Parameters
    ----------
    law : Law
        A registered law (or one built by hand).
    values : mapping, optional
        Start values overriding the declared defaults (validated against the bounds).

    Returns
    -------
    lmfit.Model
        Independent variables: the law's variables (SI).  Parameter hints: each
        fitted parameter with its default and bounds; each setting fixed
        (``vary=False``) at its value.  ``model.make_params()`` gives a ready set.
        Laws without variables (Coulomb) take a dummy independent variable ``x``
        that only sets the output shape.
    """
    import lmfit

    start = law.resolve({**law.defaults, **dict(values or {})})
    variables = list(law.variables) or ["x"]
    names = [*law.param_names, *(s.name for s in law.settings)]
    evaluate = law.evaluate
    used = tuple(law.variables)

    def model_function(**kw: Any) -> Any:
        xs = {k: kw[k] for k in used}
        out = evaluate(xs, {n: kw[n] for n in names})
        shape = np.shape(kw["x"]) if not used else np.shape(out)
        return np.broadcast_to(out, shape).copy()

    kind = inspect.Parameter.KEYWORD_ONLY
    model_function.__signature__ = inspect.Signature(  # type: ignore[attr-defined]
        [inspect.Parameter(v, kind) for v in variables]
        + [inspect.Parameter(n, kind, default=start[n]) for n in names])
    model_function.__name__ = law.id.replace("-", "_").replace("+", "_")
    model = lmfit.Model(model_function, independent_vars=variables, name=law.id)
    for p in law.params:
        lo, hi = p.bounds
        model.set_param_hint(p.name, value=start[p.name], min=lo, max=hi)
    for s in law.settings:
        model.set_param_hint(s.name, value=start[s.name], vary=False)
    return model


# ---------------------------------------------------------------------- Jupyter
def table_html(rows: Sequence[Mapping[str, Any]], columns: Sequence[str] | None = None,
               caption: str = "") -> str:
    """A small HTML table of ``rows`` (dicts), numbers to 6 significant digits."""
    if not rows:
        return f"<p>{html.escape(caption)} (empty)</p>"
    cols = list(columns or rows[0].keys())
    head = "".join(f"<th>{html.escape(str(c))}</th>" for c in cols)
    body = "".join(
        "<tr>" + "".join(f"<td>{html.escape(_cell(r.get(c)))}</td>" for c in cols) + "</tr>"
        for r in rows)
    cap = f"<caption>{html.escape(caption)}</caption>" if caption else ""
    return f"<table>{cap}<thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def _cell(x: Any) -> str:
    if x is None:
        return "-"
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, (float, np.floating)):
        return f"{float(x):.6g}"
    if isinstance(x, (tuple, list)):
        return ", ".join(_cell(v) for v in x)
    return str(x)


def law_html(law: LawEvaluation) -> str:
    """HTML for a law: title, formula (plain text), parameters, settings, evidence."""
    params = [{"name": p.name, "unit": p.unit or "-", "default": p.default,
               "bounds": p.bounds, "meaning": p.meaning} for p in law.params]
    settings = [{"name": s.name, "value": s.value, "unit": s.unit or "-",
                 "meaning": s.meaning} for s in law.settings]
    parts = [f"<h4>{html.escape(law.title)} <code>{html.escape(law.id)}</code></h4>",
             f"<p>{html.escape(law.description)}</p>",
             f"<p>variables: {html.escape(', '.join(law.variables) or 'none')} (SI); "
             f"evidence: {html.escape(law.evidence)}</p>",
             table_html(params, caption="parameters")]
    if settings:
        parts.append(table_html(settings, caption="settings (fixed)"))
    return "\n".join(parts)
