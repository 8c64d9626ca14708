"""C-Bezier bases of every order from a seed and an integral recursion (Chen and Wang 2003,
"C-Bezier curves of arbitrary order"; Mainar and Pena's normalised totally positive bases).

A definition is a ``[family]`` table like derive/families/cbezier.py's, with ``seed`` (the
basis of the lowest degree, formulas in t and the parameter on ``domain = "[0, alpha]"``) and
``recursion`` (b(i, n, t) from the degree below) in place of ``functions``. The recursion is
a formula of the grammar with the integral operators (derive/grammar, OPERATORS):
``integral(f)`` (from 0 to t), ``total(f)`` (over [0, alpha]), ``normalized(f)``
(f / total(f), 0 for the zero function) and ``kronecker(a, b)``; b(j, m, t) is the zero
function for j outside 0..m. Chen and Wang's recursion is

    kronecker(i, 0) + integral(normalized(b(i - 1, n - 1, t)) - normalized(b(i, n - 1, t)))

Each degree is evaluated exactly in the space of cbezier.py (atoms t^k, cos(m t), sin(m t),
or cosh, sinh, with coefficients in Q(alpha, S, C) modulo the circle): the space is closed
under integration (t^k -> t^(k+1)/(k+1), cos(m t) -> sin(m t)/m, sin(m t) ->
(1 - cos(m t))/m), so each order is a CDefinition like one written out by hand, and every
decision of derive/formulas/cbezier.py applies to it unchanged. A total the recursion uses
must not vanish for any alpha of the range: identically zero is decided here; a zero inside
the range by the `nonvanishing` the caller passes (formulas/cbezier_nonnegative.py, above
this layer).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from math import gcd, lcm

import flint
import sympy as sp

from ..algebra.ratfunc import RationalFunction, context, from_expr
from ..grammar import FUNCTIONS, OPERATORS, SYMBOLS, ParseError, parse_formula
from . import cbezier as cb
from .cbezier import COS, POW, SIN, A, Atom, C, CDefinition, Elem, S, T
from .definition import DefinitionError, digest

_I, _N = SYMBOLS["i"], SYMBOLS["n"]
_B = FUNCTIONS["b"]
MAX_RECURSION_DEGREE = 8  # the highest degree a recursion is evaluated to (atoms <= MAX_POWER)

# (the definition of the lowest degree, a total in (A, S, C)) -> {"verdict": True, ...}
Nonvanishing = Callable[[CDefinition, sp.Expr], dict]


def is_recursion_table(table: dict) -> bool:
    return "seed" in table or "recursion" in table


@dataclass(frozen=True)
class COrders:
    """A C-Bezier family of several degrees: one CDefinition per degree."""

    name: str
    digest: str
    orders: tuple[CDefinition, ...]


def read_orders(
    table: dict, where: str = "", nonvanishing: Nonvanishing | None = None
) -> tuple[CDefinition, ...]:
    """Every degree of a seed-and-recursion table as a CDefinition (the lowest is the seed);
    DefinitionError naming the key otherwise. `nonvanishing` decides that a total has no zero
    for alpha in the range (without it only an identically zero total is refused)."""
    prefix = f"{where}: [family]" if where else "[family]"

    def fail(key: str, message: str) -> DefinitionError:
        return DefinitionError(f"{prefix}, key {key}: {message}")

    if "functions" in table:
        raise fail(
            "functions", "a family is defined by `functions` or by `seed` and `recursion`, not both"
        )
    for key in ("seed", "recursion"):
        if key not in table:
            raise fail(key, "required with " + ("`recursion`" if key == "seed" else "`seed`"))
    lo, hi = _degrees(table.get("degrees"), fail)
    if not isinstance(table["seed"], list) or not 2 <= len(table["seed"]) <= lo + 1:
        raise fail(
            "seed",
            f"the seed is the basis of one degree d <= {lo} (the lowest of `degrees`): a "
            f"list of d + 1 functions, at most {lo + 1}",
        )
    start = len(table["seed"]) - 1  # the seed's degree; the family's orders are lo..hi
    seed_table = {k: v for k, v in table.items() if k not in ("seed", "recursion", "degrees")}
    seed_table["functions"] = table["seed"]
    seed_table["degrees"] = str(start)
    try:
        seed = cb.read_table(seed_table, where)
    except DefinitionError as exc:  # the seed's functions are the table's `seed`
        raise DefinitionError(str(exc).replace("key functions", "key seed")) from None
    if seed.form != "domain":
        raise fail(
            "domain",
            f'a recursion integrates in t on "[0, {seed.parameter}]": write the seed on that '
            "domain",
        )
    recursion = _parse_recursion(table["recursion"], seed.parameter, fail)
    seed = dataclasses.replace(seed, digest=digest(table))
    orders = [seed]
    hyp = seed.hyperbolic
    below_f = tuple(_felem(f, hyp) for f in seed.elems())
    checked: set[sp.Expr] = set()
    for degree in range(start + 1, hi + 1):
        below_f = tuple(
            _evaluate(
                recursion,
                {_I: sp.Integer(i), _N: sp.Integer(degree)},
                orders[-1],
                below_f,
                fail,
                checked,
                nonvanishing,
            )
            for i in range(degree + 1)
        )
        funcs = [
            cb.normal({atom: _to_sympy(v, hyp) for atom, v in f.items()}, hyp) for f in below_f
        ]
        orders.append(_order(seed, funcs))
    return tuple(o for o in orders if o.degree >= lo)


def _degrees(text: object, fail) -> tuple[int, int]:
    if not isinstance(text, str):
        raise fail("degrees", 'a range of degrees such as "1..6"')
    parts = text.replace(" ", "").split("..")
    if not all(p.isdigit() for p in parts) or len(parts) > 2:
        raise fail("degrees", f'{text!r} is not a degree range such as "1..6"')
    lo, hi = int(parts[0]), int(parts[-1])
    if not 1 <= lo <= hi <= MAX_RECURSION_DEGREE:
        raise fail("degrees", f"{text!r}: degrees between 1 and {MAX_RECURSION_DEGREE}, lo <= hi")
    return lo, hi


def _parse_recursion(text: object, name: str, fail) -> sp.Expr:
    alpha = sp.Symbol(name)
    symbols = {"i": _I, "n": _N, "t": T, name: alpha}
    try:
        expr = parse_formula(
            text, symbols, {"b": _B}, elementary=True, frequency=(name,), operators=True
        )
    except ParseError as exc:
        raise fail("recursion", str(exc)) from None
    extra = sorted(s.name for s in expr.free_symbols if s not in (_I, _N, T, alpha))
    if extra:
        raise fail("recursion", f"unknown symbol {extra[0]!r} (a formula in i, n, t and {name})")
    for call in expr.atoms(sp.core.function.AppliedUndef):
        if call.func == _B and (len(call.args) != 3 or call.args[2] != T):
            raise fail("recursion", f"{call} must be b(index, degree, t)")
    return expr.subs(alpha, A)


def _order(seed: CDefinition, funcs: list[Elem]) -> CDefinition:
    """One derived degree as a CDefinition: its functions exact, its written form the
    elements written out (what the ball enclosures of formulas/ read)."""
    exprs = tuple(cb.as_function(f, seed.hyperbolic) for f in funcs)
    return dataclasses.replace(
        seed,
        functions=tuple(tuple(sorted(f.items())) for f in funcs),
        functions_texts=tuple(str(e.subs(A, sp.Symbol(seed.parameter))) for e in exprs),
        written_exprs=exprs,
    )


# --------------------------------------------------------------------------- evaluation
# The coefficients are FLINT rational functions (algebra/ratfunc.py) of alpha and the half
# angle w = tan(alpha/2) (tanh for the hyperbolic space): sin(alpha) = 2w/(1 + w^2),
# cos(alpha) = (1 - w^2)/(1 + w^2). alpha and w are algebraically independent, so Q(alpha, w)
# is a field of rational functions where FLINT's gcd gives one reduced form per value: in
# (alpha, S, C) modulo the circle a gcd misses factors shared only in the quotient, and the
# coefficients of degree 5 grew to 50,000 characters (SymPy's cancel on them took minutes).
# w is infinite at alpha = pi, but only here, in the arithmetic: the result is written back
# in (alpha, S, C) with w = S/(1 + C) and reduced modulo the circle (cbezier.py's form).

Coef = RationalFunction
FElem = dict[Atom, Coef]
W = sp.Symbol("w_")
_VARS = (A, W)


def _from_sympy(e: sp.Expr, hyperbolic: bool) -> Coef:
    """A rational function of (A, S, C) in (A, w)."""
    one = 1 - W**2 if hyperbolic else 1 + W**2
    sub = {S: 2 * W / one, C: (1 + W**2 if hyperbolic else 1 - W**2) / one}
    return from_expr(sp.sympify(e).xreplace(sub), _VARS)


def _circle(p: flint.fmpq_mpoly, hyperbolic: bool) -> flint.fmpq_mpoly:
    """p(A, S, C) with S^2 -> 1 - C^2 (C^2 - 1 for the hyperbola): degree <= 1 in S."""
    if p.degrees()[1] < 2:
        return p
    ctx = p.context()
    a, s, c = ctx.gens()
    square = c**2 - 1 if hyperbolic else 1 - c**2
    out = ctx.from_dict({})
    for (i, j, k), coef in zip(p.monoms(), p.coeffs(), strict=True):
        out += coef * a**i * c**k * square ** (j // 2) * s ** (j % 2)
    return out


def _back(terms: dict, degree: int, hyperbolic: bool) -> flint.fmpq_mpoly:
    """sum c A^i w^j times (1 + C)^degree with w = S/(1 + C), reduced modulo the circle."""
    ctx = context(3)
    a, s, c = ctx.gens()
    out = ctx.from_dict({})
    for (i, j), v in terms.items():
        out += flint.fmpq(v.numerator, v.denominator) * a**i * s**j * (1 + c) ** (degree - j)
    return _circle(out, hyperbolic)


def _to_sympy(x: Coef, hyperbolic: bool) -> sp.Expr:
    """The value in (A, S, C) with a denominator free of S: numerator and denominator over
    (1 + C)^d (d their degree in w), times the conjugate D0 - S D1 of the denominator
    D0 + S D1, reduced modulo the circle and cancelled (FLINT). In Q(A, C)(S) = Q(A, C) +
    S Q(A, C) that is one form per value (up to a number, fixed below): S/(1 - C) rather than
    (1 + C)/S, which would put a spurious zero of sin at alpha = pi into the denominator."""
    num, den = x.as_pair()
    if not num:
        return sp.Integer(0)
    degree = max(m[1] for m in (*num, *den))
    top, bottom = (_back(t, degree, hyperbolic) for t in (num, den))
    s = context(3).gens()[1]
    conj = bottom.subs({"x1": 0}) - s * bottom.derivative(1)  # D0 - S D1 (D has S^<=1)
    value = RationalFunction(_circle(top * conj, hyperbolic), _circle(bottom * conj, hyperbolic))
    n_terms, d_terms = value.as_pair()
    scale = lcm(*(c.denominator for c in (*n_terms.values(), *d_terms.values())))
    common = gcd(*(int(c * scale) for c in (*n_terms.values(), *d_terms.values())))

    def of(terms: dict) -> sp.Expr:
        return sp.Add(
            *(
                sp.Integer(int(v * scale) // common) * A**i * S**j * C**k
                for (i, j, k), v in sorted(terms.items())
            )
        )

    return of(n_terms) / of(d_terms)


def _passes_pi(defn: CDefinition) -> bool:
    return bool(defn.lo < sp.pi < defn.hi or (defn.hi == sp.pi and defn.hi_closed))


def _numerator(x: Coef, hyperbolic: bool) -> sp.Expr:
    """The numerator N(A, w) of a value (coprime to its denominator: FLINT cancelled it in
    Q(A, w)) as a function of (A, S, C) with the same zeros for alpha in (0, 2 pi): w =
    (1 - C)/S times S^d (d = its degree in w), whose value at alpha = pi is N's leading
    coefficient in w (the value there of N/w^d: w is infinite at pi); w = S/(1 + C) times
    (1 + C)^d for tanh(alpha/2)."""
    terms, _ = x.as_pair()
    d = max(m[1] for m in terms)
    out = sp.Integer(0)
    for (i, j), v in terms.items():
        coef = sp.Rational(v.numerator, v.denominator) * A**i
        if hyperbolic:
            out += coef * S**j * (1 + C) ** (d - j)
        else:
            out += coef * (1 - C) ** j * S ** (d - j)
    return cb._reduce_poly(out, C**2 - 1 if hyperbolic else 1 - C**2)


def _fconst(value: int | Fraction) -> Coef:
    return RationalFunction.constant(2, Fraction(value))


def _felem(e: Elem, hyperbolic: bool) -> FElem:
    return {atom: _from_sympy(v, hyperbolic) for atom, v in e.items()}


def _fconstant(e: FElem) -> Coef | None:
    if all(atom == (POW, 0) for atom in e):
        return e.get((POW, 0), _fconst(0))
    return None


def _fadd(a: FElem, b: FElem, hyperbolic: bool) -> FElem:
    out = dict(a)
    for atom, v in b.items():
        out[atom] = out[atom] + v if atom in out else v
    return {atom: v for atom, v in out.items() if not v.is_zero()}


def _fscale(e: FElem, c: Coef, hyperbolic: bool) -> FElem:
    out = {atom: v * c for atom, v in e.items()}
    return {atom: v for atom, v in out.items() if not v.is_zero()}


def integral(e: FElem, hyperbolic: bool) -> FElem:
    """The integral from 0 to t of an element, in the same atoms (MAX_POWER bounds t^k)."""
    out: FElem = {}
    for (kind, m), v in sorted(e.items()):
        if kind == POW:
            if m + 1 > cb.MAX_POWER:
                raise ValueError(f"the integral of t**{m} is past t**{cb.MAX_POWER}")
            part = {(POW, m + 1): v * Fraction(1, m + 1)}
        elif kind == COS:  # sin(m t)/m (sinh(m t)/m), 0 at t = 0
            part = {(SIN, m): v * Fraction(1, m)}
        else:  # (1 - cos(m t))/m; (cosh(m t) - 1)/m
            sign = Fraction(1 if hyperbolic else -1, m)
            part = {(COS, m): v * sign, (POW, 0): v * -sign}
        out = _fadd(out, part, hyperbolic)
    return out


@cache
def _angle(m: int, hyperbolic: bool) -> tuple[Coef, Coef]:
    c, s = cb.angle(m, hyperbolic)
    return _from_sympy(sp.sympify(c), hyperbolic), _from_sympy(sp.sympify(s), hyperbolic)


def value_at_alpha(e: FElem, hyperbolic: bool) -> Coef:
    """The value at t = alpha."""
    total = _fconst(0)
    a = RationalFunction.variable(2, 0)
    for (kind, m), v in sorted(e.items()):
        if kind == POW:
            total = total + v * a**m
        else:
            c, s = _angle(m, hyperbolic)
            total = total + v * (c if kind == COS else s)
    return total


def total(e: Elem, hyperbolic: bool) -> sp.Expr:
    """The integral over [0, alpha] of an element (SymPy coefficients), reduced."""
    value = value_at_alpha(integral(_felem(e, hyperbolic), hyperbolic), hyperbolic)
    return cb.reduce(_to_sympy(value, hyperbolic), hyperbolic)


def _evaluate(
    expr: sp.Basic,
    env: dict,
    below: CDefinition,
    below_f: tuple[FElem, ...],
    fail,
    checked: set,
    nonvanishing: Nonvanishing | None,
) -> FElem:
    hyp = below.hyperbolic

    def walk(e: sp.Basic) -> FElem:
        if not e.has(_B, *OPERATORS.values()):
            return _closed(e)
        if isinstance(e, sp.core.function.AppliedUndef) and e.func == _B:
            idx, deg = (_integer(x) for x in e.args[:2])
            if deg != below.degree:
                raise fail(
                    "recursion",
                    f"{e.xreplace(env)} at n = {below.degree + 1}: a recursion reads the "
                    "degree below, b(., n - 1, t)",
                )
            return dict(below_f[idx]) if 0 <= idx <= deg else {}
        if isinstance(e, sp.core.function.AppliedUndef) and e.func in OPERATORS.values():
            return _operator(e, walk(e.args[0]))
        if e.is_Add:
            out: FElem = {}
            for a in e.args:
                out = _fadd(out, walk(a), hyp)
            return out
        if e.is_Mul:
            out = {(POW, 0): _fconst(1)}
            for a in e.args:
                out = _product(out, walk(a), e)
            return out
        if e.is_Pow and e.exp.is_Integer:
            c = _fconstant(walk(e.base))
            if c is None:
                raise fail(
                    "recursion",
                    f"{e}: a power of a function of t is not decided here (only numbers and "
                    "functions of the parameter are raised to powers)",
                )
            if e.exp < 0 and c.is_zero():
                raise fail("recursion", f"{_show(e)}: a division by zero at n = {env[_N]}")
            return {(POW, 0): c ** int(e.exp)}
        raise fail("recursion", f"{e} is not a sum of products the recursion can evaluate")

    def _integer(x: sp.Basic) -> int:
        v = sp.sympify(x).xreplace(env)
        if not v.is_Integer:
            raise fail("recursion", f"{x} is not an integer once i and n are set")
        return int(v)

    def _closed(e: sp.Basic) -> FElem:
        """A part without b(...) or operators: a formula in t and alpha (the seed's atoms)."""
        alpha = sp.Symbol(below.parameter)
        body = e.xreplace(env).subs(A, alpha)
        elem, kinds = cb.to_atoms(body, alpha, "domain", lambda msg: fail("recursion", msg))
        if kinds and kinds != {"hyp" if hyp else "trig"}:
            raise fail("recursion", f"{e}: trigonometric and hyperbolic functions together")
        return {atom: v for atom, v in _felem(elem, hyp).items() if not v.is_zero()}

    def _product(a: FElem, b: FElem, e: sp.Basic) -> FElem:
        ca, cb_ = _fconstant(a), _fconstant(b)
        if ca is not None:
            return _fscale(b, ca, hyp)
        if cb_ is not None:
            return _fscale(a, cb_, hyp)
        raise fail(
            "recursion",
            f"{_show(e)}: a product of two functions of t leaves the space this recursion is "
            "evaluated in (multiply by numbers and functions of the parameter only)",
        )

    def _operator(call: sp.Basic, inner: FElem) -> FElem:
        name = call.func.__name__
        if name == "normalized" and not inner:
            return {}  # b outside 0..n: delta * b is 0 by the recursion's convention
        try:
            prim = integral(inner, hyp)
        except ValueError as exc:
            raise fail("recursion", f"{_show(call)} at n = {env[_N]}: {exc}") from None
        if name == "integral":
            return prim
        tot = value_at_alpha(prim, hyp)
        _check_total(call, tot)
        if name == "total":
            return {(POW, 0): tot}
        return _fscale(inner, _fconst(1) / tot, hyp)

    def _show(x: sp.Basic) -> str:
        alpha = sp.Symbol(below.parameter)
        sin, cos = (sp.sinh, sp.cosh) if hyp else (sp.sin, sp.cos)
        return str(x.xreplace(env).subs({S: sin(alpha), C: cos(alpha), A: alpha}))

    def _check_total(call: sp.Basic, tot: Coef) -> None:
        where = f"{_show(call)} at n = {env[_N]}"
        if tot.is_zero():
            raise fail("recursion", f"{where}: the total (the integral over the domain) is 0")
        if not hyp and _passes_pi(below) and tot.num.degrees()[1] < tot.den.degrees()[1]:
            raise fail(
                "recursion",
                f"{where}: the total {_show(sp.factor(_to_sympy(tot, hyp)))} tends to 0 at "
                f"{below.parameter} = pi, inside the range {below.range_text}",
            )
        key = sp.factor(_numerator(tot, hyp))
        if nonvanishing is None or key in checked:
            return
        verdict = nonvanishing(below, key)
        if verdict.get("verdict") is not True:
            between = verdict.get("between", [None])
            detail = (
                f"it changes sign between {below.parameter} = {between[0]:.6g} and {between[1]:.6g}"
                if verdict.get("verdict") is False and isinstance(between[0], float)
                else verdict.get("reason", "it vanishes")
            )
            raise fail(
                "recursion",
                f"{where}: the total {_show(sp.factor(_to_sympy(tot, hyp)))} is not certified "
                f"free of zeros for {below.parameter} in {below.range_text} ({detail})",
            )
        checked.add(key)

    try:
        return walk(expr)
    except ZeroDivisionError as exc:
        raise fail("recursion", f"at n = {env[_N]}: {exc}") from None
