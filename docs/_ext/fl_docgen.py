"""Sphinx extension: pages generated from the code at build time.

* the **law catalogue** (``generated/catalogue/``): one page per registered
  law, built from its declaration: formula from :meth:`Law.latex`, parameters
  with units and bounds, settings, presets, domain, derived quantities,
  evidence tag, references and a plot over the law's typical range;
* the **CLI reference** (``generated/cli.rst``) from
  :func:`frictionlaws.cli.build_parser`;
* the **API reference** (``generated/api/``): one autodoc page per public
  module of the package.

Everything is regenerated on every build from the installed package, so a law,
command or module that lands is documented without touching the docs.  A law
that cannot be rendered fails the build (no silent skipping), and after writing
the catalogue the extension checks that every registered law has its page and
its row in the index.

The functions are plain Python so ``tests/test_docs.py`` can call them
without Sphinx.
"""

from __future__ import annotations

import argparse
import importlib
import io
import os
import pkgutil
import re
import warnings
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

__all__ = [
    "escape",
    "law_page",
    "law_latex",
    "symbolic_for_docs",
    "law_figure",
    "write_catalogue",
    "check_catalogue",
    "cli_reference",
    "write_cli_reference",
    "public_modules",
    "write_api_reference",
    "escape_bars",
    "shell_session",
    "readme_commands",
    "write_readme_commands",
    "write_shell_sessions",
    "setup",
]

#: Width used for the CLI help text (argparse reads COLUMNS).
CLI_COLUMNS = 96
#: Preferred order of the secondary (curve-parameter) variable in plots.
_SECONDARY_ORDER = ("T", "p", "v", "F_N", "s")
#: Plot at most this many presets (one panel each for two-variable laws).
_MAX_PANELS = 3
_MAX_CURVES = 6

# ----------------------------------------------------------------- helpers


def escape(text: str) -> str:
    """Escape reStructuredText inline markup in free text (``*``, `` ` ``, ``|``, ``_``)."""
    text = " ".join(str(text).split())
    return re.sub(r"([\\*`|_<>\[\]])", r"\\\1", text)


def _write_if_changed(path: Path, data: str | bytes) -> bool:
    """Write ``data`` unless the file already holds it (keeps incremental builds fast)."""
    raw = data.encode("utf-8") if isinstance(data, str) else data
    if path.exists() and path.read_bytes() == raw:
        return False
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(raw)
    return True


def _heading(title: str, char: str) -> str:
    return f"{title}\n{char * len(title)}\n"


def _num(x: float) -> str:
    """A compact number for tables (``inf`` as the infinity sign)."""
    x = float(x)
    if np.isinf(x):
        return "∞" if x > 0 else "−∞"
    if x == 0:
        return "0"
    s = f"{x:.6g}"
    return s.replace("-", "−") if s.startswith("-") else s


def _log10_function() -> Any:
    import sympy

    class log10(sympy.Function):  # noqa: N801 - printed name
        """Decimal logarithm, kept as one symbol so it prints as log10."""

        def _latex(self, printer: Any, exp: Any = None) -> str:
            tex = rf"\log_{{10}}{{\left({printer._print(self.args[0])}\right)}}"
            return rf"{tex}^{{{exp}}}" if exp else tex

    return log10


def symbolic_for_docs(law: Any) -> Any:
    """The law's symbolic form, tidied for reading.

    Integral floats become integers (``1.0`` -> ``1``) and every
    ``log(x)/log(10)`` that sympy made of a decimal logarithm is folded back
    into ``log10(x)``; natural logarithms stay as they are.  The result is the
    same function (``tests/test_docs.py`` checks it numerically).
    """
    import sympy

    expr = law.symbolic()
    expr = expr.xreplace({f: sympy.Integer(int(f)) for f in expr.atoms(sympy.Float)
                          if float(f).is_integer()})
    log10 = _log10_function()
    ln10 = sympy.Symbol("ln10", positive=True)
    expr = expr.subs(sympy.log(10), ln10)
    for term in sorted(expr.atoms(sympy.log), key=sympy.default_sort_key):
        trial = expr.subs(term, ln10 * log10(term.args[0]))
        if trial.count(ln10) < expr.count(ln10):
            expr = trial
    return expr.subs(ln10, sympy.log(10))


def law_latex(law: Any) -> str:
    """LaTeX of the formula for the catalogue (``\\mu = ...``), from the symbolic form.

    Natural logarithms print as ``ln``, decimal ones as ``log10``.
    """
    import sympy

    tex = sympy.latex(symbolic_for_docs(law), ln_notation=True)
    tex = re.sub(r"(?<![\d.])1(?:\.0)? \\cdot (10\^\{)", r"\1", tex)
    return r"\mu = " + tex


def _pylit(x: float) -> str:
    """A short Python literal for ``x`` (``1e-06`` -> ``1e-6``, ``100000.0`` -> ``1e5``)."""
    s = f"{float(x):.4g}"
    s = re.sub(r"e([+-])0*(\d)", lambda m: "e" + ("-" if m.group(1) == "-" else "") + m.group(2),
               s)
    if "e" not in s and "." not in s and abs(float(x)) >= 1e4:
        s = f"{float(x):.0e}".replace("e+0", "e").replace("e+", "e")
    return s


def _unit(unit: str) -> str:
    return f"``{unit}``" if unit else "–"


