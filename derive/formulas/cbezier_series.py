"""The basis of a C-Bezier family near alpha = 0 as an exact series in alpha (what the runtime
evaluates below a threshold instead of the atoms; lambda_bezier.cbezier_family).

Why: over the atoms (1, t, cos t, sin t, ...) the coefficients of b_i are quotients whose
numerators and denominators vanish like alpha^3 and higher at 0 (alpha - sin(alpha) ~
alpha^3/6), and the atoms' sum cancels to O(1) from terms of size alpha^-e: in floats the
relative error grows like 2^-53 alpha^-e (measured: 1e-12 at alpha = 0.5, 1e-7 at 0.1 for the
cubic), although the limit alpha -> 0 is removable (the Bezier cubic).

How: in u = t/alpha on [0, 1], b_i(alpha u; alpha) = N_i(alpha, u) / D_i(alpha) with N_i, D_i
entire; both are expanded exactly about alpha = 0 (cbezier_nonnegative's series: sin 0 and
cos 0 are exact, so nothing is rounded), their common order e at 0 is divided out exactly,
and the quotient is the power series sum_k alpha^k p_ik(u) with p_ik polynomials in u with
rational coefficients, by exact series division. p_i0 is the limit of the basis as
alpha -> 0 (for Zhang's cubic, the Bernstein cubic).

Truncation (measured, not proved): the series is emitted to the least even order K at which
every omitted order k in (K, K + LOOKAHEAD] has sum_j |p_ikj| * below^k < 2^-60 at the
threshold `below`; the largest such omitted term is reported as `omitted_at_threshold`. The
series converge geometrically (radius 2 pi for the cubics: the nearest complex zero of a
denominator), so the omitted tail is of the size of its first terms; the runtime's tests
compare with 40-digit mpmath over (0, below].
"""

from __future__ import annotations

from fractions import Fraction

import flint
import sympy as sp

from ..families import cbezier as cb
from ..families.cbezier import CDefinition
from .cbezier_nonnegative import _numerators, _series

BELOW = Fraction(3, 2)  # the threshold, chosen by measurement (module docstring, own-family.md)
TARGET = Fraction(1, 2**60)
LOOKAHEAD = 8
MAX_ORDER = 120


def _size(row: flint.fmpq_poly, x: Fraction, k: int) -> Fraction:
    """sum_j |p_kj| x^k: a bound of |alpha^k p_k(u)| for u in [0, 1] and alpha <= x."""
    total = sum((abs(Fraction(int(c.p), int(c.q))) for c in row.coeffs()), Fraction(0))
    return total * x**k


def _order_at_0(den: sp.Expr, hyperbolic: bool) -> int:
    """The order of the zero of a denominator at alpha = 0, exactly."""
    dn = _series({(cb.POW, 0): den}, 32, hyperbolic)
    e = next((k for k, r in enumerate(dn) if not r.is_zero()), None)
    if e is None:
        raise ArithmeticError("a denominator that vanishes to order > 32 at alpha = 0")
    return e


def _quotient(nums: dict, den: sp.Expr, order: int, hyperbolic: bool) -> list[flint.fmpq_poly]:
    """sum_k alpha^k p_k(u) = N / D to alpha^order, exactly (N, D vanish to the same order)."""
    e = _order_at_0(den, hyperbolic)
    dn = _series({(cb.POW, 0): den}, order + e, hyperbolic)
    nn = _series(nums, order + e, hyperbolic)
    if any(not r.is_zero() for r in nn[:e]):
        raise ArithmeticError("a basis function unbounded as alpha -> 0")
    d = [r.coeffs()[0] if not r.is_zero() else flint.fmpq(0) for r in dn[e:]]
    n = nn[e:]
    out: list[flint.fmpq_poly] = []
    for k in range(order + 1):
        acc = n[k]
        for m in range(1, k + 1):
            if d[m] != 0:
                acc = acc - out[k - m] * d[m]
        out.append(acc / d[0])
    return out


def small_alpha(defn: CDefinition) -> dict | None:
    """{"below", "below_float", "order", "omitted_at_threshold", "series"}: series[i] is a
    list of [k, [p_ik0, p_ik1, ...]] (rationals as text, u^j ascending) for the orders k with
    p_ik != 0; or None when nothing cancels: the range starts at or above the threshold, or
    no denominator vanishes to order 2 or more at 0 (a simple pole, such as 1/sinh(alpha) in
    sinh(alpha - t)/sinh(alpha), leaves the atoms' sum of the size of its terms)."""
    if defn.lo != 0 and sp.Rational(defn.lo) >= sp.Rational(BELOW.numerator, BELOW.denominator):
        return None
    parts = [_numerators(elem) for elem in defn.elems()]
    if max(_order_at_0(den, defn.hyperbolic) for _, den in parts) < 2:
        return None
    order = 8
    while True:
        rows = [_quotient(nums, den, order + LOOKAHEAD, defn.hyperbolic) for nums, den in parts]
        omitted = max(
            _size(r[k], BELOW, k) for r in rows for k in range(order + 1, order + LOOKAHEAD + 1)
        )
        if omitted < TARGET:
            break
        order += 2
        if order > MAX_ORDER:
            raise ArithmeticError(
                f"the series in {defn.parameter} about 0 does not reach 2^-60 at {BELOW} "
                f"within order {MAX_ORDER}"
            )
    series = [
        [
            [k, [str(Fraction(int(c.p), int(c.q))) for c in r[k].coeffs()]]
            for k in range(order + 1)
            if not r[k].is_zero()
        ]
        for r in rows
    ]
    return {
        "below": str(BELOW),
        "below_float": float(BELOW),
        "order": order,
        "omitted_at_threshold": float(omitted),
        "series": series,
    }
