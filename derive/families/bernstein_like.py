"""The Bernstein-like basis (001_33da2b0fa8491127.txt).

Axioms (as data in derive/families/bernstein_like.toml): the quadratic seed, eq. (1),
    b_{0,2} = (1 - 2λt + λt²)(1-t)²,  b_{1,2} = 2t(1-t)(1 + λ - λt + λt²),
    b_{2,2} = (1 - λ + λt²)t²,
and the recursion, eq. (2), b_{i,n} = (1-t) b_{i,n-1} + t b_{i-1,n-1} (b_{-1} = b_{n} = 0),
for λ in [-1, 1]. A degree-n curve is a polynomial of degree n + 2.
Derived here: per-degree expansions, the general-n explicit form b_{i,n} = q_i(t) B_{i,n}(t)
(the shape of eq. 5), and the values, first and second derivatives at both ends.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cache

import sympy as sp

from ..algebra import (
    LAMBDA_SAMPLES,
    check_endpoint_closed_forms,
    exact_function,
    expansion_tables,
    i,
    lam,
    linear_in_lambda,
    n,
    t,
)
from ..algebra.bernstein import bernstein_basis, bernstein_poly, endpoint_weight
from ..grammar import SYMBOLS
from .definition import builtin_definition
from .engine import FamilyModule, GeneralForm, check
from .engine import basis_polys as basis_polys_of

SCRIPT = "families/bernstein_like.py"
OUTPUT = "bernstein_like.py"
ORDERS = 2

# The axioms are data: derive/families/bernstein_like.toml holds the seed (eq. 1) and the
# recursion (eq. 2) as the records grammar reads them; the generic engine evaluates them per
# degree (and checks polynomial degree, partition of unity and Bernstein at λ = 0). What stays
# here is what no generic rule gives: the general-n explicit form (the shape of eq. 5).
DEFINITION = builtin_definition("bernstein_like")
DEGREES = DEFINITION.degrees
DEGREE_OFFSET = DEFINITION.offset  # the basis polynomials have degree n + DEGREE_OFFSET
PARAMETERS = DEFINITION.parameters  # the shape parameters' names, a tuple (issue #30)
DOMAIN = DEFINITION.domain  # the interval of t
SEED = tuple(s.xreplace({SYMBOLS["t"]: t}) for s in DEFINITION.seed)


@cache
def basis_polys(degree: int) -> tuple[sp.Poly, ...]:
    """Eq. (2) applied degree - 2 times to the seed, exactly as stated (by the engine)."""
    return tuple(basis_polys_of(DEFINITION, degree))


@cache
def explicit_factor() -> sp.Expr:
    """q_i(t) with b_{i,n} = q_i(t) B_{i,n}(t), for symbolic n and i.

    Unrolling eq. (2) down to the seed gives b_{i,n} = Σ_s B_{i-s,n-2}(t) b_{s,2}(t): the
    right side equals the seed at n = 2 and obeys eq. (2) because each B_{i-s,n-2} obeys the
    Bernstein recursion (checked symbolically below). Dividing by B_{i,n} leaves, term by term,
    C(n-2,i-s)/C(n,i) · b_{s,2}/(t^s (1-t)^(2-s)), a polynomial because b_{s,2} carries that
    factor.
    """
    ratio_rec = sp.combsimp(
        ((1 - t) * bernstein_basis(n - 1, i) + t * bernstein_basis(n - 1, i - 1))
        / bernstein_basis(n, i)
    )
    # the powers of t and 1 - t combine (same base), and what is left is rational
    if sp.cancel(sp.expand(sp.powsimp(ratio_rec - 1, force=True), force=True)) != 0:
        raise AssertionError("Bernstein recursion failed symbolically")
    q = sp.Integer(0)
    for s, seed in enumerate(SEED):
        reduced = sp.cancel(seed / (t**s * (1 - t) ** (2 - s)))
        q += sp.combsimp(sp.binomial(n - 2, i - s) / sp.binomial(n, i)) * reduced
    return sp.collect(sp.expand(q), [t, lam])


@cache
def endpoint_closed_forms(q: sp.Expr) -> dict[tuple[str, int, int], sp.Expr]:
    """Derivatives of b_{i,n} = q_i(t) B_{i,n}(t) at t=0 (i = 0..r) and at t=1 (i = n-j).

    Leibniz: (q B)^(r) = Σ_s C(r,s) q^(r-s) B^(s), and the s-th derivative of B_{i,n} at an
    end is the Bernstein endpoint weight (derived in bernstein.py), zero unless i <= s. q is a
    quadratic in t, so only its own derivatives are taken here (differentiating the product
    with the power n - i in it is far slower).
    """
    coeffs = sp.Poly(q, t).all_coeffs()  # q as a polynomial in t, coefficients in n, i, λ
    out = {}
    for r in range(ORDERS + 1):
        for idx in range(r + 1):
            for end, at, index in (("start", 0, idx), ("end", 1, n - idx)):
                q_end = sp.Poly([c.subs(i, index) for c in coeffs], t)
                total = sp.Integer(0)
                for s in range(idx, r + 1):
                    q_r = q_end.diff((t, r - s)).eval(at)
                    total += sp.binomial(r, s) * q_r * endpoint_weight(end, s, idx)
                val = sp.factor(total)
                if val != 0:
                    out[(end, r, idx)] = val
    return out


def closed_end_forms() -> dict[tuple[str, int, int], sp.Expr]:
    """The end forms every derivation module gives (joins, verify): from the explicit form."""
    return endpoint_closed_forms(explicit_factor())


def _check(q, closed) -> None:
    """The explicit form and the endpoint closed forms against the recursion, for every n."""
    check(DEFINITION)  # the definition's own claims, every degree
    coeffs = sp.Poly(q, t)
    if coeffs.degree() != 2 or not all(linear_in_lambda(c) for c in coeffs.all_coeffs()):
        raise AssertionError("explicit factor should be quadratic in t and linear in λ")
    factor = exact_function([coeffs.coeff_monomial(t**e) for e in range(3)], (n, i, lam))
    for deg in DEGREES:
        for ii, p in enumerate(basis_polys(deg)):
            for x in LAMBDA_SAMPLES:
                c = [Fraction(v) for v in factor(Fraction(deg), Fraction(ii), Fraction(x))]
                quad = sp.Poly([c[2], c[1], c[0]], t, domain="QQ")
                if quad * bernstein_poly(deg, ii).eval(lam, 0) != p.eval(lam, x):
                    raise AssertionError(f"explicit form wrong at n={deg}, i={ii}, λ={x}")
    check_endpoint_closed_forms(closed, {d: basis_polys(d) for d in DEGREES}, ORDERS)


def module_data() -> FamilyModule:
    """What the emitted module holds (derive/emit prints it): the tables, the explicit
    factor (checked) and the end forms (checked against every degree)."""
    q = explicit_factor()
    closed = endpoint_closed_forms(q)
    _check(q, closed)
    coeffs = sp.Poly(q, t)
    return FamilyModule(
        script=SCRIPT,
        doc="Bernstein-like basis b_{i,n}(t; λ) of 001_33da2b0fa8491127.txt, eqs. (1)-(2).",
        definition=DEFINITION,
        tables=expansion_tables(basis_polys, tuple(DEGREES), DEFINITION.offset),
        general_forms=(
            GeneralForm(
                "explicit_factor",
                ("n", "i", "lam"),
                "(c0, c1, c2) with b_{i,n}(t) = (c0 + c1 t + c2 t^2) B_{i,n}(t), for 0 <= i <= n.",
                tuple(sp.factor(coeffs.coeff_monomial(t**e)) for e in range(3)),
            ),
        ),
        endpoint=closed,
    )
