"""Join weights C1/C2/G1/G2 of a family of one order in several parameters (an indexed
family at each of its degrees, or a trigonometric, hyperbolic or mixed family), with every
built-in family and with itself, in both directions (issue #30).

The solve is derive/formulas/joins.py's, unchanged: the family is registered there with its
exact end values and derivatives (orders 0..2) as forms in its parameters, and for an atom
family in the constant C of its exact numbers (C = pi for a trigonometric space, C = e^W for
a hyperbolic one: both transcendental, so C is an indeterminate and every weight is an exact
element of Q(n, m, parameters, alpha, d, C)). Each parameter x is x1 on the first curve and
x2 on the second (joins.side_symbol); a built-in family's parameter is lam1 or lam2 and its
degree n (first) or m (second). Derivatives are in each curve's own parameter t on its own
domain (the end of the first curve's domain, the start of the second's), as the runtime
joins them. The solve checks every solution against its conditions for general symbols.

In the document a weight is the text "numerator / denominator", each polynomial in the
table's `variables` written as terms ``coefficient@e1,e2,...`` (data: the runtime splits it,
it parses no expression). One line per weight keeps the documents small.
"""

from __future__ import annotations

from fractions import Fraction

import sympy as sp

from ..algebra import t
from ..families.definition import CONTINUITIES, Definition
from ..families.engine import basis_polys
from ..families.registry import builtin_names
from ..families.spaces import Space, space_of
from . import joins
from .atom_family import end_values

C = sp.Symbol("C")  # the transcendental constant of an atom family's exact numbers
RULE = (
    "The second curve continues the first: P2_r = sum over (src, k) of w[r,src,k] X_k for "
    "r = 0..order (1 for C1/G1, 2 for C2/G2), X_k = P1_{n-k} (src first) or the given P2_k "
    "(src second). Conditions, in each curve's own parameter: C2(start) = C1(end), "
    "C1'(end) = alpha C2'(start), C1''(end) = alpha^2 C2''(start) + d C2'(start) (alpha = 1, "
    "d = 0 for C joins). Variables: n, m the degrees of the first and second curve, x1 and x2 "
    "the parameter x of the first and second curve (lam1, lam2 for a built-in family), and C "
    "the family's constant. Each weight is the text 'numerator / denominator', each a "
    "polynomial written as space-separated terms coefficient@e1,e2,... (the exponents of the "
    "variables in order)."
)


def polynomial_end_forms(defn: Definition, degree: int) -> dict[tuple[str, int, int], sp.Expr]:
    """{(end, r, j): d^r b_j at 0 ("start") or d^r b_(n-j) at 1 ("end")}, r = 0..2, as
    polynomials in the parameters of a polynomial family at one degree."""
    polys = basis_polys(defn, degree)
    out = {}
    for i, p in enumerate(polys):
        q = p.as_expr()
        for r in range(3):
            out[("start", r, i)] = sp.expand(q.subs(t, 0))
            out[("end", r, degree - i)] = sp.expand(q.subs(t, 1))
            q = sp.diff(q, t)
    return out


def atom_end_forms(defn: Definition, space: Space) -> dict[tuple[str, int, int], sp.Expr]:
    """The same for an atom family, exact in its parameters and the constant C."""
    syms = defn.symbols
    out = {}
    for key, number in end_values(space).items():
        if key[1] > 2:
            continue
        total = sp.Integer(0)
        for (mono, c), v in number.items():
            term = sp.Rational(v.numerator, v.denominator) * C**c
            for x, e in zip(syms, mono, strict=True):
                term *= x**e
            total += term
        out[key] = total
    return out


def end_forms(defn: Definition, degree: int | None = None) -> tuple[dict, int, str | None]:
    """(end forms, degree, constant name or None) of a family of one order: an atom family,
    or a polynomial family in several parameters at `degree` (an indexed family's expansion
    there)."""
    if defn.elementary:
        space = space_of(defn)
        return atom_end_forms(defn, space), len(space.functions) - 1, space.constant
    at = defn.at_degree(degree if degree is not None else defn.degrees.start)
    deg = degree if degree is not None else at.degrees.start
    return polynomial_end_forms(at, deg), deg, None


