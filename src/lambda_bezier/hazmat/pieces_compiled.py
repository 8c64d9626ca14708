"""Compiled helpers on one or two Bézier pieces (numba, the `fast` extra), shared by the
compiled intersection kernels (intersect_compiled, certify_compiled, settle_compiled): the
drop tests (boxes, fat lines), hodograph cones, flatness, halving, de Casteljau in scratch
arrays, compensated de Casteljau, and local Newton on a pair of pieces. Each is written once
here; scalar loops on caller-owned scratch arrays, so a kernel allocates nothing per piece.

Imported only by those kernels, and only when numba is installed and not disabled.
"""

from __future__ import annotations

import math
from typing import Any

import numba
import numpy as np

# intersect_subdivide.BLUR (a compile-time constant here; tests/test_fast_paths.py checks they
# agree): the pieces' rounding as a share of the slack
BLUR = 1.0 / 16.0
JIT: dict[str, Any] = {"cache": True, "error_model": "numpy"}

_SPLITTER = 134217729.0  # 2^27 + 1: Dekker's split of a double into two 26-bit halves


@numba.njit(**JIT)
def span_scale(points: np.ndarray) -> tuple[float, float]:
    """(span, scale) as intersect_prepared.Prepared has them: the largest extent of the
    control points, and the larger of that and their largest coordinate (at least 1e-300)."""
    span = 0.0
    big = 0.0
    for j in range(points.shape[1]):
        lo = hi = points[0, j]
        for i in range(points.shape[0]):
            lo, hi = min(lo, points[i, j]), max(hi, points[i, j])
            big = max(big, abs(points[i, j]))
        span = max(span, hi - lo)
    return span, max(span, big, 1e-300)


@numba.njit(**JIT)
def two_sum(a: float, b: float) -> tuple[float, float]:
    s = a + b
    v = s - a
    return s, (a - (s - v)) + (b - v)


@numba.njit(**JIT)
def two_prod(a: float, b: float) -> tuple[float, float]:
    p = a * b
    c = _SPLITTER * a
    ah = c - (c - a)
    al = a - ah
    c = _SPLITTER * b
    bh = c - (c - b)
    bl = b - bh
    return p, ((ah * bh - p) + ah * bl + al * bh) + al * bl


@numba.njit(**JIT)
def value_slope(
    piece: np.ndarray, u: float, work: np.ndarray, value: np.ndarray, slope: np.ndarray
) -> None:
    """p(u) and p'(u) by de Casteljau in the scratch array work (no temporaries)."""
    n, dim = piece.shape[0] - 1, piece.shape[1]
    for i in range(n + 1):
        for j in range(dim):
            work[i, j] = piece[i, j]
    for level in range(n):
        if level == n - 1:
            for j in range(dim):
                slope[j] = n * (work[1, j] - work[0, j])
        for i in range(n - level):
            for j in range(dim):
                work[i, j] += u * (work[i + 1, j] - work[i, j])
    for j in range(dim):
        value[j] = work[0, j]
    if n == 0:
        for j in range(dim):
            slope[j] = 0.0


@numba.njit(**JIT)
def compensated(
    ctrl: np.ndarray, t: float, hi: np.ndarray, lo: np.ndarray, slope: np.ndarray
) -> None:
    """p(t) as hi[0] + lo[0] (compensated de Casteljau, Graillat-Langlois-Louvet), and p'(t)
    in floats into slope. hi, lo: (n+1, d) work arrays."""
    n, dim = ctrl.shape[0] - 1, ctrl.shape[1]
    for i in range(n + 1):
        for j in range(dim):
            hi[i, j] = ctrl[i, j]
            lo[i, j] = 0.0
    _compensated_levels(t, hi, lo, slope)


@numba.njit(**JIT)
def compensated_pair(
    ctrl: np.ndarray,
    ctrl_lo: np.ndarray,
    t: float,
    hi: np.ndarray,
    lo: np.ndarray,
    slope: np.ndarray,
) -> None:
    """compensated() on control points given as double-doubles ctrl + ctrl_lo (a hodograph,
    whose float differences are not exact)."""
    n, dim = ctrl.shape[0] - 1, ctrl.shape[1]
    for i in range(n + 1):
        for j in range(dim):
            hi[i, j] = ctrl[i, j]
            lo[i, j] = ctrl_lo[i, j]
    _compensated_levels(t, hi, lo, slope)


