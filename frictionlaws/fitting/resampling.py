"""The one rule of every resampling: resamples that cannot vary give no standard error.

Every bootstrap of frictionlaws draws, within each *stratum*, as many *units* as the
stratum holds, with replacement: test conditions (the fit's bootstrap, and so a
campaign's fits, a comparison's and every fit of processed tribometer data), whole
sweeps within a kind of sweep and load level (``tyre fit-mf``'s sweep bootstrap).  A
stratum of one unit hands that unit to every resample.  When every stratum holds one
unit, every resample is the data itself: the refits land where the fit did, and their
spread (zero, or rounding) would read as a standard error of 0.  So two checks, one
before and one after, made here for every bootstrap:

* :func:`cannot_vary` (and :func:`check_can_vary`, which raises it) says why the
  resamples of a design cannot vary, before any refit is run;
* :func:`spread_errors` gives the standard deviation of each statistic's resampled
  values, and NaN (undetermined, withheld: not zero) where fewer than
  :data:`MIN_DETERMINED` resamples determine it or where its resampled values do not
  spread (all within :data:`ZERO_SPREAD` of each other, relative).

A shared fit has no resampling (its errors are asymptotic; the command line refuses
``--uncertainty`` with ``--shared``).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..base.errors import InputError

__all__ = ["ZERO_SPREAD", "MIN_DETERMINED", "cannot_vary", "check_can_vary", "no_spread",
           "spread_errors", "withheld_message"]

#: Relative spread of resampled values at or below which they do not spread at all
#: (rounding of identical refits): no error can be read from them.
ZERO_SPREAD = 1e-9
#: Fewest determined resamples from which a standard error is given.
MIN_DETERMINED = 10


def _plural(n: int, word: str) -> str:
    return f"one {word}" if n == 1 else f"{n} {word}s"


def cannot_vary(sizes: Sequence[int], *, unit: str, strata: str | None = None) -> str | None:
    """Why the resamples of this design cannot vary, or None when they can.

    Parameters
    ----------
    sizes : sequence of int
        The number of distinct units (conditions, sweeps) in each stratum; one entry
        when the units are drawn from one pool.
    unit : str
        What is drawn, in the singular (``"test condition"``, ``"sweep"``).
    strata : str, optional
        What a stratum is (``"kind of sweep x load level"``), when there are strata.

    Returns
    -------
    str or None
        The reason, as a clause (``"the data hold one test condition: every resample
        is the data itself"``), or None.
    """
    counts = [int(s) for s in sizes]
    if any(s > 1 for s in counts):
        return None
    total = sum(counts)
    if not counts or total == 0:
        return f"there is no {unit} to resample"
    if len(counts) == 1 or strata is None:
        return (f"the data hold {_plural(total, unit)}"
                f"{'' if len(counts) == 1 else ', one in each stratum'}: every resample "
                "is the data itself")
    return (f"each of the {len(counts)} strata ({strata}) holds one {unit}, and a "
            f"resample draws within each stratum: every resample is the data itself")


def check_can_vary(sizes: Sequence[int], *, unit: str, method: str,
                   strata: str | None = None, remedy: str = "",
                   source: str | None = None) -> None:
    """Refuse a resampling whose resamples cannot vary (see :func:`cannot_vary`).

    Parameters
    ----------
    sizes, unit, strata
        As for :func:`cannot_vary`.
    method : str
        The resampling, named in the message (``"the sweep bootstrap"``).
    remedy : str, optional
        What to do instead, appended to the message.
    source : str, optional
        The data's file, for the message.

    Raises
    ------
    InputError
        Saying why, and that the spread would read as a standard error of 0.
    """
    reason = cannot_vary(sizes, unit=unit, strata=strata)
    if reason is not None:
        raise InputError(f"{method} cannot vary: {reason}, so its spread would read as a "
                         f"standard error of 0{'; ' + remedy if remedy else ''}",
                         file=source)


def no_spread(values: np.ndarray) -> bool:
    """True when the finite ``values`` are too few or do not spread (see the module notes)."""
    s = np.asarray(values, float)
    s = s[np.isfinite(s)]
    return bool(s.size < MIN_DETERMINED or np.ptp(s) <= ZERO_SPREAD * max(
        float(np.max(np.abs(s))), np.finfo(float).tiny))


def spread_errors(samples: np.ndarray) -> np.ndarray:
    """The standard deviation of each column's resampled values; NaN where undetermined.

    Parameters
    ----------
    samples : ndarray, shape (B, m)
        Resampled values of m statistics (non-finite entries are left out per column).

    Returns
    -------
    ndarray, shape (m,)
        ``std(ddof=1)`` of each column, NaN where :func:`no_spread` holds.
    """
    samples = np.asarray(samples, float).reshape(len(samples), -1)
    out = np.full(samples.shape[1], np.nan)
    for j in range(samples.shape[1]):
        s = samples[:, j]
        s = s[np.isfinite(s)]
        if not no_spread(s):
            out[j] = float(np.std(s, ddof=1))
    return out


def withheld_message(method: str, names: Sequence[str]) -> str:
    """The warning for statistics whose resamples do not determine an error.

    Parameters
    ----------
    method : str
        The resampling (``"the bootstrap"``).
    names : sequence of str
        The statistics withheld.

    Returns
    -------
    str
    """
    return (f"{method} cannot determine the standard error of {', '.join(names)}: fewer "
            f"than {MIN_DETERMINED} resamples determine it, or they do not spread at all; "
            "it is withheld (undetermined, not zero)")
