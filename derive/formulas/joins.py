"""Joining two curves: the leading control points of the second curve that make the joint
C1, C2, G1 or G2 (001, Theorems 2-5; 000, Prop. 9), for every ordered pair of families.

The first curve C1 has degree n, shape λ1 and points P_{i,1}; the second C2 has degree m,
shape λ2 and points P_{j,2} (001's naming; 000's Prop. 9 swaps n and m). The conditions, in
001's convention for the geometric ones:

    C1:  C1(1) = C2(0),  C1'(1) = C2'(0)
    C2:  C1 and C1''(1) = C2''(0)
    G1:  C1(1) = C2(0),  C1'(1) = α C2'(0),  α > 0
    G2:  G1 and C1''(1) = α² C2''(0) + d C2'(0),  d free

(G2 as stated keeps the unit tangent, the curvature and the binormal direction: equal
curvature forces the factor of C2''(0) to be α², see 001 eqs. 32-35.)

Nothing here comes from the papers' printed joins. The only inputs are the endpoint closed
forms derived by each family's derivation module (closed_end_forms()): with Q_j = P_{n-j,1},

    C1^(r)(1) = Σ_j e_{r,j}(n, λ1) Q_j,    C2^(r)(0) = Σ_i s_{r,i}(m, λ2) P_{i,2}.

The conditions are linear and triangular in P_{0,2}, P_{1,2}, P_{2,2} (the r-th derivative at
0 involves P_{0,2} … P_{r,2}, and P_{3,2} too at r = 2 for a family whose second
derivative at an end involves four control points, as 000's does: there P_{2,2} is solved
with P_{3,2} given). They are solved here symbolically in n, m, λ1, λ2, α, d, and each solved
point is written as weights of the first curve's last points (and of P_{3,2}).

Checked inside derive: (1) symbolically, for general n and m, every solution satisfies its
conditions and the weights of every solved point sum to 1 (affine invariance); every
denominator divides α³ s_{1,1}(m, λ2) s_{2,2}(m, λ2) (the pivots, emitted for the runtime's
error messages); (2) exactly, the *emitted* functions (the printed module text, executed)
against endpoint derivatives read off the per-degree basis polynomials themselves, at exact
sample λ1, λ2, α, d, on a grid of degree pairs (every degree of each range against the
lowest two, middle and highest of the other: about 1,500 pairs, kept small so that derive
stays fast).
"""

from __future__ import annotations

from contextlib import contextmanager
from fractions import Fraction
from functools import cache

import flint
import sympy as sp
from sympy.polys.fields import field
from sympy.polys.rings import ring

from ..algebra import lam, m, n
from ..algebra.ratfunc import RationalFunction, context, factored, from_expr, to_sympy_field
from ..families.registry import REFERENCE, builtin_names, derivation

FAMILIES = builtin_names()  # the reference basis, then derive/families/*.toml in order
CONTINUITIES = ("C1", "C2", "G1", "G2")
ORDER = {"C1": 1, "C2": 2, "G1": 1, "G2": 2}  # derivatives matched; solved: P_{0..ORDER,2}
DEGREES = {name: tuple(derivation(name).DEGREES) for name in FAMILIES}
HAS_LAMBDA = {name: name != REFERENCE for name in FAMILIES}
# the highest end-derivative order each family has in closed form (the built-ins: 2)
CLOSED_ORDER = dict.fromkeys(FAMILIES, 2)

lam1, lam2, alpha, d = sp.symbols("lam1 lam2 alpha d")

# Exact sample values for the per-degree check: inside both λ ranges, α ≠ 1, d ≠ 0.
SAMPLES = (
    (Fraction(1, 3), Fraction(-2, 5), Fraction(3, 2), Fraction(-7, 4)),
    (Fraction(-5, 7), Fraction(4, 9), Fraction(2, 5), Fraction(5, 3)),
)


# --------------------------------------------------------------------------- inputs


# Families defined by data (derive/families/engine.py) while their joins are derived: name ->
# closed endpoint forms {(end, r, idx): expr in n, lam}; see extra_family().
_EXTRA: dict[str, dict[tuple[str, int, int], sp.Expr]] = {}
# A family in several parameters (or with atoms: derive/formulas/joins_several.py): the
# symbols of its parameters, each renamed per side (x -> x1 on the first curve, x2 on the
# second, as lam -> lam1, lam2); any other symbol of its forms (the constant C = pi or e^W of
# an atom family) is shared by both sides.
_PARAMS: dict[str, tuple[sp.Symbol, ...]] = {}


