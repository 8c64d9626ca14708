"""Closest points on a polynomial curve, compiled with numba (the `fast` extra): a certified
global minimum of the squared distance, by branch and bound on its Bernstein form.

For a query q, D(t) = |p(t) - q|^2 is a polynomial of degree 2N whose Bernstein coefficients
on [0, 1] follow from p's: D_k = sum over i + j = k of C(N, i) C(N, j) / C(2N, k) (c_i . c_j)
with c_i = P_i - q. On any interval D lies above the least of its coefficients there (the
convex hull property), so an interval whose least coefficient is not below the best value
found so far cannot hold a smaller one and is dropped. An interval is settled without
further halving when the coefficients of D' (differences of D's) change sign at most once
from - to +: D is monotone there (its least value is at an end) or has exactly one critical
point, a minimum (Descartes' rule of signs in the Bernstein basis), found by safeguarded
Newton on (p - q) . p' inside the interval. Every other interval is halved (de Casteljau at
1/2). What is returned is the best of the ends and of those minima: the global minimum,
certified up to the rounding of D's coefficients (a few ulps of their size).

Imported by extremes only when numba is installed and not disabled; numba compiles on first
use and caches the machine code next to this file.
"""

from __future__ import annotations

from typing import Any

import numba
import numpy as np

_JIT: dict[str, Any] = {"cache": True, "error_model": "numpy"}
MAX_INTERVALS = 4096  # intervals examined per query before the best so far is taken
NARROW = 1e-14  # an interval this narrow is settled by its middle


@numba.njit(**_JIT)
def _value_slope(
    pts: np.ndarray, t: float, q: np.ndarray, work: np.ndarray, second: np.ndarray
) -> tuple[float, float]:
    """g = (p(t) - q) . p'(t) and g' = |p'|^2 + (p - q) . p'' from one de Casteljau pass
    (p'' = n (n - 1) (w2 - 2 w1 + w0) of the level with three points, p' = n (w1 - w0) of
    the level with two)."""
    n, dim = pts.shape[0] - 1, pts.shape[1]
    if n == 0:
        return 0.0, 0.0
    for i in range(n + 1):
        for j in range(dim):
            work[i, j] = pts[i, j]
    for j in range(dim):
        second[j] = 0.0
    for level in range(n - 1):
        if level == n - 2:
            for j in range(dim):
                second[j] = n * (n - 1) * (work[2, j] - 2.0 * work[1, j] + work[0, j])
        for i in range(n - level):
            for j in range(dim):
                work[i, j] += t * (work[i + 1, j] - work[i, j])
    g = dg = 0.0
    for j in range(dim):
        point = work[0, j] + t * (work[1, j] - work[0, j])
        slope = n * (work[1, j] - work[0, j])
        g += (point - q[j]) * slope
        dg += slope * slope + (point - q[j]) * second[j]
    return g, dg


@numba.njit(**_JIT)
def _distance2(pts: np.ndarray, t: float, q: np.ndarray, work: np.ndarray) -> float:
    n, dim = pts.shape[0] - 1, pts.shape[1]
    for i in range(n + 1):
        for j in range(dim):
            work[i, j] = pts[i, j]
    for level in range(n):
        for i in range(n - level):
            for j in range(dim):
                work[i, j] += t * (work[i + 1, j] - work[i, j])
    total = 0.0
    for j in range(dim):
        total += (work[0, j] - q[j]) ** 2
    return total


@numba.njit(**_JIT)
def _minimum_inside(
    pts: np.ndarray, q: np.ndarray, lo: float, hi: float, work: np.ndarray, second: np.ndarray
) -> float:
    """The one zero of g = (p - q) . p' in [lo, hi], where g < 0 at lo and > 0 at hi (a
    minimum of D): Newton kept inside a shrinking bracket, bisection where it would leave."""
    a, b = lo, hi
    t = 0.5 * (a + b)
    for _ in range(60):
        g, dg = _value_slope(pts, t, q, work, second)
        if g == 0.0:
            return t
        if g < 0.0:
            a = t
        else:
            b = t
        step = g / dg if dg > 0.0 else np.inf
        nxt = t - step
        if not (a < nxt < b):
            nxt = 0.5 * (a + b)
        if abs(nxt - t) <= 1e-16 * max(1.0, abs(t)) or b - a <= 1e-16:
            return nxt
        t = nxt
    return t


