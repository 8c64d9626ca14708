"""Extremes of polynomial curves given by Taylor coefficients about t = 1/2: tight bounding
boxes, from the real roots in [0, 1] (roots.py) of each derivative component, each candidate
polished and judged on the full polynomial, the ends always among the candidates; and
closest points, by a certified branch and bound on the Bernstein form of |p − q|²
(closest_compiled with numba, closest_numpy without)."""

from __future__ import annotations

import functools
import importlib.util
import os
from math import comb
from types import ModuleType

import numpy as np

from . import closest_numpy
from . import kernels as alg
from .roots import candidate_roots, newton, significant


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
# set LAMBDA_BEZIER_NO_NUMBA=1, or USE_COMPILED = False here, for closest_numpy's
USE_COMPILED = importlib.util.find_spec("numba") is not None and not os.environ.get(
    "LAMBDA_BEZIER_NO_NUMBA"
)


# without numba, closest_numpy's branch and bound runs breadth first over all queries at once
# from this many queries on, and query by query on Python floats below (measured crossover
# 16-32 queries at degrees 3 and 8)
BREADTH_FIRST_FROM = 16


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
    and every minimum of |p − q|² inside, by a certified branch and bound on its Bernstein
    form: closest_compiled's with numba, else closest_numpy's (the same method in numpy;
    query by query on Python floats for a few queries)."""
    queries = np.ascontiguousarray(q, dtype=float)
    if c0.shape[1] < 2:  # a point: every t is nearest; t = 0, as the branch and bound's ends
        pts = np.repeat(c0.T, queries.shape[0], axis=0)
        return np.zeros(queries.shape[0]), pts, np.square(pts - queries).sum(-1)
    degree = c0.shape[1] - 1
    bern = np.ascontiguousarray(centred_to_bernstein(degree) @ c0.T)
    compiled = _compiled()
    if compiled is not None:
        t, pts, dist2 = compiled.closest(bern, queries, _product_weights(degree))
        return t, pts, dist2
    if queries.shape[0] < BREADTH_FIRST_FROM:
        return closest_numpy.closest_few(c0, bern, queries)
    return closest_numpy.closest(c0, bern, queries)
