"""A shape-parameter family from its definition: one engine for any basis.

A family is data: a ``[family]`` table (in a file of its own or at the top of a records file)
whose ``basis`` is a formula of the records grammar in i, n, t and the shape parameter. From
that definition alone this module derives what a built-in family gets:

* per degree n: the basis polynomials (negative powers that cancel are allowed; anything that
  is not a polynomial of degree <= n + degree_offset in t after cancellation is an error), the
  checks (partition of unity, reduction to Bernstein at ``bernstein_at``), the power, Bernstein
  and centred (Taylor about 1/2) tables split by powers of the parameter;
* the values and derivatives (orders 0..3) of every basis function at both ends, per degree,
  and in closed form in n where one polynomial in n reproduces every degree of the range;

What is derived for any family from these (energies, joins, singular parameters) is in
derive/formulas/; the derived JSON document is assembled and printed by derive/emit/.
Everything is exact (SymPy/FLINT rationals).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from math import comb, factorial

import flint
import sympy as sp

from ..algebra import (
    check_endpoint_closed_forms,
    expansion_tables,
    lam,
    n,
    t,
    to_fraction,
)
from ..algebra.ratfunc import RationalFunction
from ..grammar import MAX_EXPONENT
from .definition import (
    _I,
    _LAM,
    _N,
    _T,
    ENDPOINT_ORDERS,
    Definition,
    DefinitionError,
    is_operator,
)


@dataclass(frozen=True)
class GeneralForm:
    """A function of n, i and the parameter that a paper prints in closed form: the emitted
    module gets ``def name(*args): return values`` (a tuple of expressions)."""

    name: str
    args: tuple[str, ...]
    doc: str
    values: tuple[sp.Expr, ...]


@dataclass(frozen=True)
class FamilyModule:
    """Everything the emitted module of a built-in family holds, as exact data."""

    script: str  # named in the emitted banner
    doc: str
    definition: Definition
    tables: dict  # expansion_tables(): power, centred, bernstein
    general_forms: tuple[GeneralForm, ...]
    endpoint: dict  # closed end forms {(end, r, idx): expr}


# --------------------------------------------------------------------------- the basis


class _Field:
    """Q(t, parameters) as the engine evaluates in it (algebra/ratfunc.py, on FLINT): the
    variables are t and the definition's parameter symbols, in this order."""

    def __init__(self, symbols: tuple[sp.Symbol, ...]):
        self.symbols = (_T, *symbols)
        self.count = len(self.symbols)
        self._index = {s: k for k, s in enumerate(self.symbols)}

    def __call__(self, value: int | Fraction | sp.Rational) -> RationalFunction:
        return RationalFunction.constant(self.count, to_fraction(value))

    def variable(self, symbol: sp.Symbol) -> RationalFunction | None:
        k = self._index.get(symbol)
        return None if k is None else RationalFunction.variable(self.count, k)

    def expr(self, value: RationalFunction) -> sp.Expr:
        """The value as a SymPy expression (for messages)."""

        def of(terms: dict) -> sp.Expr:
            return sp.Add(
                *(
                    sp.Rational(c.numerator, c.denominator)
                    * sp.Mul(*(s**e for s, e in zip(self.symbols, m, strict=True)))
                    for m, c in terms.items()
                )
            )

        num, den = value.as_pair()
        return of(num) / of(den)


