"""The report's documents: ``report.md`` and ``report.html`` with their tables and figures, and
:func:`write_report`, which writes them with ``comparison.json`` and the PNG files.
"""

from __future__ import annotations

import base64
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ...base.errors import InputError
from ...base.sanitize import html_text, markdown_text
from ..residuals import ALPHA

if TYPE_CHECKING:  # pragma: no cover
    from ..record import ComparisonRecord

from ...base.outputs import atomic_dir
from .figures import Figure, _flagged, _test_p, make_figures
from .text import UNDETERMINED, _legend, _num, _ranges_text, _score, _yes

__all__ = ["RESIDUAL_TESTS_NOTE", "to_markdown", "to_html", "write_report"]


def _metric_table(cmp: ComparisonRecord) -> tuple[list[str], list[list[str]]]:
    head = ["rank", "law", "title", "k", "n", "R²", "adj. R²", "RMSE", "MAE", "max |res|",
            "AIC", "AICc", "BIC", "group", "Akaike w. (in group)", "CV RMSE",
            "CV RMSE (common rows)", "extrap. RMSE", "identifiable", "plausible", "residuals",
            "rank basis"]
    rows = []
    for r in cmp.results:
        m = r.metrics
        rows.append([str(r.rank), r.law.id, r.law.title, str(m["k"]), str(m["n"]),
                     _num(m["r2"], ".4f"), _num(m["adj_r2"], ".4f"), _num(m["rmse"], ".4f"),
                     _num(m["mae"], ".4f"), _num(m["max_abs_residual"], ".4f"),
                     _num(m["aic"], ".2f"), _num(m["aicc"], ".2f"), _num(m["bic"], ".2f"),
                     str(r.aic_group), _num(r.akaike_weight, ".3f"),
                     _score(r, "cv_rmse").replace("*", " *"),
                     _score(r, "cv_rmse_common").replace("*", " *"),
                     _score(r, "extrapolation_rmse"),
                     "NO" if r.fit.non_identifiable else "yes", _yes(r),
                     "structure" if r.residuals.structured else "ok", r.rank_basis])
    return head, rows


def _sections(cmp: ComparisonRecord) -> list[tuple[str, list[Any]]]:
    """(heading, items) for the prose parts; an item is a str or (str, sub-items)."""
    out: list[tuple[str, list[Any]]] = []
    plaus: list[Any] = []
    for r in cmp.results:
        if r.plausible:
            plaus.append(f"{r.law.id}: plausible (mu {_num(r.plausibility.mu_min)} .. "
                         f"{_num(r.plausibility.mu_max)} over the box)")
        else:
            plaus.append((f"{r.law.id}: IMPLAUSIBLE", list(r.plausibility.reasons)))
    out.append(("Plausibility outside the measured range", plaus))
    out.append(("Trends the data show", [t.describe() for t in cmp.trends.values()]))
    ex = []
    for r in cmp.results:
        parts = [f"{h.variable}: {h.error}" if h.error is not None else
                 f"{h.variable}: RMSE {UNDETERMINED} ({h.n_undetermined} of {h.n_test} "
                 f"held-out predictions undetermined; fitted on {h.n_train})"
                 if h.n_undetermined else
                 f"{h.variable}: implausible: {h.implausible} (fitted on {h.n_train})"
                 if h.implausible else
                 f"{h.variable}: RMSE {_num(h.rmse, '.4f')} on {h.n_test} held-out rows "
                 f"(fitted on {h.n_train})" for h in r.holdouts]
        ex.append(f"{r.law.id}: " + ("; ".join(parts) or "no holdout"))
    out.append(("Extrapolation to the held-out upper range", ex))
    cv = []
    for r in cmp.results:
        failed = {x["fold"] for x in r.cv.failed}
        und = {x["fold"] for x in r.cv.undetermined if x.get("n_undetermined")}
        folds = ", ".join(_num(f, ".3f") if f is not None else "failed" if i + 1 in failed
                          else UNDETERMINED if i + 1 in und else "no rows"
                          for i, f in enumerate(r.cv.fold_rmse))
        cv.append(f"{r.law.id}: CV RMSE {_score(r, 'cv_rmse').rstrip('*')} over "
                  f"{r.cv.n_scored} rows; "
                  f"per fold {folds}" + ("" if r.cv.complete else
                                         f"; {len(r.cv.failed)} fold(s) failed"))
    out.append(("Cross-validation", cv))
    struct: list[Any] = [(r.law.id, list(r.residuals.structure)) for r in cmp.results
                         if r.residuals.structure]
    out.append(("Residual structure (each test at the 5 % level)",
                struct or ["no law shows residual structure at the 5 % level"]))
    warn: list[Any] = [(r.law.id, list(r.fit.warnings)) for r in cmp.results if r.fit.warnings]
    out.append(("Fit warnings (identifiability, bounds)", warn or ["none"]))
    notes: list[Any] = list(cmp.data.notes) + list(cmp.notes)
    notes += [(r.law.id, r.notes + r.extra_notes) for r in cmp.results
              if r.notes or r.extra_notes]
    out.append(("Notes (dropped rows, failed folds)", notes or ["none"]))
    out.append(("Skipped laws (cannot be fitted to these data)",
                [f"{s['id']}: {s['reason']}" for s in cmp.skipped] or ["none"]))
    out.append(("Laws that failed to fit",
                [f"{f['id']}: {f['error']}" for f in cmp.failed] or ["none"]))
    return out