@numba.njit(**JIT)
def _compensated_levels(t: float, hi: np.ndarray, lo: np.ndarray, slope: np.ndarray) -> None:
    """The levels of compensated de Casteljau on hi + lo in place (the errors of each level's
    products and sums carried in lo, error-free transformations)."""
    n, dim = hi.shape[0] - 1, hi.shape[1]
    r, rho = two_sum(1.0, -t)
    if n == 0:
        for j in range(dim):
            slope[j] = 0.0
    for level in range(n):
        if level == n - 1:
            for j in range(dim):
                slope[j] = n * (hi[1, j] - hi[0, j])
        for i in range(n - level):
            for j in range(dim):
                p1, e1 = two_prod(r, hi[i, j])
                p2, e2 = two_prod(t, hi[i + 1, j])
                s, e3 = two_sum(p1, p2)
                lo[i, j] = r * lo[i, j] + t * lo[i + 1, j] + (e1 + e2 + e3 + rho * hi[i, j])
                hi[i, j] = s


@numba.njit(**JIT)
def split(piece: np.ndarray, work: np.ndarray, left: np.ndarray, right: np.ndarray) -> None:
    """de Casteljau at 1/2: left and right halves of piece (work: scratch of its shape)."""
    n, dim = piece.shape[0] - 1, piece.shape[1]
    for i in range(n + 1):
        for j in range(dim):
            work[i, j] = piece[i, j]
    for j in range(dim):
        left[0, j] = work[0, j]
        right[n, j] = work[n, j]
    for r in range(1, n + 1):
        for i in range(n - r + 1):
            for j in range(dim):
                work[i, j] = 0.5 * (work[i, j] + work[i + 1, j])
        for j in range(dim):
            left[r, j] = work[0, j]
            right[n - r, j] = work[n - r, j]


@numba.njit(**JIT)
def cone(points: np.ndarray, axis: np.ndarray, slack: float) -> float:
    """Half-angle of the circular cone about `axis` (written) holding every hodograph
    control point of `points`, widened by the rounding blur of their directions (see
    intersect_subdivide._cones); pi where it is not pointed this way."""
    count, dim = points.shape[0] - 1, points.shape[1]
    good = True
    blur = 0.0
    for j in range(dim):
        axis[j] = 0.0
    for i in range(count):
        norm = 0.0
        for j in range(dim):
            h = points[i + 1, j] - points[i, j]
            norm += h * h
        norm = math.sqrt(norm)
        if norm > 2.0 * BLUR * slack:
            for j in range(dim):
                axis[j] += (points[i + 1, j] - points[i, j]) / norm
            blur = max(blur, math.asin(2.0 * BLUR * slack / norm))
        else:
            good = False
    axis_norm = 0.0
    for j in range(dim):
        axis_norm += axis[j] * axis[j]
    axis_norm = math.sqrt(axis_norm)
    if axis_norm > 0.0:
        for j in range(dim):
            axis[j] /= axis_norm
    else:
        good = False
    if not good:
        return math.pi
    cos = np.inf
    for i in range(count):
        norm = 0.0
        dot = 0.0
        for j in range(dim):
            h = points[i + 1, j] - points[i, j]
            norm += h * h
            dot += h * axis[j]
        c = dot / math.sqrt(norm)
        cos = min(cos, c)
    if not cos > 0.0:
        return math.pi
    return math.acos(min(max(cos, -1.0), 1.0)) + blur


@numba.njit(**JIT)
def pointed(half: float, margin: float) -> bool:
    return half < math.pi / 2 - margin


