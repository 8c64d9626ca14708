"""Exact polynomial algebra shared by the derive modules.

A basis function is held as a SymPy ``Poly`` in (t, lam) over QQ. From it we read its power
coefficients and, by solving against the Bernstein polynomials of the target degree, its
Bernstein coefficients; both split by powers of λ so that the runtime can assemble
``M(λ) = M_0 + λ M_1 + …`` with numpy.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cache

import sympy as sp

from ._emit import to_fraction

t, lam = sp.symbols("t lam")
# Symbols of the general-n closed forms: integers, so SymPy may simplify binomials.
n, m, i, j, k = sp.symbols("n m i j k", integer=True, nonnegative=True)

Matrix = tuple[tuple[Fraction, ...], ...]


def poly(expr: sp.Expr) -> sp.Poly:
    """A polynomial in (t, lam); a rational expression must cancel to one."""
    try:
        return sp.Poly(expr, t, lam, domain="QQ")
    except (
        sp.PolynomialError
    ):  # negative powers that only cancel after putting over one denominator
        pass
    expr = sp.cancel(sp.sympify(expr))
    num, den = sp.fraction(expr)
    p = sp.Poly(num, t, lam, domain="QQ")
    d = sp.Poly(den, t, lam, domain="QQ")
    q, r = p.div(d)
    if not r.is_zero:
        raise ArithmeticError(f"{expr} is not a polynomial in t and lam")
    return q


@cache
def bernstein_power_matrix(degree: int) -> Matrix:
    """Row j: power coefficients of B_j^degree (imported lazily to keep the axiom in one
    place: derive/bernstein.py)."""
    from .bernstein import bernstein_basis

    x = sp.Poly(t, t, lam, domain="QQ")  # the axiom evaluated in polynomial arithmetic
    return tuple(
        power_matrices([bernstein_basis(degree, jj, x)], degree)[0][0] for jj in range(degree + 1)
    )


@cache
def power_to_bernstein_matrix(degree: int) -> Matrix:
    """Inverse of bernstein_power_matrix: row e gives t^e in the Bernstein basis.
    Computed by exact back substitution (the matrix is triangular with nonzero diagonal)."""
    a = bernstein_power_matrix(degree)
    size = degree + 1
    # B_j has lowest power t^j, so a is upper triangular: t^e = (B_e - Σ_{j<e} ...)/a[e][e]
    # solved from the top: t^e = Σ_j x[e][j] B_j with x = a^{-1}.
    inv = [[Fraction(0)] * size for _ in range(size)]
    for row in range(size - 1, -1, -1):
        for col in range(size):
            rhs = Fraction(int(row == col))
            rhs -= sum((a[row][q] * inv[q][col] for q in range(row + 1, size)), Fraction(0))
            inv[row][col] = rhs / a[row][row]
    # inv = a^{-1}; a maps Bernstein→power (rows: B_j), so power→Bernstein is inv read by rows.
    return tuple(tuple(r) for r in inv)


def lambda_degree(polys: list[sp.Poly]) -> int:
    return max(p.degree(lam) for p in polys)


def power_matrices(polys: list[sp.Poly], degree: int) -> tuple[Matrix, ...]:
    """M_p[i][e] = coefficient of lam^p t^e in basis function i, for p = 0..deg_λ."""
    size = degree + 1
    mats = [[[Fraction(0)] * size for _ in polys] for _ in range(lambda_degree(polys) + 1)]
    for row, pp in enumerate(polys):
        for (e, p), c in pp.terms():
            if e >= size:
                raise ArithmeticError(f"basis function {row} has degree {e} > {degree}")
            mats[p][row][e] = to_fraction(c)
    return tuple(tuple(tuple(r) for r in mat) for mat in mats)


def bernstein_matrices(polys: list[sp.Poly], degree: int) -> tuple[Matrix, ...]:
    """M_p[i][j] = coefficient of lam^p B_j^degree in basis function i."""
    conv = power_to_bernstein_matrix(degree)
    return tuple(
        tuple(
            tuple(
                sum((row[e] * conv[e][jj] for e in range(degree + 1)), Fraction(0))
                for jj in range(degree + 1)
            )
            for row in mat
        )
        for mat in power_matrices(polys, degree)
    )


def endpoint_table(polys: list[sp.Poly], orders: int) -> dict[tuple[str, int, int], sp.Expr]:
    """Per-degree derivatives d^r b_i/dt^r at t=0 and t=1 (nonzero ones), as polynomials in λ.
    Used to check the general-n closed forms for every degree of the range."""
    out = {}
    for idx, p in enumerate(polys):
        d = p
        for r in range(orders + 1):
            for end, at in (("start", 0), ("end", 1)):
                val = d.eval(t, at)
                if not val.is_zero:
                    out[(end, r, idx)] = val.as_expr()
            d = d.diff(t)
    return out


def bernstein_terms(expr: sp.Expr, degree: sp.Expr) -> dict[sp.Expr, sp.Expr]:
    """Read a sum of terms c · t^a (1-t)^b with a + b = degree as Σ coeff_a B_a^degree.

    Works with symbolic exponents: products are distributed without expanding the powers,
    exponents are combined, and each coefficient is divided by C(degree, a) and simplified.
    Returns {a: coefficient of B_a^degree}.
    """
    s = sp.Dummy("s")  # stands for 1 - t, so that distributing never expands it
    expr = sp.expand(expr.subs(1 - t, s), power_exp=False, power_base=False, log=False)
    out: dict[sp.Expr, sp.Expr] = {}
    for term in sp.Add.make_args(expr):
        coeff, rest = term.as_independent(t, s)
        powers = dict(sp.powsimp(rest).as_powers_dict())
        a = powers.pop(t, sp.Integer(0))
        b = powers.pop(s, sp.Integer(0))
        if any(e != 0 for e in powers.values()) or sp.simplify(a + b - degree) != 0:
            raise ArithmeticError(f"term {term} is not a multiple of a degree-{degree} Bernstein")
        out[a] = out.get(a, 0) + coeff / sp.binomial(degree, a)
    return {a: sp.factor(sp.combsimp(c)) for a, c in out.items()}


CENTRE = Fraction(1, 2)


def centred_row(row: tuple[Fraction, ...], centre: Fraction = CENTRE) -> tuple[Fraction, ...]:
    """Taylor coefficients about `centre`: Σ a_q t^q = Σ c_e (t - centre)^e, exactly.
    (Horner on these is as accurate as de Casteljau on [0, 1]; at 0 it is not.)"""
    size = len(row)
    return tuple(
        sum((row[q] * sp.binomial(q, e) * centre ** (q - e) for q in range(e, size)), Fraction(0))
        for e in range(size)
    )


def centred_matrices(mats: tuple[Matrix, ...]) -> tuple[Matrix, ...]:
    return tuple(tuple(centred_row(row) for row in mat) for mat in mats)
