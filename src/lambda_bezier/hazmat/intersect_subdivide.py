"""Candidate isolation for curve intersections: adaptive subdivision on arrays, many pairs at once.

Pure functions on control-point arrays (numpy only, no curve classes): this module belongs to
the low-level layer. `isolate` takes P pairs of classical Bézier curves of equal degrees
((P, n+1, d) and (P, m+1, d)) and halves every surviving pair of pieces level by level, all
pairs of all curve pairs in one array per level. A pair of pieces is

- dropped when it provably holds no intersection: its axis-aligned boxes are apart, or (in
  the plane) one piece's control points lie strictly on one side of the other's fat line
  (the band between its control points' extreme distances to its chord). The fat line is
  what keeps tangencies cheap: near a tangency the pieces' axis-aligned boxes overlap over a
  stretch of width ~sqrt(w) for pieces of width w, the fat lines only over ~w;
- *isolated* when it provably holds at most one intersection: the hodograph of each piece
  lies in a circular cone (so the piece is one-to-one) and the two cones share no line. Two
  intersections X != Y would put the chord X - Y in both cones (it is the integral of either
  piece's derivative between them). Newton then runs on the isolated pair (vectorised over all
  of them); a root it finds inside the pair's pieces is that pair's only intersection. Where
  Newton fails, the pair is halved further;
- kept otherwise, until `depth` halvings: what is left then are pieces of width 2^-depth
  around tangencies (or contacts closer than that), reported as unresolved for the caller's
  tangent refinement.

Two crossings a distance delta apart in parameter are therefore separated as soon as the
pieces are narrower than about delta (the cones of pieces on either side of the turning point
between them share no line), whatever delta is above 2^-depth.

With numba installed (the `fast` extra), `isolate` and `isolate_points` run the same loop
compiled (intersect_compiled); set LAMBDA_BEZIER_NO_NUMBA=1 in the environment, or
`USE_COMPILED = False` here, for the numpy version. Both are tested.
"""

from __future__ import annotations

import importlib.util
import os
from collections.abc import Callable
from types import ModuleType
from typing import NamedTuple

import numpy as np

from . import intersect_contact as _contact

DEPTH = 32  # halvings at most: 2^-32 ~ 2.3e-10 in parameter, below which a pair is unresolved
MAX_ROWS = 200_000  # pairs of pieces alive at one level, a guard against runaway subdivision
NEWTON_STEPS = 10  # local Newton iterations on an isolated pair (quadratic from its middle)
INSIDE = 1e-9  # a Newton root this far (in the pieces' local parameter) outside still counts
CONE_MARGIN = 1e-9  # radians: cones closer than this are treated as sharing a line
# the pieces' rounding (the input's half ulp and ~1 ulp per halving: 4 eps per degree of the
# size) as a share of the slack (64 eps per degree): the error the cones are widened by. The
# whole slack widened them so much that crossings 1e-6 apart were no longer isolated
BLUR = 1 / 16

# the compiled loop when numba is there and not switched off (module flag, read per call)
USE_COMPILED = importlib.util.find_spec("numba") is not None and not os.environ.get(
    "LAMBDA_BEZIER_NO_NUMBA"
)


def _compiled() -> ModuleType | None:
    if not USE_COMPILED:
        return None
    from . import intersect_compiled  # numba compiles (or loads its cache) on first use

    return intersect_compiled


class Isolated(NamedTuple):
    """Roots found on isolated pairs (pair index, s, t: float Newton, to be polished), and the
    unresolved pairs of pieces (pair index, s and t intervals [s0, s0 + width] and
    [t0, t0 + width])."""

    root_pair: np.ndarray
    root_s: np.ndarray
    root_t: np.ndarray
    left_pair: np.ndarray
    left_s0: np.ndarray
    left_t0: np.ndarray
    left_width: np.ndarray


