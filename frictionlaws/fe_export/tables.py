"""Plain grid exports: ``csv`` and ``json``.

Both hold the law tabulated on the export grid in the chosen unit system,
units in the column headers / keys, and the common header (as ``#`` comment
lines in CSV, as a ``header`` list and structured keys in JSON).
"""

from __future__ import annotations

import itertools
import json

from ..law import VARIABLES
from .job import Job, Written, commented, model_axes, tabulated

__all__ = ["write_csv", "write_json", "OUTSIDE_GRID"]

#: What happens outside the box when a solver interpolates such a grid.
OUTSIDE_GRID = ("a solver interpolating this grid linearly holds the end values (no "
                "extrapolation); the law itself is not represented there")

_ORDER = tuple(VARIABLES)  # p, v, T, F_N, s


def _num(x: float) -> str:
    return f"{float(x):.12g}"


def _grid(job: Job, what: str):
    names = [v for v in _ORDER if v in job.variables]
    grid, err, how = job.make_grid(names, what)
    return grid, err, how, tabulated(job, grid)


def write_csv(job: Job) -> Written:
    """The grid as CSV: one column per variable (model units) and ``mu [-]``."""
    grid, err, how, mu = _grid(job, "csv")
    body = [*job.box_lines(grid), *job.error_lines(err, how),
            "columns: " + ", ".join(f"{n} [{job.units.label(n)}]" for n in grid.names)
            + ", mu [-]; rows: the first column varies slowest"]
    head = job.header("grid of mu (CSV)", body, OUTSIDE_GRID)
    lines = commented(head, "# ")
    lines.append(",".join([f"{n} [{job.units.label(n)}]" for n in grid.names] + ["mu [-]"]))
    axes = model_axes(job, grid)
    for idx in itertools.product(*[range(len(a)) for a in axes]):
        row = [_num(a[i]) for a, i in zip(axes, idx, strict=True)]
        lines.append(",".join(row + [_num(mu[idx])]))
    return Written("\n".join(lines) + "\n", rows=grid.rows, error=err, grid=grid,
                   summary=body)


def write_json(job: Job) -> Written:
    """The grid as JSON: axes with units, mu as a nested list, and the header."""
    grid, err, how, mu = _grid(job, "json")
    body = [*job.box_lines(grid), *job.error_lines(err, how)]
    head = job.header("grid of mu (JSON)", body, OUTSIDE_GRID)
    axes = model_axes(job, grid)
    stderr = getattr(job.fit, "stderr", None) or {}
    doc = {
        "format": "frictionlaws-grid",
        "version": 1,
        "header": head,
        "law": job.law.id,
        "title": job.law.title,
        "parameters": {
            p.name: {"value": job.values[p.name], "unit": p.unit,
                     "stderr": stderr.get(p.name)}
            for p in job.law.params},
        "settings": {s.name: {"value": job.values[s.name], "unit": s.unit}
                     for s in job.law.settings},
        "source": job.source,
        "units": {"system": job.units.name,
                  **{n: job.units.unit(n) for n in grid.names}, "mu": ""},
        "axes": [{"name": n, "unit": job.units.unit(n), "spacing": sp,
                  "values": [float(x) for x in a]}
                 for n, sp, a in zip(grid.names, grid.spacing, axes, strict=True)],
        "mu": mu.tolist(),
        "mu_layout": "nested lists indexed [" + "][".join(grid.names) + "]"
                     if grid.names else "a single number",
        "interpolation": {
            "kind": "multilinear in the variables themselves, end values held outside",
            "max_abs_error": err.max_abs,
            "at": {k: float(job.units.to_model(k, v)) for k, v in err.where.items()},
            "rms_error": err.rms,
            "checked_points": err.n_checked,
            "grid": how,
        },
        "outside_box": OUTSIDE_GRID,
        "warnings": list(job.warnings),
    }
    return Written(json.dumps(doc, indent=1) + "\n", rows=grid.rows, error=err, grid=grid,
                   summary=body)
