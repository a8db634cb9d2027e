"""The figure helpers: a grid of fitted laws and a comparison's errors."""

from __future__ import annotations

import warnings

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import frictionlaws as fl  # noqa: E402
from frictionlaws.base.errors import InputError  # noqa: E402
from frictionlaws.comparison.plotting import plot_comparison, plot_fit_grid  # noqa: E402


@pytest.fixture(scope="module")
def fits():
    data = fl.load_dataset("thesis-steel")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        out = {law: fl.fit(law, data, on_invalid="drop")
               for law in ("thirion", "savkoor", "coulomb")}
    return data, out


def test_the_grid_has_a_panel_per_law_in_mpa(fits) -> None:
    data, results = fits
    fig = plot_fit_grid(results, data, x="p", by="v", ncol=2)
    visible = [ax for ax in fig.axes if ax.get_visible()]
    assert [ax.get_title().split()[0] for ax in visible] == ["thirion", "savkoor",
                                                                  "coulomb"]
    assert visible[-1].get_xlabel() == "p [MPa]" and visible[0].get_xlim()[1] < 0.3
    savkoor = visible[1]
    open_marks = [line for line in savkoor.lines
                  if line.get_marker() == "o" and isinstance(line.get_markerfacecolor(), str)
                  and line.get_markerfacecolor() == "none"]
    assert len(open_marks) == 1 and len(open_marks[0].get_xdata()) == 8  # the v = 0 rows
    curves = [line for line in savkoor.lines if line.get_marker() in ("None", None, "")]
    assert len(curves) == 2  # no curve at v = 0, which savkoor was not fitted on
    plt.close(fig)


def test_the_curves_are_the_fitted_laws(fits) -> None:
    data, results = fits
    fig = plot_fit_grid({"thirion": results["thirion"]}, data, by=None)
    (curve,) = [line for line in fig.axes[0].lines if line.get_marker() in ("None", "")]
    p_mpa = np.asarray(curve.get_xdata())
    expected = results["thirion"].predict(p=p_mpa * 1e6)
    np.testing.assert_allclose(curve.get_ydata(), expected, rtol=1e-10)
    plt.close(fig)


def test_the_grid_refuses_what_it_cannot_draw(fits) -> None:
    data, results = fits
    with pytest.raises(InputError, match="no column 'T'"):
        plot_fit_grid(results, data, by="T")
    with pytest.raises(InputError, match="no fits"):
        plot_fit_grid({}, data)


def test_the_comparison_plot_shows_three_errors_per_law_in_rank_order() -> None:
    from frictionlaws.comparison import compare

    cmp = compare(["coulomb", "thirion", "thesis-poly3"], "thesis-steel", folds=5,
                  holdout=0.3, seed=0, progress=False)
    fig = cmp.plot()
    ax = fig.axes[0]
    assert len(ax.patches) == 3 * len(cmp.results)
    labels = [t.get_text().split("\n")[0] for t in ax.get_xticklabels()]
    assert labels == [r.law.id for r in cmp.results]
    heights = [p.get_height() for p in ax.patches[:len(cmp.results)]]
    np.testing.assert_allclose(heights, [r.metrics["rmse"] for r in cmp.results])
    hatched = {labels[i % len(labels)] for i, p in enumerate(ax.patches) if p.get_hatch()}
    assert hatched == {r.law.id for r in cmp.results if not r.plausible}
    plt.close(fig)
    fig2, axis = plt.subplots()
    assert plot_comparison(cmp, ax=axis, log=False) is fig2
    plt.close(fig2)
