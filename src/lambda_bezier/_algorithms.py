"""Low-level algorithms on control-point arrays: de Casteljau, subdivision, Bernstein Horner.

Float paths are vectorised over parameter values; exact paths (Fractions) exist so that the
lecture notes' worked examples and exact conversions stay exact.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction

import numpy as np

ExactRows = tuple[tuple[Fraction, ...], ...]


def de_casteljau_steps(points: np.ndarray, t: np.ndarray, steps: int) -> np.ndarray:
    """`steps` rounds of de Casteljau at every t at once, on (n+1, d) points shared by all t
    or on (len(t), n+1, d) points, one set per t: returns (len(t), n+1-steps, d), the
    intermediate points b_j^steps(t)."""
    tt = t[:, None, None]
    work = np.broadcast_to(points, (t.size, *points.shape[-2:]))
    for _ in range(steps):
        work = work[:, :-1] + tt * (work[:, 1:] - work[:, :-1])
    return np.array(work)


def de_casteljau_triangle(points: Sequence[Sequence], t) -> list[list[tuple]]:
    """The whole triangular array b_j^k(t) (k = 0..n), for one t, in the arithmetic of the
    inputs (Fractions stay exact). Row k holds b_0^k … b_{n-k}^k."""
    rows = [[tuple(p) for p in points]]
    for _ in range(len(points) - 1):
        prev = rows[-1]
        rows.append(
            [
                tuple((1 - t) * a + t * b for a, b in zip(p, q, strict=True))
                for p, q in zip(prev[:-1], prev[1:], strict=True)
            ]
        )
    return rows


def split_rows(points: Sequence[Sequence], t) -> tuple[list[tuple], list[tuple]]:
    """Subdivision at t (lecture notes, 分割定理): the first points of every row of the
    triangle, and the last points in reverse order."""
    tri = de_casteljau_triangle(points, t)
    return [row[0] for row in tri], [row[-1] for row in reversed(tri)]


def bernstein_horner(ctrl: np.ndarray, binom: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Σ_j ctrl[j] C(N,j) t^j (1-t)^(N-j) at every t, in O(N) vectorised passes.

    Horner's rule in u = t/(1-t) for t <= 1/2, and on the reversed coefficients in
    (1-t)/t for t > 1/2, so |u| <= 1 and nothing is divided by a small number: stable like
    de Casteljau at the cost of power-basis Horner. ctrl has shape (N+1, ...), binom the
    C(N, j); returns shape (len(t), ...).
    """
    size = ctrl.shape[0]
    scaled = ctrl * binom.reshape(-1, *(1,) * (ctrl.ndim - 1))
    out = np.empty((t.size, *ctrl.shape[1:]))
    low = t <= 0.5
    for mask, coeffs in ((low, scaled), (~low, scaled[::-1])):
        if not mask.any():
            continue
        x = t[mask] if coeffs is scaled else 1.0 - t[mask]
        s = 1.0 - x
        u = (x / s).reshape(-1, *(1,) * (ctrl.ndim - 1))
        acc = np.empty((x.size, *ctrl.shape[1:]))
        acc[...] = coeffs[-1]
        for c in coeffs[-2::-1]:
            acc *= u
            acc += c
        acc *= (s ** (size - 1)).reshape(u.shape)
        out[mask] = acc
    return out


def exact_matmul(weights: Sequence[Sequence[Fraction]], rows: ExactRows) -> ExactRows:
    """weights (r, n+1) @ rows (n+1, d), in Fractions."""
    dim = len(rows[0])
    return tuple(
        tuple(
            sum((w * row[c] for w, row in zip(wrow, rows, strict=True)), Fraction(0))
            for c in range(dim)
        )
        for wrow in weights
    )
