"""The result of :func:`~frictionlaws.comparison.compare`: :class:`Comparison`.

The record of what the comparison found (:mod:`frictionlaws.comparison.record`) with its
views: the console table, the HTML/Markdown/PNG report
(:mod:`frictionlaws.comparison.report`, imported only when a table or a report is asked
for), the bar chart and Jupyter's HTML.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..law.interop import table_html
from .plotting import plot_comparison
from .record import (
    COMPARISON_FORMAT,
    COMPARISON_VERSION,
    FRAME_COLUMNS,
    ComparisonRecord,
    LawComparison,
    mark_undetermined,
)
from .report import format_table, write_report

__all__ = ["Comparison", "LawComparison", "COMPARISON_FORMAT", "COMPARISON_VERSION",
           "FRAME_COLUMNS", "mark_undetermined"]


@dataclass
class Comparison(ComparisonRecord):
    """The result of :func:`compare`: ranked laws, skipped and failed laws, settings.

    ``results`` is in rank order (best first).  :meth:`table` is the console
    table, :meth:`to_dict`/:meth:`to_json` the machine-readable form,
    :meth:`write_report` the HTML/Markdown/PNG report.
    """

    def _repr_html_(self) -> str:
        rows = mark_undetermined(self.to_frame()).to_dict("records")
        return table_html(rows, caption=f"laws compared on {self.data.name} "
                                        f"({self.data.n} rows), best first; n/d: "
                                        "undetermined; akaike_weight within aic_group")

    def table(self) -> str:
        """The ranked console table with the flags, skipped and failed laws."""
        return format_table(self)

    def __str__(self) -> str:
        return self.table()

    def plot(self, **kw: Any) -> Any:
        """Bar chart of each law's fit, CV and extrapolation RMSE, in rank order.

        See :func:`frictionlaws.comparison.plotting.plot_comparison` (``ax``, ``log``).

        Returns
        -------
        matplotlib.figure.Figure
        """
        return plot_comparison(self, **kw)

    def write_report(self, directory: str | Path, *, jobs: int = 1) -> dict[str, Path]:
        """Write ``report.html``, ``report.md``, ``comparison.json`` and the PNG figures.

        Parameters
        ----------
        directory : str or Path
            Where to write (created if missing).
        jobs : int
            Processes (joblib) drawing the figures; 1 draws them in this process.

        Returns
        -------
        dict of str to Path
            Name -> path of each file written.
        """
        return write_report(self, directory, jobs)