def split_rows(iso: Isolated, rows: int) -> list[Isolated]:
    """iso's roots and left pieces row by row (rows: the pairs subdivided), each row's in
    the order iso holds them: a stable sort by row, then slices."""
    root_order = np.argsort(iso.root_pair, kind="stable")
    left_order = np.argsort(iso.left_pair, kind="stable")
    bounds = np.arange(rows + 1)
    root_at = np.searchsorted(iso.root_pair[root_order], bounds).tolist()
    left_at = np.searchsorted(iso.left_pair[left_order], bounds).tolist()
    roots = [x[root_order] for x in iso[:3]]
    left = [x[left_order] for x in iso[3:]]
    return [
        Isolated(
            *[x[root_at[g] : root_at[g + 1]] for x in roots],
            *[x[left_at[g] : left_at[g + 1]] for x in left],
        )
        for g in range(rows)
    ]


_HALF_CACHE: dict[int, tuple[np.ndarray, np.ndarray]] = {}


def half_matrices(degree: int) -> tuple[np.ndarray, np.ndarray]:
    """Subdivision at 1/2 as two (n+1, n+1) matrices (de Casteljau's triangle's edges):
    left[i, k] = C(i, k) / 2^i, right[i, k] = C(n-i, k-i) / 2^(n-i). Exact in floats."""
    if degree not in _HALF_CACHE:
        from math import comb

        n = degree
        left = np.zeros((n + 1, n + 1))
        right = np.zeros((n + 1, n + 1))
        for i in range(n + 1):
            for k in range(i + 1):
                left[i, k] = comb(i, k) / 2.0**i
            for k in range(i, n + 1):
                right[i, k] = comb(n - i, k - i) / 2.0 ** (n - i)
        _HALF_CACHE[degree] = (left, right)
    return _HALF_CACHE[degree]


# ufunc reductions called directly: ndarray.min/max/sum/all/any run the same reduction
# through a Python wrapper, about a microsecond more on every call
_lo = np.minimum.reduce
_hi = np.maximum.reduce
_sum = np.add.reduce
_all = np.logical_and.reduce
_any = np.logical_or.reduce


def _boxes_apart(a: np.ndarray, b: np.ndarray, slack: np.ndarray) -> np.ndarray:
    sl = slack[:, None]
    apart: np.ndarray = _any((_lo(a, 1) > _hi(b, 1) + sl) | (_lo(b, 1) > _hi(a, 1) + sl), 1)
    return apart


# The helpers below run once or twice per level on a few rows each: numpy's fixed cost per
# call, not the arithmetic, is their time, so they make as few calls as they can (a norm as
# sqrt of a sum of squares, the same operations np.linalg.norm runs; slices for np.diff;
# the ufuncs' reductions for the array methods). The arithmetic is the same, so the results
# are bit-identical to the plainer spelling.


def _fat_line_apart(a: np.ndarray, b: np.ndarray, slack: np.ndarray) -> np.ndarray:
    """Planar pieces: True where a's control points lie beyond b's fat line (one side)."""
    base = b[:, :1]
    chord = b[:, -1] - base[:, 0]
    length = np.hypot(chord[:, 0], chord[:, 1])
    ok = length > 0
    scale = np.where(ok, length, 1.0)
    normal = np.empty_like(chord)
    np.negative(chord[:, 1], out=normal[:, 0])
    normal[:, 1] = chord[:, 0]
    normal /= scale[:, None]
    db = np.einsum("kid,kd->ki", b - base, normal)
    da = np.einsum("kid,kd->ki", a - base, normal)
    apart = (_lo(da, 1) > _hi(db, 1) + slack) | (_hi(da, 1) < _lo(db, 1) - slack)
    result: np.ndarray = apart & ok
    return result


def _norm(x: np.ndarray) -> np.ndarray:
    """np.linalg.norm(x, axis=-1), the same operations without its checks."""
    norm: np.ndarray = np.sqrt(_sum(x * x, -1))
    return norm


def _thickness(pieces: np.ndarray) -> np.ndarray:
    """The largest distance of a piece's control points from its chord (inf for a closed
    piece, whose chord is a point)."""
    rel = pieces - pieces[:, :1]
    chord = rel[:, -1]
    length = _norm(chord)
    unit = chord / np.where(length > 0, length, 1.0)[:, None]
    along = np.einsum("kid,kd->ki", rel, unit)
    off = _hi(_norm(rel - along[..., None] * unit[:, None]), 1)
    thickness: np.ndarray = np.where(length > 0, off, np.inf)
    return thickness


