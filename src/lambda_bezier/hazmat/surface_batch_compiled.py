"""The batch optimum of (λ_u, λ_v), compiled with numba (the `fast` extra): one pass over the
nets in cache-sized chunks, each chunk transposed once (net index last, so every later loop
runs over contiguous lanes and vectorises), its energy coefficients from the Gram products,
then hazmat.surface_certify's fixed-cost certified minimum, compiled from the same source.

The coefficients: e_ab = Σ_p W[p, 3a + b] g_p over the pairs p = (i, j), i <= j, of control
points, g_p = P_i · P_j (surface_optimum.pair_weights). For a bicubic net that is 136 pairs,
3 + 9 multiply-adds each: about 1,600 a net. The Kronecker route (contract the net with the
per-direction forms first, P ↦ A_u P A_v^T) costs more at these sizes: each of the nine
λ-powers needs its own pair of small products (about 3,600 multiply-adds a net for the thin
plate energy, 2,400 through orthonormal features), so the dense pair sum is kept and made
fast by lanes instead.

Validation rides along: the transposition notes any coordinate that is not finite or is above
`limit`, and the caller raises the same errors as the numpy path.
"""

from __future__ import annotations

import types
from collections.abc import Callable
from typing import Any

import numba
import numpy as np

from . import surface_certify as sc

_JIT: dict[str, Any] = {"cache": True, "error_model": "numpy", "fastmath": False}
CHUNK = 64  # nets per chunk: the transposed chunk (s·d x CHUNK floats) stays in L1


@numba.njit(inline="always", error_model="numpy")
def _select(c: bool, a: float, b: float) -> float:
    return a if c else b


def _recompiled(names: tuple[str, ...]) -> dict[str, Callable[..., Any]]:
    """surface_certify's functions compiled for scalars: the same code objects with `_where`
    bound to a scalar selection (and their calls to each other bound to the compiled ones)."""
    space: dict[str, Any] = dict(vars(sc))
    space["_where"] = _select
    out: dict[str, Callable[..., Any]] = {}
    for name in names:  # callees first
        fn = getattr(sc, name)
        copy = types.FunctionType(fn.__code__, space, name, fn.__defaults__)
        copy.__qualname__ = f"surface_batch_compiled.{name}"
        # inlined into the cached kernels below (numba inlines at its own IR level, so the
        # loops over nets see straight-line code)
        out[name] = space[name] = numba.njit(inline="always", error_model="numpy")(copy)
    return out


_certified_minimum = _recompiled(
    ("_clip", "_sweep", "_newton", "_quartic_positive", "_quadratic_positive", "_side_clear", "certified_minimum")
)["certified_minimum"]


@numba.njit(**_JIT)
def _certify_chunk(
    acc: np.ndarray,
    n: int,
    start: int,
    box: np.ndarray,
    tol: float,
    xs: np.ndarray,
    ys: np.ndarray,
    values: np.ndarray,
    deltas: np.ndarray,
    certified: np.ndarray,
) -> None:
    """certified_minimum for the chunk's n nets (a function of its own: the loop vectorises)."""
    xlo, xhi, ylo, yhi = box[0], box[1], box[2], box[3]
    for k in range(n):
        x, y, e, d, ok = _certified_minimum(
            acc[0, k],
            acc[1, k],
            acc[2, k],
            acc[3, k],
            acc[4, k],
            acc[5, k],
            acc[6, k],
            acc[7, k],
            acc[8, k],
            xlo,
            xhi,
            ylo,
            yhi,
            tol,
        )
        xs[start + k] = x
        ys[start + k] = y
        values[start + k] = e
        deltas[start + k] = d
        certified[start + k] = ok


@numba.njit(**_JIT)
def optimise(
    flat: np.ndarray,
    dim: int,
    pair_i: np.ndarray,
    pair_j: np.ndarray,
    weights: np.ndarray,
    box: np.ndarray,
    tol: float,
    limit: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, bool]:
    """For nets flat (k, s·d) (control point i's coordinates at i·d .. i·d + d − 1) and the
    energy Σ_p weights[p, 3a + b] g_p x^a y^b: per net (x, y, energy, δ, certified) of
    surface_certify.certified_minimum over box = (xlo, xhi, ylo, yhi), and whether every
    coordinate was finite and <= limit."""
    count, width = flat.shape
    n_pairs = pair_i.shape[0]
    xs = np.empty(count)
    ys = np.empty(count)
    values = np.empty(count)
    deltas = np.empty(count)
    certified = np.empty(count, np.bool_)
    lanes = np.zeros((width, CHUNK))
    acc = np.empty((9, CHUNK))
    gram = np.empty(CHUNK)
    valid = True
    for start in range(0, count, CHUNK):
        n = min(CHUNK, count - start)
        for k in range(n):
            for r in range(width):
                v = flat[start + k, r]
                valid &= abs(v) <= limit  # False for NaN too
                lanes[r, k] = v
        acc[:, :] = 0.0
        # each loop below runs over the chunk's lanes alone, so it vectorises
        for p in range(n_pairs):
            a, b = pair_i[p] * dim, pair_j[p] * dim
            for k in range(CHUNK):
                gram[k] = lanes[a, k] * lanes[b, k]
            for c in range(1, dim):
                for k in range(CHUNK):
                    gram[k] += lanes[a + c, k] * lanes[b + c, k]
            for t in range(9):
                w = weights[p, t]
                for k in range(CHUNK):
                    acc[t, k] += w * gram[k]
        _certify_chunk(acc, n, start, box, tol, xs, ys, values, deltas, certified)
    return xs, ys, values, deltas, certified, valid
