"""Classical Bézier forms at any degree: hodograph, elevation, segments by blossoming.

The formulas hold at every degree, so a classical curve of any degree works (generated/
bernstein.py tabulates degrees 1..14, derived symbolically; tests check that the two agree
where both exist). Each works in the arithmetic of its input: Fractions stay exact.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from functools import cache

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
