"""The result of a Magic Formula fit: coefficients, errors, notes, the property file written.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .... import __version__
from ....base.errors import InputError
from ....base.outputs import atomic_write, check_outputs
from ...data.table import TyreData
from ..model import MagicFormula
from ..property_file import PropertyFile
from ..tir import format_tir
from .plot import plot_fit

__all__ = ["MFFit", "check_tir_path", "UNCERTAINTIES", "LABELS"]


@dataclass
class MFFit:
    """The result of :func:`fit_mf`.

    Attributes
    ----------
    version : str
        Magic Formula version fitted (``"5.2"``, ``"6.1"``, ``"6.2"``).
    property_file : PropertyFile
        The template with the fitted coefficients, FITTYP, conditions and ranges.
    values, stderr : dict
        Fitted coefficient -> value and standard error.
    undetermined : list of str
        Coefficients the data cannot determine (left at the template value).
    errors : dict
        Per quantity: ``"x"``, ``"y"`` (pure-slip rows, F_x0 and F_y0 stages),
        ``"x_all"``, ``"y_all"`` (every row, combined model) and ``"mz"`` (every M_z
        row): ``rmse``, ``max_abs``, ``peak`` (largest measured magnitude) [N or N m]
        and ``n`` points.
    stages : dict
        Per direction, the per-load curves of stage 1 (load, mu, K, C, E, S_H, S_V).
    warnings : list of str
        What the data leave open (a peak they do not reach); also issued as
        :class:`~frictionlaws.base.errors.ExtrapolationWarning` and written as notes.
    """

    version: str
    property_file: PropertyFile
    model: MagicFormula
    values: dict[str, float]
    stderr: dict[str, float]
    undetermined: list[str]
    errors: dict[str, dict[str, float]]
    stages: dict[str, list[dict[str, float]]]
    data: TyreData
    seconds: float
    notes: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    #: How the standard errors were made (:data:`UNCERTAINTIES`, with the details).
    uncertainty: str = ""
    #: The asymptotic standard errors (equal to ``stderr`` unless bootstrapped).
    stderr_asymptotic: dict[str, float] = field(default_factory=dict)

    def tir_text(self) -> str:
        """The ``.tir`` text of the fitted property file."""
        fitted = ", ".join(LABELS[k] for k in self.errors) or "nothing"
        header = [f"FITTED by frictionlaws {__version__} fit_mf from {self.data.source} "
                  f"({len(self.data)} rows), Magic Formula {self.version}: {fitted}; "
                  "other coefficients and sections from the template.",
                  "Slip angle convention: alpha* = tan(alpha) in the lateral slip "
                  "(MFeval useMode 2x); camber as sin(gamma) in the lateral and "
                  "combined-slip terms" + (", gamma itself in PDX3's term" if "PDX3" in
                                           self.property_file.sections.get(
                                               "LONGITUDINAL_COEFFICIENTS", {}) else "")
                  + " (equations as MFeval 4.0).",
                  "Friction scaling: LMU' = LMU (A_mu = 1, as MFeval 4.0).",
                  f"Standard errors: {self.uncertainty or UNCERTAINTIES['asymptotic']}."]
        header += [f"warning: {w}" for w in self.warnings]
        header += [f"note: {n}" for n in self.notes]
        return format_tir(self.property_file, header=header)

    def write(self, path: str | Path) -> Path:
        """Write the ``.tir`` file atomically (checked as an output first)."""
        check_tir_path(path)
        check_outputs([path], inputs=[self.data.source])
        with atomic_write(path) as fh:
            fh.write(self.tir_text())
        return Path(path)

    def report(self) -> str:
        """Plain-text report: coefficients with standard errors, errors, notes."""
        lines = [f"Magic Formula {self.version} fit to {self.data.source} "
                 f"({len(self.data)} rows, {self.seconds:.1f} s)",
                 f"standard errors: {self.uncertainty or UNCERTAINTIES['asymptotic']}"]
        for name, v in self.values.items():
            se = self.stderr.get(name, math.nan)
            lines.append(f"  {name:<5} = {v:< 12.6g} +/- {se:.3g}")
        for d, e in self.errors.items():
            u = "N m" if d == "mz" else "N"
            lines.append(f"{LABELS[d]}: {int(e['n'])} points, RMSE {e['rmse']:.4g} {u}, max "
                         f"|error| {e['max_abs']:.4g} {u}, peak {e['peak']:.4g} {u}")
        lines.extend(f"warning: {w}" for w in self.warnings)
        lines.extend(f"note: {n}" for n in self.notes)
        return "\n".join(lines)

    def to_dict(self) -> dict[str, Any]:
        """JSON-able summary."""
        return {"version": self.version, "source": self.data.source, "rows": len(self.data),
                "coefficients": {k: {"value": v, "stderr": self.stderr.get(k)}
                                 for k, v in self.values.items()},
                "uncertainty": self.uncertainty or UNCERTAINTIES["asymptotic"],
                "undetermined": list(self.undetermined), "errors": self.errors,
                "stages": self.stages, "seconds": self.seconds, "notes": list(self.notes),
                "warnings": list(self.warnings)}

    def plot(self, path: str | Path) -> Path:
        """Save a figure of data and fit per load (nominal pressure, smallest camber)."""
        return plot_fit(self, path)


def check_tir_path(path: str | Path) -> None:
    """Refuse a property file name whose suffix is not ``.tir`` (the text written is
    ADAMS ``.tir``; a ``.json`` name would hold it under the wrong format)."""
    if Path(path).suffix.lower() != ".tir":
        raise InputError("the property file written is ADAMS .tir text: give the file the "
                         "suffix .tir", file=str(path))


#: How the standard errors are made (``uncertainty=`` of :func:`fit_mf`).
UNCERTAINTIES = {
    "asymptotic": "asymptotic (Gauss-Newton, s^2 (J^T J)^-1 of each stage; assumes "
                  "independent residuals, too small when a sweep's residuals share an "
                  "offset)",
    "sweeps": "sweep bootstrap"}

#: What each entry of :attr:`MFFit.errors` describes.
LABELS = {"x": "Fx0 (rows near pure slip)", "y": "Fy0 (rows near pure slip)",
           "x_all": "Fx (every row, combined slip)", "y_all": "Fy (every row, combined slip)",
           "mz": "Mz (every row, combined slip)"}