def register(
    name: str,
    forms: dict,
    degrees: tuple[int, ...],
    has_lambda: bool,
    order: int = 2,
    params: tuple[sp.Symbol, ...] = (),
) -> None:
    """`name` becomes a family of the solve, with the given closed end forms of orders
    0..order (the solve uses up to 2); it is never emitted. `params`: the symbols of a
    family in several parameters (its forms are then in them, not in n and lam)."""
    _EXTRA[name] = {key: v for key, v in forms.items() if key[1] <= min(order, 2) and v != 0}
    DEGREES[name] = degrees
    HAS_LAMBDA[name] = has_lambda
    CLOSED_ORDER[name] = order
    _PARAMS[name] = params


@contextmanager
def extra_family(
    name: str,
    forms: dict,
    degrees: tuple[int, ...],
    has_lambda: bool,
    order: int = 2,
    params: tuple[sp.Symbol, ...] = (),
):
    """register() for the duration of the block."""
    register(name, forms, degrees, has_lambda, order, params)
    try:
        yield
    finally:
        del _EXTRA[name], DEGREES[name], HAS_LAMBDA[name], CLOSED_ORDER[name], _PARAMS[name]


def side_symbol(symbol: sp.Symbol, side: int) -> sp.Symbol:
    """A parameter's symbol on the first (side 1) or second (side 2) curve of a join."""
    if symbol == lam:
        return (lam1, lam2)[side - 1]
    return sp.Symbol(f"{symbol.name}{side}")


def _renaming(family: str, side: int) -> dict:
    out = {lam: (lam1, lam2)[side - 1]}
    out.update({x: side_symbol(x, side) for x in _PARAMS.get(family, ())})
    if side == 2:
        out[n] = m
    return out


def endpoint_forms(family: str) -> dict[tuple[str, int, int], sp.Expr]:
    """{(end, r, idx): closed form in n, lam} from the family's own derivation, with the
    factorials of n cancelled (they are ratios such as n!/(n-2)! = n(n-1))."""
    if family in _EXTRA:
        return _EXTRA[family]
    return _builtin_endpoint_forms(family)


@cache
def _builtin_endpoint_forms(family: str) -> dict[tuple[str, int, int], sp.Expr]:
    if family not in FAMILIES:
        raise KeyError(f"no closed end forms for the family {family!r}")
    raw = derivation(family).closed_end_forms()
    out = {}
    for key, v in raw.items():
        if v.has(sp.factorial, sp.binomial, sp.FallingFactorial):
            v = sp.combsimp(v)
        v = sp.factor(v)
        if v.has(sp.factorial, sp.binomial, sp.FallingFactorial):
            raise AssertionError(f"{family} {key}: combinatorial function left in {v}")
        if v != 0:
            out[key] = v
    return out


def end_coefficients(family: str) -> dict[tuple[int, int], sp.Expr]:
    """e[(r, j)]: weight of Q_j = P_{n-j,1} in C1^(r)(1), in n and λ1."""
    rename = _renaming(family, 1)
    return {
        (r, j): v.xreplace(rename) for (e, r, j), v in endpoint_forms(family).items() if e == "end"
    }


def start_coefficients(family: str) -> dict[tuple[int, int], sp.Expr]:
    """s[(r, i)]: weight of P_{i,2} in C2^(r)(0), in m and λ2."""
    rename = _renaming(family, 2)
    return {
        (r, j): v.xreplace(rename)
        for (e, r, j), v in endpoint_forms(family).items()
        if e == "start"
    }


def pivots(family: str) -> tuple[sp.Expr, sp.Expr]:
    """(s_{1,1}, s_{2,2}): the coefficients the solve divides by (of P_{1,2} in C2'(0), of
    P_{2,2} in C2''(0)); a join is impossible where one vanishes."""
    s = start_coefficients(family)
    return s[(1, 1)], s[(2, 2)]


# --------------------------------------------------------------------------- the solve

Combination = dict  # ("first", j) -> weight of Q_j = P_{n-j,1}; ("second", 3) -> of P_{3,2}


BASE_SYMBOLS = (n, m, lam1, lam2, alpha, d)


