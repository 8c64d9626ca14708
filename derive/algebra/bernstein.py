"""Classical Bézier toolkit (lecture notes 002_b1311022d66a73a0.txt).

Axioms:
  * the Bernstein basis  B_{j,N}(t) = C(N, j) t^j (1 - t)^(N - j);
  * Bézier's original form p(t) = Σ a_i f_i(t), where the a_i are *relative* vectors,
    b_0 = a_0 and b_j = b_{j-1} + a_j (Forrest's change to absolute vertices).
Derived here: power-basis matrices, the hodograph (derivative) and degree-elevation matrices,
f_i in the power basis, and the k-th derivative at either end for every order, in closed form.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cache
from math import comb

import flint
import sympy as sp

from .core import (
    Matrix,
    centred_matrices,
    exact_function,
    from_flint,
    i,
    k,
    lam,
    matmul,
    n,
    power_matrices,
    t,
    to_flint,
    transpose,
)

X = sp.Poly(t, t, lam, domain="QQ")


def _fmpq(v: int | Fraction) -> flint.fmpq:
    v = Fraction(v)
    return flint.fmpq(
        v.numerator, v.denominator
    )  # evaluating the axioms at X gives them as polynomials


def bernstein_basis(degree, index, x=t):
    """The axiom: B_{index,degree}(x). Zero outside 0 <= index <= degree."""
    if isinstance(degree, int) and isinstance(index, int) and not 0 <= index <= degree:
        return sp.Integer(0)
    return sp.binomial(degree, index) * x**index * (1 - x) ** (degree - index)


@cache
def bernstein_poly(degree: int, index: int) -> sp.Poly:
    """The axiom evaluated in polynomial arithmetic (cached: every table below reuses it):
    C(degree, index) t^index (1 - t)^(degree - index) multiplied out in FLINT, then one
    SymPy Poly (the same Poly as SymPy's own arithmetic on X gives, a fifth of the time)."""
    if not 0 <= index <= degree:
        return bernstein_basis(degree, index, X)
    one_minus_t = flint.fmpz_poly([1, -1])
    product = (
        comb(degree, index) * flint.fmpz_poly([0, 1]) ** index * one_minus_t ** (degree - index)
    )
    terms = {(e, 0): int(c) for e, c in enumerate(product.coeffs()) if c}
    return sp.Poly.from_dict(terms, t, lam, domain="QQ")


def original_basis(degree: int, index: int, x=t):
    """f_i from the axiom p = Σ a_i f_i = Σ b_j B_j with b_j = Σ_{i<=j} a_i:
    collecting a_i gives f_i = Σ_{j>=i} B_j."""
    if x is X:
        terms = [bernstein_poly(degree, jj) for jj in range(index, degree + 1)]
    else:
        terms = [bernstein_basis(degree, jj, x) for jj in range(index, degree + 1)]
    return sum(terms[1:], terms[0])


def _in_bernstein(polys: list[sp.Poly], degree: int) -> Matrix:
    """Row r: the Bernstein coefficients (degree `degree`) of polys[r]."""
    return matmul(power_matrices(polys, degree)[0], power_to_bernstein_matrix(degree))


@cache
def hodograph_matrix(degree: int) -> Matrix:
    """H[j][i]: weight of control point P_i in control point j of the derivative curve
    (degree - 1), from differentiating each B_i and re-expanding in degree - 1."""
    derivatives = [bernstein_poly(degree, ii).diff(t) for ii in range(degree + 1)]
    return transpose(_in_bernstein(derivatives, degree - 1))


@cache
def elevation_matrix(degree: int) -> Matrix:
    """E[j][i]: weight of P_i in control point j of the same curve written in degree + 1."""
    polys = [bernstein_poly(degree, ii) for ii in range(degree + 1)]
    return transpose(_in_bernstein(polys, degree + 1))


def original_power_matrix(degree: int) -> Matrix:
    return power_matrices([original_basis(degree, ii, X) for ii in range(degree + 1)], degree)[0]


@cache
def endpoint_weights() -> tuple[sp.Expr, sp.Expr]:
    """Weights w_i with p^(k)(0) = Σ_{i=0}^k w_i P_i and p^(k)(1) = Σ_{i=0}^k w'_i P_{n-i}.

    At t = 0 only B_i with i <= k survive k differentiations. Leibniz on t^i · g(t),
    g = C(n,i)(1-t)^(n-i): the only term nonzero at 0 differentiates t^i exactly i times,
    giving C(k,i) i! g^(k-i)(0), and g^(r)(0) = C(n,i) (-1)^r (n-i)(n-i-1)…(n-i-r+1).
    At t = 1 the same computation in s = 1 - t (B_{n-i,n}(t) = C(n,i) s^i (1-s)^(n-i)) picks
    up (-1)^k from d/dt = -d/ds.
    """
    leibniz = (
        sp.binomial(k, i)
        * sp.factorial(i)
        * sp.binomial(n, i)
        * (-1) ** (k - i)
        * sp.ff(n - i, k - i)
    )
    start = sp.combsimp(leibniz)
    # (-1)^(k-i) = (-1)^(-i-k) for integer k, so the signs combine to (-1)^(-i) (what simplify
    # finds, without importing sympy.physics, which simplify does on first use: 0.45 s)
    end = sp.combsimp(((-1) ** k * leibniz).subs((-1) ** (k - i), (-1) ** (-i - k)))
    return start, end


@cache
def closed_end_forms() -> dict[tuple[str, int, int], sp.Expr]:
    """{(end, r, idx): the r-th derivative of B_idx (start) or B_{n-idx} (end) at the end},
    orders 0..2 in closed form in n: every derivation module's end forms, in one shape."""
    start, end = endpoint_weights()
    out = {}
    for r in range(3):
        for idx in range(r + 1):
            out[("start", r, idx)] = start.subs({k: r, i: idx})
            out[("end", r, idx)] = end.subs({k: r, i: idx})
    return out


@cache
def endpoint_weight(end: str, order: int, index: int) -> sp.Expr:
    """The weight of endpoint_weights() at a concrete order and index (0 <= index <= order):
    a polynomial in n (the factorial ratio n!/(n - order)! cancelled)."""
    w_start, w_end = endpoint_weights()
    w = w_start if end == "start" else w_end
    return sp.expand(sp.combsimp(w.subs({i: index, k: order})))


def check_endpoint_weights(start: sp.Expr, end: sp.Expr, degrees: range) -> None:
    """The closed forms agree with differentiating every B_{i,N} for every N in `degrees`."""
    # exact rationals throughout, in C: the polynomials in FLINT, the closed forms compiled
    # to Fraction arithmetic (SymPy's Poly and Integer arithmetic here were a twentieth of
    # `derive --check`, issue #29)
    w_start = exact_function(start, (n, k, i))
    w_end = exact_function(end, (n, k, i))
    one_minus_t = flint.fmpq_poly([1, -1])
    t_ = flint.fmpq_poly([0, 1])
    for deg in degrees:
        for ii in range(deg + 1):
            p0 = comb(deg, ii) * t_**ii * one_minus_t ** (deg - ii)
            p1 = comb(deg, deg - ii) * t_ ** (deg - ii) * one_minus_t**ii
            for order in range(deg + 1):
                got0, got1 = p0(0), p1(1)
                want0 = w_start(deg, order, ii) if ii <= order else 0
                want1 = w_end(deg, order, ii) if ii <= order else 0
                if got0 != _fmpq(want0) or got1 != _fmpq(want1):
                    raise AssertionError(f"endpoint weights disagree at N={deg} k={order} i={ii}")
                p0, p1 = p0.derivative(), p1.derivative()


@cache
def bernstein_power_matrix(degree: int) -> Matrix:
    """Row j: power coefficients of B_j^degree."""
    return power_matrices([bernstein_poly(degree, jj) for jj in range(degree + 1)], degree)[0]


@cache
def power_to_bernstein_matrix(degree: int) -> Matrix:
    """Inverse of bernstein_power_matrix: row e gives t^e in the Bernstein basis (exact;
    a maps Bernstein to power coefficients row by row, so power to Bernstein is a^{-1})."""
    return from_flint(to_flint(bernstein_power_matrix(degree)).inv())


def bernstein_matrices(polys: list[sp.Poly], degree: int) -> tuple[Matrix, ...]:
    """M_p[i][j] = coefficient of lam^p B_j^degree in basis function i."""
    return _bernstein_matrices(tuple(polys), degree)


@cache
def _bernstein_matrices(polys: tuple[sp.Poly, ...], degree: int) -> tuple[Matrix, ...]:
    # keyed by the polynomials themselves: the family tables, the energies (three orders k),
    # the properties and the families' own checks all ask for the same ones (issue #29)
    conv = power_to_bernstein_matrix(degree)
    return tuple(matmul(mat, conv) for mat in power_matrices(list(polys), degree))


def expansion_tables(basis_polys, degrees, offset: int) -> dict[str, dict[int, tuple]]:
    """The per-degree tables every family emits: power, centred and Bernstein coefficients
    (split by powers of λ) of the basis functions of each degree n, in degree n + offset."""
    power = {d: power_matrices(list(basis_polys(d)), d + offset) for d in degrees}
    return {
        "power": power,
        "centred": {d: centred_matrices(m) for d, m in power.items()},
        "bernstein": {d: bernstein_matrices(list(basis_polys(d)), d + offset) for d in degrees},
    }
