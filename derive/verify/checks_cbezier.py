"""Claims about a family whose parameter is the length of the domain or sits inside sin/cos
(C-Bezier families, derive/families/cbezier.py; issue #30).

A records file defining such a family uses three of checks_several.py's claim kinds, which
hand its records here:

* ``several_basis`` and ``several_end_conditions``: ``equations`` in t, the parameter (alpha),
  ``sin``/``cos`` (``sinh``/``cosh``) of integer multiples of t and alpha, the basis
  ``b(j, n, x)``, the control points ``P(j)`` and the curve ``p(x)``, with ``Derivative`` and
  ``Subs`` (end values and derivatives at t = 0 and t = alpha, partition of unity, a function
  itself). An equation mentioning i is checked at every i = 0..n.
* ``several_symmetry`` (no ``swap``): b_i(t) = b_(n-i)(alpha - t) for every i.

Each side is built from the derived functions (the family file's functions converted to exact
atoms by cbezier.read_table) and the difference is converted to the same atoms t^k, cos(m t),
sin(m t) with coefficients in Q(alpha, sin alpha, cos alpha); each coefficient is then reduced
modulo sin^2 + cos^2 = 1 (cosh^2 - sinh^2 = 1) by cbezier.reduce, where zero is decided
exactly (see cbezier's docstring). Record formulas are read by the records grammar
(derive/grammar), never by sympify.
"""

from __future__ import annotations

import sympy as sp

from ..families import cbezier as cb
from ..families.cbezier import CDefinition
from ..grammar import SYMBOLS, ParseError, parse_formula
from .checks_core import Outcome
from .checks_elementary import RecordError, curve_call, walk_equations

KINDS = ("several_basis", "several_end_conditions", "several_symmetry")

_I, _N = SYMBOLS["i"], SYMBOLS["n"]
_FUNCTIONS = {name: sp.Function(name) for name in ("P", "b", "p")}


def _parse(defn: CDefinition, text: str, key: str) -> sp.Basic:
    alpha = sp.Symbol(defn.parameter)
    symbols = {"i": _I, "n": _N, "t": cb.T, defn.parameter: alpha}
    try:
        return parse_formula(
            text, symbols, _FUNCTIONS, elementary=True, frequency=(defn.parameter,)
        )
    except ParseError as exc:
        raise RecordError(f"key {key}: {exc}") from None


def _function(defn: CDefinition, j: int) -> sp.Expr:
    """b_j as a SymPy function of the family's own t and alpha (t on [0, alpha], or u on
    [0, 1] with t = alpha*u for a family written that way)."""
    alpha = sp.Symbol(defn.parameter)
    e = cb.as_function(defn.elems()[j], defn.hyperbolic).xreplace({cb.A: alpha})
    if defn.form == "unit":
        e = e.xreplace({cb.T: alpha * cb.T})
    return e


def _realise(defn: CDefinition, expr: sp.Basic, idx: int | None) -> sp.Expr:
    degree = defn.degree
    env = {_N: sp.Integer(degree)}
    if idx is not None:
        env[_I] = sp.Integer(idx)
    e = expr.xreplace(env)

    def basis(j: int, x: sp.Expr) -> sp.Expr:
        if not 0 <= j <= degree:
            return sp.Integer(0)
        f = _function(defn, j)
        return f if x == cb.T else f.xreplace({cb.T: x})

    def model(call: sp.Basic) -> sp.Basic:
        got = curve_call(call, degree, basis)
        if got is None:
            raise RecordError(f"{call}: not a function of these claims (P, b, p)")
        return got

    e = e.replace(lambda x: isinstance(x, sp.core.function.AppliedUndef), model)
    return e.doit()


def _gap(defn: CDefinition, expr: sp.Expr, what: str) -> cb.Elem:
    """expr (a function of t, alpha and the points) in exact atoms, reduced: {} when zero."""
    alpha = sp.Symbol(defn.parameter)

    def fail(message: str) -> RecordError:
        return RecordError(f"{what}: {message}")

    stray = sorted(
        s.name for s in expr.free_symbols if s not in (cb.T, alpha) and not s.name.startswith("P_")
    )
    if stray:
        raise fail(f"unknown symbol {stray[0]!r}")
    elem, kinds = cb.to_atoms(expr, alpha, defn.form, fail)
    if kinds - {"hyp" if defn.hyperbolic else "trig"}:
        raise fail(
            f"{'trigonometric' if defn.hyperbolic else 'hyperbolic'} functions in a claim about "
            f"a {defn.space} family: not in its field"
        )
    return cb.normal(elem, defn.hyperbolic)


def _show(defn: CDefinition, elem: cb.Elem) -> str:
    alpha = sp.Symbol(defn.parameter)
    e = cb.as_function(elem, defn.hyperbolic).xreplace({cb.A: alpha})
    return str(sp.factor(e))


def equations(record: dict, defn: CDefinition) -> Outcome:
    def prepare(number: int, eq: dict) -> tuple[object, bool]:
        lhs = _parse(defn, eq["lhs"], f"equations[{number}].lhs")
        rhs = _parse(defn, eq["rhs"], f"equations[{number}].rhs")
        return (number, lhs, rhs), _I in (lhs.free_symbols | rhs.free_symbols)

    def gap(parsed: object, _degree: int, idx: int | None) -> str | None:
        number, lhs, rhs = parsed  # type: ignore[misc]
        where = f"equations[{number}]" + (f" at i = {idx}" if idx is not None else "")
        diff = _gap(defn, _realise(defn, lhs, idx) - _realise(defn, rhs, idx), where)
        return _show(defn, diff) if diff else None

    diffs, checked = walk_equations(
        record,
        (defn.degree,),
        prepare,
        gap,
        "for this family; the equation is checked at its degree (and every index i)",
        f"exact in Q({defn.parameter}, {defn.space} of {defn.parameter})",
    )
    return Outcome("mismatch" if diffs else "match", diffs, checked)


def symmetry(record: dict, defn: CDefinition) -> Outcome:
    """b_i(t) = b_(n-i)(alpha - t) for every i (the reflection of [0, alpha]; of [0, 1] for
    a family written on [0, 1]: the same identity in t = alpha*u)."""
    if record.get("swap"):
        raise RecordError(
            f"key swap: {defn.name!r} has no parameter to swap; its symmetry is "
            f"b_i(t) = b_(n-i)({defn.parameter} - t) (leave `swap` out)"
        )
    fs = defn.elems()
    n = defn.degree
    diffs = []
    for i, f in enumerate(fs):
        gap = cb.reflect(fs[n - i], defn.hyperbolic)
        for atom, v in f.items():
            cb.add_into(gap, atom, -v)
        gap = cb.normal(gap, defn.hyperbolic)
        if gap:
            diffs.append(
                f"i = {i}: b_(n-i)({defn.parameter} - t) - b_i(t) = {_show(defn, gap)} "
                "(in t on [0, " + defn.parameter + "])"
            )
            break
    checked = [f"b_i(t) = b_(n-i)({defn.parameter} - t), i = 0..{n}: exact"]
    return Outcome("mismatch" if diffs else "match", diffs, checked)
