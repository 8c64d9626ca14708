"""Kernels compiled with numba (the `fast` extra), each the same arithmetic as a numpy path
that stays as the tested fallback (the batch operations' kernels are in `batch_compiled`).

- `speeds`: |p'| at fixed nodes, the inner loop of both levels below;
- `first_level`: the first level of arclength.unit_integral (the speed at the fixed nodes,
  each piece's two rules, the accept test's sums, the least speed), which in numpy is about
  ten calls on arrays of a few hundred values, most of an arc length's cost;
  `unit_first_level` adds unit_integral's decisions around it (whether the coefficients
  need scaling, a hidden dip, a constant curve, acceptance at once), which in Python cost
  about a third as much as the level itself;
- `second_level`: unit_integral's refinement of the first level's rejected pieces on their
  fixed nodes (about one random quintic in five: numpy's dozen calls there cost more than
  the arithmetic).

The sums run in a fixed order, so the results agree with the numpy paths to rounding, not bit
for bit; tests/test_arclength.py runs both.

Imported only through `kernels.compiled()` (numba compiles on first use and caches the
machine code next to this file); set LAMBDA_BEZIER_NO_NUMBA=1, or `kernels.USE_COMPILED =
False`, for the numpy paths.
"""

from __future__ import annotations

from typing import Any

import numba
import numpy as np

_JIT: dict[str, Any] = {"cache": True, "error_model": "numpy", "nogil": True}


@numba.njit(**_JIT)
def speeds(coeffs: np.ndarray, powers: np.ndarray, square: np.ndarray, value: np.ndarray) -> None:
    """The speed |p'| at the nodes into `square`: coeffs (d, N+1) the Taylor coefficients of
    p, powers (N+1, nodes) the derivative powers at the nodes (row 0 zero, so skipped);
    `value` is scratch of the nodes' size. Both levels' inner loop, in one fixed order."""
    dim, count = coeffs.shape
    nodes = square.size
    for j in range(nodes):
        square[j] = 0.0
    for c in range(dim):
        for j in range(nodes):
            value[j] = 0.0
        for e in range(1, count):  # row 0 of the derivative powers is zero
            ce = coeffs[c, e]
            row = powers[e]
            for j in range(nodes):
                value[j] += ce * row[j]
        for j in range(nodes):
            square[j] += value[j] * value[j]
    for j in range(nodes):
        square[j] = np.sqrt(square[j])


@numba.njit(**_JIT)
def first_level(
    coeffs: np.ndarray, powers: np.ndarray, weights: np.ndarray, pieces: int, size: np.ndarray
) -> tuple[float, float, float]:
    """arclength.unit_integral's first level: coeffs (d, N+1) the Taylor coefficients of p,
    powers (N+1, pieces·r) the derivative powers at the nodes, weights (r, 2) the pieces'
    rules (difference, value). Writes |sums| (pieces, 2) into `size`; returns (Σ|difference|,
    Σ|value|, the least speed at a node)."""
    nodes = powers.shape[1]
    per = nodes // pieces
    square = np.empty(nodes)
    speeds(coeffs, powers, square, np.empty(nodes))
    least = np.inf
    for j in range(nodes):
        if square[j] < least:
            least = square[j]
    spent = 0.0
    total = 0.0
    for p in range(pieces):
        s0 = 0.0
        s1 = 0.0
        for q in range(per):
            v = square[p * per + q]
            s0 += v * weights[q, 0]
            s1 += v * weights[q, 1]
        size[p, 0] = abs(s0)
        size[p, 1] = abs(s1)
        spent += size[p, 0]
        total += size[p, 1]
    return spent, total, least


@numba.njit(**_JIT)
def unit_first_level(
    coeffs: np.ndarray,
    powers: np.ndarray,
    weights: np.ndarray,
    pieces: int,
    rtol: float,
    hidden_unit: float,
    size: np.ndarray,
) -> tuple[int, float, float, float, float]:
    """arclength.unit_integral up to its first decision, for coefficients as given (not
    scaled): (code, spent, total, least, peak) with first_level's sums and the largest
    |coefficient| but the constant terms, `size` written as there.
    Code 0: the length is `total` (0.0 for a constant curve, else accepted at once); code 1:
    the coefficients need arclength._scaled first (nothing else computed); code 2: the rule
    goes on from this level (a piece rejected, or a near-double zero of p' may hide: least
    within hidden_unit · (coordinates) · (largest coefficient) / pieces², arclength's
    bound)."""
    dim, count = coeffs.shape
    peak = 0.0  # the largest |coefficient| but the constant terms (arclength._scaled's)
    for c in range(dim):
        for e in range(1, count):
            peak = max(peak, abs(coeffs[c, e]))
    if not (peak == 0.0 or 2.0**-400 <= peak <= 2.0**400):
        return 1, 0.0, 0.0, 0.0, peak
    spent, total, least = first_level(coeffs, powers, weights, pieces, size)
    if not total > 0.0:
        return 0, spent, 0.0, least, peak
    if least <= hidden_unit * dim * peak / (pieces * pieces):
        return 2, spent, total, least, peak
    if spent <= rtol * total:
        return 0, spent, total, least, peak
    return 2, spent, total, least, peak


@numba.njit(**_JIT)
def second_level(
    coeffs: np.ndarray,
    powers: np.ndarray,
    weights: np.ndarray,
    bad: np.ndarray,
    sums: np.ndarray,
    low: np.ndarray,
) -> tuple[float, float, float]:
    """arclength.unit_integral's second level: the first-level pieces `bad` each cut in S
    parts, powers (K, N+1, S·r) the derivative powers at the parts' nodes per first-level
    piece, weights (r, 2) the parts' rules. Writes the signed sums (len(bad)·S, 2) (test −
    value, value) and each part's least speed at its nodes into `low`; returns (Σ|test −
    value|, Σ|value|, the least speed at a node)."""
    nodes = powers.shape[2]
    per = weights.shape[0]
    parts = nodes // per
    square = np.empty(nodes)
    value = np.empty(nodes)
    spent = 0.0
    total = 0.0
    least = np.inf
    for b in range(bad.size):
        speeds(coeffs, powers[bad[b]], square, value)
        for p in range(parts):
            s0 = 0.0
            s1 = 0.0
            lo = np.inf
            for q in range(per):
                v = square[p * per + q]
                s0 += v * weights[q, 0]
                s1 += v * weights[q, 1]
                lo = min(lo, v)
            k = b * parts + p
            sums[k, 0] = s0
            sums[k, 1] = s1
            low[k] = lo
            spent += abs(s0)
            total += abs(s1)
            least = min(least, lo)
    return spent, total, least