def _list_table(header: Sequence[str], rows: Iterable[Sequence[str]],
                widths: Sequence[int] | None = None) -> str:
    rows = list(rows)
    out = [".. list-table::", "   :header-rows: 1"]
    if widths:
        out.append("   :widths: " + " ".join(str(w) for w in widths))
    out.append("   :class: fl-table")
    out.append("")
    for row in [list(header)] + [list(r) for r in rows]:
        first = True
        for cell in row:
            cell = cell if cell not in ("", None) else "–"
            out.append(("   * - " if first else "     - ") + cell)
            first = False
    return "\n".join(out) + "\n"


def _var_info(name: str) -> tuple[str, str, str]:
    """(meaning, SI unit, display unit) of a variable."""
    from frictionlaws.law import VARIABLES

    var = VARIABLES.get(name)
    if var is None:
        return name, "", ""
    return var.meaning, var.unit, var.display_unit


def _variable_entry(law: Any, v: str) -> str:
    """A variable in the catalogue: unit, and the law's own meaning when it has one."""
    text = f"{v} [{_var_info(v)[1] or '–'}]"
    own = getattr(law, "variable_meanings", {}).get(v)
    opt = getattr(law, "optional_variables", {}).get(v)
    extra = [escape(own)] if own else []
    if opt:
        extra.append(f"optional when {opt[0]} = {_num(opt[1])}")
    return text + (f" ({'; '.join(extra)})" if extra else "")


def _to_display(name: str, values: np.ndarray) -> tuple[np.ndarray, str]:
    """Convert SI values of variable ``name`` to its display unit (via pint)."""
    _, si, disp = _var_info(name)
    if not disp or disp == si:
        return np.asarray(values, float), si
    from frictionlaws.base.units import from_si

    return from_si(values, disp, name), disp


def _fmt_var_value(name: str, value: float) -> str:
    shown, unit = _to_display(name, np.array([value]))
    unit = {"degC": "°C"}.get(unit, unit)
    return f"{name} = {float(shown[0]):.4g}{(' ' + unit) if unit else ''}"


def _evidence_lines(tag: str) -> list[str]:
    from frictionlaws.law import EVIDENCE_TAGS

    found = []
    for key in sorted(EVIDENCE_TAGS, key=len, reverse=True):
        if re.search(rf"(?<![A-Za-z]){key}(?![A-Za-z])", tag) and key not in found:
            found.append(key)
    order = list(EVIDENCE_TAGS)
    return [f"**{k}**: {EVIDENCE_TAGS[k]}" for k in sorted(found, key=order.index)]


# --------------------------------------------------------------- the plots


def _cases(law: Any) -> list[tuple[str, dict[str, float]]]:
    """Parameter sets to plot: the presets, or the defaults when there are none."""
    if law.presets:
        return [(name, law.resolve(preset=name)) for name in law.presets]
    return [("defaults", law.resolve(law.defaults))]


def _plot_range(law: Any, name: str) -> tuple[float, float]:
    """The x range of the catalogue plot: the typical range, or a little beyond the domain.

    A law whose typical range is just its domain (a measured box) is drawn past it, so the
    plot shows what happens outside; a slip ratio never goes past 1.
    """
    lo, hi = (float(x) for x in law.typical_range(name))
    if name in law.typical or name not in law.domain:
        return lo, hi
    if lo > 0 and hi / lo >= 100.0:
        return lo / 3.0, hi * 3.0
    span = hi - lo
    new_lo = max(0.0, lo - 0.25 * span) if lo >= 0 else lo - 0.25 * span
    new_hi = hi + 0.5 * span
    if name == "s":
        new_hi = min(new_hi, 1.0)
    return new_lo, new_hi


def _axis(law: Any, name: str, n: int = 200) -> tuple[np.ndarray, bool]:
    """SI sample points over the plot range of ``name`` and whether to use a log axis."""
    lo, hi = _plot_range(law, name)
    log = lo > 0 and hi / lo >= 100.0
    if log:
        return np.geomspace(lo, hi, n), True
    return np.linspace(lo, hi, n), False


def _levels(law: Any, name: str, k: int = 3) -> np.ndarray:
    lo, hi = (float(x) for x in law.typical_range(name))
    if lo > 0 and hi / lo >= 100.0:
        return np.geomspace(lo, hi, k + 2)[1:-1] if k < 3 else np.geomspace(lo, hi, k)
    return np.linspace(lo, hi, k)


def _mid(law: Any, name: str) -> float:
    lo, hi = (float(x) for x in law.typical_range(name))
    return float(np.sqrt(lo * hi)) if lo > 0 and hi / lo >= 100.0 else 0.5 * (lo + hi)


def _primary(law: Any) -> str:
    names = list(law.variables)
    if "s" in names:
        return "s"
    if "v" in names:
        lo, hi = law.typical_range("v")
        if lo > 0 and hi / lo >= 100.0:
            return "v"
    return names[0]


def _shade_domain(ax: Any, law: Any, name: str, x_disp: np.ndarray) -> bool:
    """Grey out the part of the x axis outside the law's domain; True when drawn."""
    if name not in law.domain:
        return False
    lo, hi = (float(v) for v in law.domain[name])
    (lo_d, hi_d), _ = _to_display(name, np.array([lo, hi]))
    xmin, xmax = float(np.min(x_disp)), float(np.max(x_disp))
    drawn = False
    if lo_d > xmin:
        ax.axvspan(xmin, lo_d, color="0.85", zorder=0, lw=0)
        drawn = True
    if hi_d < xmax:
        ax.axvspan(hi_d, xmax, color="0.85", zorder=0, lw=0)
        drawn = True
    return drawn


