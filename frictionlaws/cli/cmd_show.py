"""``frictionlaws show``: everything a law declares (and, given values, the bound law)."""

from __future__ import annotations

import argparse
import re
from typing import Any

from ..law import EVIDENCE_TAGS, VARIABLES
from ..law.registry import get_law
from ._common import add_json_option, add_law_source_options, bound_from_args, print_json
from .commands import COMMANDS

__all__ = ["add_parser", "run", "describe", "describe_bound"]


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser("show", help=COMMANDS["show"],
                       description="Show a law's formula, parameters with units and bounds, "
                       "settings, presets, domain, derived quantities, references and "
                       "evidence tag.  With --preset, --set or --params, also the law bound "
                       "to those values: each value with its unit, where it came from, the "
                       "derived quantities and the fitted ranges.")
    p.add_argument("law", metavar="LAW", help="law id or alias")
    add_law_source_options(p, fit=False)
    add_json_option(p)
    return p


def _header(law: Any) -> list[str]:
    out = [f"{law.id}: {law.title}"]
    if law.aliases:
        out.append(f"aliases: {', '.join(law.aliases)}")
    out.append(f"family: {law.family}")
    out.append(f"formula: {law.pretty()}")
    if law.description:
        out.append(f"description: {law.description}")
    out.append("variables: " + (", ".join(_variable_text(law, v) for v in law.variables)
                                or "none (constant)"))
    return out


def _declared_values(law: Any) -> list[str]:
    """Parameters, settings, floors and presets."""
    out = ["parameters:"]
    for p in law.params:
        lo, hi = p.bounds
        opt = f", default {p.default:g} if omitted" if p.optional else f", typical {p.default:g}"
        out.append(f"  {p.name:<8} [{p.unit or '-'}] bounds [{lo:g}, {hi:g}]{opt}: {p.meaning}")
    out.append("settings:" + ("" if law.settings else " none"))
    for st in law.settings:
        out.append(f"  {st.name:<8} = {st.value:g} {st.unit or '-'}: {st.meaning}")
    if law.floors:
        out.append("floors: " + ", ".join(f"{k} >= {v:g} {VARIABLES[k].unit}"
                                          for k, v in law.floors.items()))
    out.append("presets:" + ("" if law.presets else " none"))
    for name, vals in law.presets.items():
        out.append(f"  {name}: " + ", ".join(f"{k}={v:g}" for k, v in vals.items()))
    return out


def _domain_and_derived(law: Any) -> list[str]:
    if law.domain:
        out = ["domain: " + ", ".join(f"{k} {lo:g}..{hi:g} {VARIABLES[k].unit}"
                                      for k, (lo, hi) in law.domain.items())]
    else:
        out = ["domain: no stated limits (see notes)"]
    if law.derived:
        out.append("derived quantities:")
        for d in law.derived:
            out.append(f"  {d.name} [{d.unit or '-'}]: {d.meaning}{_preset_value(law, d.name)}")
    return out


def _preset_value(law: Any, name: str) -> str:
    """`` (preset X: value)`` for a derived quantity at the first preset, when it evaluates."""
    if not law.presets:
        return ""
    preset = next(iter(law.presets))
    try:
        val = law.derived_values(law.resolve(preset=preset))[name]
    except Exception:  # noqa: BLE001 - display only
        return ""
    return f" (preset {preset}: {val:.4g})"


def _references(law: Any) -> list[str]:
    out = [f"notes: {law.notes}"] if law.notes else []
    out.append("references:")
    out += [f"  - {r}" for r in law.references]
    tags = re.findall(r"\b(NF|C|S|M|I)\b", law.evidence)
    meaning = "; ".join(f"{t} = {EVIDENCE_TAGS[t]}" for t in dict.fromkeys(tags)
                        if t in EVIDENCE_TAGS)
    out.append(f"evidence: {law.evidence}" + (f" ({meaning})" if meaning else ""))
    return out


def describe(law_name: str) -> str:
    """The text ``show`` prints for a law."""
    law = get_law(law_name)
    return "\n".join([*_header(law), *_declared_values(law), *_domain_and_derived(law),
                      *_references(law)])


def describe_bound(bound: Any) -> str:
    """The lines ``show`` adds for a law bound to values (``--preset/--set/--params``)."""
    law = bound.law
    units = {p.name: p.unit for p in law.params} | {s.name: s.unit for s in law.settings}
    out = [f"bound values (from {bound.source.describe()}; SI):"]
    for k, v in bound.values.items():
        err = bound.stderr.get(k)
        extra = f" +/- {err:.3g}" if err is not None else (" (fixed)" if k in bound.fixed
                                                           else "")
        out.append(f"  {k:<8} = {v:.6g} {units.get(k) or '-'}{extra}")
    derived = bound.derived()
    if derived:
        out.append("derived at these values: " + ", ".join(
            f"{d.name} = {derived[d.name]:.4g} {d.unit}".rstrip() for d in law.derived))
    ranges = {k: r for k, r in bound.fitted_ranges.items() if k in law.variables}
    if ranges:
        out.append("fitted on: " + ", ".join(f"{k} {lo:.4g}..{hi:.4g} {VARIABLES[k].unit}"
                                             for k, (lo, hi) in ranges.items()))
    return "\n".join(out)


def _bound(args: argparse.Namespace) -> Any:
    """The bound law when values were given, else None (the declaration alone)."""
    if not (args.preset or args.set or args.params):
        return None
    return bound_from_args(args, args.law)


def run(args: argparse.Namespace) -> int:
    bound = _bound(args)
    if args.json:
        law = get_law(args.law)
        doc = law.summary()
        doc["formula"] = law.pretty()
        doc["latex"] = law.latex()
        if bound is not None:
            doc["bound"] = bound.to_dict()
        print_json(doc)
    else:
        text = describe(args.law)
        print(text if bound is None else f"{text}\n{describe_bound(bound)}")
    return 0


def _variable_text(law: Any, v: str) -> str:
    """One variable for ``show``: unit, this law's meaning, when it may be left out."""
    text = f"{v} [{VARIABLES[v].unit or '-'}] ({law.meaning(v)}"
    if v in law.optional_variables:
        pname, neutral = law.optional_variables[v]
        text += f"; optional when {pname} = {neutral:g}"
    return text + ")"