@cache
def _field(extra: tuple[sp.Symbol, ...] = ()):
    """Q(n, m, λ1, λ2, α, d) (and the parameters of families in several parameters, and
    their constant): exact rational-function arithmetic (much faster than Expr)."""
    return field([*BASE_SYMBOLS, *extra], sp.QQ)[0]


def extra_symbols(first: str, second: str) -> tuple[sp.Symbol, ...]:
    """The symbols of the pair's end forms beyond BASE_SYMBOLS, sorted by name."""
    exprs = [*end_coefficients(first).values(), *start_coefficients(second).values()]
    found = set().union(*(v.free_symbols for v in exprs)) - set(BASE_SYMBOLS)
    return tuple(sorted(found, key=lambda x: x.name))


# The solve runs in FLINT (algebra/ratfunc.py: the same field, Q(n, m, λ1, λ2, α, d) and the
# pair's extra symbols, with every operation in C; SymPy's field took a third of `derive
# --check`, issue #29), and hands SymPy's field elements, in SymPy's own normal form, to the
# printing.
@cache
def _rf_of(expr: sp.Expr, extra: tuple[sp.Symbol, ...] = ()) -> RationalFunction:
    return from_expr(expr, (*BASE_SYMBOLS, *extra))


def _rf(value: int, extra: tuple[sp.Symbol, ...] = ()) -> RationalFunction:
    return RationalFunction.constant(len(BASE_SYMBOLS) + len(extra), value)


def _combine(*terms) -> Combination:
    out: Combination = {}
    for c, comb in terms:
        for key, v in comb.items():
            out[key] = out.get(key, 0) + c * v
    return out


def solve(first: str, second: str, order: int = 2) -> tuple[Combination, ...]:
    """P_{0,2} … P_{order,2} from the G1 (order 1) or G2 (order 2) conditions, as elements of
    Q(n, m, λ1, λ2, α, d), every other control point of the second curve given: the
    conditions are linear in the unknowns, solved by elimination with the pivots in their
    natural order (for a family whose end value is P_0 and whose r-th derivative involves
    P_0..P_r, the triangular solve: G1 is then the first two rows of G2). Nothing assumes
    which points an end derivative involves: a first derivative with P_{2,2} in it (a
    three-point stencil) makes P_{2,2} a given point of the G1 solve. C1 and C2 are G1 and G2
    at α = 1, d = 0."""
    for fam in (first, second):
        if CLOSED_ORDER.get(fam, 2) < order:
            raise AssertionError(f"{fam}: end derivatives of order {order} not in closed form")
    extra = extra_symbols(first, second)
    one, zero = _rf(1, extra), _rf(0, extra)
    e = {key: _rf_of(v, extra) for key, v in end_coefficients(first).items()}
    s = {key: _rf_of(v, extra) for key, v in start_coefficients(second).items()}
    if any(r > 2 for r, _ in s) or any(r > 2 for r, _ in e):
        raise AssertionError(f"{first} -> {second}: end forms of order > 2 given")
    a, dd = _rf_of(alpha, extra), _rf_of(d, extra)
    width = 1 + max([j for _, j in e] + [order])
    c1 = [{("first", j): e[(r, j)] for j in range(width) if (r, j) in e} for r in range(3)]
    # the conditions, with the first curve's side scaled: C2^(r)(0) = target_r
    #     C2(0) = C1(1),  α C2'(0) = C1'(1),  α² C2''(0) + d C2'(0) = C1''(1)
    targets = [c1[0], _combine((1 / a, c1[1]))]
    targets.append(_combine((1 / a**2, c1[2]), (-dd / a**3, c1[1])))
    unknowns = range(order + 1)
    given = sorted({j for r, j in s if r <= order and j > order})
    # rows: ({unknown i: coefficient}, right side) with the given points moved to the right
    rows = []
    for r in range(order + 1):
        coeffs = {i: s[(r, i)] for i in unknowns if (r, i) in s}
        rhs = _combine(
            (one, targets[r]),
            *((-s[(r, j)], {("second", j): one}) for j in given if (r, j) in s),
        )
        rows.append((coeffs, rhs))
    solution: list[Combination | None] = [None] * (order + 1)
    # forward elimination, pivot P_{i,2} in row i (the natural order)
    for i in unknowns:
        pivot = rows[i][0].get(i, zero)
        if pivot == 0:
            raise AssertionError(
                f"{first} -> {second}: P_{i},2 has coefficient 0 in the condition of order {i}"
            )
        for r in range(i + 1, order + 1):
            factor = rows[r][0].get(i, zero) / pivot
            if factor != 0:
                coeffs = {
                    k: rows[r][0].get(k, zero) - factor * rows[i][0].get(k, zero)
                    for k in unknowns
                    if k > i
                }
                rows[r] = (coeffs, _combine((one, rows[r][1]), (-factor, rows[i][1])))
    for i in reversed(unknowns):
        coeffs, rhs = rows[i]
        terms = [(one / coeffs[i], rhs)]
        for k in unknowns:
            if k > i and coeffs.get(k, zero) != 0:
                terms.append((-coeffs[k] / coeffs[i], solution[k]))
        solution[i] = _combine(*terms)
    out = tuple({key: v for key, v in p.items() if v != 0} for p in solution)
    _check_symbolic(first, second, out, e, s, a, dd, order, width, given, extra)
    field_ = _field(extra)
    return tuple({key: to_sympy_field(v, field_) for key, v in p.items()} for p in out)


