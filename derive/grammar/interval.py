"""Parameter intervals as records and definitions write them: `(-2, 1]`, `[-1, 1]`."""

from __future__ import annotations

import re
from dataclasses import dataclass
from fractions import Fraction

_NUMBER = r"\s*([-+]?\d+(?:/\d+)?)\s*"
_RANGE = re.compile(rf"\s*([\(\[]){_NUMBER},{_NUMBER}([\)\]])\s*")


@dataclass(frozen=True)
class Interval:
    lo: Fraction
    hi: Fraction
    lo_open: bool = False
    hi_open: bool = False

    def __str__(self) -> str:
        return f"{'(' if self.lo_open else '['}{self.lo}, {self.hi}{')' if self.hi_open else ']'}"

    def contains(self, x: Fraction) -> bool:
        above = x > self.lo if self.lo_open else x >= self.lo
        below = x < self.hi if self.hi_open else x <= self.hi
        return above and below

    @classmethod
    def parse(cls, text: str) -> Interval:
        """`(-2, 1]`, `[-1, 1]`: exact numbers (integers or p/q), brackets say closed."""
        m = _RANGE.fullmatch(text)
        if not m:
            raise ValueError(f"parameter range {text!r} is not of the form (a, b], [a, b], ...")
        lo, hi = Fraction(m.group(2)), Fraction(m.group(3))
        if lo > hi or (lo == hi and (m.group(1) == "(" or m.group(4) == ")")):
            raise ValueError(f"parameter range {text!r} is empty")
        return cls(lo, hi, m.group(1) == "(", m.group(4) == ")")
