"""The ``parameters`` table of a derived document in several parameters, shared by the
format-3 (derive/emit/document.py) and format-4 (derive/emit/atom_document.py) writers."""

from __future__ import annotations

from ..families.definition import Definition


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
