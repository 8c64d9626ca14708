"""The same-degree λ-Bernstein basis (000_10ca634d356c575d.txt).

Axiom: eq. (1), as data in derive/families/same_degree.toml,
    b_i^n(t) = C(n,i)(1-t)^(n-i) t^i + (1-λ)(1-t)^(n-i-1) t^(i-1)
               × [C(n-3,i-3)(1-t)^2 - C(n-2,i-1)(1-t)t + C(n-3,i)t^2],
for n >= 3, λ in (-2, 1], with C(a, b) = 0 outside 0 <= b <= a.
Derived here: per-degree expansions (power and Bernstein bases), the general-n three-term
Bernstein form, and the values, first and second derivatives at both ends in closed form.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cache

import sympy as sp

from ..algebra import (
    LAMBDA_SAMPLES,
    bernstein_matrices,
    bernstein_terms,
    check_endpoint_closed_forms,
    exact_function,
    expansion_tables,
    i,
    lam,
    linear_in_lambda,
    n,
    t,
)
from ..algebra.bernstein import endpoint_weight
from ..grammar import SYMBOLS
from .definition import builtin_definition
from .engine import FamilyModule, GeneralForm, check
from .engine import basis_polys as basis_polys_of

SCRIPT = "families/same_degree.py"
OUTPUT = "same_degree.py"
ORDERS = 2  # endpoint derivatives emitted in closed form: value, first, second


# The axiom is data: derive/families/same_degree.toml holds eq. (1) as the records grammar
# reads it, and the generic engine (derive/families/engine.py) evaluates it per degree in
# Q(t, λ) (negative powers at i = 0 and i = n must cancel, checked) and checks its own claims
# (polynomial degree, partition of unity, Bernstein at λ = 1). What stays here is what no
# generic rule gives: 000's general-n three-term Bernstein form and its end closed forms.
DEFINITION = builtin_definition("same_degree")
DEGREES = DEFINITION.degrees
DEGREE_OFFSET = DEFINITION.offset  # the basis polynomials have degree n + DEGREE_OFFSET
PARAMETERS = DEFINITION.parameters  # the shape parameters' names, a tuple (issue #30)
DOMAIN = DEFINITION.domain  # the interval of t
_CLOSED_FIELD = sp.polys.fields.field([n, lam], sp.QQ)[0]


def basis_definition() -> sp.Expr:
    """Eq. (1) for symbolic n and i (derive's integer symbols), from the definition file."""
    g = SYMBOLS
    return DEFINITION.basis.xreplace({g["n"]: n, g["i"]: i, g["t"]: t, g["lam"]: lam})


@cache
def basis_polys(degree: int) -> list[sp.Poly]:
    """Eq. (1) per index, evaluated exactly by the engine."""
    return basis_polys_of(DEFINITION, degree)


@cache
def three_term_form() -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """Coefficients of B_{i-1}^n, B_i^n, B_{i+1}^n in b_i^n, for symbolic n and i."""
    terms = bernstein_terms(basis_definition(), n)
    if set(terms) != {i - 1, i, i + 1}:
        raise AssertionError(f"unexpected Bernstein support {sorted(terms, key=str)}")
    return terms[i - 1], terms[i], terms[i + 1]


@cache
def endpoint_closed_forms(form) -> dict[tuple[str, int, int], sp.Expr]:
    """{("start", r, i) or ("end", r, j): d^r/dt^r b at t=0 (index i) or t=1 (index n-j)}.

    b_i = α_i B_{i-1} + β_i B_i + γ_i B_{i+1}; the r-th derivative of B_l at 0 is the
    Bernstein endpoint weight w_start(n, r, l) for l <= r and 0 otherwise (and mirrored at 1),
    so only i <= r + 1 (resp. n - i <= r + 1) can be nonzero.
    """
    field = _CLOSED_FIELD  # the sums are added in Q(n, λ), then factored once
    out = {}
    for r in range(ORDERS + 1):
        for idx in range(r + 2):
            # start: B_l, l = idx-1, idx, idx+1; end: B_{n-l}, l = idx+1, idx, idx-1
            total_start = total_end = field(0)
            for coeff, shift in zip(form, (-1, 0, 1), strict=True):
                l0 = idx + shift
                if 0 <= l0 <= r:
                    weight = endpoint_weight("start", r, l0)
                    total_start += field(coeff.subs(i, idx)) * field(weight)
                l1 = idx - shift
                if 0 <= l1 <= r:
                    weight = endpoint_weight("end", r, l1)
                    total_end += field(coeff.subs(i, n - idx)) * field(weight)
            for end, total in (("start", total_start), ("end", total_end)):
                total = sp.factor(total.as_expr())
                if total != 0:
                    out[(end, r, idx)] = total
    return out


def closed_end_forms() -> dict[tuple[str, int, int], sp.Expr]:
    """The end forms every derivation module gives (joins, verify): from the three-term form."""
    return endpoint_closed_forms(three_term_form())


def _check(form, closed) -> None:
    """Every general-n result against the per-degree expansion of the axiom, for every n."""
    check(DEFINITION)  # the definition's own claims, every degree
    if not all(linear_in_lambda(c) for c in form):
        raise AssertionError("three-term coefficients are expected to be linear in λ")
    coeffs = exact_function(form, (n, i, lam))
    for deg in DEGREES:
        mats = bernstein_matrices(basis_polys(deg), deg)
        for ii in range(deg + 1):
            for x in LAMBDA_SAMPLES:
                got = [Fraction(c) for c in coeffs(Fraction(deg), Fraction(ii), Fraction(x))]
                for jj in range(deg + 1):
                    want = sum((mats[p][ii][jj] * x**p for p in range(len(mats))), Fraction(0))
                    shift = jj - ii
                    if (got[shift + 1] if abs(shift) <= 1 else 0) != want:
                        raise AssertionError(f"three-term form wrong at n={deg}, i={ii}, B_{jj}")
    check_endpoint_closed_forms(closed, {d: basis_polys(d) for d in DEGREES}, ORDERS)


def module_data() -> FamilyModule:
    """What the emitted module holds (derive/emit prints it): the tables, the three-term
    form (checked) and the end forms (checked against every degree)."""
    form = three_term_form()
    closed = endpoint_closed_forms(form)
    _check(form, closed)
    return FamilyModule(
        script=SCRIPT,
        doc="Same-degree λ-Bernstein basis b_i^n(t; λ) of 000_10ca634d356c575d.txt, eq. (1).",
        definition=DEFINITION,
        tables=expansion_tables(basis_polys, tuple(DEGREES), DEFINITION.offset),
        general_forms=(
            GeneralForm(
                "three_term_bernstein",
                ("n", "i", "lam"),
                "(α, β, γ) with b_i^n = α B_{i-1}^n + β B_i^n + γ B_{i+1}^n, for 0 <= i <= n "
                "(α unused at i = 0, γ at i = n).",
                tuple(form),
            ),
        ),
        endpoint=closed,
    )
