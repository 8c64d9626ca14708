"""Claims in closed form in n about a family in several parameters over a range of degrees or
an indexed family (issue #30), checked against derive's end forms and join weights in closed
form in n (derive/families/closed_n.py, derive/formulas/joins_closed_n.py).

* ``several_end_conditions``: an equation about the curve at an end, ``p(0)``, ``p(1)`` or
  ``Subs(Derivative(p(t), t, r), t, 0 or 1)``, with control points ``P(k)`` and ``P(n - k)``
  and parameters ``lam(k)``, ``lam(n - k)`` (indexed) or by name, is checked at every degree
  (checks_several.py) and, here, for a general n: each side is written with the derived end
  forms as a polynomial in n, the parameters and the points (P(k) and P(n - k) distinct
  symbols), and the two must be equal. Equal, the claim holds for every n from the forms'
  ``valid_from``; not equal, it fails for every large n.
* ``several_join`` without ``n``: the weights are compared with the closed-form weights in n
  and m. An indexed family's parameters are written per curve as ``lam1(n)``, ``lam1(n - 1)``
  (the first curve's last ones) and ``lam2(1)``, ``lam2(m - 1)`` (the second curve's).
"""

from __future__ import annotations

import sympy as sp

from ..algebra import n as _n
from ..families.closed_n import ClosedForms, closed_forms, relative_name
from ..families.definition import Definition
from ..formulas import joins
from ..formulas.joins_several import pair_weights
from ..grammar import SYMBOLS, ParseError, parse_formula
from .checks_core import Outcome
from .checks_elementary import RecordError

_N, _T = SYMBOLS["n"], SYMBOLS["t"]


def has_closed_forms(defn: Definition) -> bool:
    return len(defn.degrees) > 1 and isinstance(closed_forms(defn), ClosedForms)


def _offset(k: sp.Expr, degree: sp.Symbol, what: str) -> tuple[bool, int]:
    """(from the end, c) for an index c or degree - c."""
    e = sp.expand(k)
    if e.is_Integer:
        return False, int(e)
    c = sp.expand(degree - e)
    if c.is_Integer:
        return True, int(c)
    raise RecordError(f"{what}: the index {k} is neither a number nor n minus a number")


class _General:
    """One side of an equation in general n, from the closed forms."""

    def __init__(self, defn: Definition, closed: ClosedForms):
        self.defn = defn
        self.closed = closed
        self.orders: set[int] = set()

    def point(self, k: sp.Expr) -> sp.Symbol:
        back, c = _offset(k, _N, "P(...)")
        return sp.Symbol(("P(n)" if c == 0 else f"P(n-{c})") if back else f"P({c})")

    def parameter(self, k: sp.Expr) -> sp.Expr:
        spec = self.defn.indexed
        assert spec is not None
        back, c = _offset(k, _N, f"{spec.name}(...)")
        if (back and c < spec.last_offset) or (not back and c < spec.first):
            return sp.Integer(0)  # outside the indices at every degree
        return sp.Symbol(relative_name(spec.name, c, back))

    def end(self, r: int, at: sp.Expr) -> sp.Expr:
        if at not in (0, 1):
            raise _NotAnEnd
        self.orders.add(r)
        which = "start" if at == 0 else "end"
        total = sp.Integer(0)
        for (e, rr, j), v in self.closed.forms.items():
            if e == which and rr == r:
                total += v.xreplace({_n: _N}) * self.point(sp.Integer(j) if at == 0 else _N - j)
        return total

    def realise(self, expr: sp.Basic) -> sp.Expr:
        def subs(s: sp.Subs) -> sp.Expr:
            inner, (var,), (at,) = s.args
            if var != _T:
                raise _NotAnEnd
            if isinstance(inner, sp.Derivative) and _is_curve(inner.expr):
                (v, r), *rest = inner.variable_count
                if v != _T or rest:
                    raise _NotAnEnd
                return self.end(int(r), at)
            if _is_curve(inner):
                return self.end(0, at)
            raise _NotAnEnd

        e = expr.replace(lambda x: isinstance(x, sp.Subs), subs)

        def call(c: sp.Basic) -> sp.Expr:
            name = c.func.__name__
            if name == "p":
                return self.end(0, c.args[0])
            if name == "P":
                return self.point(c.args[0])
            if self.defn.indexed is not None and name == self.defn.indexed.name:
                return self.parameter(c.args[0])
            raise _NotAnEnd

        e = e.replace(lambda x: isinstance(x, sp.core.function.AppliedUndef), call)
        if e.has(sp.Derivative, _T, SYMBOLS["i"]):
            raise _NotAnEnd
        return sp.expand(e)


