"""What the derived family documents share, written by the format-3 (derive/emit/document.py)
and format-4 (derive/emit/atom_document.py) writers: the keys each opens with, and the
``parameters`` table of a family in several parameters."""

from __future__ import annotations

from ..families.definition import Definition

GENERATED_BY = (
    "lambda-bezier derive --family -- DO NOT EDIT; regenerate with "
    "`lambda-bezier derive --family FILE`"
)


def document_header(defn: Definition, fmt: int) -> dict:
    """{generated_by, format, definition_sha256, family, title}: the keys every derived
    family document opens with, in this order (the text is deterministic: keys keep it)."""
    return {
        "generated_by": GENERATED_BY,
        "format": fmt,
        "definition_sha256": defn.digest,
        "family": defn.name,
        "title": defn.title,
    }


def parameter_table(defn: Definition) -> list[dict]:
    """[{name, range {text, lo, hi, closed}, bernstein_at}] in the definition's order."""
    return [
        {
            "name": q.name,
            "range": {
                "text": q.range_text,
                "lo": str(q.lo),
                "hi": str(q.hi),
                "closed": [q.lo_closed, q.hi_closed],
            },
            "bernstein_at": None if q.bernstein_at is None else str(q.bernstein_at),
        }
        for q in defn.params
    ]
