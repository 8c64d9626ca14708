"""Expressions of the published records: parsing with the records grammar's fixed table
(derive/grammar), and the papers' binomial convention.

Formulas of records files (the built-in ones and a user's, which are untrusted) are read by
our own tokenizer and parser over a FIXED table of symbols and undefined functions, with
limits on length, depth and exponents; nothing in a file is ever evaluated as code.

Binomial convention. The papers use C_n^k = 0 unless 0 <= k <= n (including a negative n).
SymPy's ``binomial`` does not (``binomial(-2, 1) == -2``), so a concrete binomial is always
evaluated by ``paper_binomial``.
"""

from __future__ import annotations

from functools import cache
from math import comb

import sympy as sp
from sympy.core.function import AppliedUndef

from ..grammar import SYMBOLS, parse_formula
from ..grammar import ParseError as ParseError  # re-exported: callers catch it from here

INDEX_SYMBOLS = tuple(SYMBOLS[s] for s in ["i", "j", "k", "l", "r"])
DEGREE_SYMBOLS = (SYMBOLS["n"], SYMBOLS["m"])
# Functions whose first argument is a control-point index (shifted by the difference operator).
POINT_LIKE = frozenset(["b", "bk", "a", "P", "P1", "P2", "V", "V1", "V2", "Vl", "Ql", "Q", "W"])
# Summation ranges a formula may ask for (a hostile Sum(..., (i, 0, 10**9)) is refused).
MAX_SUM_TERMS = 10_000


def as_sympy(x: object) -> sp.Basic:
    """A number or a SymPy object as SymPy; a string is refused (sympify would evaluate it)."""
    if isinstance(x, str):
        raise TypeError("a string reaches SymPy only through parse_formula")
    return sp.sympify(x, strict=True)


@cache
def parse(text: str) -> sp.Expr:
    """A printed expression, read by the records grammar (derive/grammar/formula.py): our own parser
    over a fixed table of symbols and functions, nothing evaluated."""
    return parse_formula(text)


def parse_relation(text: str):
    """A boolean condition (convexity conclusions): relations joined by & and |."""
    return parse(text)


def fn_name(expr) -> str | None:
    return expr.func.__name__ if isinstance(expr, AppliedUndef) else None


# --------------------------------------------------------------------------- binomials


def paper_binomial(a: int, b: int) -> int:
    """C_a^b with the papers' convention: 0 unless 0 <= b <= a."""
    return comb(a, b) if 0 <= b <= a else 0
