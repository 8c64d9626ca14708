"""Tensor-product kernels: pure functions on Bézier nets and coefficient arrays.

numpy and the standard library only; nothing here knows a curve or surface class (this module
is bound for ``lambda_bezier.hazmat``). A Bézier net is an (M+1, N+1, d) array (or nested
tuples of Fractions for the exact paths); the evaluation form is the tensor of Taylor
coefficients about (1/2, 1/2), which is as well conditioned on the unit square as the
Bernstein basis (the curves use the same centre).
"""

from __future__ import annotations

import importlib.util
import itertools
import os
from collections.abc import Callable, Sequence
from fractions import Fraction
from functools import cache
from math import comb
from types import ModuleType

import numpy as np

Scalar = Fraction | float
ExactNet = tuple[tuple[tuple[Fraction, ...], ...], ...]

# the batch optimum of (λ_u, λ_v) accepts an interior point when its last Newton step is
# below this (quadratic convergence: the point is then within about that of the critical
# point); the numpy version reads it, the compiled one is passed it
OPTIMUM_STEP_TOLERANCE = 1e-13

# the compiled kernels (surface_compiled) when numba is there and not switched off (module
# flag, read per call; LAMBDA_BEZIER_NO_NUMBA=1 in the environment, or USE_COMPILED = False
# here, selects the numpy versions, which stay the tested fallback)
USE_COMPILED = importlib.util.find_spec("numba") is not None and not os.environ.get(
    "LAMBDA_BEZIER_NO_NUMBA"
)


def compiled() -> ModuleType | None:
    """hazmat.surface_compiled, or None for the numpy versions."""
    if not USE_COMPILED:
        return None
    from . import surface_compiled  # numba compiles (or loads its cache) on first use

    return surface_compiled


# ---------------------------------------------------------------------- basis changes
@cache
def bernstein_to_centred(degree: int) -> tuple[tuple[Fraction, ...], ...]:
    """T (N+1, N+1), exact: B_i^N(t) = Σ_e T[i][e] (t - 1/2)^e."""
    # t = 1/2 + s, 1 - t = 1/2 - s: expand C(N,i) (1/2 + s)^i (1/2 - s)^(N-i) in powers of s
    half = Fraction(1, 2)
    rows = []
    for i in range(degree + 1):
        a = [comb(i, k) * half ** (i - k) for k in range(i + 1)]
        b = [
            comb(degree - i, k) * half ** (degree - i - k) * (-1) ** k
            for k in range(degree - i + 1)
        ]
        row = [Fraction(0)] * (degree + 1)
        for p, x in enumerate(a):
            for q, y in enumerate(b):
                row[p + q] += comb(degree, i) * x * y
        rows.append(tuple(row))
    return tuple(rows)


@cache
def _float_centred(degree: int) -> np.ndarray:
    out = np.array(bernstein_to_centred(degree), dtype=float)
    out.setflags(write=False)
    return out


def centred_coefficients(net: np.ndarray) -> np.ndarray:
    """The Taylor tensor A (M+1, N+1, d) about (1/2, 1/2) of a float Bézier net (M+1, N+1, d)."""
    tu = _float_centred(net.shape[0] - 1)
    tv = _float_centred(net.shape[1] - 1)
    out: np.ndarray = np.einsum("ie,ijd,jf->efd", tu, net, tv, optimize=True)
    return out


def differentiate(coeffs: np.ndarray, du: int, dv: int) -> np.ndarray:
    """The Taylor tensor of ∂^(du+dv)/∂u^du ∂v^dv (one zero coefficient past the degree)."""
    out = coeffs
    for axis, k in ((0, du), (1, dv)):
        size = out.shape[axis]
        if k >= size:
            shape = list(out.shape)
            shape[axis] = 1
            out = np.zeros(shape)
            continue
        e = np.arange(size - k, dtype=float)
        factor = np.ones(size - k)
        for s in range(1, k + 1):
            factor *= e + s
        shape = [1, 1, 1]
        shape[axis] = size - k
        out = np.take(out, np.arange(k, size), axis=axis) * factor.reshape(shape)
    return out


