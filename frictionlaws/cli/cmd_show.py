"""``frictionlaws show``: everything a law declares."""

from __future__ import annotations

import argparse
import re
from typing import Any

from ._common import add_json_option, print_json


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser("show", help="show a law: formula, parameters, presets, evidence",
                       description="Show a law's formula, parameters with units and bounds, "
                       "settings, presets, domain, derived quantities, references and "
                       "evidence tag.")
    p.add_argument("law", metavar="LAW", help="law id or alias")
    add_json_option(p)
    return p


def describe(law_name: str) -> str:
    """The text ``show`` prints for a law."""
    from frictionlaws.law import EVIDENCE_TAGS, VARIABLES
    from frictionlaws.registry import get_law

    law = get_law(law_name)
    out = [f"{law.id}: {law.title}"]
    if law.aliases:
        out.append(f"aliases: {', '.join(law.aliases)}")
    out.append(f"family: {law.family}")
    out.append(f"formula: {law.pretty()}")
    if law.description:
        out.append(f"description: {law.description}")
    out.append("variables: " + (", ".join(_variable_text(law, v) for v in law.variables)
                                or "none (constant)"))
    out.append("parameters:")
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
    if law.domain:
        out.append("domain: " + ", ".join(f"{k} {lo:g}..{hi:g} {VARIABLES[k].unit}"
                                          for k, (lo, hi) in law.domain.items()))
    else:
        out.append("domain: no stated limits (see notes)")
    if law.derived:
        out.append("derived quantities:")
        for d in law.derived:
            preset_vals = ""
            if law.presets:
                name = next(iter(law.presets))
                try:
                    val = law.derived_values(law.resolve(preset=name))[d.name]
                    preset_vals = f" (preset {name}: {val:.4g})"
                except Exception:  # noqa: BLE001 - display only
                    preset_vals = ""
            out.append(f"  {d.name} [{d.unit or '-'}]: {d.meaning}{preset_vals}")
    if law.notes:
        out.append(f"notes: {law.notes}")
    out.append("references:")
    for r in law.references:
        out.append(f"  - {r}")
    tags = re.findall(r"\b(NF|C|S|M|I)\b", law.evidence)
    meaning = "; ".join(f"{t} = {EVIDENCE_TAGS[t]}" for t in dict.fromkeys(tags)
                        if t in EVIDENCE_TAGS)
    out.append(f"evidence: {law.evidence}" + (f" ({meaning})" if meaning else ""))
    return "\n".join(out)


def run(args: argparse.Namespace) -> int:
    from frictionlaws.registry import get_law

    if args.json:
        law = get_law(args.law)
        doc = law.summary()
        doc["formula"] = law.pretty()
        doc["latex"] = law.latex()
        print_json(doc)
    else:
        print(describe(args.law))
    return 0


def _variable_text(law: Any, v: str) -> str:
    """One variable for ``show``: unit, this law's meaning, when it may be left out."""
    from frictionlaws.law import VARIABLES

    text = f"{v} [{VARIABLES[v].unit or '-'}] ({law.meaning(v)}"
    if v in law.optional_variables:
        pname, neutral = law.optional_variables[v]
        text += f"; optional when {pname} = {neutral:g}"
    return text + ")"