@numba.njit(**_JIT)
def closest(
    pts: np.ndarray, queries: np.ndarray, weights: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The point nearest each query: pts (N+1, d), the Bernstein control points of the
    curve; queries (m, d); weights (N+1, N+1), C(N, i) C(N, j) / C(2N, i + j). Returns
    (t (m,), points (m, d), squared distances (m,))."""
    n, dim = pts.shape[0] - 1, pts.shape[1]
    size = 2 * n + 1
    count = queries.shape[0]
    out = np.empty(count)
    points = np.empty((count, dim))
    dist2 = np.empty(count)
    cap = 2 * 64 + 8
    coeffs = np.empty((cap, size))
    lows = np.empty(cap)
    highs = np.empty(cap)
    diff = np.empty((n + 1, dim))
    work = np.empty((n + 1, dim))
    scratch = np.empty(size)
    left = np.empty(size)
    right = np.empty(size)
    left_out = np.empty(size)
    second = np.empty(dim)
    for m in range(count):
        q = queries[m]
        for i in range(n + 1):
            for j in range(dim):
                diff[i, j] = pts[i, j] - q[j]
        top = 0
        for k in range(size):
            coeffs[0, k] = 0.0
        for i in range(n + 1):
            for k in range(i, n + 1):
                dot = 0.0
                for j in range(dim):
                    dot += diff[i, j] * diff[k, j]
                w = weights[i, k] * dot
                coeffs[0, i + k] += w if i == k else 2.0 * w
        lows[0], highs[0] = 0.0, 1.0
        top = 1
        best = _distance2(pts, 0.0, q, work)
        best_t = 0.0
        end = _distance2(pts, 1.0, q, work)
        if end < best:
            best, best_t = end, 1.0
        examined = 0
        while top > 0:
            top -= 1
            examined += 1
            lo, hi = lows[top], highs[top]
            for k in range(size):
                scratch[k] = coeffs[top, k]
            least = scratch[0]
            for k in range(1, size):
                least = min(least, scratch[k])
            if least >= best:
                continue
            # sign changes of D' (differences of D's coefficients), zeros skipped
            changes = 0
            last = 0.0
            first = 0.0
            for k in range(size - 1):
                d = scratch[k + 1] - scratch[k]
                if d == 0.0:
                    continue
                if first == 0.0:
                    first = d
                if last != 0.0 and (d > 0.0) != (last > 0.0):
                    changes += 1
                last = d
            if changes == 0 or (changes == 1 and first < 0.0):
                if changes == 0:  # monotone: its least value is at an end
                    t = lo if first >= 0.0 else hi
                else:
                    t = _minimum_inside(pts, q, lo, hi, work, second)
                value = _distance2(pts, t, q, work)
                if value < best:
                    best, best_t = value, t
                continue
            if hi - lo <= NARROW or examined >= MAX_INTERVALS or top + 2 > cap:
                t = 0.5 * (lo + hi)
                value = _distance2(pts, t, q, work)
                if value < best:
                    best, best_t = value, t
                continue
            # halve (de Casteljau at 1/2), the half with the smaller least coefficient on top
            for k in range(size):
                left[k] = scratch[k]
            right[size - 1] = scratch[size - 1]
            left_out[0] = scratch[0]
            for r in range(1, size):
                for k in range(size - r):
                    left[k] = 0.5 * (left[k] + left[k + 1])
                left_out[r] = left[0]
                right[size - 1 - r] = left[size - 1 - r]
            mid = 0.5 * (lo + hi)
            least_left = left_out.min()
            least_right = right.min()
            order = (0, 1) if least_left >= least_right else (1, 0)
            for which in order:
                if which == 0:
                    coeffs[top, :] = left_out
                    lows[top], highs[top] = lo, mid
                else:
                    coeffs[top, :] = right
                    lows[top], highs[top] = mid, hi
                top += 1
        out[m] = best_t
        dist2[m] = _distance2(pts, best_t, q, work)
        for j in range(dim):
            points[m, j] = work[0, j]
    return out, points, dist2