def _powers(t: np.ndarray, size: int) -> np.ndarray:
    """(len(t), size): (t - 1/2)^e."""
    out = np.empty((t.size, size))
    out[:, 0] = 1.0
    if size > 1:
        out[:, 1] = t - 0.5
        for e in range(2, size):
            np.multiply(out[:, e - 1], out[:, 1], out=out[:, e])
    return out


def evaluate_points(coeffs: np.ndarray, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """S(u_k, v_k) for paired 1-D arrays u, v: (len(u), d)."""
    big_m, big_n, dim = coeffs.shape
    pu = _powers(u, big_m)
    pv = _powers(v, big_n)
    # one matrix product along u, then the pairing along v; no einsum path search, which
    # cost more than the arithmetic for the few points the global searches evaluate
    along_u = (pu @ coeffs.reshape(big_m, big_n * dim)).reshape(u.size, big_n, dim)
    out: np.ndarray = np.einsum("knd,kn->kd", along_u, pv)
    return out


def evaluate_grid(coeffs: np.ndarray, us: np.ndarray, vs: np.ndarray) -> np.ndarray:
    """S(us[a], vs[b]) for every pair: (len(us), len(vs), d), a transposed view of a
    coordinate-major (d, len(us), len(vs)) array.

    Compiled (surface_compiled.grid_rows) when numba is there: each output row is written
    once, by Horner in (v - 1/2) on the row's weights (Horner in (u - 1/2) on the tensor), on
    one thread: two threads on halves of the rows measured slower (a bicubic 1000 x 1000:
    1.19x the one-thread fill against 1.07x on one thread, load 7), as was the fill itself
    on two threads (1.15x): the writes are bound by the cache's bandwidth, not the core.
    The numpy version: one small contraction along u, then per coordinate one matrix product
    (len(us), N+1) @ (N+1, len(vs)) written straight into its slab of the output.
    """
    big_m, big_n, dim = coeffs.shape
    out = np.empty((dim, us.size, vs.size))
    fast = compiled()
    if fast is not None and us.size and vs.size:
        fast.grid_rows(coeffs, us, vs, out)
        return out.transpose(1, 2, 0)
    pu = _powers(us, big_m)
    pv_t = np.ascontiguousarray(_powers(vs, big_n).T)  # (N+1, len(vs))
    left = np.ascontiguousarray(np.einsum("ai,ijd->daj", pu, coeffs))  # (d, len(us), N+1)
    for c in range(dim):
        np.matmul(left[c], pv_t, out=out[c])
    return out.transpose(1, 2, 0)


# ---------------------------------------------------------------------- exact net algebra
def exact_transform(
    left: Sequence[Sequence[Fraction]], net: ExactNet, right: Sequence[Sequence[Fraction]]
) -> ExactNet:
    """Lᵀ · net · R per coordinate, in Fractions: L (m+1, M+1), R (n+1, N+1)."""
    rows_in, cols_in = len(net), len(net[0])
    dim = len(net[0][0])
    big_m, big_n = len(left[0]), len(right[0])
    # along v first: tmp[i][b] = Σ_j net[i][j] R[j][b]
    tmp = [
        [
            tuple(
                sum(
                    (net[i][j][c] * right[j][b] for j in range(cols_in) if right[j][b]), Fraction(0)
                )
                for c in range(dim)
            )
            for b in range(big_n)
        ]
        for i in range(rows_in)
    ]
    return tuple(
        tuple(
            tuple(
                sum((tmp[i][b][c] * left[i][a] for i in range(rows_in) if left[i][a]), Fraction(0))
                for c in range(dim)
            )
            for b in range(big_n)
        )
        for a in range(big_m)
    )


def bernstein_values(degree: int, t: Scalar) -> tuple[Scalar, ...]:
    """B_i^N(t), i = 0..N, in the arithmetic of t."""
    return tuple(comb(degree, i) * t**i * (1 - t) ** (degree - i) for i in range(degree + 1))


def split_net(
    net: Sequence[Sequence[Sequence[Scalar]]], t: Scalar, axis: int
) -> tuple[list[list[tuple[Scalar, ...]]], list[list[tuple[Scalar, ...]]]]:
    """The two nets of the pieces over [0, t] and [t, 1] along `axis` (0: u, 1: v), by de
    Casteljau on every row of control points across that axis; exact for Fractions."""
    if axis == 1:
        left, right = [], []
        for row in net:
            lo, hi = _split_row([tuple(p) for p in row], t)
            left.append(lo)
            right.append(hi)
        return left, right
    transposed = [[net[i][j] for i in range(len(net))] for j in range(len(net[0]))]
    lo_t, hi_t = split_net(transposed, t, 1)
    return (
        [[lo_t[j][i] for j in range(len(lo_t))] for i in range(len(lo_t[0]))],
        [[hi_t[j][i] for j in range(len(hi_t))] for i in range(len(hi_t[0]))],
    )


def _split_row(
    points: list[tuple[Scalar, ...]], t: Scalar
) -> tuple[list[tuple[Scalar, ...]], list[tuple[Scalar, ...]]]:
    work = points
    first, last = [work[0]], [work[-1]]
    while len(work) > 1:
        work = [
            tuple((1 - t) * a + t * b for a, b in zip(p, q, strict=True))
            for p, q in zip(work[:-1], work[1:], strict=True)
        ]
        first.append(work[0])
        last.append(work[-1])
    return first, last[::-1]


def split_float(net: np.ndarray, t: float, axis: int) -> tuple[np.ndarray, np.ndarray]:
    """split_net for a float array (..., M+1, N+1, ...) along `axis`, vectorised."""
    work = np.moveaxis(net, axis, 0)
    size = work.shape[0]
    lo, hi = [work[0]], [work[-1]]
    for _ in range(size - 1):
        work = work[:-1] + t * (work[1:] - work[:-1])
        lo.append(work[0])
        hi.append(work[-1])
    return np.moveaxis(np.stack(lo), 0, axis), np.moveaxis(np.stack(hi[::-1]), 0, axis)


@cache
def _halving(degree: int) -> np.ndarray:
    """(2, N+1, N+1): the nets of the halves [0, 1/2] and [1/2, 1] of a degree-N Bézier
    polynomial as matrices on its net (de Casteljau at 1/2, exact in binary floats)."""
    out = np.zeros((2, degree + 1, degree + 1))
    for i in range(degree + 1):
        for j in range(i + 1):
            out[0, i, j] = comb(i, j) / 2**i
        for j in range(i, degree + 1):
            out[1, i, j] = comb(degree - i, j - i) / 2 ** (degree - i)
    return out


def quarters(net: np.ndarray) -> np.ndarray:
    """(2, 2, M+1, N+1): the nets of a scalar net's four quarters [a/2, (a+1)/2] x
    [b/2, (b+1)/2], by one product with the halving matrices."""
    hu, hv = _halving(net.shape[0] - 1), _halving(net.shape[1] - 1)
    out: np.ndarray = np.einsum("aij,jk,blk->abil", hu, net, hv)
    return out


def bernstein_product(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The Bézier net of the product of two scalar tensor-product Bézier polynomials,
    a (M+1, N+1) and b (P+1, Q+1) → (M+P+1, N+Q+1)."""
    m, n = a.shape[0] - 1, a.shape[1] - 1
    p, q = b.shape[0] - 1, b.shape[1] - 1
    wa = a * np.outer(_binomials(m), _binomials(n))
    wb = b * np.outer(_binomials(p), _binomials(q))
    out = np.zeros((m + p + 1, n + q + 1))
    for i in range(m + 1):
        for j in range(n + 1):
            out[i : i + p + 1, j : j + q + 1] += wa[i, j] * wb
    out /= np.outer(_binomials(m + p), _binomials(n + q))
    return out


@cache
def _binomials(n: int) -> np.ndarray:
    return np.array([comb(n, k) for k in range(n + 1)], dtype=float)


# ---------------------------------------------------------------------- global minimum
def minimise_scalar_net(
    net: np.ndarray,
    value: Callable[[np.ndarray, np.ndarray], np.ndarray],
    polish: Callable[[float, float], tuple[float, float]],
    tol: float | Callable[[float], float],
    max_patches: int = 4_000,
    denominator: np.ndarray | None = None,
) -> tuple[float, float, float, float]:
    """The global minimum over the unit square of a scalar Bézier polynomial f given by its net
    (M+1, N+1), by branch and bound: a patch's lower bound is the least of its net (the
    polynomial lies in the hull), its corners are attained values, and `polish` (Newton from a
    patch centre, kept inside the square) supplies better attained values. `value` evaluates
    f at paired arrays of parameters.

    Returns (u, v, f(u, v), lower): the best point found and a certified lower bound of the
    minimum; stops when the best value exceeds `lower` by at most `tol` (a number, or a
    function of the best value), or after `max_patches` subdivisions with the bound reached
    then (still certified, only looser than `tol`). The budget matters where the minimum is
    attained along a curve (a query point on the axis of a surface of revolution, a level set
    of a scalar field): the net's bound is only O(h²) below the minimum on a patch of size h,
    so every patch along that curve would have to shrink to about sqrt(tol) first.

    With a `denominator` net (the same shape, every entry > 0) f is the rational function
    net / denominator: a patch's bound is then the least ratio of their entries (f is a
    weighted mean of those ratios with positive weights), as for rational Bézier surfaces.
    """
    gap = tol if callable(tol) else (lambda _best: float(tol))
    if denominator is not None:
        net = np.stack([net, denominator], axis=-1)

    def bound(patch: np.ndarray) -> float:
        if denominator is None:
            return float(patch.min())
        return float((patch[..., 0] / patch[..., 1]).min())

    def split(patch: np.ndarray) -> np.ndarray:
        if denominator is None:
            return quarters(patch)
        return np.stack([quarters(patch[..., 0]), quarters(patch[..., 1])], axis=-1)

    best_u, best_v, best = 0.0, 0.0, np.inf
    for u, v in ((0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (0.5, 0.5)):
        cand = _try(u, v, value, polish)
        if cand[2] < best:
            best_u, best_v, best = cand
    # a patch is dropped when its lower bound is within `tol` of the best value then known;
    # `floor` keeps the least such bound, so min(floor, heap) bounds the minimum from below
    import heapq  # here: every program naming a surface would import it otherwise (#29)

    floor = np.inf
    tie = itertools.count()
    heap: list[tuple[float, int, float, float, float, float, np.ndarray]] = [
        (bound(net), next(tie), 0.0, 1.0, 0.0, 1.0, net)
    ]
    splits = 0
    while heap:
        lower = min(heap[0][0], floor)
        allowed = gap(best)
        if best - lower <= allowed:
            return best_u, best_v, best, lower
        lb, _, u0, u1, v0, v1, patch = heapq.heappop(heap)
        if lb > best - allowed:
            floor = min(floor, lb)
            continue
        splits += 1
        if splits > max_patches:
            return best_u, best_v, best, min(lb, heap[0][0] if heap else lb, floor)
        um, vm = (u0 + u1) / 2, (v0 + v1) / 2
        cand = _try(um, vm, value, polish)
        if cand[2] < best:
            best_u, best_v, best = cand
        # the children's corners (a 3 x 3 grid) are attained values: one evaluation
        gu = np.repeat((u0, um, u1), 3)
        gv = np.tile((v0, vm, v1), 3)
        corners = value(gu, gv)
        k = int(np.argmin(corners))
        if corners[k] < best:
            best_u, best_v, best = float(gu[k]), float(gv[k]), float(corners[k])
        children = split(patch)
        for a, (a0, a1) in enumerate(((u0, um), (um, u1))):
            for b, (b0, b1) in enumerate(((v0, vm), (vm, v1))):
                piece = children[a, b]
                lo = bound(piece)
                if lo <= best - gap(best):
                    heapq.heappush(heap, (lo, next(tie), a0, a1, b0, b1, piece))
                else:
                    floor = min(floor, lo)
    return best_u, best_v, best, min(floor, best)


def _try(
    u: float,
    v: float,
    value: Callable[[np.ndarray, np.ndarray], np.ndarray],
    polish: Callable[[float, float], tuple[float, float]],
) -> tuple[float, float, float]:
    pu, pv = polish(u, v)
    both = value(np.array([u, pu]), np.array([v, pv]))
    fa, fb = float(both[0]), float(both[1])
    return (u, v, fa) if fa <= fb else (pu, pv, fb)
