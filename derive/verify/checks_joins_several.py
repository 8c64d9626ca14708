"""The claim kind ``several_join``: a join weight of a family in several parameters (plain,
indexed at one degree ``n``) or of a trigonometric, hyperbolic or mixed family, with a
built-in family or itself (issue #30).

A record names the ordered ``pair`` ("first>second", the family's name or a built-in one),
the ``continuity`` and ``join_weights``, a table {"row,src,k": formula}: P2_row = sum of
weight * X_k with X_k = P1_{n-k} (src "first") or the given P2_k (src "second"). A formula
is in n and m (the degrees of the first and second curve), alpha and d (the G constants),
lam1 and lam2 (a built-in family's parameter, or a one-parameter family's), x1 and x2 for a
parameter x of the first and second curve, and ``pi`` (``e`` for Euler's number). It is
compared exactly with derive's weight (derive/formulas/joins_several.py): the difference,
cancelled as a rational function in these symbols and pi or e (both transcendental), is 0.
"""

from __future__ import annotations

from fractions import Fraction

import sympy as sp

from ..families.cbezier import CDefinition
from ..families.definition import Definition
from ..formulas import joins
from ..formulas.joins_several import C, end_forms, pair_weights
from ..grammar import ParseError, parse_formula
from . import checks_cbezier, checks_closed_n
from .checks_core import KIND_FAMILIES, Outcome, checker
from .checks_elementary import RecordError
from .claim_families import SEVERAL_FAMILIES

KIND_FAMILIES["several_join"] = (
    ("(families in several parameters)",),
    "it is about a family in several shape parameters or with sin, cos, sinh, cosh, exp "
    "(a records file defining one)",
)


def _constant(name: str | None) -> sp.Expr:
    if name is None:
        return C
    if name == "pi":
        return sp.pi
    return sp.exp(sp.Rational(str(Fraction(name[4:-1]))))  # "exp(W)"


def _symbols(defn: Definition) -> dict[str, sp.Symbol]:
    names = {x.name: x for x in joins.BASE_SYMBOLS}
    for side in (1, 2):
        for x in defn.symbols:
            s = joins.side_symbol(x, side)
            names[s.name] = s
    return names


@checker("several_join")
def check_several_join(record: dict, _context: object) -> Outcome:
    if isinstance(SEVERAL_FAMILIES[record["family"]], CDefinition):  # checks_cbezier.py
        return checks_cbezier.join(record, SEVERAL_FAMILIES[record["family"]])
    defn: Definition = SEVERAL_FAMILIES[record["family"]]  # type: ignore[assignment]
    pair, continuity = record.get("pair"), record.get("continuity")
    claimed = record.get("join_weights")
    if not isinstance(pair, str) or continuity not in joins.ORDER:
        raise RecordError("keys pair ('first>second') and continuity (C1, C2, G1, G2) are required")
    if not isinstance(claimed, dict) or not claimed:
        raise RecordError("key join_weights: a table {'row,src,k': formula} is required")
    degree = record.get("n")
    if degree is None and len(defn.degrees) > 1:  # weights in closed form in n and m
        return checks_closed_n.check_join(record, defn, pair, continuity, claimed)
    if defn.indexed is not None and not isinstance(degree, int):
        raise RecordError("key n: the degree is required for an indexed family")
    if degree is not None and (not isinstance(degree, int) or degree not in defn.degrees):
        raise RecordError(f"key n: {degree!r} is not a degree of the family ({defn.degrees})")
    at = defn.at_degree(degree) if defn.indexed is not None else defn
    forms, deg, constant = end_forms(defn, degree)
    derived = pair_weights(at, deg, forms, pair, continuity)
    if isinstance(derived, str):
        return Outcome("mismatch", [f"derive finds no closed-form {continuity} weights: {derived}"])
    symbols = _symbols(at)
    value = _constant(constant)
    diffs, checked = [], []
    for key, text in sorted(claimed.items()):
        try:
            got = parse_formula(text, {**symbols, "e": sp.E}, {}, elementary=True)
        except ParseError as exc:
            raise RecordError(f"key join_weights.{key}: {exc}") from None
        want = derived.get(key, sp.Integer(0)).xreplace({C: value})
        if sp.cancel(sp.together(got - want)) != 0:
            diffs.append(f"{pair} {continuity} weight {key}: printed {text}, derived {want}")
        checked.append(f"{pair} {continuity} weight {key}: exact")
    return Outcome("mismatch" if diffs else "match", diffs, checked)
