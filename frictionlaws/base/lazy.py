"""Package attributes loaded from their submodule on first use (PEP 562).

The package ``__init__`` modules list their public names with the submodule that
defines each; :func:`lazy_getattr` turns that table into the module's
``__getattr__``, so importing the package loads none of the submodules.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Mapping
from importlib import import_module
from typing import Any

__all__ = ["lazy_getattr"]


def lazy_getattr(package: str, api: Mapping[str, str]) -> Callable[[str], Any]:
    """The ``__getattr__`` of ``package``: names of ``api`` imported when first used.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    api : mapping
        Public name -> the submodule (relative to ``package``) that defines it.

    Returns
    -------
    callable
        ``__getattr__(name)``: imports the submodule, stores the name in the package
        (later lookups skip this function) and returns it; AttributeError otherwise.
    """
    def __getattr__(name: str) -> Any:
        if name in api:
            value = getattr(import_module(f"{package}.{api[name]}"), name)
            setattr(sys.modules[package], name, value)
            return value
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    return __getattr__