@numba.njit(**JIT)
def fat_line_apart(a: np.ndarray, b: np.ndarray, slack: float) -> bool:
    """Planar: a's control points lie beyond b's fat line, on one side."""
    cx, cy = b[-1, 0] - b[0, 0], b[-1, 1] - b[0, 1]
    length = math.hypot(cx, cy)
    if not length > 0.0:
        return False
    nx, ny = -cy / length, cx / length
    b_lo, b_hi = np.inf, -np.inf
    for i in range(b.shape[0]):
        dist = (b[i, 0] - b[0, 0]) * nx + (b[i, 1] - b[0, 1]) * ny
        b_lo, b_hi = min(b_lo, dist), max(b_hi, dist)
    a_lo, a_hi = np.inf, -np.inf
    for i in range(a.shape[0]):
        dist = (a[i, 0] - b[0, 0]) * nx + (a[i, 1] - b[0, 1]) * ny
        a_lo, a_hi = min(a_lo, dist), max(a_hi, dist)
    return a_lo > b_hi + slack or a_hi < b_lo - slack


@numba.njit(**JIT)
def boxes_apart(a: np.ndarray, b: np.ndarray, slack: float) -> bool:
    """Axis-aligned boxes of the control points apart by more than slack on some axis."""
    for j in range(a.shape[1]):
        a_lo = a_hi = a[0, j]
        for i in range(1, a.shape[0]):
            a_lo, a_hi = min(a_lo, a[i, j]), max(a_hi, a[i, j])
        b_lo = b_hi = b[0, j]
        for i in range(1, b.shape[0]):
            b_lo, b_hi = min(b_lo, b[i, j]), max(b_hi, b[i, j])
        if a_lo > b_hi + slack or b_lo > a_hi + slack:
            return True
    return False


@numba.njit(**JIT)
def flat_forward(piece: np.ndarray, slack: float) -> bool:
    """Every control point within slack of the chord, and the control polygon running forward
    along it (intersect_subdivide._thickness and _runs_forward)."""
    n, dim = piece.shape[0] - 1, piece.shape[1]
    length = 0.0
    for j in range(dim):
        length += (piece[n, j] - piece[0, j]) ** 2
    length = math.sqrt(length)
    if not length > 0.0:
        return False
    for i in range(n + 1):
        along = 0.0
        for j in range(dim):
            along += (piece[i, j] - piece[0, j]) * (piece[n, j] - piece[0, j]) / length
        off = 0.0
        for j in range(dim):
            r = piece[i, j] - piece[0, j] - along * (piece[n, j] - piece[0, j]) / length
            off += r * r
        if math.sqrt(off) > slack:
            return False
    for i in range(n):
        dot = 0.0
        for j in range(dim):
            dot += (piece[i + 1, j] - piece[i, j]) * (piece[n, j] - piece[0, j])
        if dot < 0.0:
            return False
    return True


@numba.njit(**JIT)
def local_newton(
    a: np.ndarray,
    b: np.ndarray,
    steps: int,
    inside: float,
    wa: np.ndarray,
    wb: np.ndarray,
    vec: np.ndarray,
) -> tuple[float, float, bool]:
    """intersect_subdivide.local_newton on one pair, in scratch arrays (wa, wb: the pieces'
    shapes; vec: (4, d)): Gauss-Newton on a(u) - b(v) from (1/2, 1/2); ok where the last
    step is below 1e-12 inside the pieces."""
    dim = a.shape[1]
    pa, da, pb, db = vec[0], vec[1], vec[2], vec[3]
    u, v, step = 0.5, 0.5, np.inf
    for _ in range(steps):
        value_slope(a, u, wa, pa, da)
        value_slope(b, v, wb, pb, db)
        aa = ab = bb = ga = gb = 0.0
        for j in range(dim):
            f = pa[j] - pb[j]
            aa += da[j] * da[j]
            ab -= da[j] * db[j]
            bb += db[j] * db[j]
            ga -= da[j] * f
            gb += db[j] * f
        det = aa * bb - ab * ab
        du = (bb * ga - ab * gb) / det
        dv = (aa * gb - ab * ga) / det
        u, v = u + du, v + dv
        step = abs(du) + abs(dv)
        if not step > 1e-15:
            break
        if not (-1.0 < u < 2.0 and -1.0 < v < 2.0):
            return u, v, False  # thrown far off: no root of these pieces near (subdivide)
    ok = math.isfinite(step) and step < 1e-12
    ok = ok and -inside <= u <= 1 + inside and -inside <= v <= 1 + inside
    return u, v, ok