def _runs_forward(pieces: np.ndarray) -> np.ndarray:
    """True where every hodograph control point has a non-negative component along the
    chord: the piece never turns back along it (a flat piece that does can pass a point, or
    cross a line, twice)."""
    chord = pieces[:, -1] - pieces[:, 0]
    along = np.einsum("kid,kd->ki", pieces[:, 1:] - pieces[:, :-1], chord)
    forward: np.ndarray = _all(along >= 0, 1) & _any(chord != 0, 1)
    return forward


def _flat(pieces: np.ndarray, slack: np.ndarray, among: np.ndarray) -> np.ndarray:
    """among & (thickness <= slack) & runs forward, the costlier tests only on rows that
    can still pass (mostly none: a piece is flat to rounding only near the end)."""
    flat = among & (_thickness(pieces) <= slack)
    if flat.any():
        rows = np.flatnonzero(flat)
        flat[rows] = _runs_forward(pieces[rows])
    return flat


def _cones(pieces: np.ndarray, slack: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The axis (unit vector) and half-angle of a circular cone holding every hodograph
    control point of each piece; half-angle >= pi/2 (not pointed) where there is none
    this way (a zero hodograph point, or directions that turn too far).

    The pieces' control points are off the true pieces' by rounding (BLUR times the slack,
    (K,), bounds it: the input's and that of repeated halving), so each difference
    b_{i+1} - b_i is off by up to twice that and its direction by up to
    asin(2 BLUR slack / |b_{i+1} - b_i|): the half-angle is widened by that blur. On narrow
    pieces it is not small (2^-20 wide at a tangency, about 1e-9 rad), and without it two
    cones that touch along the common tangent line can look
    apart, "isolating" a tangency as a crossing."""
    h = pieces[:, 1:] - pieces[:, :-1]
    norm = _norm(h)
    blur_length = 2 * BLUR * slack[:, None]
    good = _all(norm > blur_length, 1)
    unit = h / np.where(norm > 0, norm, 1.0)[..., None]
    axis = _sum(unit, 1)
    axis_norm = _norm(axis)
    good &= axis_norm > 0
    axis /= np.where(axis_norm > 0, axis_norm, 1.0)[:, None]
    cos = _lo(np.einsum("kid,kd->ki", unit, axis), 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        blur = _hi(np.arcsin(np.minimum(np.maximum(blur_length / norm, 0.0), 1.0)), 1)
        spread = np.arccos(np.minimum(np.maximum(cos, -1.0), 1.0))
    half = np.where(good & (cos > 0), spread + blur, np.pi)
    return axis, half


def _pointed(half: np.ndarray) -> np.ndarray:
    pointed: np.ndarray = half < np.pi / 2 - CONE_MARGIN
    return pointed


def _one_to_one_union(a: np.ndarray, b: np.ndarray, slack: np.ndarray) -> np.ndarray:
    """For neighbouring pieces of one curve: True where both together are one-to-one (one
    pointed cone holds both hodographs)."""
    _, half = _cones(np.concatenate([a, b[:, 1:]], axis=1), slack)
    return _pointed(half)


def _eval_with_derivative(pieces: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """p(u) and p'(u) of each piece at its own local u: (K, d) each."""
    work = pieces
    uu = u[:, None, None]
    degree = pieces.shape[1] - 1
    if degree == 0:
        return work[:, 0], np.zeros_like(work[:, 0])
    while work.shape[1] > 2:
        work = work[:, :-1] + uu * (work[:, 1:] - work[:, :-1])
    lo, hi = work[:, 0], work[:, 1]
    return lo + u[:, None] * (hi - lo), degree * (hi - lo)


def local_newton(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Gauss-Newton on a(u) - b(v) from (1/2, 1/2), on K pairs at once: (u, v, converged)
    with converged True where the last step was below 1e-12 and (u, v) lies in the pieces."""
    k = a.shape[0]
    u = np.full(k, 0.5)
    v = np.full(k, 0.5)
    step = np.full(k, np.inf)
    thrown = np.zeros(k, dtype=bool)
    both = np.concatenate([a, b]) if a.shape[1] == b.shape[1] else None
    with np.errstate(all="ignore"):
        for _ in range(NEWTON_STEPS):
            if both is not None:  # one evaluation of both sides (the same operations)
                value, slope = _eval_with_derivative(both, np.concatenate([u, v]))
                pa, pb, da, db = value[:k], value[k:], slope[:k], slope[k:]
            else:
                pa, da = _eval_with_derivative(a, u)
                pb, db = _eval_with_derivative(b, v)
            f = pa - pb
            # normal equations of [da, -db] (du, dv) = -f
            aa = np.einsum("kd,kd->k", da, da)
            ab = -np.einsum("kd,kd->k", da, db)
            bb = np.einsum("kd,kd->k", db, db)
            ga = -np.einsum("kd,kd->k", da, f)
            gb = np.einsum("kd,kd->k", db, f)
            det = aa * bb - ab * ab
            du = (bb * ga - ab * gb) / det
            dv = (aa * gb - ab * ga) / det
            u = u + du
            v = v + dv
            step = np.abs(du) + np.abs(dv)
            # thrown far off (a step too big to stop): no root of these pieces near, subdivide
            thrown |= (step > 1e-15) & ~((u > -1) & (u < 2) & (v > -1) & (v < 2))
            if not np.any(step > 1e-15):
                break
    inside = (u >= -INSIDE) & (u <= 1 + INSIDE) & (v >= -INSIDE) & (v <= 1 + INSIDE)
    converged = np.isfinite(step) & (step < 1e-12) & inside & ~thrown
    return u, v, converged


def read_only(points: np.ndarray) -> np.ndarray:
    """points as a C-contiguous float array that is read-only (a view where it was writeable),
    for the compiled kernels' curve arguments: numba compiles a kernel once per argument type,
    and a writeable array is another type than the read-only points of a curve. Measured on a
    fresh cache: the careful path (settle_compiled) compiled for both cost 45 s of CPU more;
    isolate and isolate_points a few seconds more each."""
    arr = np.ascontiguousarray(points, dtype=float)
    if arr.flags.writeable:
        arr = arr.view()
        arr.setflags(write=False)
    return arr


def isolate(
    a: np.ndarray,
    b: np.ndarray | None,
    slack: np.ndarray,
    skip: list[tuple[int, float, float, float, float]] | None = None,
    depth: int = DEPTH,
    max_rows: int = MAX_ROWS,
    corners: np.ndarray | None = None,
) -> Isolated:
    """Subdivide P pairs of curves at once. a: (P, n+1, d); b: (P, m+1, d), or None for each
    curve of a against itself (pairs of pieces ia <= ib; neighbouring pieces are dropped
    once provably one-to-one, and never isolated: they share an end point). slack: (P,),
    the distance within which boxes still count as touching. skip: (pair, s0, s1, t0, t1)
    rectangles of a shared stretch, whose pairs of pieces are dropped. max_rows: the guard
    on the pairs of pieces alive at one level (those left then are reported unresolved).
    corners: (P,) the certificate's shared end points (intersect_shared_ends.shared_corners), on
    the numpy loop only: an isolated pair of pieces holding one reports it as its root, exactly
    and without Newton, as certify_compiled does in its own loop; holding two, a NaN root."""
    same = b is None
    bb_all = a if b is None else b
    compiled = _compiled() if corners is None else None
    if compiled is not None:
        return Isolated(
            *compiled.isolate(
                read_only(a),
                read_only(bb_all),
                same,
                np.ascontiguousarray(slack, dtype=float),
                np.array(skip or [], dtype=float).reshape(-1, 5),
                depth,
                max_rows,
                NEWTON_STEPS,
                INSIDE,
                CONE_MARGIN,
                half_matrices(a.shape[1] - 1),
                half_matrices(bb_all.shape[1] - 1),
            )
        )

    def isolate_pairs(
        pa: np.ndarray,
        pb: np.ndarray,
        sl: np.ndarray,
        ia: np.ndarray,
        ib: np.ndarray,
        pid: np.ndarray,
        level: int,
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        # one-to-one pieces whose tangent cones share no line hold one root at most
        if pa.shape[1] == pb.shape[1]:  # both sides' cones in one set of calls
            k = pa.shape[0]
            axis, half = _cones(np.concatenate([pa, pb]), np.concatenate([sl, sl]))
            axis_a, axis_b, half_a, half_b = axis[:k], axis[k:], half[:k], half[k:]
        else:
            axis_a, half_a = _cones(pa, sl)
            axis_b, half_b = _cones(pb, sl)
        between = np.arccos(np.minimum(np.abs(np.einsum("kd,kd->k", axis_a, axis_b)), 1.0))
        isolated = _pointed(half_a) & _pointed(half_b) & (between > half_a + half_b + CONE_MARGIN)
        if same:
            isolated &= np.abs(ia - ib) > 1
        idx = np.flatnonzero(isolated)
        if not idx.size:
            return idx, np.zeros(0), np.zeros(0), np.zeros(0, dtype=bool)
        if corners is None:
            u, v, ok = local_newton(pa[idx], pb[idx])
            return idx, u, v, ok
        from .intersect_shared_ends import corner_held

        held = np.array(
            [
                corner_held(int(corners[pid[k]]), int(ia[k]), int(ib[k]), level)
                for k in idx.tolist()
            ],
            dtype=np.int64,
        )
        u, v, ok = np.full(idx.size, np.nan), np.full(idx.size, np.nan), held != -1
        newton = held == -1
        if newton.any():
            u[newton], v[newton], ok[newton] = local_newton(pa[idx[newton]], pb[idx[newton]])
        at = held >= 0
        u[at], v[at] = held[at] >> 1, held[at] & 1
        return idx, u, v, ok

    return _subdivide(a, bb_all, slack, isolate_pairs, same, skip or [], depth, max_rows)


# one level's test of pairs of pieces for isolation: (pieces a, pieces b, slack, ia, ib,
# pair of each row, level) -> (indices tested, u, v, converged)
_Isolation = Callable[
    [np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, int],
    tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
]


def _subdivide(
    a: np.ndarray,
    b: np.ndarray,
    slack: np.ndarray,
    isolation: _Isolation,
    same: bool,
    skip: list[tuple[int, float, float, float, float]],
    depth: int,
    max_rows: int,
) -> Isolated:
    """The numpy loop of isolate and isolate_points, level by level over every pair of pieces
    of every pair: drop, stop at the depth or the row guard, isolate, set aside the flat,
    halve. b of degree 0 (one point per pair, isolate_points) is not halved: each piece of a
    has two children, not four, and only a's flatness counts."""
    planar = a.shape[2] == 2
    fixed = b.shape[1] == 1
    children = 2 if fixed else 4
    left_a, right_a = half_matrices(a.shape[1] - 1)
    left_b, right_b = half_matrices(b.shape[1] - 1)
    pa, pb = a, b
    # each row's (pair, index of its a piece, index of its b piece) in one array: one
    # selection per filter instead of three (the loop's cost is numpy's per call)
    ids = np.zeros((3, a.shape[0]), dtype=np.int64)
    ids[0] = np.arange(a.shape[0])
    pid, ia, ib = ids
    roots: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
    left: list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]] = []
    level = 0
    while True:
        sl = slack[pid]
        if fixed:  # the point within the piece's box, as the compiled loop writes it
            target, margin = pb[:, 0], sl[:, None]
            keep = _all((_lo(pa, 1) <= target + margin) & (target - margin <= _hi(pa, 1)), 1)
        else:
            keep = ~_boxes_apart(pa, pb, sl)
        if planar:  # a point has no chord: only the piece's fat line can drop it
            if fixed or pa.shape[1] != pb.shape[1]:
                keep &= ~_fat_line_apart(pb, pa, sl)
                if not fixed:
                    keep &= ~_fat_line_apart(pa, pb, sl)
            else:  # both ways in one set of calls
                k = pa.shape[0]
                apart = _fat_line_apart(
                    np.concatenate([pb, pa]), np.concatenate([pa, pb]), np.concatenate([sl, sl])
                )
                keep &= ~(apart[:k] | apart[k:])
        width = 0.5**level
        for pair, s0, s1, t0, t1 in skip:
            inside = (pid == pair) & (ia * width >= s0) & ((ia + 1) * width <= s1)
            inside &= (ib * width >= t0) & ((ib + 1) * width <= t1)
            keep &= ~inside
        if same:
            near = np.abs(ia - ib) <= 1
            if near.any():
                diag = near & (ia == ib)
                _, half = _cones(pa[diag], sl[diag])
                drop = np.zeros_like(keep)
                drop[np.flatnonzero(diag)[_pointed(half)]] = True
                nb = near & (ia != ib)
                drop[np.flatnonzero(nb)[_one_to_one_union(pa[nb], pb[nb], sl[nb])]] = True
                keep &= ~drop
        pa, pb, ids = pa[keep], pb[keep], ids[:, keep]
        pid, ia, ib = ids
        if not pid.size:
            break
        if level == depth or children * pid.size > max_rows:
            left.append((pid, ia * width, ib * width, np.full(pid.size, width)))
            break
        idx, u, v, ok = isolation(pa, pb, slack[pid], ia, ib, pid, level)
        if idx.size:
            hit = idx[ok]
            roots.append(
                (
                    pid[hit],
                    (ia[hit] + np.clip(u[ok], 0, 1)) * width,
                    (ib[hit] + np.clip(v[ok], 0, 1)) * width,
                )
            )
            rest = np.ones(pid.size, dtype=bool)
            rest[hit] = False
            pa, pb, ids = pa[rest], pb[rest], ids[:, rest]
            pid, ia, ib = ids
            if not pid.size:
                break
        # pieces flat to within the slack on both sides are as resolved as subdivision gets
        # (a tangency or a contact of higher order, within rounding of the input)
        sl = slack[pid]
        flat = _flat(pa, sl, np.abs(ia - ib) > 1 if same else np.ones(pid.size, dtype=bool))
        if not fixed and flat.any():
            flat = _flat(pb, sl, flat)
        cells: list[tuple[int, int, int]] = []  # (row, cell of a, cell of b)
        if planar and not same and not fixed and _contact.tries(level):
            # a tangency confined to a small cell (intersect_contact): left as that cell
            for k in np.flatnonzero(~flat).tolist():
                found, ca, cb = _contact.contact_cell(
                    pa[k].tolist(),  # nested lists: plain Python indexes them fastest
                    pb[k].tolist(),
                    int(ia[k]),
                    int(ib[k]),
                    level,
                    _contact.DEEP,
                    float(sl[k]),
                )
                if found:
                    cells.append((k, ca, cb))
        if cells or flat.any():
            at_s, at_t, widths = ia * width, ib * width, np.full(pid.size, width)
            cell = 0.5**_contact.DEEP
            for k, ca, cb in cells:
                flat[k] = True
                at_s[k], at_t[k], widths[k] = ca * cell, cb * cell, cell
            left.append((pid[flat], at_s[flat], at_t[flat], widths[flat]))
            rest = ~flat
            pa, pb, ids = pa[rest], pb[rest], ids[:, rest]
            pid, ia, ib = ids
            if not pid.size:
                break
        al, ar = np.matmul(left_a, pa), np.matmul(right_a, pa)
        k = pid.size
        if fixed:  # children (2 ia, ib), (2 ia + 1, ib)
            pa, pb = np.concatenate([al, ar]), np.concatenate([pb, pb])
            ids = np.concatenate([ids, ids], axis=1)
            ids[1] *= 2
            ids[1, k:] += 1
        else:  # children (2 ia, 2 ib), (2 ia, 2 ib + 1), (2 ia + 1, 2 ib), (2 ia + 1, 2 ib + 1)
            bl, br = np.matmul(left_b, pb), np.matmul(right_b, pb)
            pa = np.concatenate([al, al, ar, ar])
            pb = np.concatenate([bl, br, bl, br])
            ids = np.concatenate([ids, ids, ids, ids], axis=1)
            ids[1:] *= 2
            ids[1, 2 * k :] += 1
            ids[2].reshape(4, k)[1::2] += 1
        pid, ia, ib = ids
        if same:
            ok_order = ia <= ib
            pa, pb, ids = pa[ok_order], pb[ok_order], ids[:, ok_order]
            pid, ia, ib = ids
        level += 1
    empty = np.zeros(0)
    if roots:
        root_pair = np.concatenate([r[0] for r in roots])
        root_s = np.concatenate([r[1] for r in roots])
        root_t = np.concatenate([r[2] for r in roots])
    else:
        root_pair, root_s, root_t = np.zeros(0, dtype=np.int64), empty, empty
    if left:
        parts = [np.concatenate([part[k] for part in left]) for k in range(4)]
    else:
        parts = [np.zeros(0, dtype=np.int64), empty, empty, empty]
    return Isolated(root_pair, root_s, root_t, *parts)


def _local_foot_newton(
    pieces: np.ndarray, points: np.ndarray, slack: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Newton on |p(u) - x|^2 / 2 restricted to the pieces' own u (Gauss-Newton: the step
    -(p - x)·p' / p'·p'), from u = 1/2: (u, converged), converged where the step fell below
    1e-12 inside the piece and p(u) is within slack of x. A foot point farther off is not
    the point: a one-to-one piece can curve round so that its box holds x while the foot
    point Newton finds is a local minimum of the distance, with x on the piece elsewhere.

    Each row stops at its own first step not above 1e-15, as the compiled twin's does: a
    row's result then does not depend on which other rows share the call (intersect
    locates the end points of many pairs in one call)."""
    u = np.full(pieces.shape[0], 0.5)
    step = np.full(pieces.shape[0], np.inf)
    active = np.ones(pieces.shape[0], dtype=bool)
    with np.errstate(all="ignore"):
        for _ in range(NEWTON_STEPS):
            value, slope = _eval_with_derivative(pieces, u)
            du = -np.einsum("kd,kd->k", value - points, slope) / np.einsum("kd,kd->k", slope, slope)
            u = np.where(active, u + du, u)
            step = np.where(active, np.abs(du), step)
            active &= step > 1e-15
            if not active.any():
                break
    converged = np.isfinite(step) & (step < 1e-12) & (u >= -INSIDE) & (u <= 1 + INSIDE)
    with np.errstate(all="ignore"):
        value, _ = _eval_with_derivative(pieces, u)
    converged &= np.linalg.norm(value - points, axis=1) <= slack
    return u, converged


def isolate_points(
    curves: np.ndarray, points: np.ndarray, slack: np.ndarray, depth: int = DEPTH
) -> Isolated:
    """The same subdivision for P curves (P, n+1, d) against P points (P, d): pieces whose
    boxes (and, in the plane, fat lines) hold the point survive; a one-to-one piece (pointed
    hodograph cone) passes the point at most once, so Newton on it is run and a root inside
    it reported. root_t is unused (zeros); left_t0 likewise."""
    compiled = _compiled()
    if compiled is not None:
        root_pair, root_s, left_pair, left_s0, left_width = compiled.isolate_points(
            read_only(curves),
            read_only(points),
            np.ascontiguousarray(slack, dtype=float),
            depth,
            MAX_ROWS,
            NEWTON_STEPS,
            INSIDE,
            CONE_MARGIN,
            half_matrices(curves.shape[1] - 1),
        )
        return Isolated(
            root_pair,
            root_s,
            np.zeros_like(root_s),
            left_pair,
            left_s0,
            np.zeros_like(left_s0),
            left_width,
        )

    def isolate_pieces(
        pieces: np.ndarray,
        target: np.ndarray,
        sl: np.ndarray,
        ia: np.ndarray,
        ib: np.ndarray,
        pid: np.ndarray,
        level: int,
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        # a one-to-one piece (pointed hodograph cone) passes the point at most once
        _, half = _cones(pieces, sl)
        idx = np.flatnonzero(_pointed(half))
        if not idx.size:
            return idx, np.zeros(0), np.zeros(0), np.zeros(0, dtype=bool)
        u, ok = _local_foot_newton(pieces[idx], target[idx, 0], sl[idx])
        return idx, u, np.zeros_like(u), ok

    return _subdivide(curves, points[:, None, :], slack, isolate_pieces, False, [], depth, MAX_ROWS)
