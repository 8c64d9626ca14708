"""A vectorised certified minimum of many polynomials in several variables over one box
(the surface energies of a batch of nets, every parameter of both directions): the
certificate of hazmat.surface_certify for any number of variables, every net's work as
rows of arrays.

The claim, per polynomial E (K of them, given as coefficients of shared monomials): its
minimiser over the box is unique and within δ <= `tol` of the returned point x (every
coordinate), about the float coefficients. Three parts, each on all nets at once:

1. a start (the caller's) polished by projected Newton steps, batched (a variable at an end
   of its range whose gradient pushes outward is held there), and put on a face it is
   within tol/2 of;
2. local: on the box R about x (half-width r a fraction of each side: the widest of 1/8,
   1/32, 1/128 that certifies; cut at the box's faces, so only inward along a held
   variable, or a free one nearer a face than r), the Hessian is at least μ I, μ > 0, from
   the Bernstein ranges of its entries over R (weighted diagonal dominance, weights
   1/sqrt(H_ii), or the scaled centre matrix's least eigenvalue less the ranges' spread,
   the larger), so E is strongly convex there and its minimiser x_R over R (convex, holding
   x) is unique and within δ = |∇E(x)| / μ of x, counting the gradient of the free
   variables only and its rounding: with t = x − x_R, optimality of x_R over R gives
   ∇E(x_R)·t >= 0, strong monotonicity μ |t|² <= (∇E(x) − ∇E(x_R))·t <= ∇E(x)·t, and a
   held variable's term g_j t_j is <= 0 (x_j at the face g_j pushes against). Part 3 then
   puts the box's minimiser in R, so it is x_R: R need not lie inside the open box, and a
   minimum near a face (within r of it, not on it) is certified like any other;
   Where the float gradient's rounding alone keeps δ above tol (ill-conditioned Hessians),
   Newton steps with the gradient computed exactly (Fractions of the float coefficients
   and point; `refine`) move x to the float lattice's best and bound |∇E| by half an ulp;
3. global: every point of the box outside R has E > E(x): rows (net, sub-box) are split
   (widest side first) until each one's least Bernstein coefficient, less its rounding
   bound, exceeds E(x) plus its own, or it lies inside R. The margin there is E's rise
   away from its minimum (about μ r²/2), never the 1e-12: generous rounding bounds
   (ROUND times the size of the terms) cost little.

A net is declined (certified False) when its Hessian is not certified over any R, or its
rows outrun MAX_ROWS or MAX_ROUNDS (a second minimum nearly as low as the first); the caller
solves those
one by one and counts them. Rounding bounds are generous estimates, not interval
arithmetic, as in surface_certify.
"""

from __future__ import annotations

from functools import cache
from math import comb
from typing import Any

import numpy as np

ROUND = 2.0**-40  # rounding bound of a Bernstein coefficient or a value, times its terms' size
# the gradient at the point by Horner: at most 2P <= 12 multiply-adds deep, so γ_24 < 25 u of
# its terms' size (u = 2^-53); 64 u for safety. This one bounds δ, so it must be tight
GRADIENT_ROUND = 64 * 2.0**-53
MAX_ROWS = 400_000  # rows (net, sub-box) alive at once, over the whole batch
MAX_ROUNDS = 60  # splitting rounds of the global exclusion
RADII = (1 / 8, 1 / 32, 1 / 128)  # R's half-width, times each side of the box


def dense(coeffs: np.ndarray, exponents: np.ndarray) -> np.ndarray:
    """(K, d_1+1, ..., d_P+1) power coefficients from (K, M) coefficients of the monomials
    x^exponents[m] (rows of (M, P))."""
    degree = exponents.max(axis=0)
    out = np.zeros((coeffs.shape[0], *(int(d) + 1 for d in degree)))
    for m, e in enumerate(exponents):
        index: tuple[Any, ...] = (slice(None), *(int(x) for x in e))
        out[index] += coeffs[:, m]
    return out


