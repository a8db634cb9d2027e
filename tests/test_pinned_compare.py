"""Pinned results of ``frictionlaws compare thesis-steel`` (the sliding laws, defaults).

The comparison is run over the laws pinned here (the sliding laws at the time), named
explicitly, so a law added later joins other comparisons without moving these numbers.

The numbers below are what the comparison gave *before* it was made faster (lean
refits in cross-validation and hold-outs, parallel folds, cheaper figures): they were
generated at commit bf71f47 by running this file as a script,

    python tests/test_pinned_compare.py > /tmp/pinned.txt

and pasting its output into ``PINNED``.  Speed work must not move them: every
per-law statistic (R^2, AIC, BIC, fit RMSE, CV RMSE over the law's own rows and
over the common rows, extrapolation RMSE) must agree to 1e-6 relative, and the
ranking must be identical.  The same holds with ``jobs=2`` (folds in parallel).
"""

from __future__ import annotations

import math
import pprint
from typing import Any

import pytest

from frictionlaws.comparison import Comparison, compare

#: Relative tolerance of every pinned number.
RTOL = 1e-6
#: The statistics pinned per law (keys of ``LawComparison.to_dict()``).
KEYS = ("r2", "aic", "bic", "rmse", "cv_rmse", "cv_rmse_common", "extrapolation_rmse")

# output of the script at commit bf71f47 (see the module docstring)
PINNED: dict[str, Any] = {'ranking': ['thirion',
             'denny',
             'quadratic-pv',
             'thesis-poly2',
             'schallamach',
             'coulomb',
             'nackenhorst-thesis',
             'savkoor',
             'thesis-poly3',
             'wriggers',
             'exponential-decay',
             'huemer',
             'nackenhorst'],
 'laws': {'thirion': {'r2': 0.9306208830539718,
                      'aic': -54.119961651599084,
                      'bic': -52.2310836932662,
                      'rmse': 0.21664988208916597,
                      'cv_rmse': 0.3308345062664467,
                      'cv_rmse_common': 0.36290955233557765,
                      'extrapolation_rmse': 0.3362084204971953},
          'denny': {'r2': 0.9306208830893307,
                    'aic': -54.11996166128235,
                    'bic': -52.231083702949476,
                    'rmse': 0.21664988203395857,
                    'cv_rmse': 0.33084050534721665,
                    'cv_rmse_common': 0.3629158320140029,
                    'extrapolation_rmse': 0.33620379406300255},
          'quadratic-pv': {'r2': 0.960035488856544,
                           'aic': -56.60024907252463,
                           'bic': -50.933615197525995,
                           'rmse': 0.16443010175279213,
                           'cv_rmse': 0.3245277416194857,
                           'cv_rmse_common': 0.37569081131246346,
                           'extrapolation_rmse': 1.3687708395505598},
          'thesis-poly2': {'r2': 0.9371429028912266,
                           'aic': -49.99568086057404,
                           'bic': -45.27348596474184,
                           'rmse': 0.20621546569173438,
                           'cv_rmse': 0.33789915728548486,
                           'cv_rmse_common': 0.384470918911311,
                           'extrapolation_rmse': 1.4080562004243853},
          'schallamach': {'r2': 0.693758986889647,
                          'aic': -25.909018098198494,
                          'bic': -24.020140139865614,
                          'rmse': 0.45517222114476397,
                          'cv_rmse': 0.5387871509030955,
                          'cv_rmse_common': 0.6355428409891913,
                          'extrapolation_rmse': 0.672986880771574},
          'coulomb': {'r2': 0.0,
                      'aic': -5.4247437107068945,
                      'bic': -4.480304731540454,
                      'rmse': 0.8225154663988842,
                      'cv_rmse': 0.9194871321379539,
                      'cv_rmse_common': 1.0736269693450564,
                      'extrapolation_rmse': 1.2392731026637034},
          'nackenhorst-thesis': {'r2': 0.9959254136050782,
                                 'aic': -47.93159206721052,
                                 'bic': -45.14632515762192,
                                 'rmse': 0.059900383790673334,
                                 'cv_rmse': 0.0995469596686375,
                                 'cv_rmse_common': 0.0995469596686375,
                                 'extrapolation_rmse': 0.07920404141817557},
          'savkoor': {'r2': 0.9924522287174118,
                      'aic': -45.15027816564522,
                      'bic': -43.16080180165336,
                      'rmse': 0.08152620100217825,
                      'cv_rmse': 0.2176292184402283,
                      'cv_rmse_common': 0.2176292184402283,
                      'extrapolation_rmse': 0.14062590154047178},
          'thesis-poly3': {'r2': 0.9727297124270621,
                           'aic': -61.86193690961515,
                           'bic': -55.25086405545007,
                           'rmse': 0.1358278830201559,
                           'cv_rmse': 0.28498839374423235,
                           'cv_rmse_common': 0.34987565968259177,
                           'extrapolation_rmse': 0.8477878204920174},
          'wriggers': {'r2': 0.923008839724587,
                       'aic': -50.14197235210375,
                       'bic': -47.30865541460443,
                       'rmse': 0.22822567770958205,
                       'cv_rmse': 0.8542804920904375,
                       'cv_rmse_common': 0.37709146514568415,
                       'extrapolation_rmse': 0.35100551172585054},
          'exponential-decay': {'r2': 0.31831745557998536,
                                'aic': -6.705376641748241,
                                'bic': -2.9276207250824804,
                                'rmse': 0.6791022349400531,
                                'cv_rmse': 0.9360531102360514,
                                'cv_rmse_common': 1.1057822328397213,
                                'extrapolation_rmse': 1.2271634623826813},
          'huemer': {'r2': 0.9959254136060756,
                     'aic': -49.931592069903026,
                     'bic': -47.5442204331128,
                     'rmse': 0.05990038378334233,
                     'cv_rmse': 2.0812719646016737,
                     'cv_rmse_common': 2.0812719646016737,
                     'extrapolation_rmse': 0.3975199963881304},
          'nackenhorst': {'r2': 0.9959254136060756,
                          'aic': -51.93159206990292,
                          'bic': -49.942115705911064,
                          'rmse': 0.059900383783342614,
                          'cv_rmse': 3.6724388637476673,
                          'cv_rmse_common': 3.6724388637476673,
                          'extrapolation_rmse': 0.9202736354564812}}}