def _check_symbolic(first, second, rows, e, s, a, dd, order, width, given, extra) -> None:
    """General n, m: the solution satisfies every condition; the weights of every solved point
    sum to 1 (affine invariance); every denominator divides α^(order+1) times the pivots'
    product (and the denominators of the end forms); P_{1,2} does not involve d where the
    stencil is triangular."""
    zero = _rf(0, extra)
    keys = [("first", j) for j in range(width)] + [("second", j) for j in given]
    for key in keys:  # everything is linear in the points: compare coefficients point by point
        c1 = [e.get((r, key[1]), zero) if key[0] == "first" else zero for r in range(3)]
        c2 = [
            sum((s.get((r, ii), zero) * rows[ii].get(key, zero) for ii in range(order + 1)), zero)
            + (s.get((r, key[1]), zero) if key[0] == "second" else zero)
            for r in range(3)
        ]
        conditions = (c2[0] - c1[0], a * c2[1] - c1[1], a**2 * c2[2] + dd * c2[1] - c1[2])
        for idx, cond in enumerate(conditions[: order + 1]):
            if cond != 0:
                raise AssertionError(f"{first} -> {second}: condition {idx} fails at {key}")
    bound = _rf_of(alpha, extra) ** (order + 1)
    for p_ in pivot_products(second, order, extra):
        bound *= RationalFunction(_rf_of(p_, extra).num)
    # end forms that are fractions (an atom family's powers C^-k of its constant e^W)
    dens = {str(x.den): x.den for x in (*e.values(), *s.values())}
    for key in sorted(dens):
        bound *= RationalFunction(dens[key])
    for row, comb in enumerate(rows):
        if sum(comb.values(), zero) != 1:
            raise AssertionError(f"{first} -> {second}: weights of P_{row},2 do not sum to 1")
        for w in comb.values():
            if not (bound / RationalFunction(w.den)).is_polynomial:
                raise AssertionError(f"{first} -> {second}: unexpected denominator {w.den}")
    # with C2(0), C2'(0) involving P_{0,2}, P_{1,2} only, those two come from the G1 rows and
    # cannot depend on d (a wider first-derivative stencil couples P_{1,2} to the G2 row)
    triangular = not any((r == 0 and j > 0) or (r == 1 and j > 1) for r, j in s)
    if triangular and any(
        w.num.degrees()[5] > 0 or w.den.degrees()[5] > 0 for w in rows[1].values()
    ):
        raise AssertionError(f"{first} -> {second}: P_1,2 depends on d")


def pivot_products(family: str, order: int, extra: tuple[sp.Symbol, ...] = ()) -> list:
    """The leading principal minors of the start stencil (orders 0..order), whose product
    bounds every denominator of the solve (for a triangular stencil: s00, s00·s11, ...)."""
    # keyed by the stencil itself, not the family's name: a family registered for one
    # derivation (register()) may have other forms under the same name in the next
    stencil = tuple(sorted(start_coefficients(family).items()))
    return list(_pivot_products(stencil, order, extra))


@cache
def _pivot_products(stencil: tuple, order: int, extra: tuple[sp.Symbol, ...]) -> tuple:
    field_ = _field(extra)
    s = {key: field_(v) for key, v in stencil}
    mat = sp.Matrix(order + 1, order + 1, lambda r, i: s.get((r, i), field_(0)).as_expr())
    return tuple(sp.factor(mat[: k + 1, : k + 1].det()) for k in range(order + 1))