def _instantiate(
    e: sp.Basic, env: dict, ring: _Field, lookup=None, totals=None
) -> RationalFunction:
    """e with n and i replaced by integers, evaluated in the field Q(t, lam): binomials with
    the papers' convention, powers bounded; b(i', n', t) of a recursion through lookup; the
    integral operators of a recursion (integral, total, normalized) on [0, 1], each total
    passed to `totals` (which refuses one that vanishes somewhere in the range)."""
    if is_operator(e):
        return _operator(e, env, ring, lookup, totals)
    if isinstance(e, sp.KroneckerDelta):
        a, b = (_integer(_instantiate(x, env, ring), "argument of kronecker", ring) for x in e.args)
        return ring(int(a == b))
    if isinstance(e, sp.core.function.AppliedUndef):
        if lookup is None:
            raise DefinitionError(f"cannot evaluate {e} in a closed formula")
        idx, deg = (_integer(_instantiate(x, env, ring), "index of b", ring) for x in e.args[:2])
        return lookup(idx, deg)
    if e.is_Symbol:
        if e in env:
            return ring(env[e])
        var = ring.variable(e)
        if var is None:
            raise DefinitionError(f"cannot evaluate {e} in a basis definition")
        return var
    if e.is_Rational:
        return ring(e)
    if isinstance(e, sp.binomial):
        a, b = (_integer(_instantiate(x, env, ring), "binomial", ring) for x in e.args)
        return ring(comb(a, b) if 0 <= b <= a else 0)
    if isinstance(e, sp.factorial):
        a = _integer(_instantiate(e.args[0], env, ring), "factorial", ring)
        if not 0 <= a <= 1000:
            raise DefinitionError(f"factorial({a}) in the basis")
        return ring(factorial(a))
    if e.is_Add:
        out = ring(0)
        for a in e.args:
            out += _instantiate(a, env, ring, lookup, totals)
        return out
    if e.is_Mul:
        out = ring(1)
        for a in e.args:
            out *= _instantiate(a, env, ring, lookup, totals)
        return out
    if e.is_Pow:
        base = _instantiate(e.base, env, ring, lookup, totals)
        ex = _integer(_instantiate(e.exp, env, ring), "exponent", ring)
        if abs(ex) > MAX_EXPONENT:
            raise DefinitionError(f"an exponent {ex} in the basis")
        if ex < 0 and base.is_zero():
            raise DefinitionError("the basis divides by zero")
        return base**ex
    raise DefinitionError(f"cannot evaluate {e} in a basis definition")


def _integral(value: RationalFunction, ring: _Field, call: sp.Basic, env: dict) -> RationalFunction:
    """The integral from 0 to t of a polynomial in t (coefficients rational functions of the
    parameters): anything else leaves the space of polynomials."""
    if value.den.degrees()[0] != 0:
        raise DefinitionError(
            f"[family] recursion: {call.subs(env)}: the integrand "
            f"{sp.factor(ring.expr(value))} is not a polynomial in t, so its integral is not "
            "in the family's space (polynomials in t)"
        )
    return RationalFunction(value.num.integral(0), value.den)


def _at_one(value: RationalFunction, ring: _Field) -> RationalFunction:
    one = flint.fmpq(1)
    return RationalFunction(value.num.subs({"x0": one}), value.den)


def _operator(e: sp.Basic, env: dict, ring: _Field, lookup, totals) -> RationalFunction:
    inner = _instantiate(e.args[0], env, ring, lookup, totals)
    name = e.func.__name__
    if name == "normalized" and inner.is_zero():
        return inner  # b outside 0..n: delta * b is 0 by the recursion's convention
    primitive = _integral(inner, ring, e, env)
    if name == "integral":
        return primitive
    total = _at_one(primitive, ring)
    if totals is not None:
        totals(total, e.subs(env))
    return total if name == "total" else inner / total


def _integer(x: RationalFunction, what: str, ring: _Field) -> int:
    value = x.constant_value()
    if value is None:
        raise DefinitionError(f"the {what} {ring.expr(x)} is not an integer once n and i are set")
    if value.denominator != 1:
        raise DefinitionError(
            f"the {what} {sp.Rational(value.numerator, value.denominator)} is not an integer"
        )
    return int(value)


@cache
def _field(symbols: tuple[sp.Symbol, ...] = (_LAM,)) -> _Field:
    return _Field(symbols)


def basis_polys(defn: Definition, degree: int) -> list[sp.Poly]:
    return list(_basis_polys(defn, degree))


def _basis_values(defn: Definition, degree: int) -> tuple:
    """The degree-`degree` functions as elements of Q(t, lam): the closed formula per index,
    or the seed at the lowest degree and the recursion above it."""
    try:
        return _basis_values_lam(defn, degree)
    except DefinitionError as exc:
        if defn.parameter == "lam":
            raise
        # the evaluator's messages quote the formula in the engine's `lam`: the user wrote
        # their own name (a whole word, never part of another)
        raise DefinitionError(re.sub(r"\blam\b", defn.parameter, str(exc))) from None