class _NotAnEnd(Exception):
    """An equation that is not about the curve at an end (checked per degree only)."""


def _is_curve(e: sp.Basic) -> bool:
    return (
        isinstance(e, sp.core.function.AppliedUndef) and e.func.__name__ == "p" and e.args == (_T,)
    )


def general_equations(defn: Definition, equations: list[tuple[str, str, sp.Basic, sp.Basic]]):
    """(differences, checked) of the equations about the curve's ends, in general n."""
    closed = closed_forms(defn)
    assert isinstance(closed, ClosedForms)
    diffs, checked = [], []
    for lhs_text, rhs_text, lhs, rhs in equations:
        side = _General(defn, closed)
        try:
            gap = sp.expand(side.realise(lhs) - side.realise(rhs))
        except _NotAnEnd:
            continue
        low = closed.valid_from[max(side.orders, default=0)]
        if gap != 0:
            diffs.append(
                f"{lhs_text} = {rhs_text} fails for general n (derive's closed forms in n): "
                f"lhs - rhs = {gap}"
            )
        else:
            checked.append(
                f"{lhs_text} = {rhs_text}: for every n >= {low}, exact (closed forms in n)"
            )
    return diffs, checked


def check_join(record: dict, defn: Definition, pair: str, continuity: str, claimed: dict):
    """A ``several_join`` record without ``n``, against the weights in closed form in n, m."""
    closed = closed_forms(defn)
    if isinstance(closed, str):
        return Outcome("mismatch", [f"derive finds no closed forms in n: {closed}"])
    forms = {k: v for k, v in closed.forms.items() if k[1] <= 2}
    derived = pair_weights(defn, defn.degrees.start, forms, pair, continuity, closed.symbols)
    if isinstance(derived, str):
        return Outcome("mismatch", [f"derive finds no closed-form {continuity} weights: {derived}"])
    names = {x.name: x for x in joins.BASE_SYMBOLS}
    functions = {}
    spec = defn.indexed
    if spec is None:
        for side in (1, 2):
            for x in closed.symbols:
                s = joins.side_symbol(x, side)
                names[s.name] = s
    else:  # the family's sides (by the pair) call lam1(...), lam2(...); a built-in keeps lamN
        for side, member in enumerate(pair.split(">"), start=1):
            if member == defn.name:
                names.pop(f"{spec.name}{side}", None)
                functions[f"{spec.name}{side}"] = sp.Function(f"{spec.name}{side}")

    def parameter(call: sp.Basic) -> sp.Expr:
        side = int(call.func.__name__[-1])
        back, c = _offset(call.args[0], (joins.n, joins.m)[side - 1], f"{call}")
        if (back and c < spec.last_offset) or (not back and c < spec.first):
            return sp.Integer(0)
        return sp.Symbol(relative_name(spec.name, c, back) + str(side))

    low = closed.valid_from[joins.ORDER[continuity]]
    diffs, checked = [], []
    for key, text in sorted(claimed.items()):
        try:
            got = parse_formula(text, names, functions)
        except ParseError as exc:
            raise RecordError(f"key join_weights.{key}: {exc}") from None
        got = got.replace(lambda x: isinstance(x, sp.core.function.AppliedUndef), parameter)
        want = derived.get(key, sp.Integer(0))
        if sp.cancel(sp.together(got - want)) != 0:
            diffs.append(f"{pair} {continuity} weight {key}: printed {text}, derived {want}")
        checked.append(f"{pair} {continuity} weight {key}: for every n, m >= {low}, exact")
    return Outcome("mismatch" if diffs else "match", diffs, checked)
