"""A pair's end points, for intersect's certificate (hazmat/intersect_certify.py, and
compiled by certify_compiled.py) and the numpy subdivision (intersect_subdivide.py): which
corners of the parameter square are exact common end points with tangents clearly apart
(`shared_corners`), and which of them a pair of pieces holds (`corner_held`); a root at an
end of one curve only, a T-junction (`end_crossing`), and whether the careful path's root
there merges into the end point it locates (`end_merged`); curves on one line, which the
careful path handles itself (`collinear`, also compiled by settle_compiled). Pure scalar
code on arrays, importing nothing of the engine (its users import it)."""

from __future__ import annotations

import math

import numpy as np


def shared_corners(a: np.ndarray, b: np.ndarray, shared_sine: float) -> int:
    """The corners (i, k) of the parameter square where end i of a (0 at s = 0, 1 at s = 1)
    is end k of b exactly, as a mask (bit 2 i + k); -1 where at one of them the end tangents
    are not clearly apart (a sine of their angle at most shared_sine, or an end that stops):
    the careful path tells tangencies there.

    Halving keeps an end point exactly (the end piece's first or last control point), so the
    pieces holding a shared point are never dropped (both boxes and both fat lines hold it).
    The shared point is a common point known exactly: where a pair of pieces holding it is
    isolated (disjoint hodograph cones: at most one common point on the pair), it is that
    pair's only one, and the certificate records it as it is, with no Newton."""
    n1, n2, dim = a.shape[0] - 1, b.shape[0] - 1, a.shape[1]
    mask = 0
    for i in range(2):
        ra = n1 if i else 0
        for k in range(2):
            rb = n2 if k else 0
            equal = True
            for j in range(dim):
                if a[ra, j] != b[rb, j]:
                    equal = False
            if not equal:
                continue
            # the end tangents: the hodograph's end control points, as _refine measures them
            nu = nv = dot = 0.0
            for j in range(dim):
                da = n1 * (a[n1, j] - a[n1 - 1, j] if i else a[1, j] - a[0, j])
                db = n2 * (b[n2, j] - b[n2 - 1, j] if k else b[1, j] - b[0, j])
                nu += da * da
                nv += db * db
                dot += da * db
            if not nu * nv > 0.0:
                return -1
            sine = math.sqrt(max(nu * nv - dot * dot, 0.0)) / math.sqrt(nu * nv)
            if not sine > shared_sine:
                return -1
            mask |= 1 << (2 * i + k)
    return mask


def corner_held(corners: int, ka: int, kb: int, lev: int) -> int:
    """The shared corner (bit index 2 i + k) the pair of pieces (ka, kb) at level lev holds,
    -1 where it holds none, -2 where it holds more than one."""
    last = (1 << lev) - 1
    held = -1
    for i in range(2):
        if ka != (last if i else 0):
            continue
        for k in range(2):
            if kb != (last if k else 0) or not (corners >> (2 * i + k)) & 1:
                continue
            held = 2 * i + k if held == -1 else -2
    return held


def end_crossing(s: float, t: float, end_margin: float) -> int:
    """Where a refined root (s, t) lies with respect to the ends: -1 inside both ranges by
    end_margin; 2 c + e where it is within end_margin of end e of curve c only (c 0: s, 1:
    t), the other parameter inside its range by end_margin (a T-junction: an end point of
    one curve in the interior of the other); -2 anywhere else (next to a corner, or beyond)."""
    near_s = not (end_margin <= s <= 1 - end_margin)
    near_t = not (end_margin <= t <= 1 - end_margin)
    if not near_s and not near_t:
        return -1
    if near_s and near_t:
        return -2
    x = s if near_s else t
    if abs(x) < end_margin:
        return 2 if near_t else 0
    if abs(x - 1.0) < end_margin:
        return 3 if near_t else 1
    return -2


def end_merged(x: float, y: float, end: float, located: float, same: float) -> bool:
    """The careful path drops an isolated root (x along the curve whose end it is, y along
    the other) as the end point it located there, (end, located): _dedupe_isolated with
    ISOLATED_SAME = same. Held here with a margin of 8 (the two refinements agree to a few
    ulps, not to the bit): both within same / 8, or x clamped to the end exactly and y
    within that margin too (the careful path's test there is the wider SAME_ROOT)."""
    near = abs(y - located) < same / 8
    return near and (abs(x - end) < same / 8 or min(max(x, 0.0), 1.0) == end)


def collinear(a: np.ndarray, b: np.ndarray, tol: float) -> bool:
    """intersect._common_line is not None: every control point of both within tol of one line
    (the points of a, then of b; no array made per point). The careful path refuses or
    reports such curves itself: the compiled careful path (settle_compiled) and the
    certificate decline them."""
    n, dim = a.shape[0], a.shape[1]
    base = a[0]
    far, length = 0, -1.0
    for i in range(n + b.shape[0]):
        x = a[i] if i < n else b[i - n]
        total = 0.0
        for j in range(dim):
            total += (x[j] - base[j]) * (x[j] - base[j])
        d = math.sqrt(total)
        if d > length:
            far, length = i, d
    if length == 0.0:
        return False
    unit = ((a[far] if far < n else b[far - n]) - base) / length
    for i in range(n + b.shape[0]):
        x = a[i] if i < n else b[i - n]
        along = 0.0
        for j in range(dim):
            along += (x[j] - base[j]) * unit[j]
        total = 0.0
        for j in range(dim):
            off = (x[j] - base[j]) - along * unit[j]
            total += off * off
        if math.sqrt(total) > tol:
            return False
    return True
