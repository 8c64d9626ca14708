"""The subdivision of intersect_subdivide, compiled with numba (the `fast` extra).

The same algorithm, test for test and in the same order: per level, drop pairs of pieces
whose boxes or (in the plane) fat lines are apart and, for a curve against itself, the
neighbouring pieces that are one-to-one; stop at the depth or the row guard; isolate pairs
whose pointed hodograph cones share no line and run local Newton on them; set aside pieces
flat to the slack; halve the rest with the same half matrices, children in the same block
order. Only the per-row loops are compiled, so a level costs a pass over its rows instead of
some forty numpy calls on a handful of them (which is what the fallback pays). The results
agree with the numpy version to rounding (loops sum in a fixed order where numpy's matmul and
einsum may not), and tests/test_intersect_robust.py runs both.

Imported only by intersect_subdivide, and only when numba is installed and not disabled;
numba compiles on first use and caches the machine code next to this file.
"""

from __future__ import annotations

import math
import types
from types import ModuleType
from typing import Any

import numba
import numpy as np
from numba.typed import List

from . import intersect_contact as _contact
from .pieces_compiled import JIT as _JIT
from .pieces_compiled import (
    boxes_apart,
    cone,
    fat_line_apart,
    flat_forward,
    local_newton,
    pointed,
    value_slope,
)


def _compiled_twins(
    module: ModuleType, names: tuple[str, ...], replaced: dict[str, Any]
) -> dict[str, Any]:
    """module's functions compiled from their own source (one source for numpy's fallback
    and the kernels): each rebuilt on a copy of the module's globals in which the others
    are the compiled ones (and `replaced` names the compiled stand-ins of its own helpers),
    so that numba resolves their calls to each other."""
    names_space = dict(vars(module))
    names_space.update(replaced)
    for name in names:
        plain = getattr(module, name)
        twin = types.FunctionType(plain.__code__, names_space, name, plain.__defaults__)
        twin.__qualname__ = plain.__qualname__
        names_space[name] = numba.njit(**_JIT)(twin)
    return {name: names_space[name] for name in names}


@numba.njit(**_JIT)
def _rows(count: int, width: int) -> np.ndarray:
    """intersect_contact._rows compiled: scratch rows as an array."""
    return np.zeros((count, width))


@numba.njit(**_JIT)
def _blocks(count: int, rows: int, width: int) -> np.ndarray:
    return np.zeros((count, rows, width))


_CONTACT = _compiled_twins(
    _contact,
    (
        "_second_order",
        "_part",
        "_interval",
        "_apart",
        "_confined",
        "_binomial",
        "_curved_range",
        "_curved_confined",
        "_newton_contact",
        "_corner_contact",
        "_certified",
        "contact_cell",
        "tries",
    ),
    {"_rows": _rows, "_blocks": _blocks},
)
contact_cell = _CONTACT["contact_cell"]
contact_tries = _CONTACT["tries"]
CONTACT_DEEP = _contact.DEEP


@numba.njit(**_JIT)
def _ints() -> List:
    return List.empty_list(numba.int64)


@numba.njit(**_JIT)
def _floats() -> List:
    return List.empty_list(numba.float64)


@numba.njit(**_JIT)
def _int_array(values: List) -> np.ndarray:
    out = np.empty(len(values), dtype=np.int64)
    for k in range(len(values)):
        out[k] = values[k]
    return out


@numba.njit(**_JIT)
def _float_array(values: List) -> np.ndarray:
    out = np.empty(len(values))
    for k in range(len(values)):
        out[k] = values[k]
    return out


@numba.njit(**_JIT)
def _halve(pieces: np.ndarray, matrix: np.ndarray) -> np.ndarray:
    count, size, dim = pieces.shape
    out = np.zeros((count, size, dim))
    for k in range(count):
        for i in range(size):
            for m in range(size):
                w = matrix[i, m]
                if w != 0.0:
                    for j in range(dim):
                        out[k, i, j] += w * pieces[k, m, j]
    return out


