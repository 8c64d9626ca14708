"""`lambda-bezier verify --coverage`: every item of the three papers, with its records or why
it has none.

The inventory is data, written by reading the papers: derive/published/coverage/<doc>.toml,
one ``[[item]]`` per numbered equation, proposition, theorem, worked example (and sentence
carrying mathematics), each with ``section``, ``item`` and either ``records`` (ids of records)
or ``reason``. The report joins it with the verdicts of a verification run; an item naming a
record that does not exist, or a built-in record that no item names, is a problem (exit 1),
so the inventory and the records cannot drift apart.
"""

from __future__ import annotations

import json
import sys
from dataclasses import dataclass
from pathlib import Path

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

COVERAGE_DIR = Path(__file__).resolve().parents[1] / "published" / "coverage"


@dataclass(frozen=True)
class Item:
    source: str
    section: str
    item: str
    records: tuple[str, ...]
    reason: str


def load(directory: Path = COVERAGE_DIR) -> list[Item]:
    out = []
    for path in sorted(directory.glob("*.toml")):
        data = tomllib.loads(path.read_text(encoding="utf-8"))
        for entry in data["item"]:
            records, reason = tuple(entry.get("records", ())), entry.get("reason", "")
            if bool(records) == bool(reason):
                raise ValueError(
                    f"{path}: item {entry.get('item')!r} needs either records or a reason"
                )
            out.append(Item(data["source"], entry["section"], entry["item"], records, reason))
    return out


def problems(items: list[Item], verdicts: dict[str, str]) -> list[str]:
    """Items naming unknown records; built-in records named by no item."""
    named = {rid for it in items for rid in it.records}
    out = [
        f"coverage: {it.source}, {it.item!r} names no record {rid!r}"
        for it in items
        for rid in it.records
        if rid not in verdicts
    ]
    out += [
        f"coverage: record {rid!r} is in no coverage item" for rid in verdicts if rid not in named
    ]
    return out


def render(items: list[Item], verdicts: dict[str, str], markdown: bool = False) -> str:
    lines = []
    by_source: dict[str, list[Item]] = {}
    for it in items:
        by_source.setdefault(it.source, []).append(it)
    for source, group in by_source.items():
        covered = sum(1 for it in group if it.records)
        lines += [
            f"**{source}**" if markdown else f"## {source}",
            "",
            f"{len(group)} items: {covered} with records, "
            f"{len(group) - covered} without (reason given)",
            "",
        ]
        if markdown:
            lines += ["| section | item | records (verdict) or reason |", "|---|---|---|"]
        section = None
        for it in group:
            what = (
                ", ".join(f"{rid} ({verdicts.get(rid, 'MISSING')})" for rid in it.records)
                if it.records
                else f"no record: {it.reason}"
            )
            if markdown:
                cell = what.replace("|", "\\|")
                lines.append(f"| {it.section} | {it.item.replace('|', '/')} | {cell} |")
            else:
                if it.section != section:
                    lines.append(f"  {it.section}")
                    section = it.section
                lines.append(f"    {it.item}")
                lines.append(f"      {what}")
        lines.append("")
    total = len(items)
    with_records = sum(1 for it in items if it.records)
    lines.append(
        f"{total} items in {len(by_source)} documents: {with_records} with records, "
        f"{total - with_records} without"
    )
    return "\n".join(lines) + "\n"


def render_json(items: list[Item], verdicts: dict[str, str]) -> str:
    """The coverage as data (`verify --coverage --format json`): every item with its document,
    section, records and their verdicts, or the reason it has none."""
    data = {
        "items": [
            {
                "document": it.source,
                "section": it.section,
                "item": it.item,
                "records": [{"id": rid, "verdict": verdicts.get(rid)} for rid in it.records],
                "reason": it.reason or None,
            }
            for it in items
        ],
        "summary": {
            "items": len(items),
            "documents": len({it.source for it in items}),
            "with_records": sum(1 for it in items if it.records),
        },
    }
    return json.dumps(data, indent=2, ensure_ascii=False) + "\n"
