"""G1 between two patches in general: their tangent planes agree along the common boundary.

With A's cross derivative a(v) = A_u(1, v), its boundary tangent b(v) = A_v(1, v) and B's
cross derivative c(v) = B_u(0, v), the patches meet G1 (geometric continuity of order 1: B
reparametrised near the boundary continues A to first order) exactly when, for every v,

    c = μ a + ν b   with   μ(v) > 0,

μ and ν free functions of v. The constant-factor join of `join_surface` (c = a / α) and its
linear factor (c = μ(v) a) are the cases ν = 0. Written without dividing:

- c lies in the span of a and b: every 3 x 3 minor of the d x 3 matrix [a b c] is zero
  (in d = 2 there is none: any regular join in the plane continues its tangent plane);
- μ > 0: μ · |a ∧ b|² = (c·a)(b·b) − (c·b)(a·b) =: N(v), so N > 0 on the boundary. N > 0
  also shows a and b independent (N = 0 where b ∥ a), so A is regular there, and then
  B_u ∧ B_v = μ a ∧ b: B is regular too and on the other side of the boundary (no fold).

For exact patches a, b and c are polynomials (their Bernstein coefficients along the boundary
given as Fractions): the minors must vanish identically and N be positive on [0, 1], which
Sturm's theorem decides (`span_exact`). For float patches, and for patches of trigonometric
or hyperbolic families, the two conditions are checked at sample points within a tolerance
(`span_sampled`): a sampled verdict.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from itertools import combinations
from math import comb
from typing import Any

import numpy as np

from .hazmat import exact_poly as ep

Point = Sequence[Any]


def _power_form(points: Sequence[Point]) -> list[list[Fraction]]:
    """Per coordinate, the power-basis coefficients in t of Σ P_i C(n, i) t^i (1 − t)^(n − i)."""
    n = len(points) - 1
    out: list[list[Fraction]] = []
    for c in range(len(points[0])):
        total: list[Fraction] = []
        for i, p in enumerate(points):
            term = [Fraction(comb(n, i)) * Fraction(p[c])]
            for _ in range(i):
                term = ep.multiply(term, [Fraction(0), Fraction(1)])
            for _ in range(n - i):
                term = ep.multiply(term, [Fraction(1), Fraction(-1)])
            total = _add(total, term)
        out.append(ep.trim(total))
    return out


def _add(p: Sequence[Fraction], q: Sequence[Fraction], sign: int = 1) -> list[Fraction]:
    size = max(len(p), len(q))
    zero = Fraction(0)
    return ep.trim(
        [
            (p[k] if k < len(p) else zero) + sign * (q[k] if k < len(q) else zero)
            for k in range(size)
        ]
    )


def _dot(x: list[list[Fraction]], y: list[list[Fraction]]) -> list[Fraction]:
    total: list[Fraction] = []
    for p, q in zip(x, y, strict=True):
        total = _add(total, ep.multiply(p, q))
    return total


def _minor(x: list[list[Fraction]], y: list[list[Fraction]], z: list[list[Fraction]]) -> bool:
    """Whether every 3 x 3 minor of [x y z] (columns of polynomials) is the zero polynomial."""
    m = ep.multiply
    for i, j, k in combinations(range(len(x)), 3):
        det = _add(
            _add(
                m(x[i], _add(m(y[j], z[k]), m(y[k], z[j]), -1)),
                m(x[j], _add(m(y[i], z[k]), m(y[k], z[i]), -1)),
                -1,
            ),
            m(x[k], _add(m(y[i], z[j]), m(y[j], z[i]), -1)),
        )
        if det:
            return False
    return True


def span_exact(a: Sequence[Point], b: Sequence[Point], c: Sequence[Point]) -> bool:
    """G1 along an exact boundary: a, b, c the Bernstein coefficients (Fractions) in v of A_u,
    A_v and B_u there (any degrees). Exact: the minors vanish, N > 0 on [0, 1] (Sturm)."""
    if len(a[0]) < 2:
        return False  # d = 1: no tangent plane (N is identically zero)
    x, y, z = _power_form(a), _power_form(b), _power_form(c)
    if not _minor(x, y, z):
        return False
    num = _add(ep.multiply(_dot(z, x), _dot(y, y)), ep.multiply(_dot(z, y), _dot(x, y)), -1)
    if not num or ep.evaluate(num, Fraction(0)) <= 0:
        return False
    return not ep.real_roots(num, Fraction(0), Fraction(1))


def span_sampled(a: np.ndarray, b: np.ndarray, c: np.ndarray, eps: float) -> bool:
    """G1 at sample points along the boundary: a, b, c arrays (k, d) of A_u, A_v and B_u
    there. c's distance from the plane of a and b must be within `eps` (the report's
    tolerance on a first derivative) and μ > 0 clear of that tolerance."""
    if a.shape[1] < 2:
        return False
    aa, bb, ab = (a * a).sum(1), (b * b).sum(1), (a * b).sum(1)
    ca, cb = (c * a).sum(1), (c * b).sum(1)
    area2 = aa * bb - ab * ab  # |a ∧ b|²
    if not np.all(area2 > 0):
        return False
    mu = (ca * bb - cb * ab) / area2
    nu = (cb * aa - ca * ab) / area2
    residual = c - mu[:, None] * a - nu[:, None] * b  # c less its projection on the plane
    return bool(
        np.all(np.sqrt((residual * residual).sum(1)) <= eps)
        and np.all(mu * np.sqrt(aa) > eps)
        and np.all(np.isfinite(mu))
    )
