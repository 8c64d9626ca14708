"""The careful path of curve intersection (hazmat.intersect) compiled with numba, for the
pairs the certificate declines: end points located on the other curve, tangencies refined on
the tangent system, the merging of hits that are one, all in one call.

It is intersect's careful path step for step (the same subdivisions, the same Newton starts,
iterations, tolerances and merging rules, in the same order), with one change of means: where
the careful path evaluates a residual exactly in rationals, this kernel evaluates it by
compensated de Casteljau (error-free transformations: as accurate as twice the working
precision), which decides the same comparisons at the tolerances involved (64 eps of the
curves' size and above). A stretch the curves share as one polynomial piece (the careful
path's _same_piece, an affine change of parameter) it reports as the careful path does: its
two ends, kind coincident, the subdivision skipping its rectangle. Two things it does not
do, and declines instead (count -1: the caller runs the careful path): a stretch between two
end hits that may be one arc under another parameterisation (the careful path's first test
point of _same_image lying once on the other stretch), and curves whose control points all
lie on one line (the careful path refuses or reports those). Hits are returned with kinds
-1 (coincident), 0 (tangent) and 1 (transversal), sorted as the careful
path sorts them. The refinement steps (Newton, tangent refinement, a hit's acceptance and
merging) are refine_compiled's; the subdivision, the Newton starts, point location and the
pair's driver are here.

Imported only by intersect_certify, and only when numba is installed and not disabled.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from . import intersect_shared_ends as _ends
from .intersect_compiled import (
    CONTACT_DEEP,
    _local_foot_newton,
    contact_cell,
    contact_tries,
    isolate_points,
)
from .pieces_compiled import JIT as _JIT
from .pieces_compiled import (
    boxes_apart,
    cone,
    fat_line_apart,
    flat_forward,
    local_newton,
    pointed,
    span_scale,
)
from .refine_compiled import (
    COINCIDENT,
    TANGENT,
    TRANSVERSAL,
    Curve,
    Halves,
    Knobs,
    _add,
    _curve,
    _d,
    _d_into,
    _gap,
    _near,
    _near_isolated,
    _norm,
    _sine,
    _size,
    _solve_from,
    _value_minus,
)


# ---------------------------------------------------------------------------- subdivision
@numba.njit(**_JIT)
def _halve(piece: np.ndarray, matrix: np.ndarray, out: np.ndarray) -> None:
    """intersect_compiled._halve on one piece (the same sums in the same order)."""
    size, dim = piece.shape
    for i in range(size):
        for j in range(dim):
            out[i, j] = 0.0
        for m in range(size):
            w = matrix[i, m]
            if w != 0.0:
                for j in range(dim):
                    out[i, j] += w * piece[m, j]


@numba.njit(**_JIT)
def _grow(values: np.ndarray) -> np.ndarray:
    """values in an array twice as long (the rest unset)."""
    out = np.empty(2 * values.size, values.dtype)
    out[: values.size] = values
    return out


@numba.njit(**_JIT)
def _breadth_first(level: np.ndarray, ia: np.ndarray, ib: np.ndarray, count: int) -> np.ndarray:
    """The order (indices) of count pairs of pieces in intersect_compiled.isolate's
    breadth-first subdivision: by level, then by the children's block (2 a-bit + b-bit) of
    the latest halving, then of the one before, and so on (each level's children are four
    blocks, each in the parents' order). The blocks as base-4 digits, latest first, in two
    keys of 16 digits each; stable sorts from the least significant key."""
    if count <= 1:  # nothing to order (most calls: a point located once, a pair of lines)
        return np.arange(count)
    high, low = np.zeros(count, np.int64), np.zeros(count, np.int64)
    for k in range(count):
        for j in range(level[k]):
            digit = 2 * ((ia[k] >> j) & 1) + ((ib[k] >> j) & 1)
            if j < 16:
                high[k] += digit << (2 * (15 - j))
            else:
                low[k] += digit << (2 * (31 - j))
    order = np.argsort(low[:count], kind="mergesort")
    order = order[np.argsort(high[order], kind="mergesort")]
    return order[np.argsort(level[:count][order], kind="mergesort")]


@numba.njit(**_JIT)
def _skipped(ka: int, kb: int, width: float, skip: np.ndarray, skips: int) -> bool:
    """The pair of pieces ka, kb of this width lies inside a shared stretch's rectangle."""
    for r in range(skips):
        if (
            ka * width >= skip[r, 0]
            and (ka + 1) * width <= skip[r, 1]
            and kb * width >= skip[r, 2]
            and (kb + 1) * width <= skip[r, 3]
        ):
            return True
    return False


@numba.njit(**_JIT)
def _isolate(
    a: np.ndarray,
    b: np.ndarray,
    slack: float,
    depth: int,
    budget: int,
    steps: int,
    inside: float,
    margin: float,
    halves_a: tuple[np.ndarray, np.ndarray],
    halves_b: tuple[np.ndarray, np.ndarray],
    skip: np.ndarray,
    skips: int,
) -> tuple[bool, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """intersect_compiled.isolate for one pair (not a curve against itself) depth first on
    a small stack, its roots and unresolved pieces put back in its breadth-first order:
    (within budget, root s, root t, left s0, left t0, left width). The pieces are halved
    with the same matrices, so the same pairs are dropped, isolated or left. skip[:skips]:
    the rectangles (s0, s1, t0, t1) of shared stretches, whose pairs of pieces are dropped
    as intersect_compiled.isolate drops them."""
    n1, n2, dim = a.shape[0], b.shape[0], a.shape[1]
    planar = dim == 2
    cap = 4 * depth + 8
    if depth > 32:  # _breadth_first's keys hold 32 halvings
        return False, np.empty(0), np.empty(0), np.empty(0), np.empty(0), np.empty(0)
    sa, sb = np.empty((cap, n1, dim)), np.empty((cap, n2, dim))
    level, ia, ib = np.empty(cap, np.int64), np.empty(cap, np.int64), np.empty(cap, np.int64)
    axis_a, axis_b = np.empty(dim), np.empty(dim)
    wa, wb = np.empty((n1, dim)), np.empty((n2, dim))
    pa, pb = np.empty((n1, dim)), np.empty((n2, dim))
    vec4 = np.empty((4, dim))
    half_a0, half_a1 = np.empty((n1, dim)), np.empty((n1, dim))
    half_b0, half_b1 = np.empty((n2, dim)), np.empty((n2, dim))
    room = 64
    r_lev, r_ia, r_ib = np.empty(room, np.int64), np.empty(room, np.int64), np.empty(room, np.int64)
    r_s, r_t = np.empty(room), np.empty(room)
    l_lev, l_ia, l_ib = np.empty(room, np.int64), np.empty(room, np.int64), np.empty(room, np.int64)
    l_s, l_t, l_w = np.empty(room), np.empty(room), np.empty(room)
    cell = 0.5**CONTACT_DEEP
    roots = lefts = 0
    sa[0], sb[0] = a, b
    level[0] = ia[0] = ib[0] = 0
    top, popped = 1, 0
    while top > 0:
        top -= 1
        popped += 1
        if popped > budget:
            return False, r_s[:0], r_t[:0], r_s[:0], r_s[:0], r_s[:0]
        pa[:, :] = sa[top]
        pb[:, :] = sb[top]
        lev, ka, kb = level[top], ia[top], ib[top]
        if boxes_apart(pa, pb, slack):
            continue
        if planar and (fat_line_apart(pa, pb, slack) or fat_line_apart(pb, pa, slack)):
            continue
        if _skipped(ka, kb, 0.5**lev, skip, skips):
            continue
        width = 0.5**lev
        s0, t0 = ka * width, kb * width  # where it is left (or its contact's cell)
        leave = lev == depth
        if not leave:
            half_a, half_b = cone(pa, axis_a, slack), cone(pb, axis_b, slack)
            if pointed(half_a, margin) and pointed(half_b, margin):
                dot = 0.0
                for j in range(dim):
                    dot += axis_a[j] * axis_b[j]
                between = math.acos(min(max(abs(dot), 0.0), 1.0))
                if between > half_a + half_b + margin:
                    u, v, ok = local_newton(pa, pb, steps, inside, wa, wb, vec4)
                    if ok:
                        if roots == r_lev.size:
                            r_lev, r_ia, r_ib = _grow(r_lev), _grow(r_ia), _grow(r_ib)
                            r_s, r_t = _grow(r_s), _grow(r_t)
                        r_lev[roots], r_ia[roots], r_ib[roots] = lev, ka, kb
                        r_s[roots] = (ka + min(max(u, 0.0), 1.0)) * width
                        r_t[roots] = (kb + min(max(v, 0.0), 1.0)) * width
                        roots += 1
                        continue
            leave = flat_forward(pa, slack) and flat_forward(pb, slack)
            if not leave and planar and contact_tries(lev):
                # a tangency confined to a small cell (intersect_contact): left as that cell
                leave, ca, cb = contact_cell(pa, pb, ka, kb, lev, CONTACT_DEEP, slack)
                if leave:
                    s0, t0, width = ca * cell, cb * cell, cell
        if leave:
            if lefts == l_lev.size:
                l_lev, l_ia, l_ib = _grow(l_lev), _grow(l_ia), _grow(l_ib)
                l_s, l_t, l_w = _grow(l_s), _grow(l_t), _grow(l_w)
            l_lev[lefts], l_ia[lefts], l_ib[lefts] = lev, ka, kb
            l_s[lefts], l_t[lefts], l_w[lefts] = s0, t0, width
            lefts += 1
            continue
        if top + 4 > cap:
            return False, r_s[:0], r_t[:0], r_s[:0], r_s[:0], r_s[:0]
        # children pushed last block first, so the stack pops them in block order; each
        # half of each piece computed once (a tangency keeps this loop busy to depth ~24)
        _halve(pa, halves_a[0], half_a0)
        _halve(pa, halves_a[1], half_a1)
        _halve(pb, halves_b[0], half_b0)
        _halve(pb, halves_b[1], half_b1)
        for c in range(3, -1, -1):
            sa[top] = half_a1 if c // 2 else half_a0
            sb[top] = half_b1 if c % 2 else half_b0
            level[top] = lev + 1
            ia[top] = 2 * ka + c // 2
            ib[top] = 2 * kb + c % 2
            top += 1
    order = _breadth_first(r_lev, r_ia, r_ib, roots)
    root_s, root_t = r_s[order], r_t[order]
    order = _breadth_first(l_lev, l_ia, l_ib, lefts)
    left_s0, left_t0, left_w = np.empty(lefts), np.empty(lefts), np.empty(lefts)
    for m in range(lefts):
        k = order[m]
        left_s0[m], left_t0[m], left_w[m] = l_s[k], l_t[k], l_w[k]
    return True, root_s, root_t, left_s0, left_t0, left_w


# ---------------------------------------------------------------------------- starts
@numba.njit(**_JIT)
def _root(parent: np.ndarray, k: int) -> int:
    while parent[k] != k:
        parent[k] = parent[parent[k]]
        k = parent[k]
    return k


@numba.njit(**_JIT)
def _starts(
    s0: np.ndarray, t0: np.ndarray, width: np.ndarray, per_cluster: int = 6
) -> tuple[np.ndarray, np.ndarray]:
    """intersect._starts (with _interval_clusters): Newton starts for unresolved pairs of
    pieces, cluster by cluster in the same order."""
    count = s0.size
    if count == 0:
        return np.empty(0), np.empty(0)
    parent = np.arange(count)
    order = np.argsort(s0, kind="mergesort")
    active = np.empty(count, dtype=np.int64)
    live = 0
    for k in order:
        kept = 0
        for m in range(live):
            j = active[m]
            if s0[j] + width[j] >= s0[k] - 1e-15:
                active[kept] = j
                kept += 1
        live = kept
        for m in range(live):
            j = active[m]
            if t0[j] <= t0[k] + width[k] + 1e-15 and t0[k] <= t0[j] + width[j] + 1e-15:
                parent[_root(parent, j)] = _root(parent, k)
        active[live] = k
        live += 1
    roots = np.empty(count, dtype=np.int64)
    for k in range(count):
        roots[k] = _root(parent, k)
    out_s, out_t = np.empty(count), np.empty(count)
    made = 0
    seen = np.zeros(count, dtype=np.bool_)
    for first in range(count):  # groups in the order of their first member
        if seen[roots[first]]:
            continue
        seen[roots[first]] = True
        members = np.array([k for k in range(count) if roots[k] == roots[first]])
        centre = np.empty(members.size)
        for m in range(members.size):
            k = members[m]
            centre[m] = (s0[k] + width[k] / 2) + (t0[k] + width[k] / 2)
        ordered = members[np.argsort(centre, kind="mergesort")]
        size = ordered.size
        if size <= per_cluster:
            picks = ordered.copy()
        else:
            spots = min(per_cluster, size)
            step = (size - 1) / (spots - 1)  # numpy.linspace(0, size - 1, spots), truncated
            extra = [ordered[size // 2]]
            last = -1
            for i in range(spots):
                x = int(i * step) if i < spots - 1 else size - 1
                if x != last and ordered[x] != ordered[size // 2]:
                    extra.append(ordered[x])
                last = x
            picks = np.array(extra)
        for k in picks:
            out_s[made] = s0[k] + width[k] / 2
            out_t[made] = t0[k] + width[k] / 2
            made += 1
    return out_s[:made], out_t[:made]


# ---------------------------------------------------------------------------- locate
@numba.njit(**_JIT)
def _isolate_point(
    pts: np.ndarray,
    point: np.ndarray,
    slack: float,
    depth: int,
    max_rows: int,
    steps: int,
    inside: float,
    margin: float,
    halves: Halves,
) -> tuple[bool, np.ndarray, np.ndarray, np.ndarray]:
    """intersect_compiled.isolate_points for one curve and one point, depth first on a small
    stack with no arrays allocated per piece (it runs four times per pair, for the end
    points): (ok, root s, left s0, left width), roots and left pieces in isolate_points'
    breadth-first order, the pieces halved with the same matrices and put through the same
    tests, so the same pieces are dropped, isolated or left. Not ok when a level holds more
    pieces than the row guard allows (where isolate_points stops the whole level early)."""
    size, dim = pts.shape
    planar = dim == 2
    if depth > 32:  # _breadth_first's keys hold 32 halvings
        return False, np.empty(0), np.empty(0), np.empty(0)
    cap = 2 * depth + 4
    # the work arrays as views of three allocations (each costs ~50 ns, a share of a
    # location, which runs four times per pair the certificate declines; issue #29)
    stack = np.empty((cap + 3, size, dim))
    piece, left_half, right_half = stack[cap], stack[cap + 1], stack[cap + 2]
    room = 16
    ints = np.empty(2 * cap + depth + 1 + 4 * room, np.int64)
    level, index = ints[:cap], ints[cap : 2 * cap]
    alive = ints[2 * cap : 2 * cap + depth + 1]
    alive[:] = 0
    found = ints[2 * cap + depth + 1 :]  # the roots' and left pieces' levels and indices
    r_lev, r_ix = found[:room], found[room : 2 * room]
    l_lev, l_ix = found[2 * room : 3 * room], found[3 * room :]
    floats = np.empty(room + dim)
    r_s, axis = floats[:room], floats[room:]
    target = point.reshape((1, dim))
    roots = lefts = 0
    stack[0] = pts
    level[0] = index[0] = 0
    top = 1
    while top > 0:
        top -= 1
        piece[:, :] = stack[top]
        lev, k = level[top], index[top]
        dropped = False
        for j in range(dim):
            lo = hi = piece[0, j]
            for i in range(1, size):
                lo, hi = min(lo, piece[i, j]), max(hi, piece[i, j])
            if not (lo <= point[j] + slack and point[j] - slack <= hi):
                dropped = True
        if dropped or (planar and fat_line_apart(target, piece, slack)):
            continue
        alive[lev] += 1
        if 2 * alive[lev] > max_rows:
            return False, np.empty(0), np.empty(0), np.empty(0)
        leave = lev == depth
        if not leave:
            if pointed(cone(piece, axis, slack), margin):
                u, ok = _local_foot_newton(piece, point, steps, inside, slack)
                if ok:
                    if roots == r_lev.size:
                        r_lev, r_ix, r_s = _grow(r_lev), _grow(r_ix), _grow(r_s)
                    r_lev[roots], r_ix[roots] = lev, k
                    r_s[roots] = (k + min(max(u, 0.0), 1.0)) * 0.5**lev
                    roots += 1
                    continue
            leave = flat_forward(piece, slack)
        if leave:
            if lefts == l_lev.size:
                l_lev, l_ix = _grow(l_lev), _grow(l_ix)
            l_lev[lefts], l_ix[lefts] = lev, k
            lefts += 1
            continue
        _halve(piece, halves[0], left_half)
        _halve(piece, halves[1], right_half)
        stack[top], level[top], index[top] = right_half, lev + 1, 2 * k + 1
        stack[top + 1], level[top + 1], index[top + 1] = left_half, lev + 1, 2 * k
        top += 2
    if roots <= 1 and lefts == 0:  # nothing to order (most locations)
        return True, r_s[:roots], r_s[:0], r_s[:0]
    none = np.zeros(max(roots, lefts), np.int64)
    order = _breadth_first(r_lev, none, r_ix, roots)
    root_s = r_s[order]
    order = _breadth_first(l_lev, none, l_ix, lefts)
    left_s0, left_w = np.empty(lefts), np.empty(lefts)
    for m in range(lefts):
        width = 0.5 ** l_lev[order[m]]
        left_s0[m], left_w[m] = l_ix[order[m]] * width, width
    return True, root_s, left_s0, left_w


@numba.njit(**_JIT)
def _locate_newton(c: Curve, point: np.ndarray, t: float) -> float:
    """intersect._locate_newton: nan where it leaves the domain."""
    dim = point.shape[0]
    pts = c[0]
    work = np.empty((4, dim))  # one allocation, not four
    diff, x, d1, d2 = work[0], work[1], work[2], work[3]
    for phase in range(2):
        exact = phase == 1
        prev = np.inf
        for it in range(3 if exact else 40):
            if exact:
                _value_minus(pts, t, point, c[4][1], c[4][2], diff, c[4][3][0])
            else:
                _d_into(c, t, 0, x)
                for j in range(dim):
                    diff[j] = x[j] - point[j]
            _d_into(c, t, 1, d1)
            _d_into(c, t, 2, d2)
            slope = 0.0
            lead = 0.0
            for j in range(dim):
                slope += d1[j] * d1[j]
            for j in range(dim):
                lead += diff[j] * d2[j]
            slope += lead
            if slope == 0.0:
                break
            num = 0.0
            for j in range(dim):
                num += diff[j] * d1[j]
            step = num / slope
            t -= step
            if not -0.5 < t < 1.5:
                return np.nan
            if abs(step) < 1e-16 or (it > 5 and abs(step) > 0.5 * prev):
                break
            prev = abs(step)
    if -1e-12 <= t <= 1 + 1e-12:
        return min(max(t, 0.0), 1.0)
    return np.nan


@numba.njit(**_JIT)
def _distance(c: Curve, t: float, point: np.ndarray) -> float:
    diff = c[4][4][0]
    _value_minus(c[0], t, point, c[4][1], c[4][2], diff, c[4][3][0])
    return float(_norm(diff))


@numba.njit(**_JIT)
def _rounding_at(c: Curve, t: float, root_residual: float) -> float:
    """intersect._rounding_at: root_residual (n sum |b_i| B_i(t) + |c'(t)|)."""
    pts = c[0]
    n = pts.shape[0] - 1
    work = c[4][4][:, 0]  # the curve's scratch (row 4, for one helper at a time; row 3's
    slope = c[4][3][0]  # first vector is written by others and read by none), no allocation
    for i in range(n + 1):
        work[i] = _norm(pts[i])
    for level in range(n):
        for i in range(n - level):
            work[i] = work[i] + t * (work[i + 1] - work[i])
    _d_into(c, t, 1, slope)
    return float(root_residual * (n * work[0] + _norm(slope)))


@numba.njit(**_JIT)
def _chord_bracket(c: Curve, point: np.ndarray, s0: float, s1: float, wide: float) -> float:
    chord = _d(c, s1, 0) - _d(c, s0, 0)
    x = c[4][4][0]
    while s1 - s0 > wide:
        middle = 0.5 * (s0 + s1)
        _d_into(c, middle, 0, x)
        dot = 0.0
        for j in range(point.shape[0]):
            dot += (x[j] - point[j]) * chord[j]
        if dot < 0.0:
            s0 = middle
        else:
            s1 = middle
    return 0.5 * (s0 + s1)


@numba.njit(**_JIT)
def _locate_all(
    c: Curve,
    scale: float,
    size: np.ndarray,
    point: np.ndarray,
    accept: float,
    exact_end: bool,
    knobs: Knobs,
    halves: Halves,
) -> np.ndarray:
    """intersect.locate_all for a float point, within=accept or exact_end: every t with
    c(t) = point. size: the curve's Prepared.size in a one-element array, negative until
    first needed (only to merge two locations: most pairs never need it, and its 129
    samples cost ~1 µs a curve)."""
    on_curve_rel, same_root, wide = knobs[0], knobs[1], knobs[7]
    depth, max_rows, steps, inside, margin = knobs[10], knobs[11], knobs[12], knobs[13], knobs[14]
    pts = c[0]
    n, dim = pts.shape[0] - 1, pts.shape[1]
    big = 0.0
    for j in range(dim):
        big = max(big, abs(point[j]))
    tol = on_curve_rel * max(scale, big)
    found = [0.0 for _ in range(0)]
    for end in range(2):
        equal = True
        for j in range(dim):
            if pts[n if end else 0, j] != point[j]:
                equal = False
        if equal:
            found.append(float(end))
    for j in range(dim):  # the point beyond the control points' box: isolate_points drops it
        lo, hi = pts[0, j], pts[0, j]
        for i in range(n + 1):
            lo, hi = min(lo, pts[i, j]), max(hi, pts[i, j])
        if not (lo <= point[j] + tol and point[j] - tol <= hi):
            return np.sort(np.array(found))
    ok, root_s, left_s0, left_width = _isolate_point(
        pts, point, tol, depth, max_rows, steps, inside, margin, halves
    )
    if not ok:  # the row guard tripped: the breadth-first loop, which knows where it stops
        _, root_s, _, left_s0, left_width = isolate_points(
            pts.copy().reshape((1, n + 1, dim)),
            point.copy().reshape((1, dim)),
            np.array([tol]),
            depth,
            max_rows,
            steps,
            inside,
            margin,
            halves,
        )
    starts = [x for x in root_s]
    if left_s0.size:  # pieces left unresolved (most calls have none): brackets, clusters
        narrow = left_width <= wide
        for k in range(left_s0.size):
            if not narrow[k]:
                starts.append(
                    _chord_bracket(c, point, left_s0[k], left_s0[k] + left_width[k], wide)
                )
        cluster_s, _ = _starts(left_s0[narrow], np.zeros(int(narrow.sum())), left_width[narrow])
        for x in cluster_s:
            starts.append(x)
    for start in starts:
        t = _locate_newton(c, point, start)
        if math.isnan(t):
            continue
        near = False
        for u in found:
            if abs(t - u) < same_root:
                near = True
        if near:
            continue
        here = _distance(c, t, point)
        if here > (_rounding_at(c, t, knobs[5]) if exact_end else accept):
            continue
        same = -1
        if len(found) and size[0] < 0.0:
            size[0] = _size(pts)
        on_curve = on_curve_rel * max(size[0], big)
        for j in range(len(found)):
            u = found[j]
            stays = True
            x = c[4][4][0]
            for m in range(17):
                _d_into(c, u + (m / 16.0) * (t - u), 0, x)
                gap = 0.0
                for i in range(dim):
                    gap += (x[i] - point[i]) ** 2
                if math.sqrt(gap) > on_curve:
                    stays = False
                    break
            if stays:
                same = j
                break
        if same < 0:
            found.append(t)
        elif here < _distance(c, found[same], point):
            found[same] = t
    return np.sort(np.array(found))


# ---------------------------------------------------------------------------- the pair
_collinear = numba.njit(**_JIT)(_ends.collinear)  # one source with the certificate's


@numba.njit(**_JIT)
def _after(s: float, t: float, kind: int, s2: float, t2: float, kind2: int) -> bool:
    """(s, t, kind) > (s2, t2, kind2) as tuples compare."""
    if s != s2:
        return s > s2
    if t != t2:
        return t > t2
    return kind > kind2


@numba.njit(**_JIT)
def _same_piece(p: Curve, q: Curve, s0: float, s1: float, t0: float, t1: float, tol: float) -> bool:
    """intersect._same_piece."""
    points = max(p[0].shape[0], q[0].shape[0]) + 1
    for k in range(points):
        x = 0.05 + k * (0.9 / (points - 1))
        if _gap(p, q, s0 + x * (s1 - s0), t0 + x * (t1 - t0)) > tol:
            return False
    return True


@numba.njit(**_JIT)
def _in_stretch(s: float, t: float, skip: np.ndarray, skips: int, start: bool) -> bool:
    """intersect._pair_finish's tests against shared stretches: a start inside one's
    rectangle (closed) is not refined; a hit strictly inside one's s interval is dropped."""
    for r in range(skips):
        if start and skip[r, 0] <= s <= skip[r, 1] and skip[r, 2] <= t <= skip[r, 3]:
            return True
        if not start and skip[r, 0] < s < skip[r, 1]:
            return True
    return False


@numba.njit(**_JIT)
def settle(
    a: np.ndarray, b: np.ndarray, knobs: Knobs, halves_a: Halves, halves_b: Halves
) -> tuple[int, np.ndarray]:
    """intersect's careful path on one pair of float curves (n+1, d), (m+1, d), d >= 2,
    (count, hits) with hits (count, 3) rows (s, t, kind code), sorted as the
    careful path sorts its hits (one array returned: boxing each costs a share of a small
    pair's time), or count -1 where it declines (a stretch between end hits that may be one
    arc under another parameterisation; control points on one line; more hits than room)."""
    same_root, isolated_same, radius, merge_gap = knobs[1], knobs[2], knobs[3], knobs[4]
    root_residual, box_slack, tangent_sine = knobs[5], knobs[6], knobs[9]
    depth, max_rows, steps, inside, margin = knobs[10], knobs[11], knobs[12], knobs[13], knobs[14]
    span_p, scale_p = span_scale(a)
    span_q, scale_q = span_scale(b)
    if span_p == 0.0 or span_q == 0.0:  # a point: the careful path says so (a ValueError)
        return -1, np.empty((0, 3))
    p, q = _curve(a), _curve(b)
    size_p, size_q = np.full(1, -1.0), np.full(1, -1.0)  # computed when first needed
    scale = max(scale_p, scale_q)
    degree = max(a.shape[0], b.shape[0]) - 1
    bound = root_residual * degree * scale
    room = 8 * a.shape[0] * b.shape[0] + 64
    fs, ft = np.zeros(room), np.zeros(room)
    fk = np.zeros(room, dtype=np.int64)
    # the end points located on the other curve
    es, et = np.zeros(room), np.zeros(room)
    ends = 0
    for s_end in range(2):
        end = a[a.shape[0] - 1 if s_end else 0]
        hits = _locate_all(q, scale_q, size_q, end, 0.0, True, knobs, halves_b)
        for t in hits:
            if ends == room:
                return -1, np.empty((0, 3))
            if not _near(float(s_end), t, es, et, ends, same_root):
                es[ends], et[ends] = float(s_end), t
                ends += 1
    for t_end in range(2):
        end = b[b.shape[0] - 1 if t_end else 0]
        hits = _locate_all(p, scale_p, size_p, end, 0.0, True, knobs, halves_a)
        for s in hits:
            if ends == room:
                return -1, np.empty((0, 3))
            if not _near(s, float(t_end), es, et, ends, same_root):
                es[ends], et[ends] = s, float(t_end)
                ends += 1
    ek = np.empty(ends, dtype=np.int64)
    for k in range(ends):
        ek[k] = TANGENT if _sine(p, q, es[k], et[k]) <= tangent_sine else TRANSVERSAL
    # two end hits bound a shared stretch: the same polynomial piece (intersect._same_piece)
    # is decided here as the careful path decides it, reported by its two ends (kind
    # coincident, in (s, t, kind) order) and skipped by the subdivision; a stretch that may
    # be one arc under another parameterisation (the careful path's first test point of
    # _same_image lies on the other stretch once) is the careful path's: declined
    count_along = max((a.shape[0] - 1) * (b.shape[0] - 1) + 1, 3)
    middle = (count_along // 2 + 0.5) / count_along
    count = 0
    skip = np.empty((ends * ends + 1, 4))
    skips = 0
    for i in range(ends):
        for j in range(i + 1, ends):
            if abs(es[i] - es[j]) < same_root or abs(et[i] - et[j]) < same_root:
                continue
            if _same_piece(p, q, es[i], es[j], et[i], et[j], bound):
                lo, hi = (j, i) if _after(es[i], et[i], ek[i], es[j], et[j], ek[j]) else (i, j)
                if count + 2 > room:
                    return -1, np.empty((0, 3))
                for k in (lo, hi):
                    fs[count], ft[count], fk[count] = es[k], et[k], COINCIDENT
                    count += 1
                skip[skips, 0], skip[skips, 1] = es[lo], es[hi]
                skip[skips, 2], skip[skips, 3] = min(et[i], et[j]), max(et[i], et[j])
                skips += 1
                continue
            probe = _d(p, es[i] + middle * (es[j] - es[i]), 0)
            lo_t, hi_t = min(et[i], et[j]) - same_root, max(et[i], et[j]) + same_root
            on_q = 0
            for t in _locate_all(q, scale_q, size_q, probe, bound, False, knobs, halves_b):
                if lo_t <= t <= hi_t:
                    on_q += 1
            if on_q == 1:
                return -1, np.empty((0, 3))
    gap_bound = merge_gap * degree * scale
    for k in range(ends):
        if not _near(es[k], et[k], fs, ft, count, same_root):
            count = _add(p, q, fs, ft, fk, count, es[k], et[k], ek[k], gap_bound, radius)
    if _collinear(a, b, bound):
        return -1, np.empty((0, 3))
    # the subdivision, then refinement from its roots and from the starts it leaves
    ok, root_s, root_t, left_s0, left_t0, left_width = _isolate(
        a,
        b,
        box_slack * degree * scale,
        depth,
        max_rows,
        steps,
        inside,
        margin,
        halves_a,
        halves_b,
        skip,
        skips,
    )
    if not ok:
        return -1, np.empty((0, 3))
    for k in range(root_s.size):
        ok, s, t, kind = _solve_from(
            p, q, root_s[k], root_t[k], fs, ft, count, True, scale, bound, knobs
        )
        if ok and not _near_isolated(s, t, fs, ft, count, isolated_same, same_root):
            if count == room:
                return -1, np.empty((0, 3))
            if skips:  # the careful path's _add: a root at a shared stretch's end is that end
                count = _add(p, q, fs, ft, fk, count, s, t, kind, gap_bound, radius)
            else:
                fs[count], ft[count], fk[count] = s, t, kind
                count += 1
    start_s, start_t = _starts(left_s0, left_t0, left_width)
    for k in range(start_s.size):
        if _in_stretch(start_s[k], start_t[k], skip, skips, True):
            continue
        ok, s, t, kind = _solve_from(
            p, q, start_s[k], start_t[k], fs, ft, count, False, scale, bound, knobs
        )
        if not ok or _near(s, t, fs, ft, count, same_root):
            continue
        if _in_stretch(s, t, skip, skips, False):
            continue
        if count == room:
            return -1, np.empty((0, 3))
        count = _add(p, q, fs, ft, fk, count, s, t, kind, gap_bound, radius)
    # sorted as tuples (s, t, kind) sort
    for k in range(1, count):
        s, t, kind = fs[k], ft[k], fk[k]
        m = k - 1
        while m >= 0 and _after(fs[m], ft[m], fk[m], s, t, kind):
            fs[m + 1], ft[m + 1], fk[m + 1] = fs[m], ft[m], fk[m]
            m -= 1
        fs[m + 1], ft[m + 1], fk[m + 1] = s, t, kind
    hits = np.empty((count, 3))
    for k in range(count):
        hits[k, 0], hits[k, 1], hits[k, 2] = fs[k], ft[k], float(fk[k])
    return count, hits
