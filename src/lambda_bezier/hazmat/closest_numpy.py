"""Closest points on a polynomial curve without numba, for batches of queries: the certified
branch and bound of closest_compiled, run breadth first over every (query, interval) row
at once in numpy.

The method is closest_compiled's (see its docstring): D(t) = |p(t) - q|^2 in the Bernstein
basis of degree 2N; an interval whose least coefficient is not below the best distance
found so far for its query is dropped; an interval whose D' coefficients (differences of
D's) change sign at most once, from - to +, is settled (D monotone there: its least value at
an end; or one minimum: bracketed Newton on g = (p - q) . p'); every other interval is
halved. Two differences of means, neither of which changes what is certified:

- the intervals of one level are examined together (breadth first), not depth first, so
  the order in which best distances are found differs; to prune as early as depth first
  does, the curve's distance at the middle of every halved interval joins the candidates
  (a point of the curve: an upper bound of the minimum, never below it);
- the halving is a product with the two (2N+1) x (2N+1) de Casteljau matrices at 1/2
  (entries C(r, k) / 2^r, exact), whose sums are in BLAS's order: the coefficients agree with
  repeated averaging to a few ulps, the rounding the certificate already allows.

What is returned is the best of the ends, the settled intervals' minima and the middles,
each distance evaluated by de Casteljau on the curve: the global minimum, certified up to
the rounding of D's coefficients, as the compiled kernel's.

Why (issue #29): it replaced a companion-matrix path (every root of (p - q) . p' from numpy's
batched eigvals of (2N - 1)-square matrices, polished by Newton), which spent most of a
large batch in eigvals: 2.1x a 512-sample numpy baseline at degree 8 for 10,000 queries
(quiet), 2.5-2.8x under load against this module's 0.5-0.7x in the same runs. For a few
queries, closest_few runs the same search depth first on Python floats.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from math import comb

import numpy as np

from . import kernels as alg

MAX_LEVELS = 60  # halvings at most (an interval is 2^-60 wide by then: settled by its middle)
BLOCK = 4096  # queries searched together (closest)
CROWDED = 64  # live intervals of one query in a level past which closest_few finishes it
MAX_INTERVALS = 4096  # intervals examined per query before the best so far is taken (compiled's)
NARROW = 1e-14  # an interval this narrow is settled by its middle (closest_compiled.NARROW)
NEWTON_STEPS = 60  # bracketed Newton's iterations at most (closest_compiled's bound)
# Newton stops once its step is within a few ulps of t (the compiled kernel's 1e-16 is below
# one ulp of t in [1/2, 1): there a step between two neighbouring floats runs on to the
# bracket's 1e-16, up to 60 rounds, cheap compiled and ~25 numpy calls a round here); the
# distance is flat at a minimum, so the few ulps of t do not show in it
STOP = 4e-16


@functools.cache
def _halving(size: int) -> tuple[np.ndarray, np.ndarray]:
    """(L, R), (size, size): the Bernstein coefficients of the left and right halves of a
    polynomial with coefficients c are L @ c and R @ c (de Casteljau at 1/2)."""
    left = np.zeros((size, size))
    for r in range(size):
        for k in range(r + 1):
            left[r, k] = comb(r, k) / 2.0**r
    right = left[::-1, ::-1].copy()
    return left, right


@functools.cache
def _product_map(degree: int) -> np.ndarray:
    """((N+1)^2, 2N+1) W: D's Bernstein coefficients are G.ravel() @ W, G the (N+1, N+1)
    Gram matrix of the differences c_i - q, W[(i, j), i + j] = C(N, i) C(N, j) / C(2N, i+j)."""
    n = degree
    out = np.zeros(((n + 1) * (n + 1), 2 * n + 1))
    for i in range(n + 1):
        for j in range(n + 1):
            out[i * (n + 1) + j, i + j] = comb(n, i) * comb(n, j) / comb(2 * n, i + j)
    return out


BLAS_THREADS_FROM = 1 << 18  # multiply-adds from which OpenBLAS runs a product on threads


def _product(x: np.ndarray, matrix: np.ndarray) -> np.ndarray:
    """x @ matrix cut into blocks of rows under OpenBLAS's threshold for threads: on a
    loaded machine its waiting threads made this module's products several times slower
    (degree 8, 10,000 queries, load 9: 365 ms against 141 ms with OPENBLAS_NUM_THREADS=1),
    as evaluate_many and batch_numpy found; each row's numbers are the same either way."""
    out = np.empty((x.shape[0], matrix.shape[1]))
    rows = max(1, BLAS_THREADS_FROM // max(1, matrix.size))
    for a in range(0, x.shape[0], rows):
        np.matmul(x[a : a + rows], matrix, out=out[a : a + rows])
    return out


def _table(c0: np.ndarray) -> np.ndarray:
    """(3d, N+1): the centred coefficients of p, p' and p'' as the rows of one table (the
    derivatives' missing top coefficients zero), so that one Horner pass gives all three."""
    dim, size = c0.shape
    rows = np.zeros((3 * dim, size))
    rows[:dim] = c0
    d1 = alg.differentiate_coefficients(c0, 1)
    d2 = alg.differentiate_coefficients(c0, 2)
    rows[dim : 2 * dim, : d1.shape[1]] = d1
    rows[2 * dim :, : d2.shape[1]] = d2
    return rows


def _distance2(c0: np.ndarray, t: np.ndarray, q: np.ndarray) -> np.ndarray:
    out: np.ndarray = np.square(alg.centred_horner(c0, t) - q).sum(-1)
    return out


def _minimum_inside(
    table: np.ndarray, q: np.ndarray, lo: np.ndarray, hi: np.ndarray, start: np.ndarray
) -> np.ndarray:
    """The one zero of g = (p - q) . p' in each [lo, hi] (g < 0 at lo, > 0 at hi): Newton
    kept inside a shrinking bracket, bisection where it would leave (closest_compiled's
    _minimum_inside, on every row at once), from `start` (the least Bernstein coefficient's
    place, not the middle: fewer rounds, each of which costs ~20 numpy calls here)."""
    dim = q.shape[1]
    a, b = lo.copy(), hi.copy()
    t = start.copy()
    live = np.arange(t.size)
    for _ in range(NEWTON_STEPS):
        if not live.size:
            break
        tl, ql = t[live], q[live]
        values = alg.centred_horner(table, tl)
        off = values[:, :dim] - ql
        slope = values[:, dim : 2 * dim]
        g = (off * slope).sum(-1)
        dg = (slope * slope).sum(-1) + (off * values[:, 2 * dim :]).sum(-1)
        zero = g == 0.0
        al = np.where(g < 0.0, tl, a[live])
        bl = np.where(g > 0.0, tl, b[live])
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(dg > 0.0, g / dg, np.inf)
        # a Newton step within a few ulps has converged: taken as it is, even where it
        # lands on the bracket's end (the compiled loop bisects on from there)
        converged = np.abs(step) <= STOP * np.maximum(1.0, np.abs(tl))
        nxt = tl - step
        nxt = np.where(converged | ((al < nxt) & (nxt < bl)), nxt, 0.5 * (al + bl))
        done = zero | converged | (np.abs(nxt - tl) <= STOP) | (bl - al <= 1e-16)
        a[live], b[live] = al, bl
        t[live] = np.where(zero, tl, nxt)
        live = live[~done]
    return t


def _sign_changes(diffs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(changes, first): per row, the sign changes of diffs with zeros skipped, and the sign
    of its first nonzero entry (0 when all are zero)."""
    signs = np.sign(diffs)
    cols = np.arange(signs.shape[1])
    last = np.maximum.accumulate(np.where(signs != 0, cols, 0), axis=1)
    filled = np.take_along_axis(signs, last, axis=1)  # the last nonzero sign so far
    changes = (filled[:, 1:] * filled[:, :-1] < 0).sum(1)
    first = np.take_along_axis(signs, np.argmax(signs != 0, axis=1)[:, None], axis=1)[:, 0]
    return changes, first


def closest(
    c0: np.ndarray, pts: np.ndarray, queries: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """extremes.closest without numba: c0 (d, N+1), the curve's centred coefficients, and
    pts (N+1, d), its Bernstein control points (N >= 1); queries (m, d). Returns (t (m,),
    points (m, d), squared distances (m,)); points and distances are evaluated on c0.

    Queries go BLOCK at a time, and a query with more than CROWDED live intervals in a level
    (a distance flat to rounding over a stretch, where breadth first would keep up to
    MAX_INTERVALS of them per query) is finished by closest_few, depth first: the rows held
    stay under BLOCK * 2 * CROWDED whatever the curve and the queries."""
    m = queries.shape[0]
    t, crowded = np.empty(m), np.zeros(m, dtype=bool)
    for a in range(0, m, BLOCK):
        t[a : a + BLOCK], crowded[a : a + BLOCK] = _closest_block(c0, pts, queries[a : a + BLOCK])
    if crowded.any():
        t[crowded] = closest_few(c0, pts, queries[crowded])[0]
    point = alg.centred_horner(c0, t)
    return t, point, np.square(point - queries).sum(-1)


def _closest_block(
    c0: np.ndarray, pts: np.ndarray, queries: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """closest's breadth-first search on one block of queries: (t, crowded), crowded
    marking the queries left to closest_few (their t not final)."""
    n = c0.shape[1] - 1
    m = queries.shape[0]
    table = _table(c0)
    diff = pts[None, :, :] - queries[:, None, :]  # (m, N+1, d)
    gram = diff[:, :, None, 0] * diff[:, None, :, 0]  # (m, N+1, N+1), coordinate by coordinate
    for j in range(1, diff.shape[2]):
        gram += diff[:, :, None, j] * diff[:, None, :, j]
    coeffs = _product(gram.reshape(m, -1), _product_map(n))  # (m, 2N+1)
    left_map, right_map = (h.T.copy() for h in _halving(2 * n + 1))
    best_t = np.zeros(m)
    best = _distance2(c0, best_t, queries)
    end = _distance2(c0, np.ones(m), queries)
    better = end < best
    best = np.where(better, end, best)
    best_t = np.where(better, 1.0, best_t)
    rows = np.arange(m)  # each live interval's query
    examined = np.zeros(m, dtype=np.int64)
    crowded = np.zeros(m, dtype=bool)
    lo, hi = np.zeros(m), np.ones(m)

    def offer(who: np.ndarray, t: np.ndarray) -> None:
        """Candidates t for the queries `who`: each query keeps its smallest distance (the
        first of equal ones, as the compiled kernel's strict comparison)."""
        if not who.size:
            return
        value = _distance2(c0, t, queries[who])
        order = np.lexsort((value, who))
        who, t, value = who[order], t[order], value[order]
        head = np.ones(who.size, dtype=bool)
        head[1:] = who[1:] != who[:-1]
        who, t, value = who[head], t[head], value[head]
        win = value < best[who]
        best[who[win]] = value[win]
        best_t[who[win]] = t[win]

    for _ in range(MAX_LEVELS):
        if not rows.size:
            break
        keep = coeffs.min(axis=1) < best[rows]
        live = np.bincount(rows[keep], minlength=m)
        crowded |= live > CROWDED
        keep &= ~crowded[rows]
        rows, lo, hi, coeffs = rows[keep], lo[keep], hi[keep], coeffs[keep]
        if not rows.size:
            break
        examined += live
        changes, first = _sign_changes(np.diff(coeffs, axis=1))
        monotone = changes == 0
        valley = (changes == 1) & (first < 0)
        narrow = ~(monotone | valley) & ((hi - lo <= NARROW) | (examined[rows] >= MAX_INTERVALS))
        offer(rows[monotone], np.where(first[monotone] >= 0, lo[monotone], hi[monotone]))
        if valley.any():
            who, a, b = rows[valley], lo[valley], hi[valley]
            start = a + (b - a) * (np.argmin(coeffs[valley], axis=1) / (2 * n))
            start = np.clip(start, a + 0.25 * (b - a) / n, b - 0.25 * (b - a) / n)
            offer(who, _minimum_inside(table, queries[who], a, b, start))
        offer(rows[narrow], 0.5 * (lo[narrow] + hi[narrow]))
        split = ~(monotone | valley | narrow)
        rows, lo, hi, coeffs = rows[split], lo[split], hi[split], coeffs[split]
        mid = 0.5 * (lo + hi)
        offer(rows, mid)
        rows = np.concatenate([rows, rows])
        coeffs = np.concatenate([_product(coeffs, left_map), _product(coeffs, right_map)])
        lo, hi = np.concatenate([lo, mid]), np.concatenate([mid, hi])
    if rows.size:  # past MAX_LEVELS (not reached in practice): settled by their middles
        offer(rows, 0.5 * (lo + hi))
    return best_t, crowded


def closest_few(
    c0: np.ndarray, pts: np.ndarray, queries: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """closest for a few queries: the same branch and bound depth first (closest_compiled's
    order) on Python floats, one query after another. Each numpy call costs about a
    microsecond whatever its size, and a level of the breadth-first loop takes dozens, so
    for one query Python's own arithmetic on the 2N+1 coefficients is the cheaper means."""
    n, dim = c0.shape[1] - 1, c0.shape[0]
    # per column of the table (p, p', p'' coordinate by coordinate), its centred
    # coefficients highest first: Horner then runs on one column's floats at a time
    table = [column[::-1] for column in _table(c0).tolist()]
    point_rows = table[:dim]
    product = _product_map(n)
    size = 2 * n + 1
    out_t = []
    for q, row in zip(queries.tolist(), queries, strict=True):
        diff = pts - row
        coeffs: list[float] = ((diff @ diff.T).reshape(-1) @ product).tolist()

        def values(t: float, q: list[float] = q) -> tuple[float, float, float]:
            """(D, g, g') at t by Horner on the centred table."""
            acc = _horner(table, t - 0.5)
            off = [acc[j] - q[j] for j in range(dim)]
            slope, second = acc[dim : 2 * dim], acc[2 * dim :]
            d2 = sum(o * o for o in off)
            g = sum(o * s for o, s in zip(off, slope, strict=True))
            dg = sum(s * s for s in slope) + sum(o * s for o, s in zip(off, second, strict=True))
            return d2, g, dg

        def distance2(t: float, q: list[float] = q) -> float:
            """D at t: values' first entry, from p's rows of the table alone."""
            return sum((a - b) ** 2 for a, b in zip(_horner(point_rows, t - 0.5), q, strict=True))

        best, best_t = distance2(0.0), 0.0
        end = distance2(1.0)
        if end < best:
            best, best_t = end, 1.0
        stack = [(coeffs, 0.0, 1.0)]
        examined = 0
        while stack:
            part, lo, hi = stack.pop()
            examined += 1
            if min(part) >= best:
                continue
            diffs = [b - a for a, b in zip(part[:-1], part[1:], strict=True) if b != a]
            changes = sum(
                (x > 0.0) != (y > 0.0) for x, y in zip(diffs[:-1], diffs[1:], strict=True)
            )
            first = diffs[0] if diffs else 0.0
            if changes == 0 or (changes == 1 and first < 0.0):
                if changes == 0:
                    t = lo if first >= 0.0 else hi
                else:
                    t = _minimum_inside_few(values, lo, hi, part, n)
            elif hi - lo <= NARROW or examined >= MAX_INTERVALS:
                t = 0.5 * (lo + hi)
            else:
                left, right = [0.0] * size, [0.0] * size
                work = list(part)
                left[0], right[size - 1] = work[0], work[size - 1]
                for r in range(1, size):
                    work = [0.5 * (a + b) for a, b in zip(work[:-1], work[1:], strict=True)]
                    left[r], right[size - 1 - r] = work[0], work[-1]
                mid = 0.5 * (lo + hi)
                value = distance2(mid)
                if value < best:
                    best, best_t = value, mid
                halves = [(left, lo, mid), (right, mid, hi)]
                if min(left) < min(right):  # the half with the smaller least coefficient on top
                    halves.reverse()
                stack += halves
                continue
            value = distance2(t)
            if value < best:
                best, best_t = value, t
        out_t.append(best_t)
    t_arr = np.array(out_t)
    point = alg.centred_horner(c0, t_arr)
    return t_arr, point, np.square(point - queries).sum(-1)


def _horner(columns: list[list[float]], u: float) -> list[float]:
    """Σ_e c_e u^e for each column c (its coefficients highest first), on Python floats.
    Column by column on scalars: the same operations in the same order as a pass over rows
    of the whole table, about 3x faster than building a list per power (degree 8, 6
    columns: 1.6 µs against 5.2 µs), and Horner is most of a single query's time."""
    out = []
    for column in columns:
        terms = iter(column)
        acc = next(terms)
        for coefficient in terms:
            acc = acc * u + coefficient
        out.append(acc)
    return out


def _minimum_inside_few(
    values: Callable[[float], tuple[float, float, float]],
    lo: float,
    hi: float,
    part: list[float],
    n: int,
) -> float:
    """_minimum_inside on Python floats, for one interval."""
    a, b = lo, hi
    k = part.index(min(part))
    t = min(max(a + (b - a) * k / (2 * n), a + 0.25 * (b - a) / n), b - 0.25 * (b - a) / n)
    for _ in range(NEWTON_STEPS):
        _, g, dg = values(t)
        if g == 0.0:
            return t
        if g < 0.0:
            a = t
        else:
            b = t
        step = g / dg if dg > 0.0 else math.inf
        if abs(step) <= STOP * max(1.0, abs(t)):
            return t - step
        nxt = t - step
        if not (a < nxt < b):
            nxt = 0.5 * (a + b)
        if abs(nxt - t) <= STOP or b - a <= 1e-16:
            return nxt
        t = nxt
    return t
