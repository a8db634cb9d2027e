"""The test table: one entry per registered law.

Each :class:`LawCase` gives true parameters for the parameter-recovery test and
the ranges (SI) where synthetic data are drawn.  ``tests/test_registry_laws.py``
runs the same battery over every entry, and its completeness guard fails when a
registered law has no entry here (or an entry names no law).
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(frozen=True)
class LawCase:
    """Test settings for one law.

    Parameters
    ----------
    params : dict
        True parameters (SI) used to generate synthetic data.
    ranges : dict
        Variable -> (low, high) in SI where points are drawn.
    log : tuple of str
        Variables drawn log-uniformly.
    n : int
        Number of synthetic points.
    fix : dict
        Parameters held at their true value during the recovery fit.
    non_identifiable : tuple of str
        Parameters the fitter must name as non-identifiable on this data
        (recovery is then not checked for them).
    seed : int
        Seed of the synthetic data.  A 3-standard-error check fails by chance
        about 0.3 % of the time per parameter; the seed is fixed so the suite is
        reproducible (the statistical honesty of the standard errors is tested
        separately over many seeds in ``tests/test_fitting.py``).
    """

    params: dict[str, float]
    ranges: dict[str, tuple[float, float]]
    log: tuple[str, ...] = ()
    n: int = 80
    fix: dict[str, float] = field(default_factory=dict)
    non_identifiable: tuple[str, ...] = ()
    seed: int = 7


CASES: dict[str, LawCase] = {
    "coulomb": LawCase({"mu0": 0.9}, {"p": (1e4, 1e6)}),
    "thirion": LawCase({"a": 0.3, "b": 3e-6}, {"p": (2e4, 1e6)}),
    "schallamach": LawCase({"mu_ref": 2.0, "n": 0.25}, {"F_N": (2.0, 200.0)}, log=("F_N",),
                          seed=8),
    "denny": LawCase({"a": 2.0, "b": 15.0}, {"p": (1e4, 2e6)}),
    "exponential-decay": LawCase({"mu_s": 1.2, "mu_d": 0.6, "v_c": 0.3, "delta": 1.3},
                                 {"v": (1e-3, 10.0)}, log=("v",), n=120),
    "quadratic-pv": LawCase({"c0": 1.2, "c1": -1.5e-6, "c2": 0.08, "c3": 2e-7, "c4": 8e-13,
                             "c5": -0.015}, {"p": (5e4, 1e6), "v": (0.0, 3.0)}),
    "thesis-poly2": LawCase({"a0": 5.18, "a1": -59.2, "a2": 220.0, "a3": 1.05, "a4": -0.303},
                            {"p": (0.03e6, 0.25e6), "v": (0.0, 2.77)}),
    "thesis-poly3": LawCase({"a0": 6.28, "a1": -108.0, "a2": 809.0, "a3": -2090.0,
                             "a4": 0.158, "a5": 0.669, "a6": -0.235},
                            {"p": (0.03e6, 0.25e6), "v": (0.0, 2.77)}, n=200),
}
