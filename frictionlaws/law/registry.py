"""The registry of friction laws.

Laws are registered by declaration: each module in :mod:`frictionlaws.laws`
builds :class:`~frictionlaws.law.Law` objects and passes them to
:func:`register`.  Third-party packages add laws through the entry-point group
``frictionlaws.laws``; an entry point may name a :class:`Law`, an iterable of
laws, or a callable returning either.
"""

from __future__ import annotations

import builtins
import difflib
import importlib
from collections.abc import Callable, Iterable
from importlib import metadata

from ..base.errors import UnknownLawError
from . import FAMILIES, Law, set_lookup

__all__ = ["Registry", "REGISTRY", "register", "get_law", "list_laws", "builtin_laws",
           "ENTRY_POINT_GROUP"]

ENTRY_POINT_GROUP = "frictionlaws.laws"


class Registry:
    """A set of laws looked up by id or alias, case-insensitively."""

    def __init__(self) -> None:
        self._laws: dict[str, Law] = {}
        self._names: dict[str, str] = {}
        self._plugin_errors: list[str] = []
        self._derived: dict[str, Law] = {}
        self._derivations: dict[str, Callable[[Law], Law]] = {}

    def register(self, law: Law) -> Law:
        """Add ``law``; raise ValueError when its id or an alias is taken."""
        if not isinstance(law, Law):
            raise TypeError(f"expected a Law, got {type(law).__name__}")
        for name in (law.id, *law.aliases):
            key = name.lower()
            if key in self._names:
                raise ValueError(
                    f"cannot register law '{law.id}': name '{name}' is already "
                    f"used by law '{self._names[key]}'"
                )
        self._laws[law.id] = law
        for name in (law.id, *law.aliases):
            self._names[name.lower()] = law.id
        return law

    def unregister(self, law_id: str) -> None:
        """Remove a law (used by tests and plugins that replace a law)."""
        law = self._laws.pop(law_id)
        for name in (law.id, *law.aliases):
            self._names.pop(name.lower(), None)

    def get(self, name: str | Law) -> Law:
        """Look a law up by id or alias (case-insensitive)."""
        if isinstance(name, Law):
            return name
        key = str(name).strip().lower().replace("_", "-")
        if key in self._names:
            return self._laws[self._names[key]]
        key2 = str(name).strip().lower()
        if key2 in self._names:
            return self._laws[self._names[key2]]
        for suffix, derive in self._derivations.items():
            if key.endswith(f"+{suffix}"):
                return self._derived_law(key[: -len(suffix) - 1], suffix, derive)
        close = difflib.get_close_matches(key, list(self._names), n=3, cutoff=0.6)
        hint = f"; did you mean {', '.join(close)}?" if close else ""
        raise UnknownLawError(
            f"unknown law '{name}'{hint} (run 'frictionlaws laws' for the list)"
        )

    def add_derivation(self, suffix: str, derive: Callable[[Law], Law]) -> None:
        """Make ``<law>+<suffix>`` a name: ``derive(base)`` builds it on first use.

        Derived laws are cached and not listed by :meth:`list`, so fits saved with
        them load again (``+wlf`` is added by :mod:`frictionlaws.viscoelastic.temperature`).
        """
        self._derivations[suffix.lower()] = derive

    def _derived_law(self, base_name: str, suffix: str, derive: Callable[[Law], Law]) -> Law:
        base = self.get(base_name)
        key = f"{base.id}+{suffix}"
        if key not in self._derived:
            self._derived[key] = derive(base)
        return self._derived[key]

    def ids(self) -> list[str]:
        """All law ids in registration order."""
        return list(self._laws)

    def list(self, family: str | None = None) -> list[Law]:
        """All laws, optionally only those of ``family`` ('sliding' or 'slip')."""
        if family is not None and family not in FAMILIES:
            raise UnknownLawError(
                f"unknown family '{family}'; expected one of {', '.join(FAMILIES)}"
            )
        return [law for law in self._laws.values() if family in (None, law.family)]

    def __contains__(self, name: str) -> bool:
        return str(name).lower() in self._names

    def __len__(self) -> int:
        return len(self._laws)

    def load_entry_points(self) -> builtins.list[str]:
        """Register laws from the ``frictionlaws.laws`` entry-point group.

        Returns the messages of plugins that failed to load (they are also kept
        in :attr:`plugin_errors`); a broken plugin never breaks the built-ins.
        """
        errors = []
        for ep in metadata.entry_points(group=ENTRY_POINT_GROUP):
            try:
                obj = ep.load()
                if callable(obj) and not isinstance(obj, Law):
                    obj = obj()
                laws: Iterable[Law] = [obj] if isinstance(obj, Law) else list(obj)
                for law in laws:
                    self.register(law)
            except Exception as exc:  # noqa: BLE001 - a plugin may fail in any way
                errors.append(f"plugin '{ep.name}' ({ep.value}): {exc}")
        self._plugin_errors.extend(errors)
        return errors

    @property
    def plugin_errors(self) -> builtins.list[str]:
        """Messages of plugins that failed to load."""
        return list(self._plugin_errors)


REGISTRY = Registry()
_loaded = False


def register(law: Law) -> Law:
    """Register a law in the global registry.

    Parameters
    ----------
    law : Law
        The law to add; its id and aliases must not be taken yet.

    Returns
    -------
    Law
        ``law`` itself, so that ``register`` can be used as an expression.

    Raises
    ------
    TypeError
        When ``law`` is not a :class:`~frictionlaws.law.Law`.
    ValueError
        When its id or one of its aliases is already used by another law.
    """
    return REGISTRY.register(law)


def _ensure_loaded() -> None:
    global _loaded
    if not _loaded:
        _loaded = True
        importlib.import_module("frictionlaws.laws")
        REGISTRY.load_entry_points()


def get_law(name: str | Law) -> Law:
    """Return the law registered under a name (id or alias, any case).

    Parameters
    ----------
    name : str or Law
        Law id or alias (case-insensitive; ``_`` and ``-`` are equivalent), or
        ``"<law>+wlf"`` for a derived law; a :class:`~frictionlaws.law.Law` is
        returned as it is.

    Returns
    -------
    Law
        The registered (or derived) law.

    Raises
    ------
    UnknownLawError
        With the closest names, when nothing matches.
    """
    _ensure_loaded()
    return REGISTRY.get(name)


set_lookup(get_law)


def list_laws(family: str | None = None) -> list[Law]:
    """Return all registered laws, optionally filtered by family.

    Parameters
    ----------
    family : {"sliding", "slip"}, optional
        Only the laws of this family; None for all.

    Returns
    -------
    list of Law
        The laws in registration order; derived laws such as ``"<law>+wlf"``
        are not listed.

    Raises
    ------
    UnknownLawError
        For an unknown family.
    """
    _ensure_loaded()
    return REGISTRY.list(family)


def builtin_laws(family: str | None = None) -> list[Law]:
    """The registered laws frictionlaws declares itself (:mod:`frictionlaws.laws`).

    Parameters
    ----------
    family : {"sliding", "slip"}, optional
        Only the laws of this family; None for all.

    Returns
    -------
    list of Law
        :func:`list_laws` without the laws plugins added (a law is built in when its
        formula is defined inside the package).
    """
    return [law for law in list_laws(family)
            if getattr(law.formula, "__module__", "").startswith("frictionlaws.")]
