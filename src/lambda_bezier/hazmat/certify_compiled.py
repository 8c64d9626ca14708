"""The certified fast path of curve intersection (intersect_certify), compiled with numba.

One call runs the whole per-pair pipeline for many pairs: subdivision depth first on a small
stack (no arrays allocated per level), the same drop and isolation tests as
intersect_subdivide (boxes, fat lines in the plane, disjoint hodograph cones, local Newton),
then Newton on the whole curves with the residual p(s) - q(t) evaluated by compensated de
Casteljau (error-free transformations: the residual as if computed in twice the working
precision, so the parameters come out as they do with the exact residual of the careful
path), then the checks of the certificate (intersect_certify's docstring) and the merging of
a root found in two neighbouring pairs of pieces. A pair whose certificate fails anywhere is
reported as such at once; the caller runs the careful path on it.

Imported only by intersect_certify, and only when numba is installed and not disabled;
numba compiles on first use and caches the machine code next to this file.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from . import intersect_shared_ends as _ends
from .intersect_compiled import CONTACT_DEEP, contact_cell, contact_tries
from .pieces_compiled import JIT as _JIT
from .pieces_compiled import (
    boxes_apart,
    compensated,
    cone,
    fat_line_apart,
    flat_forward,
    local_newton,
    span_scale,
    split,
    two_sum,
)
from .refine_compiled import Knobs, _curve
from .settle_compiled import _collinear, _locate_all


@numba.njit(**_JIT)
def _refine(
    a: np.ndarray,
    b: np.ndarray,
    s: float,
    t: float,
    work: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
    vec: np.ndarray,
) -> tuple[float, float, float, float, float]:
    """Newton (Gauss-Newton for d > 2) on p(s) - q(t) with the compensated residual, from
    (s, t): (s, t, last step, residual norm, sine of the tangents' angle)."""
    ah, al, bh, bl = work
    dim = a.shape[1]
    da, db, f = vec[0], vec[1], vec[2]
    prev = np.inf
    size = np.inf
    for it in range(16):
        compensated(a, s, ah, al, da)
        compensated(b, t, bh, bl, db)
        for j in range(dim):
            d, e = two_sum(ah[0, j], -bh[0, j])
            f[j] = d + (e + (al[0, j] - bl[0, j]))
        # least squares of [da, -db] (ds, dt) = -f through the 2x2 normal equations
        aa = ab = bb = ga = gb = 0.0
        for j in range(dim):
            aa += da[j] * da[j]
            ab -= da[j] * db[j]
            bb += db[j] * db[j]
            ga -= da[j] * f[j]
            gb += db[j] * f[j]
        det = aa * bb - ab * ab
        if not det > 0.0:
            return s, t, np.inf, np.inf, 0.0
        ds = (bb * ga - ab * gb) / det
        dt = (aa * gb - ab * ga) / det
        s, t = s + ds, t + dt
        size = abs(ds) + abs(dt)
        if not (-0.5 < s < 1.5 and -0.5 < t < 1.5):
            return s, t, np.inf, np.inf, 0.0
        if size < 1e-17 or (it >= 4 and size >= prev):
            break
        prev = size
    compensated(a, s, ah, al, da)
    compensated(b, t, bh, bl, db)
    res = 0.0
    for j in range(dim):
        d, e = two_sum(ah[0, j], -bh[0, j])
        x = d + (e + (al[0, j] - bl[0, j]))
        res += x * x
    nu = nv = dot = 0.0
    for j in range(dim):
        nu += da[j] * da[j]
        nv += db[j] * db[j]
        dot += da[j] * db[j]
    cross2 = max(nu * nv - dot * dot, 0.0)
    sine = math.sqrt(cross2) / math.sqrt(nu * nv) if nu * nv > 0.0 else 0.0
    return s, t, size, math.sqrt(res), sine


# the shared end points' and T-junctions' rules, from the one source the numpy reference runs
_shared_corners = numba.njit(**_JIT)(_ends.shared_corners)
_corner_held = numba.njit(**_JIT)(_ends.corner_held)
_end_crossing = numba.njit(**_JIT)(_ends.end_crossing)
_end_merged = numba.njit(**_JIT)(_ends.end_merged)
HALVES_UP_TO = 60  # half_matrices' binomials exact in int64 up to this degree


@numba.njit(**_JIT)
def half_matrices(n: int) -> tuple[np.ndarray, np.ndarray]:
    """intersect_subdivide.half_matrices(n) (left[i, k] = C(i, k) / 2^i, right[i, k] =
    C(n-i, k-i) / 2^(n-i)), made here: passing them in would cost every pair a Python call,
    and only a T-junction needs them. The binomials from Pascal's triangle, exact in int64
    up to degree HALVES_UP_TO, so the quotients are the same floats."""
    pascal = np.zeros((n + 1, n + 1), np.int64)
    for i in range(n + 1):
        pascal[i, 0] = 1
        for k in range(1, i + 1):
            pascal[i, k] = pascal[i - 1, k - 1] + pascal[i - 1, k]
    left, right = np.zeros((n + 1, n + 1)), np.zeros((n + 1, n + 1))
    for i in range(n + 1):
        for k in range(i + 1):
            left[i, k] = pascal[i, k] / 2.0**i
        for k in range(i, n + 1):
            right[i, k] = pascal[n - i, k - i] / 2.0 ** (n - i)
    return left, right


@numba.njit(**_JIT)
def _end_hit(
    a: np.ndarray,
    b: np.ndarray,
    end: int,
    s: float,
    t: float,
    bound: float,
    drift: float,
    same: float,
    knobs: Knobs,
) -> tuple[bool, float, float]:
    """The careful path's hit at a T-junction: the certified root (s, t) lies next to end
    `end & 1` of curve `end >> 1` (0: a, 1: b) only (_ends.end_crossing), and the careful
    path reports that end point as it locates it on the other curve (settle_compiled's
    _locate_all, the very function and arguments it runs), its own isolated root there
    merged into it. (ok, s, t) of that hit; not ok where the careful path may answer
    otherwise: the point located other than once, or farther than drift from the root; the
    root not merged into it (_ends.end_merged); the control points on one line (the careful
    path declines those)."""
    e = end & 1
    own, other = (a, b) if end >> 1 == 0 else (b, a)
    x, y = (s, t) if end >> 1 == 0 else (t, s)
    if other.shape[0] - 1 > HALVES_UP_TO or _collinear(a, b, bound):
        return False, 0.0, 0.0
    point = own[own.shape[0] - 1 if e else 0]
    _, scale = span_scale(other)
    halves = half_matrices(other.shape[0] - 1)
    located = _locate_all(_curve(other), scale, np.full(1, -1.0), point, 0.0, True, knobs, halves)
    if located.size != 1 or not abs(located[0] - y) <= drift:
        return False, 0.0, 0.0
    if not _end_merged(x, y, float(e), located[0], same):
        return False, 0.0, 0.0
    return (True, float(e), located[0]) if end >> 1 == 0 else (True, located[0], float(e))


# intersect_certify.SETTINGS: depth, max pieces, local Newton steps, inside, cone margin, end
# margin, drift, same, least sine, least sine at a shared end, a shared end's neighbourhood
# (the certificate's knobs, named there)
Settings = tuple[int, int, int, float, float, float, float, float, float, float, float]


@numba.njit(**_JIT)
def _certify_one(
    a: np.ndarray,
    b: np.ndarray,
    slack: float,
    bound: float,
    settings: Settings,
    knobs: Knobs,
    out_s: np.ndarray,
    out_t: np.ndarray,
) -> int:
    """Certified intersections of one pair into out_s, out_t: their count, or -1 where the
    certificate fails (the careful path decides). knobs: the careful path's (intersect.SETTLE),
    for the location of an end point at a T-junction (_end_hit)."""
    depth, max_pieces, newton_steps, inside, margin, end_margin, drift, same, sine_min = settings[
        :9
    ]
    shared_sine, shared_near = settings[9], settings[10]
    n1, n2, dim = a.shape[0], b.shape[0], a.shape[1]
    corners = _shared_corners(a, b, shared_sine)
    if corners < 0:
        return -1
    at_corners = 0  # the shared end points found, as a mask like corners
    planar = dim == 2
    cap = 4 * depth + 8  # depth first: at most 3 siblings wait per level
    sa = np.empty((cap, n1, dim))
    sb = np.empty((cap, n2, dim))
    level = np.empty(cap, dtype=np.int64)
    ia = np.empty(cap, dtype=np.int64)
    ib = np.empty(cap, dtype=np.int64)
    pa, pb = np.empty((n1, dim)), np.empty((n2, dim))
    wa, wb = np.empty((n1, dim)), np.empty((n2, dim))
    la, ra = np.empty((n1, dim)), np.empty((n1, dim))
    lb, rb = np.empty((n2, dim)), np.empty((n2, dim))
    axis_a, axis_b = np.empty(dim), np.empty(dim)
    vec4 = np.empty((4, dim))
    room = out_s.shape[0]
    start_s, start_t = np.empty(room), np.empty(room)
    found = 0
    sa[0], sb[0] = a, b
    level[0] = ia[0] = ib[0] = 0
    top = 1
    popped = 0
    while top > 0:
        top -= 1
        popped += 1
        if popped > max_pieces:
            return -1
        pa[:], pb[:] = sa[top], sb[top]
        lev, ka, kb = level[top], ia[top], ib[top]
        if boxes_apart(pa, pb, slack):
            continue
        if planar and (fat_line_apart(pa, pb, slack) or fat_line_apart(pb, pa, slack)):
            continue
        if lev == depth:
            return -1  # unresolved at the depth: a tangency, or crossings closer than that
        width = 0.5**lev
        half_a = cone(pa, axis_a, slack)
        half_b = cone(pb, axis_b, slack)
        if half_a < math.pi / 2 - margin and half_b < math.pi / 2 - margin:
            dot = 0.0
            for j in range(dim):
                dot += axis_a[j] * axis_b[j]
            between = math.acos(min(abs(dot), 1.0))
            if between > half_a + half_b + margin:
                held = _corner_held(corners, ka, kb, lev) if corners else -1
                if held == -2:
                    return -1
                if held >= 0:  # its only common point: the shared end point, exactly
                    at_corners |= 1 << held
                    continue
                u, v, ok = local_newton(pa, pb, newton_steps, inside, la, lb, vec4)
                if ok:
                    if found == room:
                        return -1
                    start_s[found] = (ka + min(max(u, 0.0), 1.0)) * width
                    start_t[found] = (kb + min(max(v, 0.0), 1.0)) * width
                    found += 1
                    continue
        if flat_forward(pa, slack) and flat_forward(pb, slack):
            return -1  # flat to rounding on both sides: the careful path's tangent refinement
        # a tangency, confined to a cell around its contact (intersect_contact): likewise
        if (
            planar
            and contact_tries(lev)
            and contact_cell(pa, pb, ka, kb, lev, CONTACT_DEEP, slack)[0]
        ):
            return -1
        if top + 4 > cap:
            return -1
        split(pa, wa, la, ra)
        split(pb, wb, lb, rb)
        for c in range(4):
            sa[top] = la if c < 2 else ra
            sb[top] = lb if c % 2 == 0 else rb
            level[top] = lev + 1
            ia[top] = 2 * ka + (0 if c < 2 else 1)
            ib[top] = 2 * kb + c % 2
            top += 1
    # refinement on the whole curves; every root must pass the certificate's checks
    work = (np.empty((n1, dim)), np.empty((n1, dim)), np.empty((n2, dim)), np.empty((n2, dim)))
    vec = np.empty((3, dim))
    count = 0
    tee, tee_s, tee_t = -1, 0.0, 0.0  # a root at an end of one curve only (a T-junction)
    for k in range(found):
        s, t, step, res, sine = _refine(a, b, start_s[k], start_t[k], work, vec)
        if not (step < 1e-12 and res <= bound and sine > sine_min):
            return -1
        if abs(s - start_s[k]) > drift or abs(t - start_t[k]) > drift:
            return -1
        end = _end_crossing(s, t, end_margin)
        if end >= 0:  # its end point located on the other curve below, as the careful path
            if tee >= 0 and end == tee and abs(s - tee_s) < same and abs(t - tee_t) < same:
                continue  # the same root, found in the next pair of pieces
            if tee >= 0 or corners or not sine > shared_sine:
                return -1  # the careful path's (two end hits, or a small angle)
            tee, tee_s, tee_t = end, s, t
            continue
        if end == -2:
            return -1  # next to a corner: the careful path locates the ends exactly
        for m in range(4):  # the careful path may merge hits this close (_add)
            near = abs(s - (m >> 1)) < shared_near and abs(t - (m & 1)) < shared_near
            if (at_corners >> m) & 1 and near:
                return -1
        duplicate = False
        for m in range(count):
            if abs(out_s[m] - s) < same and abs(out_t[m] - t) < same:
                duplicate = True
        if not duplicate:
            out_s[count] = s
            out_t[count] = t
            count += 1
    for m in range(4):  # last, in the order of (s, t): a stable sort by s keeps it
        if (at_corners >> m) & 1:
            if count == room:
                return -1
            out_s[count] = float(m >> 1)
            out_t[count] = float(m & 1)
            count += 1
    if tee >= 0:
        if count == room:
            return -1
        ok, x, y = _end_hit(a, b, tee, tee_s, tee_t, bound, drift, same, knobs)
        if not ok:
            return -1
        for m in range(count):  # the careful path may merge hits this close (_add)
            if abs(out_s[m] - x) < shared_near and abs(out_t[m] - y) < shared_near:
                return -1
        out_s[count], out_t[count] = x, y
        count += 1
    return count


@numba.njit(**_JIT)
def certify(
    a: np.ndarray,
    b: np.ndarray,
    slack: np.ndarray,
    bound: np.ndarray,
    settings: Settings,
    knobs: Knobs,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """P pairs (P, n+1, d) and (P, m+1, d): (count (P,), -1 where the certificate fails;
    s (P, room), t (P, room)), the first count entries of each row being its roots."""
    pairs = a.shape[0]
    room = 4 * a.shape[1] * b.shape[1] + 8  # Bezout's n m roots, each in up to 4 pieces
    counts = np.empty(pairs, dtype=np.int64)
    out_s = np.zeros((pairs, room))
    out_t = np.zeros((pairs, room))
    for k in range(pairs):
        counts[k] = _certify_one(
            a[k],
            b[k],
            slack[k],
            bound[k],
            settings,
            knobs,
            out_s[k],
            out_t[k],
        )
    return counts, out_s, out_t


@numba.njit(**_JIT)
def certify_one(
    a: np.ndarray,
    b: np.ndarray,
    box_slack: float,
    root_residual: float,
    settings: Settings,
    knobs: Knobs,
) -> tuple[int, np.ndarray]:
    """One pair, with its slack and residual bound computed here as the careful path does
    (intersect._slack, _root_bound): (count, roots) with roots (2, count) the s and t of its
    crossings, sorted by s; count -1 where the certificate fails (or either curve is a point:
    the careful path says so). One array returned, not two: boxing each result array costs
    a share of a small pair's whole time (issue #29)."""
    span_a, scale_a = span_scale(a)
    span_b, scale_b = span_scale(b)
    room = 4 * a.shape[0] * b.shape[0] + 8
    out_s = np.zeros(room)
    out_t = np.zeros(room)
    if span_a == 0.0 or span_b == 0.0:
        return -1, np.empty((2, 0))
    degree = max(a.shape[0], b.shape[0]) - 1
    scale = max(scale_a, scale_b)
    count = _certify_one(
        a,
        b,
        box_slack * degree * scale,
        root_residual * degree * scale,
        settings,
        knobs,
        out_s,
        out_t,
    )
    for k in range(1, max(count, 0)):  # insertion sort by s: a handful of roots
        s, t = out_s[k], out_t[k]
        m = k - 1
        while m >= 0 and out_s[m] > s:
            out_s[m + 1], out_t[m + 1] = out_s[m], out_t[m]
            m -= 1
        out_s[m + 1], out_t[m + 1] = s, t
    roots = np.empty((2, max(count, 0)))
    roots[0], roots[1] = out_s[: roots.shape[1]], out_t[: roots.shape[1]]
    return count, roots