@numba.njit(**_JIT)
def isolate(
    a: np.ndarray,
    b: np.ndarray,
    same: bool,
    slack: np.ndarray,
    skip: np.ndarray,
    depth: int,
    max_rows: int,
    newton_steps: int,
    inside: float,
    margin: float,
    halves_a: tuple[np.ndarray, np.ndarray],
    halves_b: tuple[np.ndarray, np.ndarray],
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """intersect_subdivide.isolate's loop; skip is (m, 5): pair, s0, s1, t0, t1."""
    planar = a.shape[2] == 2
    dim = a.shape[2]
    pa, pb = a.copy(), b.copy()
    pid = np.arange(a.shape[0])
    ia = np.zeros(a.shape[0], dtype=np.int64)
    ib = np.zeros(a.shape[0], dtype=np.int64)
    root_pair, root_s, root_t = _ints(), _floats(), _floats()
    left_pair, left_s, left_t, left_w = _ints(), _floats(), _floats(), _floats()
    axis_a, axis_b = np.empty(dim), np.empty(dim)
    wa, wb = np.empty((a.shape[1], dim)), np.empty((b.shape[1], dim))
    vec4 = np.empty((4, dim))
    union = np.empty((pa.shape[1] + pb.shape[1] - 1, dim))
    level = 0
    while True:
        width = 0.5**level
        count = pid.size
        keep = np.ones(count, dtype=np.bool_)
        for k in range(count):
            sl = slack[pid[k]]
            if boxes_apart(pa[k], pb[k], sl):
                keep[k] = False
                continue
            if planar and (fat_line_apart(pa[k], pb[k], sl) or fat_line_apart(pb[k], pa[k], sl)):
                keep[k] = False
                continue
            for r in range(skip.shape[0]):
                if (
                    pid[k] == int(skip[r, 0])
                    and ia[k] * width >= skip[r, 1]
                    and (ia[k] + 1) * width <= skip[r, 2]
                    and ib[k] * width >= skip[r, 3]
                    and (ib[k] + 1) * width <= skip[r, 4]
                ):
                    keep[k] = False
            if keep[k] and same and abs(ia[k] - ib[k]) <= 1:
                if ia[k] == ib[k]:
                    keep[k] = not pointed(cone(pa[k], axis_a, sl), margin)
                else:
                    size = pa.shape[1]
                    union[:size] = pa[k]
                    union[size:] = pb[k, 1:]
                    keep[k] = not pointed(cone(union, axis_a, sl), margin)
        pa, pb, pid, ia, ib = pa[keep], pb[keep], pid[keep], ia[keep], ib[keep]
        count = pid.size
        if count == 0:
            break
        if level == depth or 4 * count > max_rows:
            for k in range(count):
                left_pair.append(pid[k])
                left_s.append(ia[k] * width)
                left_t.append(ib[k] * width)
                left_w.append(width)
            break
        rest = np.ones(count, dtype=np.bool_)
        for k in range(count):
            if same and abs(ia[k] - ib[k]) <= 1:
                continue
            sl = slack[pid[k]]
            half_a = cone(pa[k], axis_a, sl)
            half_b = cone(pb[k], axis_b, sl)
            if not (pointed(half_a, margin) and pointed(half_b, margin)):
                continue
            dot = abs(float(np.sum(axis_a * axis_b)))
            between = math.acos(min(max(dot, 0.0), 1.0))
            if not between > half_a + half_b + margin:
                continue
            u, v, ok = local_newton(pa[k], pb[k], newton_steps, inside, wa, wb, vec4)
            if ok:
                root_pair.append(pid[k])
                root_s.append((ia[k] + min(max(u, 0.0), 1.0)) * width)
                root_t.append((ib[k] + min(max(v, 0.0), 1.0)) * width)
                rest[k] = False
        contact = planar and not same and contact_tries(level)
        cell = 0.5**CONTACT_DEEP
        for k in range(count):
            if not rest[k] or (same and abs(ia[k] - ib[k]) <= 1):
                continue
            sl = slack[pid[k]]
            if flat_forward(pa[k], sl) and flat_forward(pb[k], sl):
                left_pair.append(pid[k])
                left_s.append(ia[k] * width)
                left_t.append(ib[k] * width)
                left_w.append(width)
                rest[k] = False
            elif contact:  # a tangency confined to a small cell (intersect_contact)
                found, ca, cb = contact_cell(pa[k], pb[k], ia[k], ib[k], level, CONTACT_DEEP, sl)
                if found:
                    left_pair.append(pid[k])
                    left_s.append(ca * cell)
                    left_t.append(cb * cell)
                    left_w.append(cell)
                    rest[k] = False
        pa, pb, pid, ia, ib = pa[rest], pb[rest], pid[rest], ia[rest], ib[rest]
        if pid.size == 0:
            break
        al, ar = _halve(pa, halves_a[0]), _halve(pa, halves_a[1])
        bl, br = _halve(pb, halves_b[0]), _halve(pb, halves_b[1])
        pa = np.concatenate((al, al, ar, ar))
        pb = np.concatenate((bl, br, bl, br))
        pid = np.concatenate((pid, pid, pid, pid))
        ia = np.concatenate((2 * ia, 2 * ia, 2 * ia + 1, 2 * ia + 1))
        ib = np.concatenate((2 * ib, 2 * ib + 1, 2 * ib, 2 * ib + 1))
        if same:
            order = ia <= ib
            pa, pb, pid, ia, ib = pa[order], pb[order], pid[order], ia[order], ib[order]
        level += 1
    return (
        _int_array(root_pair),
        _float_array(root_s),
        _float_array(root_t),
        _int_array(left_pair),
        _float_array(left_s),
        _float_array(left_t),
        _float_array(left_w),
    )


@numba.njit(**_JIT)
def _local_foot_newton(
    piece: np.ndarray, point: np.ndarray, steps: int, inside: float, slack: float
) -> tuple[float, bool]:
    dim = piece.shape[1]
    scratch = np.empty((piece.shape[0] + 2, dim))  # one allocation, not three
    value, slope, work = scratch[0], scratch[1], scratch[2:]
    u, step = 0.5, np.inf
    for _ in range(steps):
        value_slope(piece, u, work, value, slope)
        # np.sum's order (from 0, element by element), without its temporaries
        along = speed = 0.0
        for j in range(dim):
            along += (value[j] - point[j]) * slope[j]
        for j in range(dim):
            speed += slope[j] * slope[j]
        du = -along / speed
        u += du
        step = abs(du)
        if not step > 1e-15:
            break
    ok = math.isfinite(step) and step < 1e-12 and -inside <= u <= 1 + inside
    if ok:  # the point itself, not a foot point off it (see intersect_subdivide)
        value_slope(piece, u, work, value, slope)
        gap = 0.0
        for j in range(dim):
            gap += (value[j] - point[j]) ** 2
        ok = math.sqrt(gap) <= slack
    return u, ok


@numba.njit(**_JIT)
def isolate_points(
    curves: np.ndarray,
    points: np.ndarray,
    slack: np.ndarray,
    depth: int,
    max_rows: int,
    newton_steps: int,
    inside: float,
    margin: float,
    halves: tuple[np.ndarray, np.ndarray],
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """intersect_subdivide.isolate_points' loop: (root pair, root s, left pair, left s0,
    left width)."""
    planar = curves.shape[2] == 2
    dim = curves.shape[2]
    pieces, pid = curves.copy(), np.arange(curves.shape[0])
    index = np.zeros(curves.shape[0], dtype=np.int64)
    root_pair, root_s = _ints(), _floats()
    left_pair, left_s, left_w = _ints(), _floats(), _floats()
    axis = np.empty(dim)
    level = 0
    while pid.size:
        count = pid.size
        keep = np.ones(count, dtype=np.bool_)
        for k in range(count):
            sl = slack[pid[k]]
            target = points[pid[k]]
            for j in range(dim):
                lo, hi = pieces[k, :, j].min(), pieces[k, :, j].max()
                if not (lo <= target[j] + sl and target[j] - sl <= hi):
                    keep[k] = False
            if keep[k] and planar and fat_line_apart(target.reshape(1, dim), pieces[k], sl):
                keep[k] = False
        pieces, pid, index = pieces[keep], pid[keep], index[keep]
        count = pid.size
        if count == 0:
            break
        width = 0.5**level
        if level == depth or 2 * count > max_rows:
            for k in range(count):
                left_pair.append(pid[k])
                left_s.append(index[k] * width)
                left_w.append(width)
            break
        rest = np.ones(count, dtype=np.bool_)
        for k in range(count):
            if pointed(cone(pieces[k], axis, slack[pid[k]]), margin):
                u, ok = _local_foot_newton(
                    pieces[k], points[pid[k]], newton_steps, inside, slack[pid[k]]
                )
                if ok:
                    root_pair.append(pid[k])
                    root_s.append((index[k] + min(max(u, 0.0), 1.0)) * width)
                    rest[k] = False
        for k in range(count):
            if rest[k] and flat_forward(pieces[k], slack[pid[k]]):
                left_pair.append(pid[k])
                left_s.append(index[k] * width)
                left_w.append(width)
                rest[k] = False
        pieces, pid, index = pieces[rest], pid[rest], index[rest]
        if pid.size == 0:
            break
        pieces = np.concatenate((_halve(pieces, halves[0]), _halve(pieces, halves[1])))
        pid = np.concatenate((pid, pid))
        index = np.concatenate((2 * index, 2 * index + 1))
        level += 1
    return (
        _int_array(root_pair),
        _float_array(root_s),
        _int_array(left_pair),
        _float_array(left_s),
        _float_array(left_w),
    )
