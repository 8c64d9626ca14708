"""Surface kernels compiled with numba (the `fast` extra): the batch optimum of (λ_u, λ_v),
one pass per net, and grid evaluation.

Grid evaluation (`grid_rows`): every output row once, from its weights by Horner, one thread.
numpy's version is a product per coordinate, which numpy hands to BLAS, whose threads cost
more than the arithmetic when the machine is busy (measured on a loaded two-core machine:
3.5x the output's write cost with one BLAS thread, 50x with OpenBLAS's threads). Until
round 20 this module did that product itself, four loads and four products a value from a
table of powers of (v - 1/2) (1.6-2.1x the one-thread fill in the benchmark, load 7);
Horner on (v - 1/2) takes one load and three multiply-adds (1.07x there).

The batch optimum:

The numpy version (lambda_bezier.surface_optimum.optimal_parameters_batch) makes some forty
passes over the batch and finds the resultant's roots by eigenvalues of companion matrices;
here each net is done in one loop iteration, in registers:

1. the energy's coefficients e_ab (E = Σ_{a,b<=2} e_ab x^a y^b) from the net's Gram products
   g_ij = Σ_d P_id P_jd, i <= j, and the pair weights of the energy matrices (`pair_weights`);
2. the candidates: the four corners and the minima of the edges (quadratics, closed form),
   and the interior critical points: y a root of the resultant R(y) = γβ² − δαβ + εα² (degree
   <= 5) in the open box, found by the derivative chain (the roots of R^(j+1) split the box
   into intervals where R^(j) is monotone; a sign change there brackets exactly one root,
   found by Newton safeguarded by bisection), x = −β/α, and Newton on ∇E = 0;
3. the certification of the numpy version: a net is `uncertain` (and solved again exactly by
   the caller) when the winner is an interior point whose last Newton step is not below
   `step_tolerance` with a positive definite Hessian, or another candidate at a distinct point
   comes within 1e-12 (relative) of the least energy, or R's leading coefficient is tiny, or R
   nearly touches zero at one of its local extremes without crossing (a nearly double root:
   the companion eigenvalue test "nearly real" of the numpy version).

Imported only by surface_optimum and surfaces, when numba is installed and not disabled.
"""

from __future__ import annotations

import math
from typing import Any

import numba
import numpy as np

_JIT: dict[str, Any] = {"cache": True, "error_model": "numpy", "fastmath": False}
NEAR_DOUBLE = 1e-9  # |R| at a local extreme below this times R's size: a nearly double root


@numba.njit(**_JIT)
def _horner(c: np.ndarray, deg: int, x: float) -> float:
    acc = 0.0
    for i in range(deg, -1, -1):
        acc = acc * x + c[i]
    return acc


@numba.njit(**_JIT)
def _bracketed_root(c: np.ndarray, deg: int, a: float, b: float, fa: float) -> float:
    """The one root of the polynomial c (degree deg, low first) in (a, b), where it is
    monotone and changes sign; Newton kept inside the shrinking bracket, else bisection."""
    x = 0.5 * (a + b)
    for _ in range(200):
        fx = 0.0
        dfx = 0.0
        for i in range(deg, -1, -1):
            dfx = dfx * x + fx
            fx = fx * x + c[i]
        if fx == 0.0:
            return x
        if (fx > 0.0) == (fa > 0.0):
            a, fa = x, fx
        else:
            b = x
        step_ok = dfx != 0.0
        nx = x - fx / dfx if step_ok else 0.5 * (a + b)
        if not (a < nx < b):
            nx = 0.5 * (a + b)
        if nx == x or b - a <= 4e-16 * max(1.0, abs(a), abs(b)):
            return nx
        x = nx
    return x