@cache
def _basis_values_lam(defn: Definition, degree: int) -> tuple:
    field = _field(defn.symbols)
    if defn.functions_texts is not None:
        return tuple(_instantiate(f, {_N: degree}, field) for f in defn.functions)
    if defn.basis_text is not None:
        basis = defn.basis
        return tuple(_instantiate(basis, {_N: degree, _I: idx}, field) for idx in range(degree + 1))
    if degree == defn.degrees.start:
        return tuple(_instantiate(f, {_N: degree}, field) for f in defn.seed)
    below = _basis_values(defn, degree - 1)

    def lookup(idx: int, deg: int):
        if deg != degree - 1:
            raise DefinitionError(
                f"[family] recursion: b({idx}, {deg}, t) at n = {degree}; a recursion reads "
                "the degree below, b(., n - 1, t)"
            )
        return below[idx] if 0 <= idx <= deg else field(0)

    rec = defn.recursion

    def totals(total: RationalFunction, call: sp.Basic) -> None:
        _check_total(defn, field, total, call, degree)

    return tuple(
        _instantiate(rec, {_N: degree, _I: idx}, field, lookup, totals) for idx in range(degree + 1)
    )


def _check_total(
    defn: Definition, field: _Field, total: RationalFunction, call: sp.Basic, degree: int
) -> None:
    """A total (an integral over [0, 1]) the recursion divides by or uses: a function of the
    parameters that must not vanish anywhere in their range (decided exactly: the real
    roots of its numerator in the closed range, then the ends that are open)."""
    where = f"[family] recursion: {call} at n = {degree}"
    if total.is_zero():
        raise DefinitionError(f"{where}: the total is 0 (the integral over [0, 1] vanishes)")
    value = field.expr(total)
    if value.has(_T):  # pragma: no cover - a total is evaluated at t = 1
        raise AssertionError(value)
    if total.constant_value() is not None:
        return
    if defn.several:
        raise DefinitionError(
            f"{where}: the total {value} depends on the parameters; whether it vanishes "
            "somewhere in a box of several parameters is not decided (one parameter only)"
        )
    num = sp.Poly(sp.numer(sp.together(value)), _LAM)
    lo, hi = (sp.Rational(x.numerator, x.denominator) for x in (defn.lo, defn.hi))
    for root in num.real_roots():
        inside = (lo < root or (defn.lo_closed and root == lo)) and (
            root < hi or (defn.hi_closed and root == hi)
        )
        if inside:
            raise DefinitionError(
                f"{where}: the total {defn.show(sp.factor(value))} is 0 at "
                f"{defn.parameter} = {root}, inside the range {defn.range_text}"
            )


@cache
def _basis_polys(defn: Definition, degree: int) -> tuple[sp.Poly, ...]:
    big = degree + defn.offset
    out = []
    field = _field(defn.symbols)
    gens = (t, *defn.symbols)
    for idx, value in enumerate(_basis_values(defn, degree)):
        if not value.is_polynomial:
            raise DefinitionError(
                f"[family] basis: b({idx}, {degree}, t) is not a polynomial: "
                f"{defn.show(sp.factor(field.expr(value)))} (a negative power that does not "
                "cancel)"
            )
        terms = value.terms()
        p = sp.Poly.from_dict(
            {m: sp.QQ(c.numerator, c.denominator) for m, c in terms.items()}
            or {(0,) * len(gens): 0},
            gens,
            domain="QQ",
        )
        if p.degree(t) > big:
            raise DefinitionError(
                f"[family] basis: b({idx}, {degree}, t) has degree {p.degree(t)} in t, more "
                f"than n + degree_offset = {big}"
            )
        out.append(p)
    return tuple(out)


