"""The batch operations' kernels compiled with numba (the `fast` extra), each the same
arithmetic as a numpy path that stays as the tested fallback (issue #29).

- `energy_coefficients`: the energy coefficients of many control polygons in one pass.
  energy.optimal_lambda's numpy path computes, per chunk of polygons, one matrix product
  Z = Fᵀ P (F the Kronecker form of the factored energy, 16 × 12 for a planar quintic at
  k = 2), then three row-wise dot products of Z and the squared norms of P: five calls, each
  a pass over the chunk, and a BLAS product that OpenBLAS may run on two threads. Here it is
  one single-threaded loop over blocks of polygons on the compact form (F without the
  Kronecker zeros).
- `energy_optimum`: the same coefficients and, in the same pass, λ* = −a₁/(2a₂), the clamped
  λ, their admissibility and the energies there, written straight into the result arrays:
  the numpy path's dozen passes over each chunk (and the Python work per chunk) become one.
  A polygon the pass cannot answer (a non-finite coefficient, or a₂ within its rounding
  bound: coordinates near the float limits, NaN, or λ without effect) is flagged and left to
  the careful path, which rescales it or names it in the error.
- `odd_curves`: evaluate_many's test of the curves' magnitudes (batch._curve_scales' rule),
  in one pass; the products themselves are BLAS's (batch._products_many).

Both compute each polygon's sums in the order the previous kernel did (kept bit for bit, so
a result does not depend on which of the two ran), and the optimum with the numpy path's
operations in its order (`energy._optimum`): results agree with the numpy fallback to
rounding, and with `energy_coefficients` + `energy._optimum` exactly.

Imported only through `kernels.batch_compiled()`; numba compiles on first use and caches the
machine code next to this file.
"""

from __future__ import annotations

from typing import Any

import numba
import numpy as np

_JIT: dict[str, Any] = {"cache": True, "error_model": "numpy", "nogil": True}

_BLOCK = 256  # polygons per block: the transposed block and the sums stay in L1


@numba.njit(**_JIT)
def _block_coefficients(
    points: np.ndarray,
    lo: int,
    count: int,
    compact: np.ndarray,
    rows: int,
    block: np.ndarray,
    acc: np.ndarray,
) -> None:
    """acc[0..3, :count] = (Σ f², Σ f·g, Σ g², Σ P²) of polygons lo .. lo+count-1 (acc[4..5]
    are scratch for f and g).

    The block is transposed (coordinate-major, polygons along the rows), so every inner loop
    runs along the polygons and compiles to vector instructions. The sum over the control
    points of f = Σᵢ Fᵢᵣ Pᵢ is taken three terms per pass (one load and store of f per three
    terms instead of per term), in the same order as one term per pass."""
    size = points.shape[1]
    dim = points.shape[2]
    flat = points.reshape(points.shape[0], size * dim)
    s0, s1, s2, norm, f, g = acc[0], acc[1], acc[2], acc[3], acc[4], acc[5]
    for j in range(count):
        s0[j] = 0.0
        s1[j] = 0.0
        s2[j] = 0.0
        norm[j] = 0.0
    for e in range(size * dim):  # the transpose (strided loads, contiguous stores) and Σ P²
        row = block[e]
        for j in range(count):
            x = flat[lo + j, e]
            row[j] = x
            norm[j] += x * x
    for c in range(dim):
        for r in range(rows):
            if size == 6:  # quintics: the whole sum in one pass, f and g never stored
                _six_terms(compact, r, rows, block, c, dim, count, s0, s1, s2)
                continue
            for j in range(count):
                f[j] = 0.0
                g[j] = 0.0
            i = 0
            while i + 3 <= size:
                f0, f1, f2 = compact[i, r], compact[i + 1, r], compact[i + 2, r]
                g0, g1, g2 = (
                    compact[i, rows + r],
                    compact[i + 1, rows + r],
                    compact[i + 2, rows + r],
                )
                x0, x1, x2 = block[i * dim + c], block[(i + 1) * dim + c], block[(i + 2) * dim + c]
                for j in range(count):
                    f[j] = ((f[j] + f0 * x0[j]) + f1 * x1[j]) + f2 * x2[j]
                    g[j] = ((g[j] + g0 * x0[j]) + g1 * x1[j]) + g2 * x2[j]
                i += 3
            while i < size:
                f0, g0, x0 = compact[i, r], compact[i, rows + r], block[i * dim + c]
                for j in range(count):
                    f[j] += f0 * x0[j]
                    g[j] += g0 * x0[j]
                i += 1
            for j in range(count):
                s0[j] += f[j] * f[j]
                s1[j] += f[j] * g[j]
                s2[j] += g[j] * g[j]


@numba.njit(**_JIT)
def _six_terms(
    compact: np.ndarray,
    r: int,
    rows: int,
    block: np.ndarray,
    c: int,
    dim: int,
    count: int,
    s0: np.ndarray,
    s1: np.ndarray,
    s2: np.ndarray,
) -> None:
    """_block_coefficients' sums for column r of a six-point form: f and g in registers."""
    f0, f1, f2 = compact[0, r], compact[1, r], compact[2, r]
    f3, f4, f5 = compact[3, r], compact[4, r], compact[5, r]
    g0, g1, g2 = compact[0, rows + r], compact[1, rows + r], compact[2, rows + r]
    g3, g4, g5 = compact[3, rows + r], compact[4, rows + r], compact[5, rows + r]
    x0, x1, x2 = block[c], block[dim + c], block[2 * dim + c]
    x3, x4, x5 = block[3 * dim + c], block[4 * dim + c], block[5 * dim + c]
    for j in range(count):
        f = (((((0.0 + f0 * x0[j]) + f1 * x1[j]) + f2 * x2[j]) + f3 * x3[j]) + f4 * x4[j]) + (
            f5 * x5[j]
        )
        g = (((((0.0 + g0 * x0[j]) + g1 * x1[j]) + g2 * x2[j]) + g3 * x3[j]) + g4 * x4[j]) + (
            g5 * x5[j]
        )
        s0[j] += f * f
        s1[j] += f * g
        s2[j] += g * g


