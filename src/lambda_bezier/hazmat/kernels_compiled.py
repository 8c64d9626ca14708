"""Kernels compiled with numba (the `fast` extra), each the same arithmetic as a numpy path
that stays as the tested fallback.

- `energy_coefficients`: the energy coefficients of many control polygons in one pass.
  energy.optimal_lambda's numpy path computes, per chunk of polygons, one matrix product
  Z = Fᵀ P (F the Kronecker form of the factored energy, 16 × 12 for a planar quintic at
  k = 2), then three row-wise dot products of Z and the squared norms of P: five calls, each
  a pass over the chunk, and a BLAS product that OpenBLAS may run on two threads (with the
  other core busy that doubled its time). Here it is one single-threaded loop over blocks of
  polygons on the compact form (F without the Kronecker zeros).
- `first_level`: the first level of arclength.unit_integral (the speed at the fixed nodes,
  each piece's two rules, the accept test's sums, the least speed), which in numpy is about
  ten calls on arrays of a few hundred values, most of an arc length's cost.

The sums run in a fixed order, so the results agree with the numpy paths to rounding, not bit
for bit; tests/test_batch.py and tests/test_arclength.py run both.

Imported only through `kernels.compiled()` (numba compiles on first use and caches the
machine code next to this file); set LAMBDA_BEZIER_NO_NUMBA=1, or `kernels.USE_COMPILED =
False`, for the numpy paths.
"""

from __future__ import annotations

from typing import Any

import numba
import numpy as np

_JIT: dict[str, Any] = {"cache": True, "error_model": "numpy", "nogil": True}


_BLOCK = 256  # polygons per block: the transposed block and the sums stay in L1


@numba.njit(**_JIT)
def energy_coefficients(
    points: np.ndarray, compact: np.ndarray, rows: int, rounding_weight: float, out: np.ndarray
) -> None:
    """out[:, j] = (a0, a1, a2, rounding bound) of polygon j of points (m, n+1, d), with
    compact (n+1, 2·rows): columns [0, rows) the f-part and [rows, 2·rows) the g-part of the
    factored form, per coordinate (energy._factored_forms without the Kronecker product).

    Blocks of polygons are transposed (coordinate-major, polygons along the rows), so every
    inner loop runs along the polygons of a block and compiles to vector instructions; each
    polygon's sums are still added in a fixed order."""
    m, size, dim = points.shape
    block = np.empty((size * dim, _BLOCK))
    f = np.empty(_BLOCK)
    g = np.empty(_BLOCK)
    s0 = np.empty(_BLOCK)
    s1 = np.empty(_BLOCK)
    s2 = np.empty(_BLOCK)
    norm = np.empty(_BLOCK)
    for lo in range(0, m, _BLOCK):
        count = min(_BLOCK, m - lo)
        for j in range(count):
            for i in range(size):
                for c in range(dim):
                    block[i * dim + c, j] = points[lo + j, i, c]
        for j in range(count):
            s0[j] = 0.0
            s1[j] = 0.0
            s2[j] = 0.0
            norm[j] = 0.0
        for e in range(size * dim):
            row = block[e]
            for j in range(count):
                norm[j] += row[j] * row[j]
        for c in range(dim):
            for r in range(rows):
                for j in range(count):
                    f[j] = 0.0
                    g[j] = 0.0
                for i in range(size):
                    bf = compact[i, r]
                    bg = compact[i, rows + r]
                    row = block[i * dim + c]
                    for j in range(count):
                        f[j] += bf * row[j]
                        g[j] += bg * row[j]
                for j in range(count):
                    s0[j] += f[j] * f[j]
                    s1[j] += f[j] * g[j]
                    s2[j] += g[j] * g[j]
        for j in range(count):
            out[0, lo + j] = s0[j]
            out[1, lo + j] = 2.0 * s1[j]
            out[2, lo + j] = s2[j]
            out[3, lo + j] = norm[j] * rounding_weight


@numba.njit(**_JIT)
def first_level(
    coeffs: np.ndarray, powers: np.ndarray, weights: np.ndarray, pieces: int, size: np.ndarray
) -> tuple[float, float, float]:
    """arclength.unit_integral's first level: coeffs (d, N+1) the Taylor coefficients of p,
    powers (N+1, pieces·r) the derivative powers at the nodes, weights (r, 2) the pieces'
    rules (difference, value). Writes |sums| (pieces, 2) into `size`; returns (Σ|difference|,
    Σ|value|, the least speed at a node)."""
    dim, count = coeffs.shape
    nodes = powers.shape[1]
    per = nodes // pieces
    square = np.zeros(nodes)
    value = np.empty(nodes)
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
    least = np.inf
    for j in range(nodes):
        square[j] = np.sqrt(square[j])
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
