"""The built-in laws. Importing this package registers every law.

One module per group of laws; each declares its laws once with
:func:`frictionlaws.registry.register`.
"""

from importlib import import_module

__all__ = ["LAW_MODULES"]

#: The modules that declare built-in laws, in registration order.
LAW_MODULES = ("basic", "thesis", "velocity", "slip", "persson")

for _name in LAW_MODULES:
    import_module(f"{__name__}.{_name}")