@numba.njit(**_JIT)
def _roots_in(
    c: np.ndarray, lo: float, hi: float, out: np.ndarray, ders: np.ndarray, pts: np.ndarray
) -> tuple[int, bool]:
    """The real roots of c (degree <= 5, low first) in the open interval (lo, hi), into out;
    (count, nearly_double). ders (6, 6) and pts (7,) are scratch."""
    size = 0.0
    for i in range(6):
        size = max(size, abs(c[i]))
    deg = 5
    while deg > 0 and c[deg] == 0.0:
        deg -= 1
    if deg == 0:
        return 0, c[0] == 0.0  # R ≡ 0: no isolated roots; the caller cannot decide
    # derivative chain: ders[j] holds R^(j), low first
    ders[:] = 0.0
    for i in range(deg + 1):
        ders[0, i] = c[i]
    for j in range(1, deg):
        for i in range(deg - j + 1):
            ders[j, i] = ders[j - 1, i + 1] * (i + 1)
    count = 0
    # R^(deg-1) is linear
    j = deg - 1
    if ders[j, 1] != 0.0:
        r = -ders[j, 0] / ders[j, 1]
        if lo < r < hi:
            out[0] = r
            count = 1
    near = False
    for j in range(deg - 2, -1, -1):
        d = deg - j
        pts[0] = lo
        for k in range(count):
            pts[k + 1] = out[k]
        pts[count + 1] = hi
        n_pts = count + 2
        count = 0
        fa = _horner(ders[j], d, pts[0])
        for k in range(n_pts - 1):
            a, b = pts[k], pts[k + 1]
            fb = _horner(ders[j], d, b)
            if k > 0 and fa == 0.0:
                out[count] = a
                count += 1
            elif (fa > 0.0 and fb < 0.0) or (fa < 0.0 and fb > 0.0):
                out[count] = _bracketed_root(ders[j], d, a, b, fa)
                count += 1
            if j == 0 and k > 0 and fa != 0.0:
                # a local extreme of R (an interior point of the chain) close to zero
                scale = 0.0
                for i in range(d + 1):
                    scale += abs(ders[0, i]) * abs(a) ** i
                if abs(fa) <= NEAR_DOUBLE * max(scale, size):
                    near = True
            fa = fb
    return count, near


@numba.njit(**_JIT)
def _energy(e: np.ndarray, x: float, y: float) -> float:
    px = (1.0, x, x * x)
    py = (1.0, y, y * y)
    out = 0.0
    for a in range(3):
        for b in range(3):
            out += e[a, b] * px[a] * py[b]
    return out


@numba.njit(**_JIT)
def _edge_min(c0: float, c1: float, c2: float, lo: float, hi: float) -> float:
    if c2 > 0.0:
        t = -c1 / (2.0 * c2)
        if not math.isfinite(t):
            t = lo
    else:
        t = lo
    return min(max(t, lo), hi)


@numba.njit(**_JIT)
def _polymul(a: np.ndarray, na: int, b: np.ndarray, nb: int, out: np.ndarray) -> None:
    for i in range(na + nb - 1):
        out[i] = 0.0
    for i in range(na):
        for j in range(nb):
            out[i + j] += a[i] * b[j]