@numba.njit(**_JIT)
def energy_coefficients(
    points: np.ndarray, compact: np.ndarray, rows: int, rounding_weight: float, out: np.ndarray
) -> None:
    """out[:, j] = (a0, a1, a2, rounding bound) of polygon j of points (m, n+1, d), with
    compact (n+1, 2·rows): columns [0, rows) the f-part and [rows, 2·rows) the g-part of the
    factored form, per coordinate (energy._factored_forms without the Kronecker product)."""
    m, size, dim = points.shape
    block = np.empty((size * dim, _BLOCK))
    acc = np.empty((6, _BLOCK))
    for lo in range(0, m, _BLOCK):
        count = min(_BLOCK, m - lo)
        _block_coefficients(points, lo, count, compact, rows, block, acc)
        for j in range(count):
            out[0, lo + j] = acc[0, j]
            out[1, lo + j] = 2.0 * acc[1, j]
            out[2, lo + j] = acc[2, j]
            out[3, lo + j] = acc[3, j] * rounding_weight


@numba.njit(**_JIT)
def energy_optimum(
    points: np.ndarray,
    compact: np.ndarray,
    rows: int,
    rounding_weight: float,
    bounds: np.ndarray,
    clamp: bool,
    best: np.ndarray,
    ok_best: np.ndarray,
    energy_best: np.ndarray,
    lam: np.ndarray,
    ok: np.ndarray,
    energy: np.ndarray,
) -> int:
    """λ* (best), whether it is admissible, E_k(λ*), and with `clamp` the same at λ clipped
    to bounds[0:2] (else lam, ok, energy are not written: the caller passes the first three
    again), for every polygon of points (m, n+1, d); returns the index of the first polygon
    left to the careful path, or m when there is none (that polygon's entries are not
    meaningful, the ones before it are final; the caller restarts after redoing it).

    bounds = (clip low, clip high, least admissible, greatest admissible): the admissible
    range as two closed float bounds equivalent to the family's exact (possibly open) ones
    (energy._admissible_bounds), so x ≥ bounds[2] and x ≤ bounds[3] decide admissibility
    exactly as energy._optimum's comparisons with the exact ends do."""
    m, size, dim = points.shape
    block = np.empty((size * dim, _BLOCK))
    acc = np.empty((6, _BLOCK))
    clip_lo, clip_hi, least, greatest = bounds[0], bounds[1], bounds[2], bounds[3]
    for lo in range(0, m, _BLOCK):
        count = min(_BLOCK, m - lo)
        _block_coefficients(points, lo, count, compact, rows, block, acc)
        # the block's test first (a vector loop), so the optimum's loops have no exit
        declined = 0
        for j in range(count):
            a0, a2 = acc[0, j], acc[2, j]
            bad = not (np.isfinite(a0) and np.isfinite(a2)) or a2 <= acc[3, j] * rounding_weight
            declined += bad
        final = count  # the polygons before the first declined one are answered
        if declined:
            for j in range(count):
                a0, a2 = acc[0, j], acc[2, j]
                if not (np.isfinite(a0) and np.isfinite(a2)) or a2 <= acc[3, j] * rounding_weight:
                    final = j
                    break
        for j in range(final):
            a0, a1, a2 = acc[0, j], 2.0 * acc[1, j], acc[2, j]
            x = -a1 / (2.0 * a2)
            best[lo + j] = x
            ok_best[lo + j] = (x >= least) & (x <= greatest)
            energy_best[lo + j] = a0 + a1 * x + a2 * x * x
        if clamp:
            for j in range(final):
                a0, a1, a2 = acc[0, j], 2.0 * acc[1, j], acc[2, j]
                y = min(max(best[lo + j], clip_lo), clip_hi)
                lam[lo + j] = y
                ok[lo + j] = (y >= least) & (y <= greatest)
                energy[lo + j] = a0 + a1 * y + a2 * y * y
        if final < count:
            return int(lo + final)
    return int(m)


@numba.njit(**_JIT)
def odd_curves(points: np.ndarray) -> int:
    """How many curves of points (m, n+1, d) evaluate_many cannot take as they are: a
    non-finite coordinate, or the largest |coordinate| at or above 2^900 or in (0, 2^-901)
    (batch._curve_scales' rule: those are scaled by a power of two). One pass, no working
    array: numpy's test of the same takes four passes and a temporary of the chunk's size,
    a fifth of evaluate_many's time at 64 parameters."""
    m, size, dim = points.shape
    odd = 0
    for j in range(m):
        big = 0.0
        nan = False
        for i in range(size):
            for c in range(dim):
                # without a branch per coordinate (a compare-and-keep that may hold a NaN):
                # the maximum and a NaN flag, selects the compiler keeps in registers, twice
                # as fast (issue #29)
                a = abs(points[j, i, c])
                big = max(big, a)
                nan |= a != a
        odd += nan or not (big < 2.0**900 and (big >= 2.0**-901 or big == 0.0))
    return odd