def _method(cmp: ComparisonRecord) -> list[str]:
    s = cmp.settings
    box = "; ".join(f"{k} {v['display']}" for k, v in s["extended_box"].items())
    hold = "; ".join(sp.describe() for sp in cmp.splits) or "none"
    return [
        f"Ranking: {s['ranking']}.",
        f"Cross-validation: {s['folds']} folds, rows shuffled with seed {s['seed']}; the same "
        "folds for every law; each fold refitted from the law's own data-driven start.",
        f"Extrapolation: {s['holdout_rule']}. Splits: {hold}.",
        f"Plausibility box: {box} ({s['extended_box_rule']}); physical limits "
        f"{s['mu_limits'][0]:g} <= mu <= {s['mu_limits'][1]:g}; {s['trend_rule']} "
        f"({s['trend_tolerance']['relative']:.0%} of mu, at least "
        f"{s['trend_tolerance']['absolute']:g}).",
        f"Akaike weights: {s['akaike_weights']}.",
        f"Residual tests: {s['residual_tests']}.",
        "RMSE, MAE, CV RMSE and extrapolation RMSE are in units of mu (dimensionless, -).",
    ]


RESIDUAL_TESTS_NOTE = (
    "One-sided Wald-Wolfowitz runs test on the signs of the residuals put in order of each "
    "variable and of the fitted value (small p: residuals of one sign cluster, a systematic "
    "misfit), Kendall's tau test of a monotone trend, and the Shapiro-Wilk test of "
    f"normal-looking residuals; each at the {ALPHA * 100:g} % level on its own. Marked: p < "
    f"{ALPHA:g} (a red band in the residuals figure). n/a: the test does not apply (a "
    "constant variable, or residuals all of one sign).")


def _residual_table(cmp: ComparisonRecord) -> tuple[list[str], list[list[tuple[str, bool]]]]:
    """Every residual test's p-value per law: header, rows of (text, below ALPHA)."""
    cols = [*cmp.design.varying, "fitted"]
    head = ["law"]
    for c in cols:
        name = "fitted mu" if c == "fitted" else c
        head += [f"runs p ({name})", f"Kendall p ({name})"]
    head.append("Shapiro-Wilk p")
    rows = []
    for r in cmp.results:
        ps = [p for c in cols for p in _test_p(r, c).values()] + [r.residuals.shapiro_p]
        rows.append([(f"{r.rank}. {r.law.id}", False)]
                    + [(_num(p, ".2g"), _flagged(p)) for p in ps])
    return head, rows


def _md_residual_tests(cmp: ComparisonRecord) -> list[str]:
    """The table of residual-test p-values in Markdown, the flagged ones in bold."""
    head, rows = _residual_table(cmp)
    lines = ["## Residual tests (p-values)", "", RESIDUAL_TESTS_NOTE, "",
             "| " + " | ".join(head) + " |", "|" + "|".join("---" for _ in head) + "|"]
    return lines + ["| " + " | ".join(f"**{markdown_text(t)}**" if bad else markdown_text(t)
                                      for t, bad in row) + " |" for row in rows]