@numba.njit(**_JIT)
def _solve_one(
    e: np.ndarray,
    box: np.ndarray,
    work: np.ndarray,
    kind: np.ndarray,
    posdef: np.ndarray,
    step_tolerance: float,
) -> tuple[float, float, float, int, bool]:
    """(x, y, E, where, uncertain) for one net's coefficients e (3, 3); where: 0 edge,
    1 interior, 2 corner. work (12, 13), kind (13,) and posdef (13,) are scratch (no
    allocation per net: it would cost more than the arithmetic)."""
    xlo, xhi, ylo, yhi = box[0], box[1], box[2], box[3]
    cx, cy, steps, values = work[0], work[1], work[2], work[3]
    alpha, beta, gamma, delta, eps = work[4, :3], work[5, :3], work[6, :2], work[7, :2], work[8, :2]
    t1, t2, res, roots = work[9, :5], work[10, :6], work[11, :6], work[4, 6:12]
    ders, pts = work[12:18, :6], work[18, :7]
    kind[:] = 0  # 1 for an interior candidate
    posdef[:] = False
    steps[:] = np.inf
    n = 0
    for x0 in (xlo, xhi):
        c0 = e[0, 0] + e[1, 0] * x0 + e[2, 0] * x0 * x0
        c1 = e[0, 1] + e[1, 1] * x0 + e[2, 1] * x0 * x0
        c2 = e[0, 2] + e[1, 2] * x0 + e[2, 2] * x0 * x0
        for y in (ylo, yhi, _edge_min(c0, c1, c2, ylo, yhi)):
            cx[n] = x0
            cy[n] = y
            n += 1
    for y0 in (ylo, yhi):
        c0 = e[0, 0] + e[0, 1] * y0 + e[0, 2] * y0 * y0
        c1 = e[1, 0] + e[1, 1] * y0 + e[1, 2] * y0 * y0
        c2 = e[2, 0] + e[2, 1] * y0 + e[2, 2] * y0 * y0
        cx[n] = _edge_min(c0, c1, c2, xlo, xhi)
        cy[n] = y0
        n += 1
    # interior: E_x = α(y) x + β(y), E_y = γ(y) x² + δ(y) x + ε(y)
    for i in range(3):
        alpha[i] = 2 * e[2, i]
        beta[i] = e[1, i]
    for i in range(2):
        gamma[i] = (i + 1) * e[2, i + 1]
        delta[i] = (i + 1) * e[1, i + 1]
        eps[i] = (i + 1) * e[0, i + 1]
    res[:] = 0.0
    _polymul(beta, 3, beta, 3, t1)
    _polymul(gamma, 2, t1, 5, t2)
    for i in range(6):
        res[i] += t2[i]
    _polymul(alpha, 3, beta, 3, t1)
    _polymul(delta, 2, t1, 5, t2)
    for i in range(6):
        res[i] -= t2[i]
    _polymul(alpha, 3, alpha, 3, t1)
    _polymul(eps, 2, t1, 5, t2)
    for i in range(6):
        res[i] += t2[i]
    size = 0.0
    for i in range(6):
        size = max(size, abs(res[i]))
    suspect = not (abs(res[5]) > 1e-9 * size)
    count, near = _roots_in(res, ylo, yhi, roots, ders, pts)
    suspect = suspect or near
    for r in range(count):
        y = roots[r]
        a_y = alpha[0] + alpha[1] * y + alpha[2] * y * y
        if a_y == 0.0:
            suspect = True
            continue
        x = -(beta[0] + beta[1] * y + beta[2] * y * y) / a_y
        step = np.inf
        pd = False
        for _ in range(4):
            px1, py1 = x, y
            gx = (e[1, 0] + e[1, 1] * y + e[1, 2] * y * y) + 2 * x * (
                e[2, 0] + e[2, 1] * y + e[2, 2] * y * y
            )
            gy = (e[0, 1] + 2 * e[0, 2] * y) + x * (e[1, 1] + 2 * e[1, 2] * y)
            gy += x * x * (e[2, 1] + 2 * e[2, 2] * y)
            hxx = 2 * (e[2, 0] + e[2, 1] * y + e[2, 2] * y * y)
            hyy = 2 * (e[0, 2] + e[1, 2] * x + e[2, 2] * x * x)
            hxy = (e[1, 1] + 2 * e[1, 2] * y) + 2 * x * (e[2, 1] + 2 * e[2, 2] * y)
            det = hxx * hyy - hxy * hxy
            dx = (hyy * gx - hxy * gy) / det
            dy = (hxx * gy - hxy * gx) / det
            x, y = px1 - dx, py1 - dy
            step = max(abs(dx), abs(dy)) / (1 + abs(x) + abs(y))
            pd = hxx > 0 and det > 0
        if not (math.isfinite(x) and math.isfinite(y)):
            suspect = True  # a degenerate Hessian on the way: the caller decides exactly
            continue
        if xlo < x < xhi and ylo < y < yhi and math.isfinite(x) and math.isfinite(y):
            cx[n] = x
            cy[n] = y
            kind[n] = 1
            steps[n] = step
            posdef[n] = pd
            n += 1
    best = 0
    emax = 0.0
    for a in range(3):
        for b in range(3):
            emax = max(emax, abs(e[a, b]))
    for k in range(n):
        values[k] = _energy(e, cx[k], cy[k])
        if values[k] < values[best]:
            best = k
    bx, by, bval = cx[best], cy[best], values[best]
    uncertain = suspect
    if kind[best] == 1 and not (steps[best] < step_tolerance and posdef[best]):
        uncertain = True
    margin = 1e-12 * max(abs(bval), emax)
    for k in range(n):
        if abs(cx[k] - bx) + abs(cy[k] - by) > 1e-9 and values[k] <= bval + margin:
            uncertain = True
    where = 1 if kind[best] == 1 else 0
    if bx in (xlo, xhi) and by in (ylo, yhi):
        where = 2
    return bx, by, bval, where, uncertain


