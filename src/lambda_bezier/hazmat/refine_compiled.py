"""The refinement steps of intersect's careful path compiled with numba (used by
settle_compiled): a curve's points, hodographs and sizes; the careful path's float and
exact-residual Newton, its tangent refinement, its acceptance of a hit and its merging rule,
each step for step as hazmat.intersect has it, with residuals evaluated by compensated de
Casteljau where the careful path uses rationals.

Imported only by settle_compiled, and only when numba is installed and not disabled.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .pieces_compiled import JIT as _JIT
from .pieces_compiled import compensated, compensated_pair, two_prod, two_sum, value_slope

# a curve as the kernel carries it (_curve): points, p' (hi, lo), p'', scratch. The scratch
# (SCRATCH_ROWS, n+1, d) lets the refinement run without allocating per step (an allocation
# costs ~50 ns, a share of a Newton step; issue #29): row 0 de Casteljau's work array (_at,
# _d_into, value_slope), rows 1 and 2 compensated de Casteljau's hi and lo (_residual,
# _derivative_into, _value_minus), row 3's first vector the unused slope those write, row 4's
# first vector a value for one helper at a time (_sine, _gap, _on_both, _distance ...). A
# helper writes only its own curve's scratch, so p's and q's never clash.
Curve = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]
SCRATCH_ROWS = 5
Halves = tuple[np.ndarray, np.ndarray]  # intersect_subdivide.half_matrices
# kind codes, in the order of the careful path's kind strings ("coincident" < "tangent" <
# "transversal"), so that hits sort as its tuples do
COINCIDENT, TANGENT, TRANSVERSAL = -1, 0, 1

# intersect.SETTLE: on curve, same root, isolated same, merge radius, merge gap, root
# residual, box slack, wide piece, near found, tangent sine, then intersect_subdivide's
# depth, max rows, Newton steps, inside, cone margin
Knobs = tuple[
    float,
    float,
    float,
    float,
    float,
    float,
    float,
    float,
    float,
    float,
    int,
    int,
    int,
    float,
    float,
]


# ---------------------------------------------------------------------------- one curve
@numba.njit(**_JIT)
def _hodograph(pts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """n (b_{i+1} - b_i) as double-doubles (hi, lo): the difference is exact as a two_sum,
    the product by n as a two_prod. A degree-0 input gives one zero row."""
    n, dim = pts.shape[0] - 1, pts.shape[1]
    if n == 0:
        return np.zeros((1, dim)), np.zeros((1, dim))
    hi, lo = np.empty((n, dim)), np.empty((n, dim))
    for i in range(n):
        for j in range(dim):
            d, e = two_sum(pts[i + 1, j], -pts[i, j])
            p, f = two_prod(float(n), d)
            hi[i, j], lo[i, j] = two_sum(p, f + n * e)
    return hi, lo


@numba.njit(**_JIT)
def _at(ctrl: np.ndarray, s: float, work: np.ndarray, out: np.ndarray) -> None:
    """ctrl's curve at s in floats (de Casteljau, as Prepared.at)."""
    n, dim = ctrl.shape[0] - 1, ctrl.shape[1]
    for i in range(n + 1):
        for j in range(dim):
            work[i, j] = ctrl[i, j]
    for level in range(n):
        for i in range(n - level):
            for j in range(dim):
                work[i, j] = work[i, j] + s * (work[i + 1, j] - work[i, j])
    for j in range(dim):
        out[j] = work[0, j]


