"""The comparison report's content: tables, captions and cheap figures.

The residual p-values left the residuals figure for a table in report.md and report.html;
the figure marks the strips whose tests find structure.  These tests pin that nothing was
lost on the way: every p-value is in both tables, the marks agree with them, and the
values drawn in panel titles read as in the rest of the report.
"""

from __future__ import annotations

import html
import math

import pytest

from frictionlaws.comparison import Comparison, compare
from frictionlaws.comparison import report as rep
from frictionlaws.comparison.report import documents as rep_documents
from frictionlaws.comparison.report import figures as rep_figures
from frictionlaws.comparison.report import text as rep_text
from frictionlaws.comparison.residuals import ALPHA

LAWS = ["coulomb", "thirion", "savkoor"]  # coulomb leaves structure; savkoor drops v = 0


@pytest.fixture(scope="module")
def cmp() -> Comparison:
    return compare(LAWS, "thesis-steel", seed=2, progress=False)


def _p_values(r, columns):
    """Every p-value of a law's residual tests, in the table's column order."""
    out = []
    for c in columns:
        t = r.residuals.tests.get(c, {})
        out += [(t.get("runs") or {}).get("p_value"), t.get("kendall_p")]
    return out + [r.residuals.shapiro_p]


def test_every_residual_p_value_is_in_the_markdown_and_html_tables(cmp: Comparison) -> None:
    figures = rep.make_figures(cmp)
    md = rep.to_markdown(cmp, figures)
    page = rep.to_html(cmp, figures)
    assert "## Residual tests (p-values)" in md and "<h2>Residual tests (p-values)</h2>" in page
    columns = [*cmp.design.varying, "fitted"]
    head = md.split("## Residual tests (p-values)")[1].split("## Figures")[0]
    for name in ("runs p (p)", "Kendall p (v)", "runs p (fitted mu)", "Shapiro-Wilk p"):
        assert name in head and html.escape(name) in page
    some_flagged = False
    for r in cmp.results:
        row = next(line for line in head.splitlines() if line.startswith(f"| {r.rank}. "))
        cells = [c.strip() for c in row.strip("|").split("|")][1:]
        ps = _p_values(r, columns)
        assert len(cells) == len(ps) == 2 * len(columns) + 1
        for cell, p in zip(cells, ps):
            text = rep_text._num(p, ".2g")
            flagged = p is not None and math.isfinite(p) and p < ALPHA
            some_flagged |= flagged
            assert cell == (f"**{text}**" if flagged else text)
            wanted = (f"<span class='bad-word'>{text}</span>" if flagged else f"<td>{text}</td>")
            assert wanted in page
    assert some_flagged  # coulomb's residuals trend with p on these data


def test_the_red_bands_of_the_residuals_figure_agree_with_the_table(cmp: Comparison) -> None:
    _, rows = rep_documents._residual_table(cmp)
    for r, row in zip(cmp.results, rows):
        flags = [bad for _, bad in row[1:]]
        for j, c in enumerate(cmp.design.varying + ["fitted"]):
            assert rep_figures._strip(cmp, r, c)[2] == (flags[2 * j] or flags[2 * j + 1])
        assert rep_figures._strip(cmp, r, "qq")[2] == flags[-1]
    assert any(rep_figures._strip(cmp, r, "p")[2] for r in cmp.results)
    assert not all(rep_figures._strip(cmp, r, "qq")[2] for r in cmp.results)


def test_the_metrics_axis_is_labelled_in_plain_numbers() -> None:
    fig = rep_figures._new_figure(4, 3)
    ax = fig.subplots()
    ax.barh([0, 1], [0.03, 2.0])
    rep_figures._log_axis(ax, 0.02, 4.0)
    fig.canvas.draw()
    lo, hi = ax.get_xlim()
    labels = [t.get_text() for t, x in zip(ax.get_xticklabels(), ax.get_xticks())
              if lo <= x <= hi]
    assert labels == ["0.02", "0.05", "0.1", "0.2", "0.5", "1", "2"]
    assert not ax.xaxis.get_minor_locator()()  # no minor ticks: the 1-2-5 ticks replace them


def test_captions_name_the_table_the_p_values_went_to(cmp: Comparison) -> None:
    from frictionlaws.base.sanitize import markdown_text

    figures = {f.name: f for f in rep.make_figures(cmp)}
    assert "table of residual tests" in figures["residuals"].caption
    assert "ranking table" in figures["metrics"].caption
    md = rep.to_markdown(cmp, list(figures.values()))
    for name in figures:  # every figure is still linked, with its caption
        assert f"]({name}.png)" in md and markdown_text(figures[name].caption) in md