@cache
def _coefficient_ring():
    return ring([n, m, lam1, lam2], sp.QQ)[0]


def _printed(poly) -> sp.Expr:
    """A polynomial in (n, m, λ1, λ2, α, d) as Σ α^a d^b · (factored coefficient)."""
    ring_ = _coefficient_ring()
    groups: dict = {}
    for mon, c in poly.terms():
        groups[mon[4:]] = groups.get(mon[4:], ring_(0)) + ring_({mon[:4]: c})
    total = sp.Integer(0)
    for (ea, ed), g in groups.items():
        total += _factored(tuple(sorted(g.terms()))) * alpha**ea * d**ed
    return total


@cache
def _factored(terms: tuple) -> sp.Expr:
    """A polynomial in (n, m, λ1, λ2), given by its terms, factored (the same coefficients
    recur across family pairs, hence the cache)."""
    # FLINT factors, in SymPy's form of factor_list (algebra/ratfunc.factored): SymPy's own
    # multivariate factoring was a tenth of `derive --check` (issue #29)
    qq = _coefficient_ring().domain
    exact = {mon: Fraction(int(qq.numer(c)), int(qq.denom(c))) for mon, c in terms}
    return factored(exact, (n, m, lam1, lam2))


# Rational points at which the printed form of each weight is compared with the field element.
_PROBES = (
    (Fraction(7), Fraction(5), Fraction(1, 3), Fraction(-3, 7), Fraction(5, 2), Fraction(-2, 9)),
    (Fraction(11), Fraction(4), Fraction(-5, 6), Fraction(2, 9), Fraction(3, 7), Fraction(8, 5)),
)


def _value(poly, point: tuple[Fraction, ...]) -> flint.fmpq:
    """A polynomial of Q(n, m, λ1, λ2, α, d) at a rational point, evaluated in FLINT (SymPy's
    ring evaluation at Fractions was a tenth of the joins, issue #29)."""
    qq = _field().domain
    terms = {mon: flint.fmpq(int(qq.numer(c)), int(qq.denom(c))) for mon, c in poly.terms()}
    at = [flint.fmpq(v.numerator, v.denominator) for v in point]
    return context(len(point)).from_dict(terms)(*at)


def printed(w) -> sp.Expr:
    """One fraction per weight, numerator grouped by powers of α and d (the printing only
    regroups and factors; compared with w at probe points, and the emitted text is checked
    against the per-degree tables below)."""
    expr = _printed(w.numer) / _printed(w.denom)
    for probe in _PROBES:
        got = expr.xreplace(
            {
                x: sp.Rational(v.numerator, v.denominator)
                for x, v in zip((n, m, lam1, lam2, alpha, d), probe, strict=True)
            }
        )
        want = _value(w.numer, probe) / _value(w.denom, probe)
        if got != sp.Rational(int(want.p), int(want.q)):
            raise AssertionError(f"printing changed a weight: {expr}")
    return expr


def joins() -> dict[tuple[str, str, str], dict[tuple[int, str, int], sp.Expr]]:
    """{(first, second, continuity): {(row, source, j): weight}}: P_{row,2} = Σ weight · X with
    X = P_{n-j,1} for source "first", X = P_{j,2} (j = 3) for "second". The C forms are the
    printed G forms at α = 1, d = 0 (kept in that shape), checked against the C solve."""
    out = {}
    for first in FAMILIES:
        for second in FAMILIES:
            geo = {
                k: [{key: printed(w) for key, w in row.items()} for row in solve(first, second, k)]
                for k in (1, 2)
            }
            par = {k: [_at_unit_alpha(row) for row in geo[k]] for k in (1, 2)}
            for cont in CONTINUITIES:
                rows = (geo if cont.startswith("G") else par)[ORDER[cont]]
                out[(first, second, cont)] = {
                    (row, src, j): w
                    for row in range(ORDER[cont] + 1)
                    for (src, j), w in rows[row].items()
                }
    return out


def _at_unit_alpha(row: dict) -> dict:
    """A printed G weight at α = 1, d = 0, keeping its shape."""
    out = {}
    for key, w in row.items():
        num, den = sp.fraction(w)
        num = num.xreplace({alpha: 1, d: 0})
        if num != 0:
            out[key] = num / den.xreplace({alpha: 1, d: 0})
    return out