@numba.njit(**_JIT)
def _curve(pts: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(points, p' hi, p' lo, p'' in floats, scratch): a curve as the kernel uses it."""
    h1, h1_lo = _hodograph(pts)
    h2, _ = _hodograph(h1)
    return pts, h1, h1_lo, h2, np.empty((SCRATCH_ROWS, pts.shape[0], pts.shape[1]))


@numba.njit(**_JIT)
def _size(pts: np.ndarray) -> float:
    """Prepared.size: the extent and distance from the origin of 129 samples."""
    dim = pts.shape[1]
    work, x = np.empty(pts.shape), np.empty(dim)
    lo, hi = np.full(dim, np.inf), np.full(dim, -np.inf)
    big = 0.0
    for k in range(129):
        _at(pts, k / 128.0, work, x)
        for j in range(dim):
            lo[j], hi[j] = min(lo[j], x[j]), max(hi[j], x[j])
            big = max(big, abs(x[j]))
    span = 0.0
    for j in range(dim):
        span = max(span, hi[j] - lo[j])
    return max(span, big, 1e-300)


@numba.njit(**_JIT)
def _norm(v: np.ndarray) -> float:
    total = 0.0
    for j in range(v.shape[0]):
        total += v[j] * v[j]
    return math.sqrt(total)


@numba.njit(**_JIT)
def _value_minus(
    pts: np.ndarray,
    s: float,
    target: np.ndarray,
    hi: np.ndarray,
    lo: np.ndarray,
    out: np.ndarray,
    slope: np.ndarray,
) -> None:
    """p(s) - target by compensated de Casteljau (the careful path's exact residual); slope:
    a (d,) array written with p'(s) (unused)."""
    compensated(pts, s, hi, lo, slope)
    for j in range(pts.shape[1]):
        d, e = two_sum(hi[0, j], -target[j])
        out[j] = d + (e + lo[0, j])


@numba.njit(**_JIT)
def _residual(p: Curve, q: Curve, s: float, t: float, out: np.ndarray) -> None:
    """p(s) - q(t), compensated (in p's and q's scratch rows 1-3)."""
    dim = out.shape[0]
    ah, al, bh, bl = p[4][1], p[4][2], q[4][1], q[4][2]
    compensated(p[0], s, ah, al, p[4][3][0])
    compensated(q[0], t, bh, bl, q[4][3][0])
    for j in range(dim):
        d, e = two_sum(ah[0, j], -bh[0, j])
        out[j] = d + (e + (al[0, j] - bl[0, j]))


@numba.njit(**_JIT)
def _derivative_into(c: Curve, s: float, out_hi: np.ndarray, out_lo: np.ndarray) -> None:
    """p'(s) as a double-double (out_hi, out_lo), compensated on the double-double
    hodograph (in c's scratch rows 1-3)."""
    h1, h1_lo = c[1], c[2]
    rows = h1.shape[0]
    hi, lo = c[4][1][:rows], c[4][2][:rows]
    compensated_pair(h1, h1_lo, s, hi, lo, c[4][3][0])
    for j in range(h1.shape[1]):
        out_hi[j], out_lo[j] = hi[0, j], lo[0, j]


@numba.njit(**_JIT)
def _d_into(c: Curve, s: float, which: int, out: np.ndarray) -> None:
    """p (which 0), p' or p'' at s in floats, into out (c's scratch row 0 the work array)."""
    ctrl = c[0] if which == 0 else (c[1] if which == 1 else c[3])
    _at(ctrl, s, c[4][0], out)


@numba.njit(**_JIT)
def _d(c: Curve, s: float, which: int) -> np.ndarray:
    """_d_into in a new array (where a call is not repeated in a loop)."""
    out = np.empty(c[0].shape[1])
    _d_into(c, s, which, out)
    return out


@numba.njit(**_JIT)
def _gap(p: Curve, q: Curve, s: float, t: float) -> float:
    """|p(s) - q(t)| in floats (as _norm(_d(p, s, 0) - _d(q, t, 0)), without allocating)."""
    x, y = p[4][4][0], q[4][4][0]
    _d_into(p, s, 0, x)
    _d_into(q, t, 0, y)
    total = 0.0
    for j in range(x.shape[0]):
        diff = x[j] - y[j]
        total += diff * diff
    return math.sqrt(total)


# ---------------------------------------------------------------------------- least squares
@numba.njit(**_JIT)
def _lstsq2(jac: np.ndarray, rhs: np.ndarray) -> tuple[float, float]:
    """_lstsq2_into with its work arrays made here."""
    ds, dt = _lstsq2_into(jac, rhs, np.empty(jac.shape[0]), np.empty(jac.shape[0]))
    return ds, dt


@numba.njit(**_JIT)
def _lstsq2_into(
    jac: np.ndarray, rhs: np.ndarray, q1: np.ndarray, w: np.ndarray
) -> tuple[float, float]:
    """The least-squares solution of jac (m, 2) x = rhs, minimum norm when jac is rank
    deficient (numpy.linalg.lstsq's answer, rcond = eps max(m, 2)): Householder-free
    Gram-Schmidt twice on two columns, the rank-one case by the pseudo-inverse. q1, w: (m,)
    work arrays."""
    m = jac.shape[0]
    c1, c2 = jac[:, 0], jac[:, 1]
    r11 = _norm(c1)
    cut = np.finfo(np.float64).eps * max(m, 2)
    if not r11 > 0.0:
        r22 = _norm(c2)
        if not r22 > 0.0:
            return 0.0, 0.0
        dot = 0.0
        for i in range(m):
            dot += c2[i] * rhs[i]
        return 0.0, dot / (r22 * r22)
    for i in range(m):
        q1[i] = c1[i] / r11
    r12 = 0.0
    for i in range(m):
        r12 += q1[i] * c2[i]
    for i in range(m):
        w[i] = c2[i] - r12 * q1[i]
    again = 0.0
    for i in range(m):
        again += q1[i] * w[i]
    for i in range(m):
        w[i] -= again * q1[i]
    r12 += again
    r22 = _norm(w)
    big = max(r11, abs(r12), r22)
    if r22 > cut * big:
        b1 = b2 = 0.0
        for i in range(m):
            b1 += q1[i] * rhs[i]
            b2 += (w[i] / r22) * rhs[i]
        x1 = b2 / r22
        return (b1 - r12 * x1) / r11, x1
    # rank one: jac ~ q1 (r11, r12); minimum norm x = (r11, r12) (q1 . rhs) / (r11² + r12²)
    b1 = 0.0
    for i in range(m):
        b1 += q1[i] * rhs[i]
    den = r11 * r11 + r12 * r12
    return r11 * b1 / den, r12 * b1 / den


@numba.njit(**_JIT)
def _gauss_newton_step(u: np.ndarray, v: np.ndarray, f: np.ndarray) -> tuple[float, float]:
    """intersect._gauss_newton_step."""
    dim = u.shape[0]
    a = b = c = g = h = 0.0
    for j in range(dim):
        a += u[j] * u[j]
        b += u[j] * v[j]
        c += v[j] * v[j]
    det = a * c - b * b
    if det > 1e-24 * a * c:
        for j in range(dim):
            g -= u[j] * f[j]
            h -= v[j] * f[j]
        return (c * g - b * h) / det, (a * h - b * g) / det
    jac = np.empty((dim, 2))
    jac[:, 0], jac[:, 1] = u, v
    ds, dt = _lstsq2(jac, -f)
    return ds, dt


# ---------------------------------------------------------------------------- Newton
@numba.njit(**_JIT)
def _newton(p: Curve, q: Curve, s: float, t: float) -> tuple[float, float, int]:
    """intersect._newton: status 0 out, 1 converged, 2 slow."""
    dim = p[0].shape[1]
    ps, dps, qt, dqt = np.empty(dim), np.empty(dim), np.empty(dim), np.empty(dim)
    f, mdq = np.empty(dim), np.empty(dim)
    prev = np.inf
    for it in range(40):
        value_slope(p[0], s, p[4][0], ps, dps)
        value_slope(q[0], t, q[4][0], qt, dqt)
        for j in range(dim):
            f[j] = ps[j] - qt[j]
            mdq[j] = -dqt[j]
        ds, dt = _gauss_newton_step(dps, mdq, f)
        s, t = s + ds, t + dt
        if not (-0.5 < s < 1.5 and -0.5 < t < 1.5) or not (math.isfinite(s) and math.isfinite(t)):
            return s, t, 0
        size = abs(ds) + abs(dt)
        if size < 1e-15:
            return s, t, 1
        if it >= 8 and size > 0.25 * prev:
            break
        prev = size
    return s, t, 2


@numba.njit(**_JIT)
def _polish(p: Curve, q: Curve, s: float, t: float, steps: int) -> tuple[float, float, bool]:
    """intersect._polish, the residual compensated."""
    dim = p[0].shape[1]
    f, u, v = np.empty(dim), np.empty(dim), np.empty(dim)
    ds = dt = np.inf
    for _ in range(steps):
        _residual(p, q, s, t, f)
        _d_into(p, s, 1, u)
        _d_into(q, t, 1, v)
        for j in range(dim):
            v[j] = -v[j]
        ds, dt = _gauss_newton_step(u, v, f)
        s, t = s + ds, t + dt
        if abs(ds) + abs(dt) < 1e-17:
            break
    return s, t, abs(ds) + abs(dt) < 1e-15


@numba.njit(**_JIT)
def _cross_count(dim: int) -> int:
    return dim * (dim - 1) // 2


@numba.njit(**_JIT)
def _tangent_residual(
    p: Curve, q: Curve, s: float, t: float, weight: float, exact: bool
) -> np.ndarray:
    """_tangent_residual_into in new arrays."""
    dim = p[0].shape[1]
    out = np.empty(dim + _cross_count(dim))
    _tangent_residual_into(p, q, s, t, weight, exact, out, np.empty((4, dim)))
    return out


@numba.njit(**_JIT)
def _tangent_residual_into(
    p: Curve,
    q: Curve,
    s: float,
    t: float,
    weight: float,
    exact: bool,
    out: np.ndarray,
    work: np.ndarray,
) -> None:
    """intersect._tangent_residual into out (d + d(d-1)/2,): [p(s) - q(t); weight (p'(s) x
    q'(t)) / (|p'| |q'|)...] as the careful path has it (the cross terms scaled by weight
    only, in floats; exact: both compensated). work: (4, d)."""
    dim = p[0].shape[1]
    if exact:
        _residual(p, q, s, t, out[:dim])
        ah, al, bh, bl = work[0], work[1], work[2], work[3]
        _derivative_into(p, s, ah, al)
        _derivative_into(q, t, bh, bl)
        k = dim
        for i in range(dim):
            for j in range(i + 1, dim):
                x, ex = two_prod(ah[i], bh[j])
                ex += ah[i] * bl[j] + al[i] * bh[j]
                y, ey = two_prod(ah[j], bh[i])
                ey += ah[j] * bl[i] + al[j] * bh[i]
                d, e = two_sum(x, -y)
                out[k] = (d + (e + (ex - ey))) * weight
                k += 1
        return
    a, b, u, v = work[0], work[1], work[2], work[3]
    _d_into(p, s, 0, a)
    _d_into(q, t, 0, b)
    _d_into(p, s, 1, u)
    _d_into(q, t, 1, v)
    for j in range(dim):
        out[j] = a[j] - b[j]
    k = dim
    for i in range(dim):
        for j in range(i + 1, dim):
            out[k] = (u[i] * v[j] - u[j] * v[i]) * weight
            k += 1


@numba.njit(**_JIT)
def _tangent_refine(
    p: Curve, q: Curve, s: float, t: float, scale: float, float_phase: bool, exact_phase: bool
) -> tuple[float, float]:
    """intersect._tangent_refine: Gauss-Newton on the tangent system, a float phase and an
    exact (compensated) one, each kept at its smallest step."""
    dim = p[0].shape[1]
    rows = dim + _cross_count(dim)
    d1p, d1q = _d(p, s, 1), _d(q, t, 1)
    weight = scale / max(_norm(d1p) * _norm(d1q), 1e-300)
    jac = np.empty((rows, 2))
    res, minus_res, q1, w = np.empty(rows), np.empty(rows), np.empty(rows), np.empty(rows)
    work = np.empty((4, dim))
    d2p, d2q = np.empty(dim), np.empty(dim)
    for phase in range(2):
        exact = phase == 1
        if (exact and not exact_phase) or (not exact and not float_phase):
            continue
        best_size, best_s, best_t = np.inf, s, t
        stalled = 0
        for _ in range(100):
            _tangent_residual_into(p, q, s, t, weight, exact, res, work)
            zero = True
            for r in range(rows):
                if res[r] != 0.0:
                    zero = False
            if zero:
                best_size, best_s, best_t = 0.0, s, t
                break
            _d_into(p, s, 1, d1p)
            _d_into(q, t, 1, d1q)
            _d_into(p, s, 2, d2p)
            _d_into(q, t, 2, d2q)
            for j in range(dim):
                jac[j, 0], jac[j, 1] = d1p[j], -d1q[j]
            k = dim
            for i in range(dim):
                for j in range(i + 1, dim):
                    jac[k, 0] = (d2p[i] * d1q[j] - d2p[j] * d1q[i]) * weight
                    jac[k, 1] = (d1p[i] * d2q[j] - d1p[j] * d2q[i]) * weight
                    k += 1
            for r in range(rows):
                minus_res[r] = -res[r]
            ds, dt = _lstsq2_into(jac, minus_res, q1, w)
            if not (math.isfinite(ds) and math.isfinite(dt)):
                break
            s, t = s + ds, t + dt
            size = abs(ds) + abs(dt)
            if size < best_size:
                best_size, best_s, best_t, stalled = size, s, t, 0
            else:
                stalled += 1
            if size < 1e-17 * (1 + abs(s) + abs(t)) or stalled >= 3:
                break
        s, t = best_s, best_t
    return s, t


@numba.njit(**_JIT)
def _sine(p: Curve, q: Curve, s: float, t: float) -> float:
    u, v = p[4][4][0], q[4][4][0]
    _d_into(p, s, 1, u)
    _d_into(q, t, 1, v)
    nu, nv = _norm(u), _norm(v)
    if nu == 0.0 or nv == 0.0:
        return 0.0
    cross = 0.0
    for i in range(u.shape[0]):
        for j in range(i + 1, u.shape[0]):
            c = u[i] * v[j] - u[j] * v[i]
            cross += c * c
    return float(math.sqrt(cross) / (nu * nv))


# ---------------------------------------------------------------------------- one hit
@numba.njit(**_JIT)
def _near(s: float, t: float, fs: np.ndarray, ft: np.ndarray, count: int, radius: float) -> bool:
    """intersect._near_found and _dedupe: a hit within radius in both parameters."""
    for k in range(count):  # noqa: SIM110 (numba compiles no generator into any())
        if abs(s - fs[k]) < radius and abs(t - ft[k]) < radius:
            return True
    return False


@numba.njit(**_JIT)
def _near_isolated(
    s: float, t: float, fs: np.ndarray, ft: np.ndarray, count: int, same: float, radius: float
) -> bool:
    """intersect._dedupe_isolated: within `same` in both parameters, or at the same end of
    one curve as a found hit and within `radius` in the other parameter."""
    if _near(s, t, fs, ft, count, same):
        return True
    for k in range(count):
        if s == fs[k] and (s == 0.0 or s == 1.0) and abs(t - ft[k]) < radius:
            return True
        if t == ft[k] and (t == 0.0 or t == 1.0) and abs(s - fs[k]) < radius:
            return True
    return False


@numba.njit(**_JIT)
def _on_both(p: Curve, q: Curve, s: float, t: float, bound: float) -> bool:
    f = p[4][4][0]
    _residual(p, q, s, t, f)
    return bool(_norm(f) <= bound)


@numba.njit(**_JIT)
def _solve_from(
    p: Curve,
    q: Curve,
    s: float,
    t: float,
    fs: np.ndarray,
    ft: np.ndarray,
    count: int,
    isolated: bool,
    scale: float,
    bound: float,
    knobs: Knobs,
) -> tuple[bool, float, float, int]:
    """intersect._solve_from: (found, s, t, kind)."""
    near_found, tangent_sine = knobs[8], knobs[9]
    s0, t0 = s, t
    s, t, status = _newton(p, q, s, t)
    if status == 0:
        s, t = _tangent_refine(p, q, s0, t0, scale, True, False)
        if not (-0.5 < s < 1.5 and -0.5 < t < 1.5):
            return False, s, t, TRANSVERSAL
    if not isolated and _near(s, t, fs, ft, count, near_found):
        return False, s, t, TRANSVERSAL
    if _gap(p, q, s, t) > 1e-6 * scale:
        return False, s, t, TRANSVERSAL
    polished = False
    ps, pt = s, t
    if isolated or _sine(p, q, s, t) > tangent_sine:
        ps, pt, polished = _polish(p, q, s, t, 12 if isolated else 4)
        polished = polished or (isolated and _on_both(p, q, ps, pt, bound))
    if polished:
        s, t, kind = ps, pt, TRANSVERSAL
    else:
        s, t = _tangent_refine(p, q, s, t, scale, True, False)
        if _near(s, t, fs, ft, count, near_found):
            return False, s, t, TRANSVERSAL
        s, t = _tangent_refine(p, q, s, t, scale, False, True)
        kind = TANGENT if _sine(p, q, s, t) <= tangent_sine else TRANSVERSAL
    if not _on_both(p, q, s, t, bound):
        return False, s, t, kind
    tol = 1e-12
    if not (-tol <= s <= 1 + tol and -tol <= t <= 1 + tol):
        return False, s, t, kind
    return True, min(max(s, 0.0), 1.0), min(max(t, 0.0), 1.0), kind


@numba.njit(**_JIT)
def _quality(p: Curve, q: Curve, s: float, t: float) -> float:
    return float(_norm(_tangent_residual(p, q, s, t, 1.0, True)))


@numba.njit(**_JIT)
def _add(
    p: Curve,
    q: Curve,
    fs: np.ndarray,
    ft: np.ndarray,
    fk: np.ndarray,
    count: int,
    s: float,
    t: float,
    kind: int,
    gap_bound: float,
    radius: float,
) -> int:
    """intersect._add: the new count (the hit merged into one found, or appended; an end of
    a shared stretch is kept, not replaced)."""
    for k in range(count):
        if abs(s - fs[k]) < radius and abs(t - ft[k]) < radius:
            gap = 0.0
            for m in range(9):
                u = m / 8.0
                gap = max(gap, _gap(p, q, fs[k] + u * (s - fs[k]), ft[k] + u * (t - ft[k])))
            if gap <= gap_bound:
                if fk[k] != COINCIDENT and _quality(p, q, s, t) < _quality(p, q, fs[k], ft[k]):
                    fs[k], ft[k], fk[k] = s, t, kind
                return count
    fs[count], ft[count], fk[count] = s, t, kind
    return count + 1
