"""Join weights from a derived document, for families in several parameters, indexed
families at one degree, and trigonometric, hyperbolic or mixed families (issue #30).

`lambda-bezier derive --family` solves the C1/C2/G1/G2 conditions of such a family with every
built-in family and with itself, exactly (derive/formulas/joins_several.py), and writes the
weights into the document's ``joins`` table: P2_r = Σ w[r, src, k] X_k, X_k = P1_{n-k}
(src "first") or a given P2_k (src "second"), each weight a quotient of polynomials in the
table's ``variables`` (n, m, lam1, lam2, alpha, d, each parameter x of the first and second
curve as x1 and x2, and the constant C of an atom family: pi or e^W). The text of a weight is
data ("coefficient@exponents ... / ..."), split here, never evaluated as an expression.

A one-parameter family's document (format 3) holds the same weights as polynomial data in its
``surface_joins`` table (the column-wise curve joins, in closed form in n and m: C1 and G1,
and C2 where derive found one), [num, den] of [coefficient, e1, ...] terms; `lookup` reads
both forms, so the curves' joins (_atom_joins.join_side) and the surfaces' derived joins
(surface_joins) take those weights through this one evaluation.

`lookup` gives the weights of a join at given values, or None where the document has none
(another family on the other side, a pair the derivation could not solve in closed form):
the callers then solve the join per degree (_join_engine, _atom_joins).
"""

from __future__ import annotations

import math
import re
from fractions import Fraction
from typing import Any

Number = Fraction | float
Key = tuple[int, str, int]

_TERM = re.compile(r"^(-?[0-9]+(?:/[0-9]+)?)@([0-9]+(?:,[0-9]+)*)?$")
_WEIGHT_KEY = re.compile(r"^([0-2]),(first|second),([0-9]{1,3})$")
_CONSTANT = re.compile(r"^(?:pi|exp\((-?[0-9]+(?:/[0-9]+)?)\))$")


class SingularWeight(ValueError):
    """A weight of the document's closed form has a vanishing denominator at these values:
    the join may still exist there (a removable singularity) or not; a per-degree solve
    decides and names the point it cannot determine (joins._generic_weights)."""


def side_values(side: int, names: tuple[str, ...], values: tuple[Number, ...]) -> dict[str, Any]:
    """The variables of one curve of the join: a one-parameter family's parameter is lam1 or
    lam2 whatever its name (derive's symbol `lam`), several parameters keep their names."""
    if len(names) == 1:
        return {f"lam{side}": values[0]}
    return {f"{x}{side}": v for x, v in zip(names, values, strict=True)}


def is_closed(table: object) -> bool:
    """Whether a joins table is in closed form in n and m (it has ``valid_from``)."""
    return isinstance(table, dict) and "pairs" in table and "valid_from" in table


def holds_at(table: dict[str, Any], continuity: str, degree: int) -> bool:
    """Whether a closed-form table's weights of `continuity` hold at this degree of the
    family: derive proved them for every degree from ``valid_from`` on (per order: "1" for
    C1/G1, "2" for C2/G2)."""
    if "valid_from" not in table:  # a one-parameter family's, derived for a general n and m
        return True
    order = "2" if continuity in ("C2", "G2") else "1"
    low = table["valid_from"].get(order) if isinstance(table["valid_from"], dict) else None
    if not isinstance(low, int):
        raise ValueError(f"joins: valid_from[{order!r}] must be a degree, got {low!r}")
    return degree >= low


def relative_values(
    side: int, base: str, degree: int, names: tuple[str, ...], values: dict[str, Any]
) -> dict[str, Any]:
    """An indexed family's parameters at one degree under their index-relative names of a
    closed-form table: name(k) and name(n-k) (name(n) for k = 0) with the side's suffix, for
    every index of the degree (the names are `base_k`)."""
    out = {}
    for name in names:
        k = int(name.rsplit("_", 1)[1])
        back = degree - k
        out[f"{base}({k}){side}"] = values[name]
        out[f"{base}(n){side}" if back == 0 else f"{base}(n-{back}){side}"] = values[name]
    return out


def constant_value(text: object) -> float:
    """The float of a table's constant: "pi" or "exp(W)" with W rational."""
    found = _CONSTANT.match(text) if isinstance(text, str) else None
    if found is None:
        raise ValueError(f"joins: constant {text!r} is neither 'pi' nor 'exp(W)'")
    return math.pi if found.group(1) is None else math.exp(float(Fraction(found.group(1))))


