"""Low-level algorithms on control-point arrays: de Casteljau, subdivision, Horner.

Float paths are vectorised over parameter values; exact paths (Fractions) exist so that the
lecture notes' worked examples and exact conversions stay exact.
"""

from __future__ import annotations

import importlib.util
import itertools
import os
from collections.abc import Callable, Sequence
from fractions import Fraction
from types import ModuleType
from typing import TYPE_CHECKING, TypeVar

import numpy as np

if TYPE_CHECKING:
    from concurrent.futures import ThreadPoolExecutor

ExactRows = tuple[tuple[Fraction, ...], ...]
# rows of exact or float coordinates: the exact paths keep Fractions, the others floats
Scalar = Fraction | float
Row = tuple[Scalar, ...]
Rows = tuple[Row, ...]


def de_casteljau_steps(points: np.ndarray, t: np.ndarray, steps: int) -> np.ndarray:
    """`steps` rounds of de Casteljau at every t at once, on (n+1, d) points shared by all t
    or on (len(t), n+1, d) points, one set per t: returns (len(t), n+1-steps, d), the
    intermediate points b_j^steps(t)."""
    tt = t[:, None, None]
    work = np.broadcast_to(points, (t.size, *points.shape[-2:]))
    for _ in range(steps):
        work = work[:, :-1] + tt * (work[:, 1:] - work[:, :-1])
    return np.array(work)


def de_casteljau_triangle(points: Sequence[Sequence[Scalar]], t: Scalar) -> list[list[Row]]:
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


def split_rows(points: Sequence[Sequence[Scalar]], t: Scalar) -> tuple[list[Row], list[Row]]:
    """Subdivision at t (lecture notes, 分割定理): the first points of every row of the
    triangle, and the last points in reverse order."""
    tri = de_casteljau_triangle(points, t)
    return [row[0] for row in tri], [row[-1] for row in reversed(tri)]


# The compiled kernels (kernels_compiled) when numba is there and not switched off
# (LAMBDA_BEZIER_NO_NUMBA=1); a module flag, read per call, so tests can run both paths.
USE_COMPILED = importlib.util.find_spec("numba") is not None and not os.environ.get(
    "LAMBDA_BEZIER_NO_NUMBA"
)


_LOADED: dict[str, ModuleType] = {}  # kernels_compiled once imported (per call: 0.6 us)


def compiled() -> ModuleType | None:
    """hazmat.kernels_compiled when USE_COMPILED, else None (the numpy paths)."""
    if not USE_COMPILED:
        return None
    module = _LOADED.get("kernels")
    if module is None:
        from . import kernels_compiled  # numba compiles (or loads its cache) on first use

        module = _LOADED["kernels"] = kernels_compiled
    return module


def batch_compiled() -> ModuleType | None:
    """hazmat.batch_compiled (optimal_lambda's kernels) when USE_COMPILED, else None (the
    numpy paths)."""
    if not USE_COMPILED:
        return None
    from . import batch_compiled as module  # numba compiles (or loads its cache) on first use

    return module


# Elements of one chunk's working block in the batch operations (evaluate_many, optimal_lambda):
# 2 MB of floats, inside the L2 cache, and a bound on their extra memory at any batch size.
CHUNK_ELEMENTS = 1 << 18


# the batch operations' thread pools by (process, threads): a child made by fork inherits
# the parent's pool without its threads (its jobs would never run), so each process makes
# its own
_POOLS: dict[tuple[int, int], ThreadPoolExecutor] = {}
_T = TypeVar("_T")


def thread_pool(workers: int) -> ThreadPoolExecutor:
    """The pool of `workers` threads the batch operations share out their slabs on."""
    key = (os.getpid(), workers)
    pool = _POOLS.get(key)
    if pool is None:
        # imported on first use: concurrent.futures brings logging, queue and traceback,
        # about 3 ms of every program's import that most never spend (#29)
        from concurrent.futures import ThreadPoolExecutor

        pool = _POOLS.setdefault(
            key, ThreadPoolExecutor(workers, thread_name_prefix="lambda_bezier")
        )
    return pool


