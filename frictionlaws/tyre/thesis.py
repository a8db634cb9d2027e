"""The thesis' tyre comparison: constant mu against friction fitted to the tribometer data.

The source thesis (chapter 6) ran a commercial FE tyre model (inflation
0.22 MPa, road at 10 km/h, loads 2 to 6.5 kN, slip angles 1, 2, 3 degrees)
with constant mu = 0.9 and 1.0 and with mu-against-pressure tables from its
tribometer tests, and found that the cornering stiffness keeps rising with
load for constant mu but rises less and levels off with pressure-dependent
friction (Table 6-2, stored here as :data:`TABLE_6_2`).

:func:`thesis_comparison` repeats the experiment with the brush model of
:mod:`frictionlaws.tyre.brush`: ``coulomb`` at 0.9 and 1.0 against laws
fitted to the packaged ``thesis-steel`` dataset (``thirion`` by default), at
the same loads and angles, and puts the result beside Table 6-2.  The brush
model is not the FE model and is not expected to reproduce its numbers; the
check is the qualitative difference, summarised by the ratio
CS(6.5 kN)/CS(2 kN).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..base.errors import InputError
from ..fitting import fit
from .brush import DEFAULT_ANGLES_DEG, BrushModel, BrushTyre, CorneringResult

__all__ = ["TABLE_6_2", "THESIS_LOADS_KN", "ThesisComparison", "thesis_comparison",
           "thesis_ratios"]

#: Loads of the thesis' FE cornering runs [kN].
THESIS_LOADS_KN = (2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0, 5.5, 6.0, 6.5)

#: Thesis Table 6-2: cornering stiffness [kN/deg] of the FE tyre against normal load [kN].
TABLE_6_2: dict[str, Any] = {
    "source": "source thesis (rubber friction on a rotary pin-on-disc tribometer and its use "
              "in tyre FE analysis), chapter 6, Table 6-2; FE tyre at 0.22 MPa inflation, "
              "road 10 km/h, slip angles 1, 2, 3 deg; see shared/reference/thesis-data.md",
    "unit": "kN/deg",
    "loads_kN": THESIS_LOADS_KN,
    "columns": {
        "mu 0.9": (0.463, 0.581, 0.688, 0.793, 0.890, 0.969, 1.055, 1.116, 1.183, 1.226),
        "mu 1.0": (0.489, 0.613, 0.726, 0.834, 0.935, 1.015, 1.102, 1.161, 1.228, 1.266),
        "S120": (0.826, 1.003, 1.151, 1.242, 1.380, 1.422, 1.514, 1.522, 1.583, 1.562),
        "S400": (0.776, 0.959, 1.103, 1.209, 1.341, 1.391, 1.491, 1.502, 1.567, 1.554),
        "steel": (0.805, 0.987, 1.132, 1.226, 1.366, 1.409, 1.505, 1.514, 1.576, 1.555),
    },
    # Table 6-1: load range where the FE model converged in the brake-traction runs
    "converged_kN": {"mu 0.9": (2.0, 6.0), "mu 1.0": (2.0, 6.0), "steel": (2.0, 4.5),
                     "S120": (2.0, 5.5), "S400": (2.0, 4.5)},
}


def thesis_ratios() -> dict[str, float]:
    """CS(6.5 kN)/CS(2 kN) of every column of Table 6-2 (mu 0.9: 2.65, S120: 1.89)."""
    return {k: v[-1] / v[0] for k, v in TABLE_6_2["columns"].items()}


@dataclass
class ThesisComparison:
    """Brush-model cornering stiffness beside thesis Table 6-2.

    Attributes
    ----------
    results : dict
        Column label -> :class:`CorneringResult` (``"coulomb 0.9"``,
        ``"coulomb 1.0"``, ``"thirion (thesis-steel)"``...).
    fits : dict
        Label -> the :class:`~frictionlaws.fitting.FitResult` of each fitted law.
    """

    loads_kN: np.ndarray
    angles_deg: np.ndarray
    results: dict[str, CorneringResult]
    fits: dict[str, Any] = field(default_factory=dict)
    tyre: dict[str, Any] = field(default_factory=dict)

    def ratios(self) -> dict[str, float]:
        """CS(last load)/CS(first load) of each brush-model column."""
        return {k: r.ratio() for k, r in self.results.items()}

    def thesis_ratios(self) -> dict[str, float]:
        """The same ratio for the columns of Table 6-2."""
        return thesis_ratios()

    def table(self) -> str:
        """Side-by-side text table [kN/deg] with the ratios."""
        ours = list(self.results)
        theirs = list(TABLE_6_2["columns"])
        w = {k: max(8, len(k)) for k in ours}
        head = (f"{'load [kN]':>9}  " + "  ".join(f"{k:>{w[k]}}" for k in ours) + "  |  "
                + "  ".join(f"{k:>7}" for k in theirs))
        lines = ["cornering stiffness [kN/deg]: brush model (left) and thesis FE, Table 6-2 "
                 f"(right); slip angles {', '.join(f'{a:g}' for a in self.angles_deg)} deg",
                 head]
        tl = np.asarray(TABLE_6_2["loads_kN"])
        for i, load in enumerate(self.loads_kN):
            row = f"{load:>9.3g}  " + "  ".join(
                f"{self.results[k].cs_kN_per_deg[i]:>{w[k]}.4f}" for k in ours)
            j = np.flatnonzero(np.isclose(tl, load))
            row += "  |  " + "  ".join(
                f"{TABLE_6_2['columns'][k][j[0]]:>7.3f}" if j.size else f"{'-':>7}"
                for k in theirs)
            lines.append(row)
        r = self.ratios()
        t = thesis_ratios()
        lines.append(f"{'ratio':>9}  " + "  ".join(f"{r[k]:>{w[k]}.3f}" for k in ours) + "  |  "
                     + "  ".join(f"{t[k]:>7.3f}" for k in theirs))
        lines.append(f"(ratio = CS({self.loads_kN[-1]:g} kN) / CS({self.loads_kN[0]:g} kN); "
                     "load ratio 3.25)")
        for k, res in self.results.items():
            lines.extend(f"warning [{k}]: {w}" for w in res.warnings)
        lines.extend(f"warning [{k}]: {w}" for k, w in self.fit_warnings())
        return "\n".join(lines)

    def fit_warnings(self) -> list[tuple[str, str]]:
        """(label, text) of every warning of the fits, first the parameters they cannot tell.

        A column computed from a fit whose data cannot determine some parameter shows
        the friction at an arbitrary point of a flat valley: that is said, not hidden.
        """
        out = []
        for label, f in self.fits.items():
            if f.non_identifiable:
                out.append((label, f"fit: the data cannot determine {', '.join(f.non_identifiable)}"
                                   f" of law '{f.law.id}': this column rests on arbitrary "
                                   "values of them"))
            out.extend((label, f"fit: {w}") for w in f.warnings)
        return out

    def to_dict(self) -> dict[str, Any]:
        """JSON-able comparison."""
        return {
            "loads_kN": self.loads_kN.tolist(),
            "angles_deg": self.angles_deg.tolist(),
            "unit": "kN/deg",
            "brush": {k: r.to_dict() for k, r in self.results.items()},
            "ratios": self.ratios(),
            "thesis_table_6_2": {"source": TABLE_6_2["source"],
                                 "loads_kN": list(TABLE_6_2["loads_kN"]),
                                 "columns": {k: list(v) for k, v in
                                             TABLE_6_2["columns"].items()},
                                 "ratios": thesis_ratios()},
            "fits": {k: {"law": f.law.id, "params": f.param_values,
                         "r2": f.metrics.get("r2"), "rmse": f.metrics.get("rmse"),
                         "undetermined": list(f.non_identifiable),
                         "warnings": list(f.warnings)}
                     for k, f in self.fits.items()},
            "tyre": self.tyre,
        }


def thesis_comparison(*, laws: Sequence[str] = ("thirion",), dataset: Any = "thesis-steel",
                      tyre: BrushTyre | None = None,
                      loads_kN: Sequence[float] = THESIS_LOADS_KN,
                      angles_deg: Sequence[float] = DEFAULT_ANGLES_DEG,
                      constant_mu: Sequence[float] = (0.9, 1.0)) -> ThesisComparison:
    """Compute the brush tyre's cornering stiffness with constant and fitted friction.

    Parameters
    ----------
    laws : sequence of str
        Laws of the contact pressure (and/or sliding speed) fitted to
        ``dataset`` with :func:`frictionlaws.fitting.fit`.
    dataset : str or dataset
        Data the laws are fitted to (default the packaged ``thesis-steel``).
    tyre : BrushTyre, optional
        The brush tyre (default :class:`BrushTyre()`, sized like the thesis' tyre).
    loads_kN, angles_deg : sequence of float
        Loads [kN] and slip angles [deg] (default: the thesis').
    constant_mu : sequence of float
        Constant friction coefficients (law ``coulomb``).

    Returns
    -------
    ThesisComparison
        One :class:`~frictionlaws.tyre.brush.CorneringResult` per constant mu
        (``"coulomb 0.9"``...) and per fitted law (``"thirion (thesis-steel)"``),
        the fit results, the loads [kN], angles [deg] and tyre, ready to be set
        beside Table 6-2 of the thesis (cornering stiffness in kN/deg).
    """
    tyre = tyre or BrushTyre()
    loads = np.asarray(loads_kN, dtype=float) * 1000.0
    results: dict[str, CorneringResult] = {}
    fits: dict[str, Any] = {}
    for mu in constant_mu:
        model = BrushModel("coulomb", {"mu0": float(mu)}, tyre=tyre)
        label = f"coulomb {mu:.1f}" if float(mu * 10).is_integer() else f"coulomb {mu:g}"
        results[label] = model.cornering(loads, angles_deg)
    name = getattr(dataset, "name", dataset) if not isinstance(dataset, str) else dataset
    for law in laws:
        result = fit(law, dataset)
        label = f"{result.law.id} ({name})"
        if label in fits:  # one column per law: a second would replace the first unseen
            raise InputError(f"laws: '{law}' is law '{result.law.id}', given twice")
        fits[label] = result
        results[label] = BrushModel(result, tyre=tyre).cornering(loads, angles_deg)
    return ThesisComparison(loads_kN=loads / 1000.0, angles_deg=np.asarray(angles_deg, float),
                            results=results, fits=fits, tyre=tyre.describe())
