"""Classical Bézier forms at any degree: hodograph, elevation, segments by blossoming.

The formulas hold at every degree, so a classical curve of any degree works (generated/
bernstein.py tabulates degrees 1..14, derived symbolically; tests check that the two agree
where both exist). Each works in the arithmetic of its input: Fractions stay exact.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from functools import cache
from math import comb

import numpy as np

from .kernels import Scalar

Rows = tuple[tuple[Fraction | float, ...], ...]  # exact (Fractions) or float rows


@cache
def hodograph_matrix(degree: int) -> tuple[tuple[Fraction, ...], ...]:
    """(n, n+1) weights of p' = n Σ (P_{i+1} - P_i) B_{i,n-1} (equal to generated/bernstein.py's
    HODOGRAPH where that exists: a test checks). Degree 0 has a zero derivative: one zero row."""
    if degree == 0:
        return ((Fraction(0),),)
    return tuple(
        tuple(
            Fraction(degree) * ((c == r + 1) - (c == r))  # n (P_{r+1} - P_r)
            for c in range(degree + 1)
        )
        for r in range(degree)
    )


@cache
def centred_matrix(degree: int) -> tuple[tuple[Fraction, ...], ...]:
    """(n+1, n+1): row i holds the Taylor coefficients of B_i^n about t = 1/2, exactly, at
    any degree (equal to generated/bernstein.py's CENTRED where that exists: a test checks)."""
    return centred_expansion(degree)


def centred_expansion(degree: int) -> tuple[tuple[Fraction, ...], ...]:
    """centred_matrix computed: with u = t - 1/2, B_i^n = C(n, i) (1/2 + u)^i (1/2 - u)^(n-i),
    a product of two binomial expansions."""
    half = Fraction(1, 2)
    rows = []
    for i in range(degree + 1):
        rise = [comb(i, e) * half ** (i - e) for e in range(i + 1)]  # (1/2 + u)^i
        fall = [
            comb(degree - i, e) * half ** (degree - i - e) * (-1) ** e
            for e in range(degree - i + 1)
        ]  # (1/2 - u)^(n-i)
        row = [Fraction(0)] * (degree + 1)
        for a, x in enumerate(rise):
            for b, y in enumerate(fall):
                row[a + b] += comb(degree, i) * x * y
        rows.append(tuple(row))
    return tuple(rows)


def basis_matrix(kind: str, degree: int) -> tuple[tuple[Fraction, ...], ...]:
    """The classical basis's table of `kind` ("power", "centred" or "bernstein") at any
    degree: row i holds B_i^n's coefficients (power: C(n, i) C(n − i, k − i) (−1)^(k − i) for
    t^k; centred: centred_matrix; bernstein: the identity)."""
    if kind == "centred":
        return centred_matrix(degree)
    if kind == "bernstein":
        return tuple(
            tuple(Fraction(int(r == c)) for c in range(degree + 1)) for r in range(degree + 1)
        )
    if kind != "power":
        raise ValueError(f"no basis table of kind {kind!r}")
    return tuple(
        tuple(
            Fraction(comb(degree, i) * comb(degree - i, k - i) * (-1) ** (k - i))
            if k >= i
            else Fraction(0)
            for k in range(degree + 1)
        )
        for i in range(degree + 1)
    )


def gram_form(degree: int) -> tuple[Fraction, tuple[tuple[Fraction, ...], ...]]:
    """(s, U) as generated/energy.py's GRAM[m] (∫_0^1 B_a^m B_b^m dt = s·U[a][b] for a = b,
    s·U[a][b]/2 for a < b), computed for a degree past that table:
    ∫ B_a^m B_b^m = C(m, a) C(m, b) / (C(2m, a + b) (2m + 1)), from B_a^m B_b^m =
    C(m, a) C(m, b) / C(2m, a + b) · B_{a+b}^{2m} and ∫ B_c^N = 1 / (N + 1)."""
    m = degree
    return Fraction(1), tuple(
        tuple(
            Fraction(
                comb(m, a) * comb(m, b) * (2 if b > a else 1), comb(2 * m, a + b) * (2 * m + 1)
            )
            if b >= a
            else Fraction(0)
            for b in range(m + 1)
        )
        for a in range(m + 1)
    )


@cache
def elevation_matrix(degree: int) -> tuple[tuple[Fraction, ...], ...]:
    """(n+2, n+1) weights of one degree elevation, Q_i = i/(n+1) P_{i-1} + (1 - i/(n+1)) P_i:
    equal to generated/bernstein.py's ELEVATION where that exists (a test checks)."""
    top = degree + 1
    return tuple(
        tuple(
            Fraction(i, top) if c == i - 1 else (1 - Fraction(i, top)) if c == i else Fraction(0)
            for c in range(degree + 1)
        )
        for i in range(degree + 2)
    )


def blossom(points: Sequence[Sequence[Scalar]], params: Sequence[Scalar]) -> tuple[Scalar, ...]:
    """The polar form b[u_1, …, u_n] of the curve: de Casteljau with a different parameter
    at each level (u_i = t for all i gives p(t))."""
    work = [tuple(p) for p in points]
    for u in params:
        work = [
            tuple((1 - u) * a + u * b for a, b in zip(p, q, strict=True))
            for p, q in zip(work[:-1], work[1:], strict=True)
        ]
    return work[0]


def segment_rows(
    points: Sequence[Sequence[Scalar]], t1: Scalar, t2: Scalar
) -> list[tuple[Scalar, ...]]:
    """Control points of the piece over [t1, t2] reparametrised to [0, 1], for any t1, t2
    (outside [0, 1] too): Q_k = b[t1^(n-k), t2^k] (blossoming)."""
    n = len(points) - 1
    return [blossom(points, [t1] * (n - k) + [t2] * k) for k in range(n + 1)]


def as_float_rows(rows: Rows) -> np.ndarray:
    return np.array([[float(v) for v in row] for row in rows], dtype=float)