def on_threads(run: Callable[[int, int], _T], count: int, workers: int) -> list[_T]:
    """run(a, b) on `workers` consecutive slices [a, b) of range(count), one a thread of
    `thread_pool(workers)`, the results in slice order. Every slice has finished before this
    returns or raises (none writes into a result later), and the error raised is the first
    slice's, as in one thread."""
    cuts = [count * w // workers for w in range(workers + 1)]
    pool = thread_pool(workers)
    jobs = [pool.submit(run, a, b) for a, b in itertools.pairwise(cuts)]
    for error in [job.exception() for job in jobs]:
        if error is not None:
            raise error
    return [job.result() for job in jobs]


def cpu_count() -> int:
    """The CPUs this process may run on."""
    cpus = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    return cpus or 1


def chunk_ranges(m: int, per_item: int) -> list[tuple[int, int]]:
    """[lo, hi) ranges covering range(m), each of about CHUNK_ELEMENTS elements when an item
    takes `per_item` elements (at least one item per chunk)."""
    step = max(1, CHUNK_ELEMENTS // max(per_item, 1))
    return [(lo, min(lo + step, m)) for lo in range(0, m, step)]


BLOCK = 65536  # parameters per block: a (d, BLOCK) accumulator stays in the L2 cache


def centred_horner(coeffs: np.ndarray, t: np.ndarray, centre: float = 0.5) -> np.ndarray:
    """Σ_e coeffs[:, e] (t - centre)^e at every t: coeffs (d, N+1) → (len(t), d).

    Coordinate-major (each of the N in-place multiply-add passes runs over a contiguous
    (d, block) slab) and blocked over t so the slab stays in cache: the passes then run at
    cache speed instead of memory speed (about twice as fast at 10⁶ parameters). About
    t = 1/2 the monomials are as well conditioned on [0, 1] as the Bernstein basis, unlike
    the monomials about 0. The transposed view is returned.
    """
    size = coeffs.shape[1]
    out = np.empty((coeffs.shape[0], t.size))
    if size == 1:
        out[...] = coeffs
        return out.T
    for start in range(0, t.size, BLOCK):
        u = t[start : start + BLOCK] - centre
        acc = out[:, start : start + BLOCK]
        np.multiply(coeffs[:, -1:], u, out=acc)  # the first Horner step, fused with the fill
        acc += coeffs[:, -2:-1]
        for e in range(size - 3, -1, -1):
            acc *= u
            acc += coeffs[:, e : e + 1]
    return out.T


def differentiate_coefficients(coeffs: np.ndarray, k: int) -> np.ndarray:
    """Coefficients (…, N+1) of the k-th derivative of Σ c_e u^e, in the same layout
    (…, N+1-k); at least one zero coefficient when k exceeds the degree."""
    size = coeffs.shape[-1]
    if k >= size:
        return np.zeros((*coeffs.shape[:-1], 1))
    e = np.arange(size - k, dtype=float)
    factor = np.ones(size - k)
    for s in range(1, k + 1):
        factor *= e + s
    return coeffs[..., k:] * factor


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


def solve_exact(a: list[list[Fraction]], b: list[list[Fraction]]) -> list[list[Fraction]] | None:
    """x with a x = b (a: rows × cols, full column rank), or None when inconsistent."""
    rows, cols = len(a), len(a[0])
    aug = [list(a[r]) + list(b[r]) for r in range(rows)]
    piv_row = 0
    for c in range(cols):
        p = next((r for r in range(piv_row, rows) if aug[r][c] != 0), None)
        if p is None:
            raise ArithmeticError("rank deficient")
        aug[piv_row], aug[p] = aug[p], aug[piv_row]
        inv = 1 / aug[piv_row][c]
        aug[piv_row] = [v * inv for v in aug[piv_row]]
        for r in range(rows):
            if r != piv_row and aug[r][c] != 0:
                f = aug[r][c]
                aug[r] = [v - f * w for v, w in zip(aug[r], aug[piv_row], strict=True)]
        piv_row += 1
    if any(v != 0 for r in range(piv_row, rows) for v in aug[r][cols:]):
        return None
    return [aug[r][cols:] for r in range(cols)]