def check(defn: Definition) -> list[str]:
    """The definition's own claims, for every degree: what was checked (raises on failure)."""
    done = []
    field = _field(defn.symbols)
    for deg in defn.degrees:
        polys = basis_polys(defn, deg)  # raises unless every function is a polynomial
        values = _basis_values(defn, deg)  # the same functions in FLINT: the checks run there
        big = deg + defn.offset
        total = values[0]
        for v in values[1:]:
            total += v
        if total.constant_value() != 1:
            raise DefinitionError(
                f"[family] basis: no partition of unity at n = {deg}: the functions sum to "
                f"{defn.show(sp.factor(field.expr(total)))}"
            )
        if defn.bernstein_at is not None:
            at = {
                f"x{k + 1}": q.bernstein_at
                for k, q in enumerate(defn.params or (defn,))
                if q.bernstein_at is not None
            }
            where = ", ".join(
                f"{name} = {v}" for name, v in zip(defn.parameters, at.values(), strict=True)
            )
            point = {k: flint.fmpq(v.numerator, v.denominator) for k, v in at.items()}
            t_ = RationalFunction.variable(field.count, 0)
            one = field(1)
            for idx, v in enumerate(values):
                want = field(comb(deg, idx)) * t_**idx * (one + field(-1) * t_) ** (deg - idx)
                got = RationalFunction(v.num.subs(point))
                if got.num != want.num:
                    raise DefinitionError(
                        f"[family] bernstein_at: at {where}, b({idx}, {deg}, t) "
                        f"= {sp.factor(field.expr(got))}, not the Bernstein function "
                        f"{sp.factor(field.expr(want))}"
                    )
        generic = max(p.degree(t) for p in polys)
        if generic != big:
            # name the key that holds the functions: with no degree_offset in the file the
            # user never wrote the key an offset message would blame
            key = (
                "functions"
                if defn.functions_texts is not None
                else "basis"
                if defn.basis_text is not None
                else "seed/recursion"
            )
            # (a degree above n + degree_offset was refused function by function earlier)
            raise DefinitionError(
                f"[family] {key}: at n = {deg} the basis functions have degree "
                f"{generic} in t, not n + degree_offset = {big}: {deg + 1} functions of "
                f"degree {generic} cannot be linearly independent, so they are not a basis "
                f"of the polynomials of degree {big}"
            )
    done.append(
        f"polynomials of degree n + {defn.offset}, n = {defn.degrees.start}.."
        f"{defn.degrees.stop - 1}"
    )
    done.append("partition of unity, every degree")
    if defn.bernstein_at is not None and not defn.several:
        done.append(f"Bernstein basis at {defn.parameter} = {defn.bernstein_at}, every degree")
    elif defn.bernstein_at is not None:
        at = ", ".join(f"{q.name} = {q.bernstein_at}" for q in defn.params)
        done.append(f"Bernstein basis at {at}, every degree")
    return done


# --------------------------------------------------------------------------- artifacts


def _lam_coeffs(p: sp.Poly) -> list[str] | dict[str, str]:
    """A polynomial in lam as its coefficients, constant first, exact strings; in several
    parameters, {"e_1,...,e_k": coefficient} by monomial (exponent tuple), sorted."""
    if len(p.gens) > 1:
        return {",".join(map(str, m)): str(c) for m, c in sorted(p.terms())}
    return [str(c) for c in reversed(p.all_coeffs())]


def endpoint_table(defn: Definition) -> dict[str, dict[str, list[str]]]:
    """{n: {"start,r,j" | "end,r,j": lam-coefficients}}: d^r/dt^r of b_j (start, at t = 0)
    and of b_{n-j} (end, at t = 1)."""
    return _endpoint_table(defn)


@cache
def _endpoint_table(defn: Definition) -> dict[str, dict[str, list[str]]]:
    out = {}
    for deg in defn.degrees:
        row = {}
        for idx, p in enumerate(basis_polys(defn, deg)):
            d = p
            for r in range(ENDPOINT_ORDERS + 1):
                for end, at, j in (("start", 0, idx), ("end", 1, deg - idx)):
                    value = d.eval(t, at)  # a Poly in lam
                    if not value.is_zero:
                        row[f"{end},{r},{j}"] = _lam_coeffs(value)
                d = d.diff(t)
        out[str(deg)] = dict(sorted(row.items()))
    return out


def closed_endpoint_forms(defn: Definition) -> dict[tuple[str, int, int], sp.Expr] | None:
    """Closed forms in n of the end values/derivatives of orders 0..closed_endpoint_order():
    for each entry, the polynomial in n (of degree at most #degrees - 3) through the values at
    all degrees but the last two that also gives those two. An order is in closed form only
    when every entry of it and of the orders below has such a polynomial (a family whose
    second derivative at 0 involves P_n, say, has its values and first derivatives in closed
    form and its second per degree). None when not even the end values are (or the range has
    fewer than five degrees): then the family is checked per degree only."""
    forms, order = _closed_endpoint_forms(defn)
    return forms if order >= 0 else None


def closed_endpoint_order(defn: Definition) -> int:
    """The highest order r such that the end derivatives of orders 0..r are in closed form in
    n (-1: none)."""
    return _closed_endpoint_forms(defn)[1]


