"""How a fault in an untrusted file is quoted back: short enough to read.

jsonschema's messages quote the offending value whole (a 40,000-character formula that is too
long, a list of 10,000 entries); these helpers keep the quote to a readable stretch.
"""

from __future__ import annotations

MAX_MESSAGE = 300  # characters of a schema message shown; the rest is elided in the middle


def clip(text: str, limit: int = MAX_MESSAGE) -> str:
    """`text` itself when short, else its head and tail around an elision that says how much."""
    if len(text) <= limit:
        return text
    head = text[: limit * 2 // 3]
    tail = text[-(limit // 3) :]
    return f"{head} ... [{len(text) - len(head) - len(tail)} characters elided] ... {tail}"


def schema_message(error: object) -> str:
    """A jsonschema ValidationError's message, clipped (the value it quotes may be huge). A
    string that misses its pattern is told the schema's `description` of the form wanted,
    never the regular expression."""
    schema = getattr(error, "schema", None)
    if getattr(error, "validator", None) == "pattern" and isinstance(schema, dict):
        wanted = schema.get("description")
        if wanted:
            return clip(f"{getattr(error, 'instance', '')!r} is not {wanted}")
    return clip(str(getattr(error, "message", error)))