@cache
def _to_bernstein(n: int) -> np.ndarray:
    out = np.array(
        [[comb(k, j) / comb(n, j) if j <= k else 0.0 for j in range(n + 1)] for k in range(n + 1)]
    )
    out.setflags(write=False)
    return out


def bernstein(power: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """The tensor Bernstein coefficients of every row's polynomial (power (R, ...)) over its
    box [lo, hi] (rows of (R, P)), x_j = lo_j + (hi_j − lo_j) s_j.

    Along each axis: the Taylor shift to lo (Horner's synthetic division), the scaling by
    the width, then the constant change to the Bernstein basis, each step one array
    operation over every row at once. (Until round 20: a matrix per row, each applied by a
    stacked product of tiny matrices; at 372 to 40,000 rows of 3 x 3 coefficients that
    measured 3x slower.) The rounding stays far inside ROUND: a few ulps of the terms' size
    per step, at the degrees these energies have."""
    out = power
    rows = power.shape[0]
    for axis in range(power.ndim - 1):
        n = power.shape[axis + 1] - 1
        c = np.moveaxis(out, axis + 1, 0).copy()  # (n+1, rows, ...): c[j] the x^j coefficients
        shape = (rows,) + (1,) * (c.ndim - 2)
        a = lo[:, axis].reshape(shape)
        h = (hi[:, axis] - lo[:, axis]).reshape(shape)
        for i in range(n):  # Taylor shift to a: c[i] becomes the (x − a)^i coefficient
            for j in range(n - 1, i - 1, -1):
                c[j] += a * c[j + 1]
        scale = h
        for i in range(1, n + 1):  # x − a = h s
            c[i] *= scale
            if i < n:
                scale = scale * h
        to_bernstein = _to_bernstein(n)
        b = np.empty_like(c)
        for k in range(n + 1):  # b_k = Σ_{i <= k} C(k, i) / C(n, i) d_i
            acc = c[0].copy()
            for i in range(1, k + 1):
                acc += to_bernstein[k, i] * c[i]
            b[k] = acc
        out = np.moveaxis(b, 0, axis + 1)
    return out


def _size(power: np.ndarray, reach: np.ndarray) -> np.ndarray:
    """Σ |c_e| Π reach_j^e_j per row: the size of the terms anywhere with |x_j| <= reach_j
    (the rounding bounds' measure)."""
    out = np.abs(power)
    for axis in range(power.ndim - 1):
        n = power.shape[axis + 1]
        shape = [1] * power.ndim
        shape[0], shape[axis + 1] = -1, n
        out = out * (reach[:, axis : axis + 1] ** np.arange(n)).reshape(shape)
    total: np.ndarray = out.reshape(power.shape[0], -1).sum(axis=1)
    return total


def _derivative(power: np.ndarray, axis: int) -> np.ndarray:
    n = power.shape[axis + 1]
    if n == 1:
        return np.zeros_like(power)
    shape = [1] * power.ndim
    shape[axis + 1] = n - 1
    return np.take(power, range(1, n), axis=axis + 1) * np.arange(1, n).reshape(shape)


def value(power: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Every row's polynomial at its point (rows of x), Horner along each axis."""
    out = power
    for axis in range(power.ndim - 2, -1, -1):
        acc = out[..., -1]
        t = x[:, axis].reshape((-1,) + (1,) * (acc.ndim - 1))
        for k in range(out.shape[-1] - 2, -1, -1):
            acc = acc * t + out[..., k]
        out = acc
    return np.asarray(out)


def polish(
    power: np.ndarray, x: np.ndarray, lo: np.ndarray, hi: np.ndarray, steps: int = 8
) -> np.ndarray:
    """Projected Newton steps for every row at once, clipped to the box (a row keeps its
    point where its Hessian is not positive definite or the step does not lower E)."""
    count = power.shape[0]
    dims = power.ndim - 1
    grads = [_derivative(power, j) for j in range(dims)]
    hess = [[_derivative(grads[i], j) for j in range(dims)] for i in range(dims)]
    x = np.clip(x, lo, hi)
    fx = value(power, x)
    for _ in range(steps):
        g = np.stack([value(grads[i], x) for i in range(dims)], axis=1)
        h = np.stack(
            [np.stack([value(hess[i][j], x) for j in range(dims)], axis=1) for i in range(dims)],
            axis=1,
        )
        # variables at an end whose gradient pushes outward are held: Newton on the others
        held = ((x <= lo) & (g > 0)) | ((x >= hi) & (g < 0))
        pair = held[:, :, None] | held[:, None, :]
        h = np.where(pair, np.eye(dims)[None], h)
        g = np.where(held, 0.0, g)
        ok = np.all(np.linalg.eigvalsh(h) > 0, axis=1)
        safe = np.where(ok[:, None, None], h, np.eye(dims)[None])
        step = np.linalg.solve(safe, g[:, :, None])[:, :, 0]
        y = np.clip(x - np.where(ok[:, None], step, 0.0), lo, hi)
        fy = value(power, y)
        better = ok & (fy <= fx)
        x = np.where(better[:, None], y, x)
        fx = np.where(better, fy, fx)
    return x.reshape(count, dims)


def _local(
    power: np.ndarray,
    x: np.ndarray,
    lo: np.ndarray,
    hi: np.ndarray,
    frac: float,
    tol: float,
    exact: tuple[np.ndarray, np.ndarray] | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(rlo, rhi, δ, ok) of part 2 for half-width frac · (hi − lo): R's corners (within
    the box), the distance bound, and where it certifies.

    A variable at an end of its range whose gradient pushes outward (beyond its rounding)
    is held there: R spans [end, end ± r] in it, and the distance bound counts only the
    other variables' gradient (strong monotonicity, μ |t|² <= −∇E(x)·t, and the held
    ones' terms are <= 0). The Hessian's lower bound H >= μ I over R is the larger of two:
    weighted diagonal dominance (weights 1/sqrt(H_ii)) and the least eigenvalue of the
    scaled centre matrix less its rounding and the scaled ranges' spread."""
    count, dims = x.shape
    r = frac * (hi - lo)
    grads = [_derivative(power, j) for j in range(dims)]
    if exact is None:
        g = np.stack([value(grads[i], x) for i in range(dims)], axis=1)
        g_round = np.stack(
            [GRADIENT_ROUND * _size(grads[i], np.abs(x)) for i in range(dims)], axis=1
        )
    else:  # the gradient computed exactly (refine), and its float's rounding
        g, g_round = exact
    at_lo, at_hi = (x <= lo) & (g > g_round), (x >= hi) & (g < -g_round)
    held = at_lo | at_hi
    rlo = np.where(at_lo, lo, np.maximum(x - r, lo))  # cut at the faces: see the module's doc
    rhi = np.where(at_hi, hi, np.minimum(x + r, hi))
    reach = np.maximum(np.abs(rlo), np.abs(rhi))
    low = np.empty((count, dims, dims))
    high = np.empty((count, dims, dims))
    for i in range(dims):
        for j in range(i, dims):
            hij = _derivative(grads[i], j)
            coeffs = bernstein(hij, rlo, rhi).reshape(count, -1)
            slack = ROUND * _size(hij, reach)
            low[:, i, j] = low[:, j, i] = coeffs.min(axis=1) - slack
            high[:, i, j] = high[:, j, i] = coeffs.max(axis=1) + slack
    diag = np.diagonal(low, axis1=1, axis2=2)
    w = 1 / np.sqrt(np.where(diag > 0, diag, 1.0))
    off = np.maximum(np.abs(low), np.abs(high)) * (1 - np.eye(dims))[None]
    dominance = (diag - np.einsum("rij,rj->ri", off, w) / w).min(axis=1)
    scaled = 0.5 * (low + high) * w[:, :, None] * w[:, None, :]
    spread = (0.5 * (high - low) * w[:, :, None] * w[:, None, :]).sum(axis=2).max(axis=1)
    eig = np.linalg.eigvalsh(scaled)
    least = eig[:, 0] - 1e-12 * np.abs(eig).max(axis=1) - spread  # scaled: H >= least D^-2
    spectral = least * (1 / (w * w)).min(axis=1)
    mu = np.maximum(dominance, spectral)
    free = np.where(held, 0.0, np.abs(g) + g_round)
    with np.errstate(divide="ignore", invalid="ignore"):
        delta = np.sqrt((free**2).sum(axis=1)) / np.where(mu > 0, mu, 1.0)
    ok = (mu > 0) & (delta <= tol)
    return rlo, rhi, np.where(mu > 0, delta, np.inf), ok


def _dyadic(values: np.ndarray) -> tuple[list[int], list[int]]:
    """(m, k) with value = m · 2^k exactly, for every float of `values` (flattened)."""
    mant, expo = np.frexp(np.ravel(values))
    m = (mant * 2.0**53).astype(np.int64)  # exact: |mant| < 1 has 53 bits
    return [int(v) for v in m], [int(e) - 53 for e in expo]


def _exact_gradient(power: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(g, bound) per row: ∇E at the float point x computed exactly, g its float and
    bound >= |g − exact| (half a unit in the last place, and the least subnormal).

    Every float is an integer times a power of two, so each term c_e e_i Π x_j^(e_j − δ_ij)
    is one too (Python integers, no rounding); the terms are summed on their least power of
    two and the sum divided once, which Python rounds correctly (int / int): the same
    exact value as with Fractions, without their gcd at every step."""
    count, dims = x.shape
    shape = power.shape[1:]
    exps = [tuple(int(v) for v in e) for e in np.ndindex(*shape)]
    g = np.empty((count, dims))
    for k in range(count):
        cm, ck = _dyadic(power[k])
        xm, xk = _dyadic(x[k])
        powers = [[xm[j] ** a for a in range(shape[j])] for j in range(dims)]
        for i in range(dims):
            nums: list[int] = []
            twos: list[int] = []
            for e, m, c_two in zip(exps, cm, ck, strict=True):
                if m == 0 or e[i] == 0:
                    continue
                num, two = m * e[i], c_two
                for j in range(dims):
                    a = e[j] - (j == i)
                    num *= powers[j][a]
                    two += xk[j] * a
                nums.append(num)
                twos.append(two)
            if not nums:
                g[k, i] = 0.0
                continue
            low = min(twos)
            total = sum(n << (t - low) for n, t in zip(nums, twos, strict=True))
            g[k, i] = total * 2.0**low if low >= 0 else total / (1 << -low)
    return g, np.abs(g) * 2.0**-53 + 2.0**-1074


def refine(
    power: np.ndarray, x: np.ndarray, lo: np.ndarray, hi: np.ndarray, steps: int = 2
) -> tuple[np.ndarray, tuple[np.ndarray, np.ndarray]]:
    """(x, (g, bound)): Newton steps with the gradient computed exactly (the float Hessian
    for the step; held variables as in polish), for points whose float gradient is all
    rounding; the last point's exact gradient and its bound, for _local."""
    dims = x.shape[1]
    grads = [_derivative(power, j) for j in range(dims)]
    hess = [[_derivative(grads[i], j) for j in range(dims)] for i in range(dims)]
    for _ in range(steps):
        g, _ = _exact_gradient(power, x)
        h = np.stack(
            [np.stack([value(hess[i][j], x) for j in range(dims)], axis=1) for i in range(dims)],
            axis=1,
        )
        held = ((x <= lo) & (g > 0)) | ((x >= hi) & (g < 0))
        h = np.where(held[:, :, None] | held[:, None, :], np.eye(dims)[None], h)
        g = np.where(held, 0.0, g)
        ok = np.all(np.linalg.eigvalsh(h) > 0, axis=1)
        safe = np.where(ok[:, None, None], h, np.eye(dims)[None])
        step = np.linalg.solve(safe, g[:, :, None])[:, :, 0]
        x = np.clip(x - np.where(ok[:, None], step, 0.0), lo, hi)
    return x, _exact_gradient(power, x)


def certified_minimum(
    coeffs: np.ndarray,
    exponents: np.ndarray,
    lo: np.ndarray,
    hi: np.ndarray,
    start: np.ndarray,
    tol: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(x, E(x), δ, certified) for every row of `coeffs` (polynomials in the monomials
    `exponents`) over the box [lo, hi], from the points `start`; see the module's doc."""
    power = dense(coeffs, exponents)
    count, dims = start.shape
    x = polish(power, start, lo, hi)
    # a coordinate within tol/2 of a face is put on it: polish keeps a point a few ulps
    # inside a face where E's rounding hides its last step, and the one-net path names such
    # a minimum's end; the certificate below is of whichever point it is given
    x = np.where(x - lo <= tol / 2, lo, np.where(hi - x <= tol / 2, hi, x))
    energy = value(power, x)
    size = _size(power, np.broadcast_to(np.maximum(np.abs(lo), np.abs(hi)), (count, dims)))
    rlo, rhi = np.empty((count, dims)), np.empty((count, dims))
    delta, ok = np.full(count, np.inf), np.zeros(count, bool)
    for frac in RADII:  # the widest R that certifies, per net
        todo = np.flatnonzero(~ok)
        if todo.size == 0:
            break
        a, b, d, good = _local(power[todo], x[todo], lo, hi, frac, tol)
        pick = todo[good]
        rlo[pick], rhi[pick], delta[pick], ok[pick] = a[good], b[good], d[good], True
    # nets whose gradient's rounding keeps δ above tol: refined with exact gradients
    todo = np.flatnonzero(~ok)
    if todo.size:
        x[todo], exact = refine(power[todo], x[todo], lo, hi)
        energy[todo] = value(power[todo], x[todo])
        for frac in RADII:
            a, b, d, good = _local(power[todo], x[todo], lo, hi, frac, tol, exact)
            pick = todo[good & ~ok[todo]]
            good = good & ~ok[todo]
            rlo[pick], rhi[pick], delta[pick], ok[pick] = a[good], b[good], d[good], True
    level = energy + ROUND * size
    # part 3: the rows (net, sub-box) of the nets still in play
    net = np.flatnonzero(ok)
    blo = np.broadcast_to(lo, (net.size, dims)).copy()
    bhi = np.broadcast_to(hi, (net.size, dims)).copy()
    for _ in range(MAX_ROUNDS):
        if net.size == 0:
            break
        if net.size > MAX_ROWS:  # decline the nets with the most rows until it fits
            rows_per = np.bincount(net, minlength=count)
            order = np.argsort(-rows_per)
            total, dropped = net.size, []
            for k in order:
                if total <= MAX_ROWS:
                    break
                total -= rows_per[k]
                dropped.append(k)
            ok[dropped] = False
            keep = ok[net]
            net, blo, bhi = net[keep], blo[keep], bhi[keep]
            continue
        inside = np.all((blo >= rlo[net]) & (bhi <= rhi[net]), axis=1)
        sub = power[net]
        coeffs_b = bernstein(sub, blo, bhi).reshape(net.size, -1)
        reach = np.maximum(np.abs(blo), np.abs(bhi))
        bound = coeffs_b.min(axis=1) - ROUND * _size(sub, reach)
        open_ = ~inside & ~(bound > level[net])
        net, blo, bhi = net[open_], blo[open_], bhi[open_]
        if net.size == 0:
            break
        # split across the widest side relative to the box
        axis = np.argmax((bhi - blo) / (hi - lo), axis=1)
        rows = np.arange(net.size)
        mid = 0.5 * (blo[rows, axis] + bhi[rows, axis])
        left_hi, right_lo = bhi.copy(), blo.copy()
        left_hi[rows, axis] = mid
        right_lo[rows, axis] = mid
        net = np.concatenate([net, net])
        blo = np.concatenate([blo, right_lo])
        bhi = np.concatenate([left_hi, bhi])
    if net.size:  # rows left after the last round: those nets are declined
        ok[np.unique(net)] = False
    return x, energy, delta, ok