def _label(name: str) -> str:
    meaning, _, disp = _var_info(name)
    disp = {"degC": "°C"}.get(disp, disp)
    return f"{meaning} {name}" + (f" [{disp}]" if disp else " [–]")


def law_figure(law: Any) -> Any:
    """A matplotlib figure of ``law`` over its typical range, for every preset.

    One variable: one curve per preset.  Two or more: the primary variable on
    the x axis (slip ratio, else a velocity spanning decades, else the first
    variable), curves at three levels of a second variable, any further
    variable held at the middle of its range; one panel per preset.  The part
    of the x axis outside the law's declared domain is shaded.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cases = _cases(law)
    variables = list(law.variables)
    if len(variables) <= 1:
        fig, ax = plt.subplots(figsize=(6.4, 3.6), layout="constrained")
        name = variables[0] if variables else "p"
        x, log = _axis(law, name) if variables else (np.linspace(1e4, 1e6, 50), False)
        x_disp, _ = _to_display(name, x)
        for label, params in cases[:_MAX_CURVES]:
            y = law.evaluate({name: x} if variables else {"p": x}, params)
            ax.plot(x_disp, np.broadcast_to(y, x.shape), label=label, lw=2)
        shaded = _shade_domain(ax, law, name, x_disp) if variables else False
        _finish(ax, law, name, log)
        if not variables:
            ax.set_xlabel(_label(name) + "  (μ does not depend on it)")
        if shaded:
            ax.plot([], [], color="0.85", lw=8, label="outside domain")
        ax.legend(fontsize="small", title="preset" if law.presets else None)
        ax.set_title(law.title, fontsize="medium")
        return fig

    primary = _primary(law)
    rest = [v for v in variables if v != primary]
    secondary = sorted(rest, key=lambda v: _SECONDARY_ORDER.index(v)
                       if v in _SECONDARY_ORDER else len(_SECONDARY_ORDER))[0]
    x, log = _axis(law, primary)
    x_disp, _ = _to_display(primary, x)

    def curve(params: dict[str, float], fixed: dict[str, float]) -> np.ndarray:
        vals = {primary: x, **{k: np.full_like(x, v) for k, v in fixed.items()}}
        return np.broadcast_to(law.evaluate(vals, params), x.shape)

    if law.family == "slip" and len(cases) > 1:
        # road surfaces side by side: one panel, one curve per preset
        fixed = {v: _mid(law, v) for v in rest}
        fig, ax = plt.subplots(figsize=(7.2, 3.8), layout="constrained")
        for label, params in cases[:8]:
            ax.plot(x_disp, curve(params, fixed), lw=2, label=label)
        shaded = _shade_domain(ax, law, primary, x_disp)
        if shaded:
            ax.plot([], [], color="0.85", lw=8, label="outside domain")
        _finish(ax, law, primary, log)
        ax.legend(fontsize="small", title="preset", loc="center left", bbox_to_anchor=(1.01, 0.5))
        ax.set_title(law.title + "\n" + ", ".join(_fmt_var_value(k, v) for k, v in fixed.items()),
                     fontsize="medium")
        return fig

    others = {v: _mid(law, v) for v in rest if v != secondary}
    levels = _levels(law, secondary)
    panels = cases[:_MAX_PANELS]
    ncol = min(2, len(panels))
    nrow = int(np.ceil(len(panels) / ncol))
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.6 * ncol + 0.4, 3.4 * nrow + 0.4),
                             layout="constrained", squeeze=False)
    colors = plt.get_cmap("viridis")(np.linspace(0.0, 0.85, len(levels)))
    for ax, (label, params) in zip(axes.flat, panels):
        ys = [curve(params, {secondary: level, **others}) for level in levels]
        finite = np.concatenate([y[np.isfinite(y)] for y in ys]) if ys else np.array([0.0])
        scale = float(np.max(np.abs(finite))) if finite.size else 1.0
        same = all(np.allclose(y, ys[0], rtol=1e-9, atol=1e-12 * max(scale, 1.0),
                               equal_nan=True) for y in ys[1:])
        if same:
            ax.plot(x_disp, ys[0], color=colors[0], lw=2,
                    label=f"any {secondary} (no effect with these values)")
        else:
            for y, level, color in zip(ys, levels, colors):
                ax.plot(x_disp, y, color=color, lw=2, label=_fmt_var_value(secondary, level))
        shaded = _shade_domain(ax, law, primary, x_disp)
        title = f"preset '{label}'" if law.presets else "default parameters"
        if others:
            title += "; " + ", ".join(_fmt_var_value(k, v) for k, v in others.items())
        ax.set_title(title, fontsize="small")
        if shaded:
            ax.plot([], [], color="0.85", lw=8, label="outside domain")
        _finish(ax, law, primary, log)
        ax.legend(fontsize="x-small")
    for ax in axes.flat[len(panels):]:
        ax.set_visible(False)
    fig.suptitle(law.title, fontsize="medium")
    return fig


def _finish(ax: Any, law: Any, primary: str, log: bool) -> None:
    """Axis scale, labels, grid; μ axis from zero when the law is non-negative there."""
    ax.set_xscale("log" if log else "linear")
    ax.set_xlabel(_label(primary))
    ax.set_ylabel("friction coefficient μ [–]")
    ax.grid(True, alpha=0.3)
    data = [np.asarray(line.get_ydata(), float) for line in ax.get_lines()]
    data = [d[np.isfinite(d)] for d in data if d.size]
    data = [d for d in data if d.size]
    if data and min(float(d.min()) for d in data) >= 0.0:
        ax.set_ylim(bottom=0.0, top=max(ax.get_ylim()[1], 1e-3))


def _figure_png(law: Any) -> bytes:
    import matplotlib.pyplot as plt

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # extrapolation warnings are the point of the shading
        with np.errstate(all="ignore"):
            fig = law_figure(law)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110, metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()


# ---------------------------------------------------------- the catalogue


def _page_name(law_id: str) -> str:
    return re.sub(r"[^a-z0-9_.-]+", "-", law_id.lower())


def law_page(law: Any, image: str | None = None) -> str:
    """The reStructuredText page of one law, from its declaration."""
    lines: list[str] = [f".. _law-{_page_name(law.id)}:", "", _heading(law.title, "=")]
    meta = [f"**id** ``{law.id}``", f"**family** {law.family}"]
    if law.aliases:
        meta.append("**aliases** " + ", ".join(f"``{a}``" for a in law.aliases))
    if law.variables:
        meta.append("**variables** " + ", ".join(_variable_entry(law, v) for v in law.variables))
    else:
        meta.append("**variables** none (constant)")
    meta.append(f"**evidence** {escape(law.evidence)}")
    lines += ["| " + "  ·  ".join(meta), ""]
    if law.description:
        lines += [escape(law.description), ""]
    lines += [".. math::", "", "   " + law_latex(law), ""]
    if law.floors:
        lines += ["Floors applied before the formula: " + ", ".join(
            f"{k} ≥ {_num(v)} {_var_info(k)[1]}".rstrip() for k, v in law.floors.items())
            + ("; the sliding velocity enters as ``|v|``." if "v" in law.variables else "."),
            ""]
    if image:
        lines += [f".. figure:: {image}", f"   :alt: {law.id} over its typical range",
                  "   :class: fl-law-plot", "",
                  "   " + escape(_caption(law)), ""]

    lines += [_heading("Parameters", "-")]
    rows = []
    for p in law.params:
        lo, hi = p.bounds
        rows.append([f"``{p.name}``", _unit(p.unit), _num(p.default),
                     f"[{_num(lo)}, {_num(hi)}]",
                     escape(p.meaning) + (" *(optional)*" if p.optional else "")])
    lines += [_list_table(["name", "unit", "default", "bounds", "meaning"], rows,
                          [12, 14, 12, 18, 44])]
    if law.settings:
        lines += [_heading("Settings (fixed)", "-"),
                  "Reference scales held fixed in a fit unless freed "
                  "(``fit(..., free=[...])`` or ``--free``).", ""]
        rows = [[f"``{s.name}``", _unit(s.unit), _num(s.value), escape(s.meaning)]
                for s in law.settings]
        lines += [_list_table(["name", "unit", "value", "meaning"], rows, [14, 14, 14, 58])]
    if law.presets:
        names = list(law.param_names) + [s.name for s in law.settings
                                         if any(s.name in pr for pr in law.presets.values())]
        lines += [_heading("Presets", "-")]
        rows = [[f"``{name}``"] + [_num(pr[k]) if k in pr else "" for k in names]
                for name, pr in law.presets.items()]
        lines += [_list_table(["preset"] + [f"``{k}``" for k in names], rows)]
        if law.derived:
            rows = []
            for name in law.presets:
                vals = law.derived_values(law.resolve(preset=name))
                rows.append([f"``{name}``"] + [_num(vals[d.name]) for d in law.derived])
            lines += ["Derived quantities of the presets:", "",
                      _list_table(["preset"] + [f"``{d.name}``" for d in law.derived], rows)]
    if law.derived:
        lines += [_heading("Derived quantities", "-")]
        rows = [[f"``{d.name}``", _unit(d.unit), escape(d.meaning)] for d in law.derived]
        lines += [_list_table(["name", "unit", "meaning"], rows, [18, 14, 68])]
    lines += [_heading("Domain", "-")]
    if law.domain:
        rows = []
        for k, (lo, hi) in law.domain.items():
            (lo_d, hi_d), unit = _to_display(k, np.array([lo, hi], float))
            unit = {"degC": "°C"}.get(unit, unit)
            rows.append([f"``{k}``", f"{_num(lo)} .. {_num(hi)} {_var_info(k)[1]}".rstrip(),
                         f"{_num(lo_d)} .. {_num(hi_d)} {unit}".rstrip()])
        lines += ["Outside these ranges the law is an extrapolation (fits and exports warn).",
                  "", _list_table(["variable", "SI", "display units"], rows)]
    else:
        lines += ["No domain declared: the law is not tied to a measured box.", ""]
    typical = []
    for v in law.variables:
        lo, hi = law.typical_range(v)
        (lo_d, hi_d), unit = _to_display(v, np.array([lo, hi], float))
        unit = {"degC": "°C"}.get(unit, unit)
        typical.append(f"{v} {_num(lo_d)} .. {_num(hi_d)} {unit}".rstrip())
    if typical:
        lines += ["Typical range (plots and tables): " + ", ".join(typical) + ".", ""]
    if law.notes:
        lines += [_heading("Notes", "-"), escape(law.notes), ""]
    lines += [_heading("Evidence", "-"), f"Tag: **{escape(law.evidence)}**", ""]
    lines += [f"- {e}" for e in _evidence_lines(law.evidence)] + [""]
    if law.references:
        lines += [_heading("References", "-")]
        lines += [f"#. {escape(r)}" for r in law.references] + [""]
    lines += [_heading("Use it", "-"), ".. code-block:: console", "",
              f"   $ frictionlaws show {law.id}", ""]
    example_params = ("preset=" + repr(next(iter(law.presets)))) if law.presets else ", ".join(
        f"{p.name}={_pylit(p.default)}" for p in law.params if not p.optional)
    vars_ = ", ".join(f"{v}={_pylit(_mid(law, v))}" for v in law.variables)
    call = ", ".join(x for x in (vars_, example_params) if x)
    lines += [".. code-block:: python", "", "   import frictionlaws as fl", "",
              f"   law = fl.get_law({law.id!r})", f"   mu = law({call})", ""]
    return "\n".join(lines)


def _x_variable(law: Any) -> str | None:
    """The variable on the x axis of the catalogue plot (None for a constant law)."""
    if not law.variables:
        return None
    return law.variables[0] if len(law.variables) == 1 else _primary(law)


def _shaded(law: Any) -> bool:
    """Whether the catalogue plot shades part of its x axis as outside the domain."""
    x = _x_variable(law)
    if x is None or x not in law.domain:
        return False
    lo, hi = (float(v) for v in law.domain[x])
    t_lo, t_hi = _plot_range(law, x)
    return lo > t_lo or hi < t_hi


def _caption(law: Any) -> str:
    what = "the presets" if law.presets else "the default parameters"
    x = _x_variable(law)
    if x is not None and x in law.domain and x not in law.typical and _shaded(law):
        return (f"{law.title} over its domain and beyond, for {what}. The shaded band lies "
                "outside the declared domain: there the law is an extrapolation.")
    shade = " The shaded band lies outside the declared domain." if _shaded(law) else ""
    return f"{law.title} over its typical range, for {what}.{shade}"


def _index_page(laws: Sequence[Any]) -> str:
    from frictionlaws.law import EVIDENCE_TAGS

    lines = [".. _law-catalogue:", "", _heading("Law catalogue", "="),
             "Every law registered in frictionlaws, generated from its declaration each "
             "time the documentation is built: the formula comes from the law's symbolic "
             "form, the tables from its parameters, settings and presets, and the plot "
             "from evaluating it over its typical range. "
             f"This build lists **{len(laws)} laws**.", "",
             "Evidence tags: " + "; ".join(f"**{k}** {v}" for k, v in EVIDENCE_TAGS.items())
             + ".", ""]
    families = {"sliding": "Sliding-velocity laws (rubber, tribometer)",
                "slip": "Slip-ratio laws (tyre, rolling wheel)"}
    for family, title in families.items():
        members = [law for law in laws if law.family == family]
        if not members:
            continue
        lines += [_heading(title, "-")]
        rows = [[f":ref:`{law.id} <law-{_page_name(law.id)}>`", escape(law.title),
                 ", ".join(law.variables) or "–", str(len(law.params)),
                 escape(law.evidence)] for law in members]
        lines += [_list_table(["id", "law", "variables", "k", "evidence"], rows,
                              [18, 40, 12, 5, 25])]
    lines += [".. toctree::", "   :hidden:", ""]
    lines += [f"   {_page_name(law.id)}" for law in laws] + [""]
    return "\n".join(lines)


def write_catalogue(outdir: str | Path, laws: Sequence[Any] | None = None,
                    plots: bool = True) -> list[str]:
    """Write the catalogue (index, one page and one plot per law) into ``outdir``.

    Returns the law ids written.  A law that fails to render raises
    :class:`RuntimeError` naming it.
    """
    from frictionlaws.law.registry import list_laws

    outdir = Path(outdir)
    laws = list(list_laws() if laws is None else laws)
    written = []
    for law in laws:
        name = _page_name(law.id)
        try:
            image = None
            if plots:
                _write_if_changed(outdir / f"{name}.png", _figure_png(law))
                image = f"{name}.png"
            _write_if_changed(outdir / f"{name}.rst", law_page(law, image))
        except Exception as exc:
            raise RuntimeError(f"law catalogue: cannot render law '{law.id}': "
                               f"{type(exc).__name__}: {exc}") from exc
        written.append(law.id)
    _write_if_changed(outdir / "index.rst", _index_page(laws))
    keep = {f"{_page_name(i)}{ext}" for i in written for ext in (".rst", ".png")} | {"index.rst"}
    for stale in outdir.iterdir():
        if stale.name not in keep:
            stale.unlink()
    return written


def check_catalogue(outdir: str | Path) -> list[str]:
    """Registered law ids missing from the catalogue in ``outdir`` (empty when complete)."""
    from frictionlaws.law.registry import list_laws

    outdir = Path(outdir)
    index = (outdir / "index.rst").read_text(encoding="utf-8") if (
        outdir / "index.rst").exists() else ""
    missing = []
    for law in list_laws():
        name = _page_name(law.id)
        page = outdir / f"{name}.rst"
        if (f"<law-{name}>`" not in index or not page.exists()
                or f"``{law.id}``" not in page.read_text(encoding="utf-8")):
            missing.append(law.id)
    return missing


# -------------------------------------------------------- the CLI reference


def _subparsers(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices)
    return {}


def _help_text(parser: argparse.ArgumentParser) -> str:
    old = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = str(CLI_COLUMNS)
    try:
        return parser.format_help()
    finally:
        if old is None:
            os.environ.pop("COLUMNS", None)
        else:
            os.environ["COLUMNS"] = old


def _indent(text: str, n: int = 3) -> str:
    return "\n".join((" " * n + line) if line.strip() else "" for line in text.splitlines())


def cli_reference() -> str:
    """The CLI reference page, generated from :func:`frictionlaws.cli.build_parser`."""
    from frictionlaws.cli import build_parser, main

    parser = build_parser()
    subs = _subparsers(parser)
    help_of = {}
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            help_of = {a.dest: a.help for a in action._choices_actions}
    doc = " ".join((main.__doc__ or "").split())
    lines = [".. _cli-reference:", "", _heading("Command-line reference", "="),
             "Generated from the argument parser of the installed package "
             "(``frictionlaws.cli.build_parser()``) when the documentation is built, so it "
             "always matches ``frictionlaws COMMAND --help``.", ""]
    exit_doc = (importlib.import_module("frictionlaws.cli").__doc__ or "")
    m = re.search(r"Exit codes:(.*?)(?:\n\s*\n|$)", exit_doc, re.S)
    if m:
        lines += ["**Exit codes:** " + " ".join(m.group(1).split()), ""]
    elif doc:
        lines += [escape(doc), ""]
    rows = [[f":ref:`{name} <cli-{name}>`", escape(help_of.get(name) or "")]
            for name in subs]
    lines += [_list_table(["command", "what it does"], rows, [20, 80])]
    lines += [_heading("frictionlaws", "-"), *_options_block("frictionlaws", parser)]
    for name, sub in subs.items():
        lines += _command_section(name, sub, help_of.get(name), "-")
    return "\n".join(lines)


def _command_section(name: str, parser: argparse.ArgumentParser, help_text: str | None,
                     level: str) -> list[str]:
    """The section of one command, with a subsection per nested sub-command."""
    anchor = name.replace(" ", "-")
    lines = [f".. _cli-{anchor}:", "", _heading(f"frictionlaws {name}", level)]
    if help_text:
        lines += [escape(help_text[:1].upper() + help_text[1:]) + ".", ""]
    lines += _options_block(f"frictionlaws {name}", parser)
    nested = _subparsers(parser)
    if nested:
        helps = {}
        for action in parser._actions:
            if isinstance(action, argparse._SubParsersAction):
                helps = {a.dest: a.help for a in action._choices_actions}
        for sub_name, sub in nested.items():
            lines += _command_section(f"{name} {sub_name}", sub, helps.get(sub_name), "~")
    return lines


def _usage(parser: argparse.ArgumentParser) -> str:
    old = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = str(CLI_COLUMNS)
    try:
        return parser.format_usage()
    finally:
        if old is None:
            os.environ.pop("COLUMNS", None)
        else:
            os.environ["COLUMNS"] = old


def _option_help(parser: argparse.ArgumentParser, action: argparse.Action) -> str:
    """An action's help with argparse's ``%(default)s`` expanded, and its choices."""
    text = parser._get_formatter()._expand_help(action) if action.help else ""
    if action.choices and not isinstance(action, argparse._SubParsersAction):
        text += f" (choices: {', '.join(map(str, action.choices))})"
    return escape(" ".join(text.split())) or "(no description)"


def _option_name(action: argparse.Action) -> str:
    """The ``.. option::`` signature: every flag with its metavar, or the positional."""
    if not action.option_strings:
        return str(action.metavar or action.dest)
    if action.nargs == 0:
        return ", ".join(action.option_strings)
    metavar = action.metavar or action.dest.upper()
    return ", ".join(f"{flag} {metavar}" for flag in action.option_strings)


def _options_block(program: str, parser: argparse.ArgumentParser) -> list[str]:
    """Usage, description and one ``.. option::`` (an anchor each) per argument."""
    lines = [".. code-block:: text", "", _indent(_usage(parser)), ""]
    if parser.description:
        lines += [escape(" ".join(parser.description.split())), ""]
    lines += [f".. program:: {program}", ""]
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction) or action.help == argparse.SUPPRESS:
            continue
        lines += [f".. option:: {_option_name(action)}", "",
                  _indent(_option_help(parser, action)), ""]
    return lines


def export_formats_table() -> str:
    """The docs' table of export formats, from the library's one table of them."""
    from frictionlaws.fe_export.formats import FORMATS

    def options(fmt: Any) -> str:
        return "; ".join(f"``{o.name}``: {escape(o.meaning)}, {o.lo}..{o.hi}, default "
                         f"{o.default}" for o in fmt.options)

    return _list_table(("format", "what is written", "options"),
                       ((f"``{name}``", f.description + ("" if f.needs_box
                                                         else " (no ranges needed)"),
                         options(f)) for name, f in FORMATS.items()), (18, 56, 26))


def write_export_formats(path: str | Path) -> list[str]:
    """Write the table of export formats to ``path``; return the formats listed."""
    from frictionlaws.fe_export.formats import FORMATS

    _write_if_changed(Path(path), export_formats_table())
    return list(FORMATS)


def write_cli_reference(path: str | Path) -> list[str]:
    """Write the CLI reference to ``path``; return the command names documented."""
    from frictionlaws.cli import build_parser

    _write_if_changed(Path(path), cli_reference())
    return list(_subparsers(build_parser()))


# -------------------------------------------------------- the API reference

#: Modules left out of the API reference (documented elsewhere).
_API_SKIP = re.compile(r"(^|\.)_|^frictionlaws\.cli\.cmd_")


def public_modules() -> list[str]:
    """Public modules of the installed package (no ``_private`` ones, no CLI commands)."""
    import frictionlaws

    names = []
    for info in pkgutil.walk_packages(frictionlaws.__path__, "frictionlaws."):
        if _API_SKIP.search(info.name):
            continue
        names.append(info.name)
    return sorted(names)


def _first_line(module: Any) -> str:
    doc = (module.__doc__ or "").strip()
    return escape(doc.split("\n\n")[0]) if doc else ""


_DATA_TYPES = (int, float, complex, str, bytes, tuple, list, dict, set, frozenset)


def _assigns(module: Any, name: str) -> bool:
    """True when the source of ``module`` assigns ``name`` at top level."""
    import inspect

    try:
        source = inspect.getsource(module)
    except (OSError, TypeError):
        return False
    return re.search(rf"^{re.escape(name)}\s*(:[^=\n]*)?=(?!=)", source, re.M) is not None


def _home(module: Any, name: str) -> str:
    """The module that defines ``module.name`` (data objects: the one that assigns it)."""
    obj = getattr(module, name, None)
    home = getattr(obj, "__module__", None)
    if isinstance(home, str) and not isinstance(obj, _DATA_TYPES):
        return home
    if _assigns(module, name):
        return module.__name__
    prefix = module.__name__ + "."
    for other in public_modules():
        if other.startswith(prefix):
            sub = importlib.import_module(other)
            if vars(sub).get(name) is obj and _assigns(sub, name):
                return other
    return module.__name__


def _own_members(module: Any) -> list[str] | None:
    """Names of ``module.__all__`` defined in the module itself (None without ``__all__``).

    Re-exported names are documented once, on the page of the module that
    defines them; the package page links to them instead.
    """
    names = getattr(module, "__all__", None)
    if names is None:
        return None
    return [name for name in names if _home(module, name) == module.__name__]


def _reexports(module: Any) -> list[tuple[str, str]]:
    out = []
    for name in getattr(module, "__all__", None) or ():
        home = _home(module, name)
        if home != module.__name__ and home.startswith("frictionlaws"):
            obj = getattr(module, name, None)
            qual = getattr(obj, "__qualname__", name) if not isinstance(
                obj, _DATA_TYPES) else name
            out.append((name, f"{home}.{qual}"))
    return out


def write_api_reference(outdir: str | Path) -> list[str]:
    """Write ``index.rst`` and one autodoc page per public module into ``outdir``."""
    import frictionlaws

    outdir = Path(outdir)
    modules = public_modules()
    rows = []
    for name in modules:
        module = importlib.import_module(name)
        title = f"``{name}``"
        page = [f".. _api-{name}:", "", _heading(title, "="), f".. automodule:: {name}"]
        own = _own_members(module)
        if own is None:
            page += ["   :members:"]
        elif own:
            page += ["   :members: " + ", ".join(own)]
        else:
            page += ["   :no-members:"]
        page += ["   :show-inheritance:", ""]
        reexports = _reexports(module)
        if reexports:
            page += [_heading("Also available here", "-"),
                     f"Imported into ``{name}`` for convenience; documented where they are "
                     "defined.", "",
                     _list_table(["name", "defined as"],
                                 [[f"``{n}``", f":py:obj:`{target}`"] for n, target in reexports],
                                 [30, 70])]
        _write_if_changed(outdir / f"{name}.rst", "\n".join(page))
        rows.append([f":doc:`{name} <{name}>`", _first_line(module)])
    api_rows = []
    for public, module in sorted(frictionlaws._API.items()):
        api_rows.append([f"``fl.{public}``", f":py:obj:`frictionlaws.{module}.{public}`"])
    index = [".. _api-reference:", "", _heading("Module reference", "="),
             "Every module of the package, generated with autodoc from the numpydoc "
             "docstrings of the installed package; the :doc:`public API </api>` page groups "
             "what a user calls by task. Everything is SI inside: p in Pa, v in m/s, T in K, "
             "F_N in N, s dimensionless.", "",
             _heading("Top-level names", "-"),
             "``import frictionlaws as fl`` gives these names; they are imported lazily so "
             "that ``import frictionlaws`` and the command line stay fast.", "",
             _list_table(["name", "defined as"], api_rows, [30, 70]),
             _heading("Modules", "-"),
             _list_table(["module", "summary"], rows, [30, 70]),
             ".. toctree::", "   :hidden:", ""]
    index += [f"   {name}" for name in modules] + [""]
    _write_if_changed(outdir / "index.rst", "\n".join(index))
    keep = {f"{m}.rst" for m in modules} | {"index.rst"}
    for stale in outdir.glob("*.rst"):
        if stale.name not in keep:
            stale.unlink()
    return modules


# ------------------------------------------------------ captured CLI output

#: Commands whose real output the getting-started page shows (file name -> argv).
SHELL_SESSIONS = {
    "first_fit.txt": ["fit", "--law", "thirion", "thesis-steel"],
    "laws.txt": ["laws"],
}


def shell_session(argv: Sequence[str]) -> str:
    """``$ frictionlaws ARGS`` followed by what the command prints; raises on failure."""
    import contextlib

    from frictionlaws.cli import main

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(list(argv))
    if code != 0:
        raise RuntimeError(f"'frictionlaws {' '.join(argv)}' exited with {code}: "
                           f"{err.getvalue().strip()}")
    return f"$ frictionlaws {' '.join(argv)}\n{out.getvalue().rstrip()}\n"


def write_shell_sessions(outdir: str | Path) -> list[str]:
    """Run :data:`SHELL_SESSIONS` and write their transcripts into ``outdir``."""
    outdir = Path(outdir)
    for name, argv in SHELL_SESSIONS.items():
        _write_if_changed(outdir / name, shell_session(argv))
    return list(SHELL_SESSIONS)


# ------------------------------------------------- docstrings as reStructuredText

_PROTECTED = re.compile(r"(``.+?``|:math:`[^`]*`|`[^`]*`_{0,2})")


def escape_bars(lines: list[str]) -> None:
    """Escape ``|x|`` (absolute values) in docstring prose, in place.

    Docstrings here use ``|v|`` for a magnitude, which reStructuredText would
    read as a substitution reference.  Bars inside inline literals, roles,
    math blocks, literal blocks and table borders are left alone.
    """
    in_block = None  # indentation of the directive/literal block being skipped
    for i, line in enumerate(lines):
        stripped = line.lstrip()
        indent = len(line) - len(stripped)
        if in_block is not None:
            if stripped and indent <= in_block:
                in_block = None
            else:
                continue
        if stripped.startswith(".. ") or line.rstrip().endswith("::"):
            in_block = indent
            continue
        if "|" not in line or stripped.startswith(("|", "+-", "+=")):
            continue
        parts = _PROTECTED.split(line)
        for k in range(0, len(parts), 2):
            parts[k] = re.sub(r"(?<!\\)\|", r"\\|", parts[k])
        lines[i] = "".join(parts)


def _process_docstring(app: Any, what: str, name: str, obj: Any, options: Any,
                       lines: list[str]) -> None:
    escape_bars(lines)


# ------------------------------------------------------- the README's commands


def readme_commands(readme: str | Path) -> list[str]:
    """The two set-up commands of the README (the bash blocks of its "Set-up" section).

    Raises
    ------
    RuntimeError
        When the section or its two commands cannot be found.
    """
    text = Path(readme).read_text(encoding="utf-8")
    parts = re.split(r"^## +Set-up\b.*$", text, maxsplit=1, flags=re.M)
    if len(parts) != 2:
        raise RuntimeError(f"{readme}: no '## Set-up' section with the two commands")
    section = re.split(r"^## ", parts[1], maxsplit=1, flags=re.M)[0]
    blocks = [b.strip() for b in re.findall(r"```(?:bash|sh|console)?\n(.*?)```", section, re.S)]
    if len(blocks) != 2:
        raise RuntimeError(f"{readme}: the Set-up section has {len(blocks)} command blocks, "
                           "expected 2")
    return blocks


def write_readme_commands(readme: str | Path, outdir: str | Path) -> list[str]:
    """Write the README's two commands to ``setup_1.txt`` and ``setup_2.txt`` in ``outdir``."""
    commands = readme_commands(readme)
    for i, command in enumerate(commands, 1):
        _write_if_changed(Path(outdir) / f"setup_{i}.txt", command + "\n")
    return commands


