"""Degree reduction of classical Bézier curves: the inverse of degree elevation.

A degree-n curve is a degree elevation of a degree n-1 curve exactly when its control points
P satisfy P = E Q for the (n+1, n) elevation matrix E. With exact (Fraction) points that is
decided exactly: Q is solved from the first n rows (E is lower bidiagonal) and the last row
checked. Otherwise Q is the least-squares solution of E Q = P, and its error is the largest
distance |P_i - (E Q)_i|: by the convex hull property it bounds the distance between the
curve and the reduced one at every t.
"""

from __future__ import annotations

from fractions import Fraction
from typing import NamedTuple

import numpy as np

from . import forms
from . import kernels as alg

Rows = tuple[tuple[Fraction, ...], ...]  # exact control points


class Reduction(NamedTuple):
    """points: the reduced control points (Fractions when exact); error: max_i |P_i - (EQ)_i|,
    a bound on the distance between the curves (0 when the curve is an elevation)."""

    points: Rows | np.ndarray
    error: float
    exact: bool


def reduce_exact(rows: Rows) -> Rows | None:
    """Q with E Q = P exactly, or None when P is not a degree elevation."""
    n = len(rows) - 1  # E is (n+1, n): elevation from degree n-1
    if n < 1:
        raise ValueError("a degree-0 curve (a point) cannot be reduced")
    q: list[tuple[Fraction, ...]] = [tuple(rows[0])]
    for i in range(1, n):
        w = Fraction(i, n)
        q.append(tuple((p - w * a) / (1 - w) for p, a in zip(rows[i], q[-1], strict=True)))
    elevated = alg.exact_matmul(forms.elevation_matrix(n - 1), tuple(q))
    return tuple(q) if elevated == tuple(tuple(r) for r in rows) else None


def reduce_least_squares(points: np.ndarray) -> tuple[np.ndarray, float]:
    n = points.shape[0] - 1
    if n < 1:
        raise ValueError("a degree-0 curve (a point) cannot be reduced")
    e = np.array(forms.elevation_matrix(n - 1), dtype=float)
    q = np.linalg.lstsq(e, points, rcond=None)[0]
    error = float(np.linalg.norm(e @ q - points, axis=1).max())
    return q, error


def reduce(points: np.ndarray, rows: Rows | None) -> Reduction:
    if rows is not None:
        exact = reduce_exact(rows)
        if exact is not None:
            return Reduction(exact, 0.0, True)
    q, error = reduce_least_squares(points)
    return Reduction(q, error, False)


def full_reduce(points: np.ndarray, rows: Rows | None, tol: float) -> Reduction:
    """Reduce while the curve is an elevation: exactly for exact points, else while the
    least-squares error stays within tol (relative to the control points' size)."""
    scale = max(float(np.abs(points).max()), 1e-300)
    current = Reduction(rows if rows is not None else points, 0.0, rows is not None)
    while len(current.points) > 1:
        if isinstance(current.points, tuple):  # exact rows
            step = reduce(forms.as_float_rows(current.points), current.points)
        else:
            step = reduce(current.points, None)
        if not step.exact and current.error + step.error > tol * scale:
            break
        # errors add up along the chain (triangle inequality)
        current = step if step.exact else Reduction(step.points, current.error + step.error, False)
    return current