def summary(cmp: Comparison) -> dict[str, Any]:
    """The pinned view of a comparison: the ranking and the statistics per law.

    Parameters
    ----------
    cmp : Comparison
        A comparison of the thesis-steel data.

    Returns
    -------
    dict
        ``{"ranking": [...], "laws": {id: {key: value}}}``.
    """
    laws = {}
    for r in cmp.results:
        d = r.to_dict()
        laws[r.id] = {k: float(d[k]) for k in KEYS}
    return {"ranking": list(cmp.ranking), "laws": laws}


def _check(got: dict[str, Any]) -> None:
    assert got["ranking"] == PINNED["ranking"]
    for law, stats in PINNED["laws"].items():
        for key, want in stats.items():
            have = got["laws"][law][key]
            if math.isnan(want):
                assert math.isnan(have), (law, key, have)
            else:
                assert have == pytest.approx(want, rel=RTOL, abs=0.0), (law, key, have, want)


@pytest.fixture(scope="module")
def serial() -> dict[str, Any]:
    return summary(compare(data="thesis-steel", laws=list(PINNED["laws"]), progress=False))


@pytest.mark.slow
def test_compare_thesis_steel_is_pinned(serial: dict[str, Any]) -> None:
    _check(serial)



@pytest.mark.slow
def test_compare_in_two_processes_gives_the_same_results(serial: dict[str, Any]) -> None:
    parallel = summary(compare(data="thesis-steel", laws=list(PINNED["laws"]), progress=False,
                               jobs=2))
    assert parallel["ranking"] == serial["ranking"]
    for law, stats in serial["laws"].items():
        for key, value in stats.items():
            have = parallel["laws"][law][key]
            assert have == value or (math.isnan(have) and math.isnan(value)), (law, key)


if __name__ == "__main__":
    pprint.pprint(summary(compare(data="thesis-steel", laws=list(PINNED["laws"]),
                                  progress=False)), width=100,
                  sort_dicts=False)
