"""Energies E_k(λ) = ∫_0^1 |p^(k)(t)|² dt as quadratics in λ (000, section 3), for both families.

From the basis only: a curve of either family is p = Σ_j (Q_j − λ W_j) B_j^N with
Q = M_0ᵀ D and W = −M_1ᵀ D, where M(λ) = M_0 + λ M_1 is the family's Bernstein matrix
(derived by the family's derivation module) and D = (P_0 … P_n)ᵀ. With f = Σ Q_j B_j,
g = Σ W_j B_j (eq. 19), E_k = ∫f⁽ᵏ⁾·f⁽ᵏ⁾ − 2λ ∫f⁽ᵏ⁾·g⁽ᵏ⁾ + λ² ∫g⁽ᵏ⁾·g⁽ᵏ⁾, and each integral is a
quadratic form Dᵀ S D with S = M K Mᵀ, K = Hᵀ G H: H the k-fold hodograph matrix and G the
Gram matrix ∫B_a^m B_b^m of the Bernstein basis of degree m = N − k.

The Gram matrix comes from exact Bernstein algebra, derived once symbolically here:
B_a^m B_b^m = ρ(m, a, b) B_{a+b}^{2m} with ρ constant in t, and ∫_0^1 B_c^N = 1/(N + 1).
No polynomial is ever integrated numerically or expanded for integration.

Published normalisation (eq. 20 and the X_n^k, Y_n^k that follow it): λ* = c · DᵀXD / DᵀYD
with X, Y upper-triangular primitive integer matrices (off-diagonal entries doubled from the
symmetric form), the first nonzero diagonal entry positive, and c a rational scale.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cache, reduce
from math import comb, gcd, lcm

import flint
import sympy as sp

from ..algebra import Matrix, bernstein_matrices, t, to_flint, to_fraction
from ..algebra.bernstein import bernstein_basis, hodograph_matrix
from ..families.registry import builtin_families

ORDERS = (1, 2, 3)
# the built-in families' derivation modules, in their order (derive/families/*.toml)
FAMILIES = {b.name: b.module() for b in builtin_families()}
# Families defined by data (derive/families/engine.py), for verify's energy checks: not emitted.
EXTRA: dict = {}
GRAM_DEGREES = range(0, 15)

_m, _a, _b, _c, _N = sp.symbols("m a b c N", integer=True, nonnegative=True)


@cache
def bernstein_identities() -> tuple[sp.Expr, sp.Expr]:
    """(ρ(m, a, b), ∫_0^1 B_c^N dt), derived symbolically from the Bernstein definition."""
    rho = sp.combsimp(
        sp.powsimp(
            bernstein_basis(_m, _a) * bernstein_basis(_m, _b) / bernstein_basis(2 * _m, _a + _b)
        )
    )
    if rho.has(t):
        raise AssertionError("product of Bernstein polynomials is not a Bernstein multiple")
    # ∫_0^1 t^c (1-t)^(N-c) dt is Euler's Beta function B(c+1, N-c+1) (SymPy's beta is
    # defined by that integral); the rest is simplification.
    integral = sp.combsimp(sp.binomial(_N, _c) * sp.beta(_c + 1, _N - _c + 1).rewrite(sp.gamma))
    if integral.has(_c):
        raise AssertionError(f"integral of B_c^N should not depend on c: {integral}")
    return rho, integral


def _exact_binomial(a, b):
    a, b = int(a), int(b)
    return Fraction(comb(a, b)) if 0 <= b <= a else Fraction(0)  # math.comb: exact, no SymPy


@cache
def _rho_function():
    rho, _ = bernstein_identities()
    return sp.lambdify((_m, _a, _b), rho, modules=[{"binomial": _exact_binomial}])


@cache
def gram(m: int) -> Matrix:
    """G[a][b] = ∫_0^1 B_a^m B_b^m dt, exact."""
    _, integral = bernstein_identities()
    rho_f = _rho_function()
    scale = to_fraction(integral.subs(_N, 2 * m))
    return tuple(
        tuple(Fraction(rho_f(m, a, b)) * scale for b in range(m + 1)) for a in range(m + 1)
    )


@cache
def stiffness(degree: int, k: int) -> flint.fmpq_mat:
    """K with ∫|p^(k)|² = Σ_coords cᵀ K c for Bézier control points c of degree `degree`
    (a FLINT matrix: energy_forms multiplies it on both sides). For k > degree the k-th
    derivative vanishes identically, so K = 0: E_k ≡ 0 is a result, and there is no hodograph
    of negative degree to build."""
    if k > degree:
        return flint.fmpq_mat(degree + 1, degree + 1)
    h = flint.fmpq_mat(degree + 1, degree + 1)
    for r in range(degree + 1):
        h[r, r] = 1
    for d in range(degree, degree - k, -1):
        h = to_flint(hodograph_matrix(d)) * h
    return h.transpose() * to_flint(gram(degree - k)) * h


def upper_form(sym) -> tuple[Fraction, tuple[tuple[int, ...], ...]]:
    """A symmetric quadratic form (rows of exact rationals: Fraction or FLINT fmpq) as
    scale · U, U upper-triangular primitive integers (U_ii = S_ii, U_ij = 2 S_ij for i < j),
    first nonzero diagonal entry positive."""
    size = len(sym)
    upper = [
        [sym[r][c] * (2 if c > r else 1) if c >= r else 0 for c in range(size)] for r in range(size)
    ]
    denom = reduce(lcm, (int(v.denominator) for row in upper for v in row), 1)
    ints = [[int(v.numerator) * (denom // int(v.denominator)) for v in row] for row in upper]
    numer = reduce(gcd, (x for row in ints for x in row), 0)
    if numer == 0:
        return Fraction(0), tuple(tuple(0 for _ in range(size)) for _ in range(size))
    entries = [x for row in ints for x in row if x != 0]
    lead = next((ints[r][r] for r in range(size) if ints[r][r] != 0), entries[0])
    sign = -1 if lead < 0 else 1
    return Fraction(sign * numer, denom), tuple(
        tuple(sign * x // numer for x in row) for row in ints
    )


@cache
def energy_forms(family: str, n: int, k: int) -> dict[str, tuple[Fraction, tuple]]:
    """{"ff", "fg", "gg"}: (scale, U) with ∫f⁽ᵏ⁾·f⁽ᵏ⁾ = scale·DᵀUD etc. (see module doc)."""
    module = FAMILIES[family] if family in FAMILIES else EXTRA[family]
    return forms_from_polys(list(module.basis_polys(n)), n + module.DEGREE_OFFSET, k)


def forms_from_polys(polys, big: int, k: int) -> dict[str, tuple[Fraction, tuple]]:
    """energy_forms of any basis linear in λ (polynomials of degree `big` in t)."""
    m0, m1 = (to_flint(mat) for mat in bernstein_matrices(polys, big))
    kk = stiffness(big, k)
    w = -m1  # W = −M_1ᵀ D
    fg = m0 * kk * w.transpose()
    return {
        "ff": upper_form((m0 * kk * m0.transpose()).table()),
        "fg": upper_form(((fg + fg.transpose()) / 2).table()),
        "gg": upper_form((w * kk * w.transpose()).table()),
    }


def published_form(family: str, n: int, k: int) -> tuple[Fraction, tuple, tuple]:
    """(c, X, Y) with λ* = c · DᵀXD / DᵀYD (eq. 20 in the paper's normalisation)."""
    forms = energy_forms(family, n, k)
    (s_fg, x), (s_gg, y) = forms["fg"], forms["gg"]
    if s_gg == 0:
        raise ZeroDivisionError(f"λ has no effect on E_{k} for {family} of degree {n}")
    return s_fg / s_gg, x, y


def _quadratic(u, points) -> Fraction:
    size = len(u)
    return sum(
        (
            u[r][c]
            * sum(
                (Fraction(a) * Fraction(b) for a, b in zip(points[r], points[c], strict=True)),
                Fraction(0),
            )
            for r in range(size)
            for c in range(r, size)
        ),
        Fraction(0),
    )


def optimal_lambda_exact(points, k: int, family: str) -> Fraction:
    """λ* for exact control points, from the derived forms (used by verify's worked example)."""
    c, x, y = published_form(family, len(points) - 1, k)
    return c * _quadratic(x, points) / _quadratic(y, points)
