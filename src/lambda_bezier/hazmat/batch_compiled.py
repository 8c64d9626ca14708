"""Batch kernels compiled with numba (the `fast` extra): the energy coefficients of many
control polygons in one pass.

energy.optimal_lambda's numpy path computes, per chunk of polygons, one matrix product
Z = Fᵀ P (F the Kronecker form of the factored energy, 16 × 12 for a planar quintic at
k = 2), then three row-wise dot products of Z and the squared norms of P: five calls, each a
pass over the chunk, and a BLAS product that OpenBLAS may run on two threads (with the other
core busy that doubled its time). Here the same arithmetic is one single-threaded loop per
polygon on the compact form B (F without the Kronecker zeros), so each polygon is read once.
The sums run in a fixed order, so the results agree with the numpy path to rounding, not
bit for bit; tests/test_batch.py runs both.

Imported only through `compiled()` below (numba compiles on first use and caches the machine
code next to this file); set LAMBDA_BEZIER_NO_NUMBA=1, or `USE_COMPILED = False` here, for
the numpy path.
"""

from __future__ import annotations

from typing import Any

import numba
import numpy as np

_JIT: dict[str, Any] = {"cache": True, "error_model": "numpy", "nogil": True}


@numba.njit(**_JIT)
def energy_coefficients(
    points: np.ndarray, compact: np.ndarray, rows: int, rounding_weight: float, out: np.ndarray
) -> None:
    """out[:, j] = (a0, a1, a2, rounding bound) of polygon j of points (m, n+1, d), with
    compact (n+1, 2·rows): columns [0, rows) the f-part and [rows, 2·rows) the g-part of the
    factored form, per coordinate (energy._factored_forms without the Kronecker product)."""
    m, size, dim = points.shape
    z = np.empty(2 * rows)
    for j in range(m):
        s0 = 0.0
        s1 = 0.0
        s2 = 0.0
        norm = 0.0
        for c in range(dim):
            for r in range(2 * rows):
                z[r] = 0.0
            for i in range(size):
                p = points[j, i, c]
                norm += p * p
                for r in range(2 * rows):
                    z[r] += compact[i, r] * p
            for r in range(rows):
                f = z[r]
                g = z[rows + r]
                s0 += f * f
                s1 += f * g
                s2 += g * g
        out[0, j] = s0
        out[1, j] = 2.0 * s1
        out[2, j] = s2
        out[3, j] = norm * rounding_weight
