"""The fits pinned by tests/fitting/test_pinned_fits.py, and the script that produced the pins.

Run ``python tests/fitting/_pin_cases.py`` to print the table of pinned values (it was run on the
main code before the fit-speed work (commit bf71f47), and its output pasted
into tests/fitting/test_pinned_fits.py).  Never regenerate the pins to make a failing test pass.
"""

from __future__ import annotations

from typing import Any

import numpy as np

#: Sliding laws fitted to the packaged thesis data (p, v), with their fit options.
DATASET_LAWS = ("coulomb", "thirion", "denny", "exponential-decay", "quadratic-pv",
                "thesis-poly2", "thesis-poly3", "savkoor", "nackenhorst", "huemer",
                "wriggers")
DATASETS = ("thesis-steel",)
#: Laws also fitted to the thesis' own table layout (loader mapping and units).
ORIGINAL_LAWS = ("thirion", "savkoor", "wriggers")
ORIGINAL = {"mapping": {"mu": "FC", "p": "CP", "v": "DV"}, "units": {"p": "MPa", "v": "m/s"}}
#: Laws also fitted to their synthetic data with uneven weights.
WEIGHTED_LAWS = ("thirion", "savkoor", "pacejka", "burckhardt")
#: Laws fitted to seeded synthetic data drawn from the example table
#: (frictionlaws.validation.law_examples).
SYNTHETIC_LAWS = ("thirion", "schallamach", "denny", "exponential-decay", "savkoor",
                  "nackenhorst", "huemer", "wriggers", "park", "pacejka", "burckhardt",
                  "burckhardt-sqrt", "kiencke-daiss", "germann")


def synthetic(law_id: str) -> tuple[dict[str, np.ndarray], dict[str, float]]:
    """Seeded synthetic data (2 % noise) from the example table, and the parameters held."""
    import frictionlaws as fl
    from frictionlaws.validation.law_examples import EXAMPLES

    ex = EXAMPLES[law_id].battery
    law = fl.get_law(law_id)
    rng = np.random.default_rng(ex.seed)
    x = {}
    for var, (lo, hi) in ex.ranges.items():
        x[var] = (np.exp(rng.uniform(np.log(lo), np.log(hi), ex.n)) if var in ex.log
                  else rng.uniform(lo, hi, ex.n))
    mu = np.asarray(law.evaluate(x, law.resolve({**ex.params, **ex.fix})), float)
    mu = mu + 0.02 * np.mean(np.abs(mu)) * rng.standard_normal(ex.n)
    return {**x, "mu": mu}, dict(ex.fix)


def cases() -> list[tuple[str, str, Any, dict[str, Any]]]:
    """(case name, law id, data, fit options) for every pinned fit."""
    out: list[tuple[str, str, Any, dict[str, Any]]] = [
        (f"{law}@{ds}", law, ds, {}) for ds in DATASETS for law in DATASET_LAWS]
    out += [(f"{law}@thesis-steel-original", law, "thesis-steel-original", dict(ORIGINAL))
            for law in ORIGINAL_LAWS]
    for law in SYNTHETIC_LAWS:
        data, fix = synthetic(law)
        out.append((f"{law}@synthetic", law, data, {"fix": fix}))
        if law in WEIGHTED_LAWS:
            w = 1.0 / (0.05 + np.abs(data["mu"]))
            out.append((f"{law}@synthetic-weighted", law, data, {"fix": fix, "weights": w}))
    return out


def run(law: str, data: Any, options: dict[str, Any]) -> dict[str, Any]:
    """The pinned numbers of one fit: parameter values, chi^2, R^2."""
    import warnings

    import frictionlaws as fl

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = fl.fit(law, data, on_invalid="drop", **options)
    return {"params": {k: p.value for k, p in res.params.items()},
            "stderr": {k: p.stderr for k, p in res.params.items()},
            "chisqr": res.metrics["chisqr"], "r2": res.metrics["r2"],
            "non_identifiable": list(res.non_identifiable)}


if __name__ == "__main__":
    import pprint

    table = {name: run(law, data, options) for name, law, data, options in cases()}
    for entry in table.values():
        del entry["stderr"]  # the tolerance of the check, not a pinned value
    print("PINS = " + pprint.pformat(table, width=92, sort_dicts=False))