@cache
def _closed_endpoint_forms(defn: Definition) -> tuple[dict[tuple[str, int, int], sp.Expr], int]:
    if defn.several:  # closed forms in n are fitted per power of one parameter only
        return {}, -1
    table = endpoint_table(defn)
    keys = sorted({k for row in table.values() for k in row})
    nn = n
    out = {}
    degrees = list(defn.degrees)
    if len(degrees) < 5:
        return {}, -1
    failed = ENDPOINT_ORDERS + 1  # the lowest order with an entry that has no closed form
    for key in keys:
        end, r, j = key.split(",")
        pts = [(deg, table[str(deg)].get(key, ["0"])) for deg in degrees if int(j) <= deg]
        form = sp.Integer(0) if len(pts) >= 5 else None
        width = max(len(c) for _, c in pts)
        for p in range(width if form is not None else 0):
            xs = [sp.Integer(deg) for deg, _ in pts]
            ys = [sp.Rational(c[p]) if p < len(c) else sp.Integer(0) for _, c in pts]
            poly = sp.interpolate(list(zip(xs[:-2], ys[:-2], strict=True)), nn)
            if any(poly.subs(nn, x) != y for x, y in zip(xs[-2:], ys[-2:], strict=True)):
                form = None
                break
            form += sp.expand(poly) * lam**p
        if form is None:
            failed = min(failed, int(r))
        elif form != 0:
            out[(end, int(r), int(j))] = sp.factor(form)
    return {key: v for key, v in out.items() if key[1] < failed}, failed - 1


class GenericDerivation:
    """What a derivation module provides (DEGREES, DEGREE_OFFSET, PARAMETERS, DOMAIN,
    basis_polys, closed_end_forms, OUTPUT, module_data), for a built-in family from its
    definition alone: the emitted module has the tables and the end forms in closed form in n
    (fitted, then checked against every degree of the range), and no general form of a
    paper's own."""

    SCRIPT = "families/engine.py"

    def __init__(self, defn: Definition):
        self.DEFINITION = defn
        self.DEGREES = defn.degrees
        self.DEGREE_OFFSET = defn.offset
        self.PARAMETERS = defn.parameters  # the shape parameters' names, a tuple (issue #30)
        self.DOMAIN = defn.domain  # the interval of t
        self.OUTPUT = f"{defn.name}.py"

    def basis_polys(self, degree: int) -> list[sp.Poly]:
        return basis_polys(self.DEFINITION, degree)

    def closed_end_forms(self) -> dict[tuple[str, int, int], sp.Expr]:
        closed = closed_endpoint_forms(self.DEFINITION)
        if closed is None:
            raise DefinitionError(
                f"{self.DEFINITION.name}: a built-in family needs its end values and "
                "derivatives in closed form in n (the joins are emitted in n, m); this "
                "definition has none, so give it a derivation module or keep it a user family"
            )
        return {key: v for key, v in closed.items() if key[1] <= 2}

    def module_data(self) -> FamilyModule:
        """What the emitted module holds (derive/emit prints it)."""
        defn = self.DEFINITION
        check(defn)
        closed = self.closed_end_forms()
        check_endpoint_closed_forms(closed, {d: self.basis_polys(d) for d in defn.degrees}, 2)
        return FamilyModule(
            script=self.SCRIPT,
            doc=f"{defn.title or defn.name}: derived from its definition alone.",
            definition=defn,
            tables=expansion_tables(self.basis_polys, tuple(defn.degrees), defn.offset),
            general_forms=(),
            endpoint=closed,
        )


@cache
def _generic_derivation(defn: Definition) -> GenericDerivation:
    return GenericDerivation(defn)


# --------------------------------------------------------------------------- several parameters


def monomial_split(defn: Definition, degree: int) -> dict[tuple[int, ...], list[sp.Poly]]:
    """{exponent tuple of the parameters: the degree-`degree` functions' coefficients of that
    monomial, as Polys in t (and lam, of degree 0: the tables' shape)}, sorted by monomial."""
    polys = basis_polys(defn, degree)
    monomials = sorted({m[1:] for p in polys for m in p.monoms()})
    out = {}
    for mono in monomials:
        row = []
        for p in polys:
            coeffs = {(m[0], 0): c for m, c in p.terms() if m[1:] == mono}
            row.append(sp.Poly.from_dict(coeffs or {(0, 0): 0}, t, lam, domain="QQ"))
        out[mono] = row
    return out


