"""Strict parsing of numbers typed by users: integers, decimals and p/q, nothing else.

User text is never evaluated as code: no eval, no sympify. Every accepted form is exact. The
grammar is ASCII: digits 0-9 only (Python's int() and regular expressions would also take
full-width and other Unicode digits), surrounding spaces and tabs only.
"""

from __future__ import annotations

import re
import sys
from fractions import Fraction

_NUMBER = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:/[+-]?[0-9]+)?")
_RATIO = re.compile(r"[+-]?[0-9]+/[+-]?[0-9]+")
_SPACE = " \t"
# a command-line word that is a negative number or a point starting with one ("-1,2", "-.5")
NEGATIVE = re.compile(r"-[0-9.][0-9.,/+-]*")


def parse_number(text: str) -> Fraction:
    """'3', '-0.25', '.5', '690/319' -> Fraction. Anything else raises ValueError."""
    s = text.strip(_SPACE)
    if not _NUMBER.fullmatch(s) or ("/" in s and not _RATIO.fullmatch(s)):
        raise ValueError(
            f"not a number: {text!r} (use an integer, a decimal such as -0.25, or p/q such as 3/4)"
        )
    digits = sum(c.isdigit() for c in s)
    limit = sys.get_int_max_str_digits()
    if limit and digits > limit:  # int() would raise its own message, naming a sys function
        raise ValueError(
            f"not a number: a coordinate of {digits} digits (at most {limit}, Python's limit "
            "for converting text to an integer)"
        )
    if "/" in s:
        p, q = s.split("/")
        if int(q) == 0:
            raise ValueError(f"not a number: {text!r} (zero denominator)")
        return Fraction(int(p), int(q))
    return Fraction(s)


def parse_int(text: str) -> int:
    """An ASCII integer (argparse's type=int would take '２' or '1_0')."""
    s = text.strip(_SPACE)
    if not re.fullmatch(r"[+-]?[0-9]+", s):
        raise ValueError(f"not an integer: {text!r}")
    return int(s)


def parse_point(text: str) -> tuple[Fraction, ...]:
    """'x,y' or 'x,y,z' -> a tuple of Fractions."""
    parts = text.split(",")
    if len(parts) not in (2, 3):
        raise ValueError(f"not a point: {text!r} (write x,y or x,y,z, e.g. 0,6 or 1/2,0.25,3)")
    return tuple(parse_number(p) for p in parts)