@numba.njit(**_JIT)
def _optimise_range(
    flat: np.ndarray,
    pair_i: np.ndarray,
    pair_j: np.ndarray,
    weights: np.ndarray,
    box: np.ndarray,
    step_tolerance: float,
    start: int,
    stop: int,
    out: np.ndarray,
    where: np.ndarray,
    uncertain: np.ndarray,
) -> None:
    dim = flat.shape[2]
    n_pairs = pair_i.shape[0]
    acc = np.empty(9)
    e = acc.reshape((3, 3))
    work = np.empty((19, 13))
    kind = np.empty(13, np.int64)
    posdef = np.empty(13, np.bool_)
    for k in range(start, stop):
        acc[:] = 0.0
        for p in range(n_pairs):
            g = 0.0
            for c in range(dim):
                g += flat[k, pair_i[p], c] * flat[k, pair_j[p], c]
            for t in range(9):
                acc[t] += weights[p, t] * g
        x, y, v, w, u = _solve_one(e, box, work, kind, posdef, step_tolerance)
        out[0, k], out[1, k], out[2, k], where[k], uncertain[k] = x, y, v, w, u


@numba.njit(**_JIT)
def optimise(
    flat: np.ndarray,
    pair_i: np.ndarray,
    pair_j: np.ndarray,
    weights: np.ndarray,
    box: np.ndarray,
    step_tolerance: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """For nets flat (k, s, d) and the energy as Σ_p weights[p, 3a + b] g_p x^a y^b over the
    pairs p = (pair_i[p], pair_j[p]) with g_p = Σ_d flat[:, i, d] flat[:, j, d]: the least
    energy over box = (xlo, xhi, ylo, yhi), per net (x, y, energy, where, uncertain).

    One thread: numba's parallel loop over chunks measured slower on the shared two-core
    machine the benchmarks run on, and each net's work is too small to split."""
    count = flat.shape[0]
    out = np.empty((3, count))
    where = np.empty(count, np.int64)
    uncertain = np.empty(count, np.bool_)
    _optimise_range(
        flat, pair_i, pair_j, weights, box, step_tolerance, 0, count, out, where, uncertain
    )
    return out[0], out[1], out[2], where, uncertain


@numba.njit(cache=True, error_model="numpy", fastmath={"contract"})
def grid_rows(coeffs: np.ndarray, us: np.ndarray, vs: np.ndarray, out: np.ndarray) -> None:
    """out[c, a, b] = S_c(us[a], vs[b]) for the Taylor tensor coeffs (M+1, N+1, d) about
    (1/2, 1/2); out (d, len(us), len(vs)), C-contiguous, written in place.

    Per row: the N+1 weights w_k = Σ_i coeffs[i, k, c] (u - 1/2)^i by Horner (registers),
    then out[c, a, b] = Σ_k w_k (v_b - 1/2)^k by Horner, three coefficients a pass over the
    row (one pass for N <= 3, a bicubic's row written once, from L1 while it is built):
    one load of (v_b - 1/2) and three fused multiply-adds per value, where the products with
    a powers table cost four loads and four products. fastmath "contract" only (one rounding
    per multiply-add, no reassociation)."""
    big_m, big_n, dim = coeffs.shape
    nv = vs.size
    # the row's weights padded with zeros above the degree to 4 + 3j (zeros change nothing:
    # 0 * s + w is w exactly), so every pass takes three of them
    size = 4 if big_n <= 4 else 4 + (big_n - 2) // 3 * 3
    w = np.zeros(size)
    sv = np.empty(nv)
    for b in range(nv):
        sv[b] = vs[b] - 0.5
    for c in range(dim):
        for a in range(us.size):
            su = us[a] - 0.5
            for k in range(big_n):
                acc = coeffs[big_m - 1, k, c]
                for i in range(big_m - 2, -1, -1):
                    acc = acc * su + coeffs[i, k, c]
                w[k] = acc
            row = out[c, a]
            w0, w1, w2, w3 = w[size - 4], w[size - 3], w[size - 2], w[size - 1]
            for b in range(nv):
                s = sv[b]
                row[b] = w0 + s * (w1 + s * (w2 + s * w3))
            for k in range(size - 5, 0, -3):
                w0, w1, w2 = w[k - 2], w[k - 1], w[k]
                for b in range(nv):
                    s = sv[b]
                    row[b] = w0 + s * (w1 + s * (w2 + s * row[b]))