def symmetry(defn: Definition) -> tuple[str, ...] | None:
    """The parameter substitution s (the new value of each parameter, as text) with
    b_i(t; x) = b_{n-i}(1 - t; s(x)) for every degree and i: the identity, a transposition
    of two parameters, or either with signs flipped (a parameter per leg maps to minus the
    mirrored leg's); None when none of these is."""
    syms = defn.symbols
    count = len(syms)
    names = defn.parameters
    for perm, sign in symmetry_candidates(count):
        swap = {syms[k]: sign[k] * syms[perm[k]] for k in range(count)}
        if all(
            sp.expand(p.as_expr().subs({**swap, t: 1 - t}, simultaneous=True) - q.as_expr()) == 0
            for deg in defn.degrees
            for p, q in zip(basis_polys(defn, deg), reversed(basis_polys(defn, deg)), strict=True)
        ):
            return tuple(("-" if sign[k] < 0 else "") + names[perm[k]] for k in range(count))
    return None


def symmetry_candidates(count: int) -> list[tuple[tuple[int, ...], tuple[int, ...]]]:
    """The (permutation, signs) pairs a symmetry of `count` parameters is sought among, in
    the order tried: the identity, each transposition, then the reversal of the parameter
    order (per-leg families) when it is none of those; each with every sign pattern (up to
    4 parameters; only + past that). Shared by the polynomial and the atom symmetry."""
    import itertools

    perms = [tuple(range(count))]
    for a in range(count):
        for b in range(a + 1, count):
            perm = list(range(count))
            perm[a], perm[b] = b, a
            perms.append(tuple(perm))
    reversal = tuple(reversed(range(count)))
    if reversal not in perms:
        perms.append(reversal)
    signs = list(itertools.product((1, -1), repeat=count)) if count <= 4 else [(1,) * count]
    return [(perm, sign) for perm in perms for sign in signs]


def _negative_point(p: sp.Poly) -> sp.Rational | None:
    """A rational t in [0, 1] where the polynomial p(t) is negative, or None when p >= 0 on
    [0, 1]. Exact: between consecutive real roots p keeps its sign, so p is evaluated at both
    ends, at the ends of small isolating intervals of its roots in [0, 1] (sorted, disjoint)
    and at a point between each two of them: every gap between roots holds one of these."""
    if p.is_zero:
        return None
    ivs = sorted(
        (sp.Rational(a), sp.Rational(b))
        for (a, b), _ in p.sqf_part().intervals(inf=0, sup=1, eps=sp.Rational(1, 10**9))
    )
    points = {sp.Integer(0), sp.Integer(1)}
    if ivs:  # no root in [0, 1]: the ends decide the sign
        following = [c for c, _ in ivs[1:]] + [sp.Integer(1)]
        for (a, b), c in zip(ivs, following, strict=True):
            points.update((a, b, (b + c) / 2))
        points.add(ivs[0][0] / 2)
    for x in sorted(points):
        if 0 <= x <= 1 and p.eval(x) < 0:
            return x
    return None


def nonnegative_over_box(defn: Definition) -> dict:
    """Whether every basis function is >= 0 for t in [0, 1] and every parameter value of the
    box, decided exactly for a basis affine in the parameters jointly: for fixed t a function
    is affine in them, so its least value over the box is at a vertex (an open end by
    continuity), and each vertex leaves a polynomial in t. {"nonnegative": true} or a
    counterexample; a reason when the basis is not affine."""
    import itertools

    for deg in defn.degrees:
        if any(sum(m[1:]) > 1 for p in basis_polys(defn, deg) for m in p.monoms()):
            return {"reason": f"not affine in the parameters jointly at n = {deg}: not decided"}
    corners = [(q.lo, q.hi) for q in defn.params]
    for deg in defn.degrees:
        for vertex in itertools.product(*corners):
            at = {
                s: sp.Rational(v.numerator, v.denominator)
                for s, v in zip(defn.symbols, vertex, strict=True)
            }
            for idx, p in enumerate(basis_polys(defn, deg)):
                q = sp.Poly(p.as_expr().xreplace(at), t)
                x = _negative_point(q)
                if x is not None:
                    return {
                        "nonnegative": False,
                        "counterexample": {
                            "n": deg,
                            "i": idx,
                            "t": str(x),
                            **{
                                name: str(v)
                                for name, v in zip(defn.parameters, vertex, strict=True)
                            },
                            "value": str(q.eval(x)),
                        },
                    }
    return {"nonnegative": True}
