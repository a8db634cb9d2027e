"""Third-party laws load through the ``frictionlaws.laws`` entry-point group."""

from __future__ import annotations

from importlib import metadata

import pytest

from frictionlaws.law.registry import ENTRY_POINT_GROUP, Registry


def fake_entry_points(*eps):
    def entry_points(group=None):
        return [ep for ep in eps if group in (None, ep.group)]
    return entry_points


def test_entry_point_law_is_registered_and_broken_plugins_are_reported(monkeypatch):
    good = metadata.EntryPoint("linear", "plugin_example:LAW", ENTRY_POINT_GROUP)
    bad = metadata.EntryPoint("broken", "plugin_example:broken", ENTRY_POINT_GROUP)
    other = metadata.EntryPoint("other", "plugin_example:LAW", "some.other.group")
    monkeypatch.setattr(metadata, "entry_points", fake_entry_points(good, bad, other))
    reg = Registry()
    errors = reg.load_entry_points()
    assert reg.get("PLUGIN-LINEAR-P").id == "plugin-linear-p"
    assert len(reg) == 1
    assert len(errors) == 1 and "broken on purpose" in errors[0]
    assert reg.plugin_errors == errors


def test_plugin_cannot_shadow_a_builtin(monkeypatch):
    from plugin_example import LAW

    reg = Registry()
    reg.register(LAW)
    with pytest.raises(ValueError, match="already used"):
        reg.register(LAW)


def test_family_filter_and_unknown_family():
    from frictionlaws import list_laws
    from frictionlaws.base.errors import UnknownLawError

    assert all(law.family == "sliding" for law in list_laws("sliding"))
    with pytest.raises(UnknownLawError, match="unknown family"):
        list_laws("rolling")