def to_markdown(cmp: ComparisonRecord, figures: Sequence[Figure]) -> str:
    """The report as Markdown, linking the PNG files."""
    d = cmp.data
    esc = markdown_text  # every text from data, files or laws: one line, HTML escaped

    lines = [f"# Comparison of friction laws on {esc(d.name)}", "",
             f"Data: {esc(d.name)} ({esc(d.source)}), {d.n} rows; {esc(_ranges_text(cmp))}.",
             ""]
    lines += [f"- {esc(m)}" for m in _method(cmp)] + [""]
    head, rows = _metric_table(cmp)
    lines += ["## Ranking", "", "| " + " | ".join(esc(h) for h in head) + " |",
              "|" + "|".join("---" for _ in head) + "|"]
    lines += ["| " + " | ".join(esc(c) for c in r) + " |" for r in rows]
    lines += ["", "`*` cross-validation incomplete. Groups: laws fitted to the same rows; "
              "AIC-based numbers compare within a group only.", ""]
    lines += [f"- {esc(t)}" for t in _legend(cmp)] + [""]
    for heading, items in _sections(cmp):
        lines += [f"## {heading}", ""]
        for item in items:
            if isinstance(item, tuple):
                lines.append(f"- {esc(item[0])}")
                lines += [f"    - {esc(sub)}" for sub in item[1]]
            else:
                lines.append(f"- {esc(item)}")
        lines.append("")
    lines += _md_residual_tests(cmp) + ["", "## Figures", ""]
    for f in figures:
        lines += [f"### {esc(f.title)}", "", f"![{esc(f.title)}]({esc(f.name)}.png)", "",
                  esc(f.caption), ""]
    return "\n".join(lines)


_CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Helvetica,Arial,sans-serif;margin:2em;
color:#222;max-width:1400px}
table{border-collapse:collapse;font-size:13px;margin:1em 0}
th,td{border:1px solid #ccc;padding:3px 5px;text-align:right}
td.l,th.l{text-align:left}
td.law{min-width:13em;max-width:19em}
span.title{font-size:11px;color:#555}
tr.bad td{background:#fff0f0}
th{background:#f3f3f3}
.bad-word{color:#b00;font-weight:bold}
figure{margin:1.5em 0}
figure img{max-width:100%;border:1px solid #ddd}
figcaption{font-size:13px;color:#444;max-width:1100px}
li{margin:0.2em 0}
"""


def _html_ranking(cmp: ComparisonRecord) -> list[str]:
    """The ranking table in HTML; each law's title under its id."""
    e = html_text
    head, rows = _metric_table(cmp)
    # the title goes under the law id (a separate column makes the table too wide)
    skip = head.index("title")
    parts = ["<table><tr>" + "".join(f"<th class='{'l' if h == 'law' else ''}'>{e(h)}</th>"
                                     for i, h in enumerate(head) if i != skip) + "</tr>"]
    for r, row in zip(cmp.results, rows):
        cells = []
        for i, c in enumerate(row):
            if i == skip:
                continue
            text, cls_td = e(c), ""
            if head[i] in ("plausible", "identifiable") and c == "NO":
                text = "<span class='bad-word'>NO</span>"
            if head[i] == "law":
                text = f"<b>{e(c)}</b><br><span class='title'>{e(row[skip])}</span>"
                cls_td = "l law"
            cells.append(f"<td class='{cls_td}'>{text}</td>")
        cls = "" if r.plausible else " class='bad'"
        parts.append(f"<tr{cls}>" + "".join(cells) + "</tr>")
    parts.append("</table>")
    return parts


def _html_sections(cmp: ComparisonRecord) -> list[str]:
    """The prose sections as HTML lists, IMPLAUSIBLE highlighted."""
    e = html_text

    def mark(text: str) -> str:
        return e(text).replace("IMPLAUSIBLE", "<span class='bad-word'>IMPLAUSIBLE</span>")

    parts = []
    for heading, items in _sections(cmp):
        parts.append(f"<h2>{e(heading)}</h2><ul>")
        for item in items:
            if isinstance(item, tuple):
                subs = "".join(f"<li>{mark(sub)}</li>" for sub in item[1])
                parts.append(f"<li><b>{mark(item[0])}</b><ul>{subs}</ul></li>")
            else:
                parts.append(f"<li>{mark(item)}</li>")
        parts.append("</ul>")
    return parts


def _html_residual_tests(cmp: ComparisonRecord) -> list[str]:
    """The table of residual-test p-values in HTML, the flagged ones marked."""
    e = html_text
    head, rows = _residual_table(cmp)
    parts = ["<h2>Residual tests (p-values)</h2>", f"<p>{e(RESIDUAL_TESTS_NOTE)}</p>",
             "<table><tr>" + "".join(f"<th class='{'l' if i == 0 else ''}'>{e(h)}</th>"
                                     for i, h in enumerate(head)) + "</tr>"]
    for row in rows:
        cells = [f"<td class='l'>{e(row[0][0])}</td>"]
        cells += [f"<td><span class='bad-word'>{e(t)}</span></td>" if bad else f"<td>{e(t)}</td>"
                  for t, bad in row[1:]]
        parts.append("<tr>" + "".join(cells) + "</tr>")
    parts.append("</table>")
    return parts


def to_html(cmp: ComparisonRecord, figures: Sequence[Figure]) -> str:
    """Write the report as one self-contained HTML page (figures embedded as base64 PNG).

    Parameters
    ----------
    cmp : Comparison
        The comparison.
    figures : sequence of Figure
        The figures to embed, in order.

    Returns
    -------
    str
        The HTML page.
    """
    e = html_text
    d = cmp.data
    parts = ["<!DOCTYPE html>", "<html lang='en'><head><meta charset='utf-8'>",
             f"<title>Comparison of friction laws on {e(d.name)}</title>",
             f"<style>{_CSS}</style></head><body>",
             f"<h1>Comparison of friction laws on {e(d.name)}</h1>",
             f"<p>Data: <b>{e(d.name)}</b> ({e(d.source)}), {d.n} rows; "
             f"{e(_ranges_text(cmp))}.</p>",
             "<ul>" + "".join(f"<li>{e(m)}</li>" for m in _method(cmp)) + "</ul>",
             "<h2>Ranking</h2>", *_html_ranking(cmp),
             "<p>* cross-validation incomplete. Group: laws fitted to the same rows; "
             "AIC, AICc, BIC and Akaike weights compare laws within a group only (a law "
             "alone in its group has weight 1 trivially).</p>",
             "<ul>" + "".join(f"<li>{e(t)}</li>" for t in _legend(cmp)) + "</ul>",
             *_html_sections(cmp), *_html_residual_tests(cmp), "<h2>Figures</h2>"]
    for f in figures:
        b64 = base64.b64encode(f.png).decode("ascii")
        parts.append(f"<figure id='{e(f.name)}'><h3>{e(f.title)}</h3>"
                     f"<img alt='{e(f.title)}' src='data:image/png;base64,{b64}'>"
                     f"<figcaption>{e(f.caption)}</figcaption></figure>")
    parts.append("</body></html>")
    return "\n".join(parts)


def write_report(cmp: ComparisonRecord, directory: str | Path, jobs: int = 1) -> dict[str, Path]:
    """Write the PNG figures, ``report.md``, ``report.html`` and ``comparison.json``.

    Parameters
    ----------
    cmp : Comparison
        The comparison.
    directory : str or Path
        Where to write (created if missing).
    jobs : int
        Processes drawing the figures (see :func:`make_figures`).

    Returns
    -------
    dict of str to Path
        Name -> path of each file written.

    Notes
    -----
    The files are written by the output guard (:func:`frictionlaws.base.outputs.atomic_dir`):
    all of them or none, and never over a file read in this process.
    """
    if isinstance(jobs, bool) or not isinstance(jobs, int) or not (jobs >= 1 or jobs == -1):
        raise InputError(f"jobs must be a whole number >= 1, or -1 for one per core, not "
                         f"{jobs!r}", option="jobs")
    out = Path(directory)
    with atomic_dir(out) as tmp:  # checks the directory before the figures are drawn
        figures = make_figures(cmp, jobs)
        for f in figures:
            (tmp / f"{f.name}.png").write_bytes(f.png)
        (tmp / "report.md").write_text(to_markdown(cmp, figures) + "\n", encoding="utf-8")
        (tmp / "report.html").write_text(to_html(cmp, figures) + "\n", encoding="utf-8")
        (tmp / "comparison.json").write_text(cmp.to_json() + "\n", encoding="utf-8")
    written = {f.name: out / f"{f.name}.png" for f in figures}
    written.update({n: out / n for n in ("report.md", "report.html", "comparison.json")})
    return written

