"""frictionlaws: friction laws for rubber and tyres, fitted, compared and exported.

The public API is imported lazily so that ``import frictionlaws`` and the CLI
stay fast; heavy modules (lmfit, pandas, pint, sympy, matplotlib) load only
when a function that needs them is called.
"""

from __future__ import annotations

from .base.lazy import lazy_getattr

__version__ = "0.1.0"

#: public name -> module that defines it
_API = {
    "get_law": "law.registry",
    "list_laws": "law.registry",
    "register": "law.registry",
    "REGISTRY": "law.registry",
    "Law": "law",
    "Param": "law",
    "Setting": "law",
    "Derived": "law",
    "VARIABLES": "law",
    "InputError": "base.errors",
    "FitError": "base.errors",
    "UnknownLawError": "base.errors",
    "fit": "fitting",
    "FitResult": "fitting",
    "load_result": "fitting",
    "BoundLaw": "law.bound",
    "with_wlf": "viscoelastic.temperature",
    "wlf_log_aT": "viscoelastic.temperature",
    "build_master_curve": "viscoelastic.mastercurve",
    "load_dataset": "io",
    "Dataset": "io",
    "list_datasets": "io",
    "export": "fe_export",
    "compare": "comparison",
    "BrushModel": "tyre",
    "BrushTyre": "tyre",
    "MagicFormula": "tyre",
    "reduce_mf": "tyre",
    "thesis_comparison": "tyre",
    "process_campaign": "tribometer",
    "load_rig": "tribometer",
    "run_validation": "validation",
}

__all__ = sorted(_API) + ["__version__"]


__getattr__ = lazy_getattr(__name__, _API)


def __dir__() -> list[str]:
    return __all__
