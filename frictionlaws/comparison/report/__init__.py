"""The comparison as a console table, Markdown, self-contained HTML and PNG figures.

Figures (matplotlib with the Agg backend, imported only here):

* ``fits_<x>_by_<g>.png``: the data with every fitted law, mu against one
  variable with one panel per level of the other (mu vs p per velocity, mu vs
  v per pressure); each curve spans the range of the rows its law was fitted
  on, and a law is not drawn in a panel all of whose rows it had to drop;
* ``residuals.png``: for every law, residuals against each variable and the
  fitted value, and the normal Q-Q plot, a red band where a test finds structure
  (the p-values are in the residual-tests table of ``report.md`` and ``report.html``);
* ``extrapolation_holdout.png``: each law fitted below the holdout threshold,
  with the held-out points it is scored on;
* ``extrapolation_box.png``: each fully fitted law over the extended box, with
  the measured range, the physical limits and the points where the
  plausibility scan flagged it;
* ``metrics.png``: fit RMSE, cross-validated RMSE and extrapolation RMSE per law
  (the values are in the ranking table).

Figures cost little to draw: few axes with fixed layouts, one artist for
many repeated marks, unhinted text, no mathtext; ``benchmarks/bench_report.py`` times
them.

``report.html`` embeds every PNG as base64 and needs nothing else; ``report.md``
links the PNG files next to it; ``comparison.json`` is :meth:`Comparison.to_json`.
"""

from __future__ import annotations

from .documents import (
    RESIDUAL_TESTS_NOTE,
    to_html,
    to_markdown,
    write_report,
)
from .figures import (
    FLAG_COLOUR,
    STRIP,
    Figure,
    make_figures,
)
from .text import (
    BIN_ABOVE,
    DPI,
    MAX_PANELS,
    PNG_COMPRESSION,
    RANK_RULE,
    RC,
    SCATTERED,
    TICKS,
    UNDETERMINED,
    format_table,
)

__all__ = ["format_table", "write_report", "make_figures", "Figure", "MAX_PANELS", "BIN_ABOVE",
           "SCATTERED", "DPI", "RC", "TICKS", "PNG_COMPRESSION", "UNDETERMINED", "RANK_RULE",
           "STRIP", "FLAG_COLOUR", "RESIDUAL_TESTS_NOTE", "to_markdown",
           "to_html"]
