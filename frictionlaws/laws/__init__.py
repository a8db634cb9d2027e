"""The built-in laws. Importing this package registers every law.

One module per group of laws; each declares its laws once with
:func:`frictionlaws.law.registry.register`.  Every public module of this package is a
law module: a new one is found here without being listed anywhere.
"""

import pkgutil
from importlib import import_module

__all__ = ["LAW_MODULES"]

#: Registration order of the first law modules (the order ``frictionlaws laws``, the
#: catalogue and comparisons list the laws in); any other module follows, by name.
_FIRST = ("basic", "polynomial", "velocity", "slip", "persson")


def _law_modules() -> tuple[str, ...]:
    found = {m.name for m in pkgutil.iter_modules(__path__) if not m.name.startswith("_")}
    return tuple(n for n in _FIRST if n in found) + tuple(sorted(found - set(_FIRST)))


#: The modules that declare built-in laws, in registration order.
LAW_MODULES = _law_modules()

for _name in LAW_MODULES:
    import_module(f"{__name__}.{_name}")
