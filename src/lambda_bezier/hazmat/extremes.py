"""Extremes of polynomial curves given by Taylor coefficients about t = 1/2: tight bounding
boxes and closest points, from the real roots in [0, 1] (roots.py) of a derivative component
or of (p − q)·p', each candidate polished and judged on the full polynomial, the ends always
among the candidates."""

from __future__ import annotations

import functools
import importlib.util
import os
from math import comb
from types import ModuleType

import numpy as np

from . import kernels as alg
from .roots import candidate_roots, newton, newton_pair, significant


def _eval(coeffs: np.ndarray, t: np.ndarray) -> np.ndarray:
    """(len(t), d) values of the polynomial with centred coefficients (d, N+1)."""
    return alg.centred_horner(coeffs, np.ascontiguousarray(t, dtype=float).ravel())


def box(
    p0: np.ndarray, p1: np.ndarray, p2: np.ndarray, ends: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """(lo, hi): the tight axis-aligned box of the polynomial curve with centred coefficients
    p0 (d, N+1), from its values at the ends (`ends`, (2, d): the exact first and last
    control points) and at every root in [0, 1] of each coordinate's derivative (p1, p2: the
    first and second derivatives' coefficients)."""
    candidates = []
    for axis in range(p0.shape[0]):
        c1 = significant(p1[axis])
        c2 = p2[axis : axis + 1]
        if c1.shape[-1] < 2 or not c1.any():
            continue
        roots = candidate_roots(c1)[0]
        roots = roots[np.isfinite(roots)]

        def slope(t: np.ndarray, a: int = axis) -> np.ndarray:
            return _eval(p1[a : a + 1], t)[:, 0]

        def bend(t: np.ndarray, c: np.ndarray = c2) -> np.ndarray:
            return _eval(c, t)[:, 0]

        polished = newton(
            roots.copy(),
            slope,
            bend,
        )
        candidates += [roots, polished]
    t = np.concatenate([np.empty(0), *candidates])
    # a root within 1e-12 of an end adds nothing to the end itself (the coordinate is flat
    # there), and the ends are the Bézier form's first and last control points, exactly
    t = t[(t > 1e-12) & (t < 1 - 1e-12)]
    values = np.vstack([ends, _eval(p0, t)])
    return values.min(axis=0), values.max(axis=0)


# the compiled branch and bound (closest_compiled) when numba is there and not switched off;
# set LAMBDA_BEZIER_NO_NUMBA=1, or USE_COMPILED = False here, for the companion-matrix path
USE_COMPILED = importlib.util.find_spec("numba") is not None and not os.environ.get(
    "LAMBDA_BEZIER_NO_NUMBA"
)


def _compiled() -> ModuleType | None:
    if not USE_COMPILED:
        return None
    from . import closest_compiled

    return closest_compiled


@functools.cache
def centred_to_bernstein(degree: int) -> np.ndarray:
    """(N+1, N+1) M with M[k, e] the k-th Bernstein coefficient of (t - 1/2)^e:
    2^-e sum_j C(e, j) (-1)^(e-j) C(N-e, k-j) / C(N, k) ((t - 1/2) = (t - (1 - t)) / 2,
    raised to degree N by ((1 - t) + t)^(N-e))."""
    n = degree
    out = np.zeros((n + 1, n + 1))
    for e in range(n + 1):
        for k in range(n + 1):
            total = sum(
                comb(e, j) * (-1) ** (e - j) * comb(n - e, k - j)
                for j in range(max(0, k - (n - e)), min(e, k) + 1)
            )
            out[k, e] = total / comb(n, k) / 2.0**e
    return out


@functools.cache
def _product_weights(degree: int) -> np.ndarray:
    """C(N, i) C(N, j) / C(2N, i + j): the Bernstein coefficients of a product of two
    degree-N polynomials from theirs."""
    n = degree
    return np.array(
        [[comb(n, i) * comb(n, j) / comb(2 * n, i + j) for j in range(n + 1)] for i in range(n + 1)]
    )


def closest(c0: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Parameters, points and squared distances of the points of the polynomial curve with
    centred coefficients c0 (d, N+1) nearest to each row of q (m, d): the best of both ends
    and every root in [0, 1] of (p − q)·p'. With numba, closest_compiled's certified branch
    and bound on the Bernstein form of |p − q|²; else the companion matrix's roots."""
    compiled = _compiled()
    if compiled is not None and c0.shape[1] >= 2:
        degree = c0.shape[1] - 1
        bern = np.ascontiguousarray(centred_to_bernstein(degree) @ c0.T)
        t, pts, dist2 = compiled.closest(
            bern, np.ascontiguousarray(q, dtype=float), _product_weights(degree)
        )
        return t, pts, dist2
    return _closest_roots(c0, q)


def _closest_roots(c0: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """closest by the companion matrix: every root in [0, 1] of (p − q)·p', polished."""
    p = significant(c0)  # (d, N'+1) with the true leading term
    m, dim = q.shape
    size = p.shape[1]
    cands = [np.zeros((m, 1)), np.ones((m, 1))]
    if size >= 2:
        dp = alg.differentiate_coefficients(p, 1)  # (d, N')
        # g(u) = (p(u) - q) · p'(u) = Σ_c p_c p'_c − Σ_c q_c p'_c: degree 2N' − 1
        fixed = sum(np.convolve(p[c], dp[c]) for c in range(dim))
        g = np.tile(fixed, (m, 1))
        g[:, : size - 1] -= q @ dp
        roots = candidate_roots(g)
        d2 = alg.differentiate_coefficients(p, 2)
        # p, p' and p'' as the rows of one table (the derivatives' missing top coefficients
        # zero: Horner then gives the same numbers as on their own), so that a Newton step
        # evaluates once, not five times: the per-call cost of numpy's passes is most of a
        # single query's time (issue #29)
        rows = np.zeros((3 * dim, size))
        rows[:dim], rows[dim : 2 * dim, : dp.shape[1]], rows[2 * dim :, : d2.shape[1]] = p, dp, d2

        def g_and_gprime(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            values = _eval(rows, t).reshape(*t.shape, 3 * dim)
            pts, der, sec = values[..., :dim], values[..., dim : 2 * dim], values[..., 2 * dim :]
            off = pts - q[:, None, :]
            g: np.ndarray = (off * der).sum(-1)
            dg: np.ndarray = (der * der).sum(-1) + (off * sec).sum(-1)
            return g, dg

        polished = newton_pair(roots.copy(), g_and_gprime)
        # a missing root (NaN) becomes the end t = 0, a candidate already; roots and polished
        # roots are otherwise finite (clipped to [0, 1], and Newton keeps them there), so
        # np.where does nan_to_num's work here, at a fraction of its cost (issue #29)
        found = np.concatenate([roots, polished], axis=1)
        cands.append(np.where(np.isnan(found), 0.0, found))
    t = np.concatenate(cands, axis=1)
    pts = _eval(c0, t).reshape(*t.shape, dim)
    dist2 = np.square(pts - q[:, None, :]).sum(-1)
    best = np.argmin(dist2, axis=1)
    rows = np.arange(m)
    return t[rows, best], pts[rows, best], dist2[rows, best]