# ------------------------------------------------------------------- Sphinx


def _generate(app: Any) -> None:
    from sphinx.errors import ExtensionError
    from sphinx.util import logging

    log = logging.getLogger(__name__)
    gen = Path(app.srcdir) / "generated"
    try:
        ids = write_catalogue(gen / "catalogue")
    except RuntimeError as exc:
        raise ExtensionError(str(exc)) from exc
    missing = check_catalogue(gen / "catalogue")
    if missing:
        raise ExtensionError(f"law catalogue is missing registered law(s): {', '.join(missing)}")
    commands = write_cli_reference(gen / "cli.rst")
    write_export_formats(gen / "export-formats.rst")
    from fl_mf_coefficients import write_mf_coefficients

    write_mf_coefficients(gen / "mf-coefficients.rst")
    modules = write_api_reference(gen / "api")
    try:
        write_shell_sessions(gen / "shell")
        write_readme_commands(Path(app.srcdir).parent / "README.md", gen / "shell")
    except RuntimeError as exc:
        raise ExtensionError(str(exc)) from exc
    log.info(f"[fl_docgen] catalogue: {len(ids)} laws; CLI: {len(commands)} commands; "
             f"API: {len(modules)} modules")


def setup(app: Any) -> dict[str, Any]:
    app.connect("builder-inited", _generate)
    app.connect("autodoc-process-docstring", _process_docstring, priority=900)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}


# ------------------------------------------------------------ gallery order

#: The gallery's sections (sub-folders of ``examples/``), in reading order.
GALLERY_SECTIONS = ("fitting", "export", "tribometer", "physics", "tyres")

#: Within a section, the examples to read first, in order; others follow by file name.
GALLERY_FIRST = (
    "plot_sliding_laws_thesis_steel.py",
    "plot_compare_laws.py",
    "plot_identifiability_nackenhorst.py",
    "plot_campaign_shared_parameters.py",
    "plot_thesis_polynomials_outside_box.py",
    "plot_wlf_shift.py",
    "plot_brush_cornering_stiffness.py",
)


class GalleryOrder:
    """sphinx-gallery's ``within_subsection_order``: :data:`GALLERY_FIRST`, then by name."""

    def __init__(self, src_dir: str) -> None:
        self.src_dir = src_dir

    def __call__(self, filename: str) -> tuple[int, str]:
        name = Path(filename).name
        rank = GALLERY_FIRST.index(name) if name in GALLERY_FIRST else len(GALLERY_FIRST)
        return rank, name

    def __repr__(self) -> str:  # sphinx-gallery compares configurations by their repr
        return f"GalleryOrder({GALLERY_FIRST!r})"