def pair_weights(
    defn: Definition,
    degree: int,
    forms: dict,
    pair: str,
    continuity: str,
    symbols: tuple[sp.Symbol, ...] | None = None,
):
    """{"row,src,k": weight as an expression in the side symbols and C} of one ordered pair
    ("first>second", each the family's name or a built-in one), or a reason (str) where the
    closed-form solve has none. `symbols`: as for join_table."""
    first, _, second = pair.partition(">")
    known = (*builtin_names(), defn.name)
    if first not in known or second not in known or defn.name not in (first, second):
        return f"{pair!r} is not a pair of {defn.name} with itself or a built-in family"
    order = joins.ORDER[continuity]
    syms = defn.symbols if symbols is None else symbols
    with joins.extra_family(defn.name, forms, (degree,), True, 2, syms):
        try:
            solved = joins.solve(first, second, order)
        except (AssertionError, KeyError, ZeroDivisionError) as exc:
            return str(exc)
    out = {}
    for row, combo in enumerate(solved):
        for (src, j), w in sorted(combo.items()):
            num, den = _weight(w, continuity.startswith("C"))
            if num != 0:
                out[f"{row},{src},{j}"] = num / den
    return out


def _order_of(symbol: sp.Symbol, names: list[str]) -> tuple:
    return (names.index(symbol.name),) if symbol.name in names else (len(names), symbol.name)


def join_table(
    defn: Definition,
    degree: int,
    forms: dict,
    constant: str | None = None,
    symbols: tuple[sp.Symbol, ...] | None = None,
) -> dict:
    """The document's ``joins`` of the family `defn` at `degree` (its end `forms`), with every
    built-in family and itself in both directions; `constant` names C ("pi", "exp(W)").
    `symbols`: the parameter symbols of the forms when they are not the definition's (forms
    in closed form in n of an indexed family: lam(1), lam(n), ...)."""
    name = defn.name
    syms = defn.symbols if symbols is None else symbols
    pairs: dict = {}
    used: set[sp.Symbol] = set()
    with joins.extra_family(name, forms, (degree,), True, 2, syms):
        for other in (*builtin_names(), name):
            for first, second in ((name, other), (other, name)):
                key = f"{first}>{second}"
                if key in pairs:
                    continue
                entry: dict = {}
                reasons = []
                for order in (1, 2):
                    try:
                        solved = joins.solve(first, second, order)
                    except (AssertionError, KeyError, ZeroDivisionError) as exc:
                        reasons.append(f"{'C2/G2' if order == 2 else 'C1/G1'}: {exc}")
                        continue
                    for cont in CONTINUITIES:
                        if joins.ORDER[cont] != order:
                            continue
                        entry[cont] = {}
                        for row, combo in enumerate(solved):
                            for (src, j), w in sorted(combo.items()):
                                num, den = _weight(w, cont.startswith("C"))
                                if num:
                                    used.update(num.free_symbols | den.free_symbols)
                                    entry[cont][f"{row},{src},{j}"] = (num, den)
                if reasons:
                    entry["reason"] = "; ".join(reasons)
                pairs[key] = entry
    # the variables in a fixed order: the base symbols, each parameter on side 1 then 2, C
    order = [x.name for x in joins.BASE_SYMBOLS]
    order += [joins.side_symbol(x, s).name for s in (1, 2) for x in syms] + [C.name]
    variables = sorted(used, key=lambda x: _order_of(x, order))
    for entry in pairs.values():
        for cont in CONTINUITIES:
            for k, (num, den) in entry.get(cont, {}).items():
                entry[cont][k] = f"{_terms(num, variables)} / {_terms(den, variables)}"
    table = {"rule": RULE, "variables": [x.name for x in variables]}
    if constant is not None and C in used:
        table["constant"] = constant
    table["pairs"] = pairs
    return table


def _weight(w, unit_alpha: bool) -> tuple[sp.Expr, sp.Expr]:
    """(numerator, denominator) of a solved weight (an element of joins' field), at
    alpha = 1, d = 0 for a C joint, cancelled."""
    if unit_alpha:
        a, dd = _gen(w, joins.alpha), _gen(w, joins.d)
        num = w.numer.subs(a, 1).subs(dd, 0)
        den = w.denom.subs(a, 1).subs(dd, 0)
        w = w.field(num) / w.field(den)
    return w.numer.as_expr(), w.denom.as_expr()


def _gen(w, symbol: sp.Symbol):
    ring = w.numer.ring
    return ring.gens[list(ring.symbols).index(symbol)]


def _terms(poly: sp.Expr, variables: list[sp.Symbol]) -> str:
    p = sp.Poly(poly, *variables) if variables else sp.Poly(poly, sp.Dummy())
    out = []
    for exps, c in sorted(p.terms(), key=lambda term: term[0]):
        q = Fraction(int(sp.Rational(c).p), int(sp.Rational(c).q))
        out.append(f"{q}@{','.join(map(str, exps)) if variables else ''}")
    return " ".join(out)