def _polynomial(text: str, size: int, where: str) -> list[tuple[Fraction, tuple[int, ...]]]:
    out = []
    for term in text.split():
        found = _TERM.match(term)
        exps = () if found is None or found.group(2) is None else found.group(2).split(",")
        if found is None or len(exps) != size:
            raise ValueError(f"{where}: {term!r} is not a term coefficient@e1,...,e{size}")
        out.append((Fraction(found.group(1)), tuple(int(e) for e in exps)))
    return out


def lookup(
    table: object, pair: str, continuity: str, values: dict[str, Any]
) -> dict[Key, Number] | None:
    """{(row, src, k): weight} of `pair` ("first>second") and `continuity` at `values` (by
    variable name), exact when every value used is exact and the weights do not involve the
    constant C; None when the table has no such weights. ValueError where a weight's
    denominator vanishes at these values (the join does not exist there)."""
    if not isinstance(table, dict) or "pairs" not in table:
        return None
    entry = table["pairs"].get(pair)
    if not isinstance(entry, dict) or continuity not in entry:
        return None
    variables = table.get("variables")
    if not isinstance(variables, list) or not all(isinstance(v, str) for v in variables):
        raise ValueError("joins: variables must be a list of names")
    point: list[Any] = []
    for name in variables:
        if name == "C":
            point.append(constant_value(table.get("constant")))
        else:  # None: a variable of another pair (checked where a term uses it)
            v = values.get(name)
            point.append(Fraction(v) if isinstance(v, int) else v)
    where = f"joins of {pair}, {continuity}"
    out: dict[Key, Number] = {}
    for key, text in entry[continuity].items():
        found = _WEIGHT_KEY.match(key)
        if found is None:
            raise ValueError(f"{where}: {key!r}: not a weight 'row,src,k': 'num / den'")
        num, den = (_value(h, point, variables) for h in _halves(text, len(point), where, key))
        if den == 0:
            raise SingularWeight(
                f"cannot solve {continuity}: the derived weight of P_{{{found.group(1)},2}} in "
                f"{pair} has a vanishing denominator at these degrees and parameters "
                "(choose another degree or parameters)"
            )
        out[(int(found.group(1)), found.group(2), int(found.group(3)))] = num / den
    if any(isinstance(w, float) for w in out.values()):
        return {k: float(w) for k, w in out.items()}
    return out


def _halves(
    weight: object, size: int, where: str, key: str
) -> tuple[list[tuple[Fraction, tuple[int, ...]]], list[tuple[Fraction, tuple[int, ...]]]]:
    """(numerator, denominator) of one weight as [(coefficient, exponents)]: the ``joins``
    text "num / den" of "coefficient@e1,...", or the ``surface_joins`` data [num, den] of
    [coefficient, e1, ...] terms (a one-parameter family's document); data, never evaluated."""
    if isinstance(weight, str):
        halves = weight.split(" / ")
        if len(halves) == 2:
            return _polynomial(halves[0], size, where), _polynomial(halves[1], size, where)
    elif isinstance(weight, list) and len(weight) == 2:
        out = []
        for half in weight:
            if not isinstance(half, list) or not all(
                isinstance(t, list)
                and len(t) == size + 1
                and isinstance(t[0], str)
                and all(isinstance(e, int) and 0 <= e <= 64 for e in t[1:])
                for t in half
            ):
                break
            out.append([(Fraction(t[0]), tuple(t[1:])) for t in half])
        if len(out) == 2:
            return out[0], out[1]
    raise ValueError(
        f"{where}: {key!r}: not a weight 'num / den' or [num, den] of {size} variables"
    )


def _value(
    poly: list[tuple[Fraction, tuple[int, ...]]], point: list[Any], names: list[str]
) -> Number:
    total: Any = Fraction(0)  # a float only where a float value enters with exponent > 0
    for coef, exps in poly:
        term: Any = coef
        for x, e, name in zip(point, exps, names, strict=True):
            if e and x is None:
                raise ValueError(f"joins: no value for the variable {name!r}")
            if e:
                term *= x**e
        total += term
    return total  # type: ignore[no-any-return]
