"""The fixed-cost certified minimum of one surface energy E(x, y) = Σ_{a,b<=2} e_ab x^a y^b
over a box, written once for both engines: every function here is elementwise (arithmetic,
np.where, np.minimum, np.maximum, np.sqrt, np.abs), so the numpy engine calls it on arrays
of a whole batch and hazmat.surface_batch_compiled compiles the same source with numba and
calls it per net inside its chunk loop (scalars).

The method, the same fixed work for every net (no root isolation, no branches on the data):

1. a start by alternating exact minimisation (E is a quadratic in x for fixed y and in y for
   fixed x: each half-step is a closed form, clipped to the box), then Newton on ∇E = 0;
2. local: on the square R of half-width r about the point (x, y), E is strongly convex with a
   certified modulus μ (interval bounds of E_xx, E_yy and |E_xy| over R, widened by a rounding
   bound), so E has exactly one critical point in R, within δ = (|∇E(x, y)| + rounding) / μ
   of (x, y), and its minimum over R is at most |∇E|² / (2μ) below E(x, y);
3. global: every point of the box outside R has a larger energy than E(x, y) (plus its
   rounding bound). With E = A(y) x² + B(y) x + C(y), min over all real x of E(·, y) exceeds a
   level L exactly when A > 0 and p(y) = 4 A (C − L) − B² > 0, a quartic in y: p is positive
   on [ylo, y − r] and on [y + r, yhi] when its Bernstein coefficients there are (and A's on
   the whole side). The same in x with E = F(x) y² + G(x) y + H(x) covers |x' − x| >= r.

A net is certified when all of that holds with δ <= `tol` (and 2δ < r) and R inside the
open box; the minimiser is then unique and within δ of the returned point. The certificate
is about the float coefficients e_ab; its rounding bounds are generous estimates (a few
hundred units in the last place of each quantity's size), not interval arithmetic. A net
whose minimum is on an edge or a corner, or near one, or whose energy is not convex enough
about its minimum, is declined; the caller solves it by the careful path (surface_optimum)
and counts it.
"""

from __future__ import annotations

from typing import Any

import numpy as np

# certified_minimum makes 4 alternating closed-form sweeps, then 5 Newton steps (quadratic
# convergence: from the sweeps' start, enough to reach the rounding level)
RADIUS = 1.0 / 64  # half-width of the square R of local strong convexity, times the box size
# a rounding bound: every value, gradient or Hessian entry below is a sum of at most nine
# terms, each at most 4 |e_ab| |x|^a |y|^b; a few dozen roundings of unit 2^-53 each
ROUND = 64 * 2.0**-53
# E_x and E_y: Horner on quadratics, then two more operations; at most 8 roundings, so
# γ_8 < 9 * 2^-53 of the sum of the terms' sizes (twice that, for safety)
GRADIENT_ROUND = 16 * 2.0**-53
BERNSTEIN_SLACK = 1e-12  # Bernstein coefficients must exceed this times the polynomial's size

F = Any  # a float, or an array of floats (the numpy engine)

# the one non-arithmetic selection: np.where for arrays; the compiled engine recompiles these
# functions with a scalar `c ? a : b` in its place (numba's np.where on scalars allocates a
# 0-d array per call)
_where = np.where


def _clip(t: F, lo: float, hi: float) -> F:
    return np.minimum(np.maximum(t, lo), hi)


def _sweep(
    e01: F,
    e02: F,
    e10: F,
    e11: F,
    e12: F,
    e20: F,
    e21: F,
    e22: F,
    x: F,
    y: F,
    xlo: float,
    xhi: float,
    ylo: float,
    yhi: float,
) -> tuple[F, F]:
    """One alternating step: x minimising E(·, y) on [xlo, xhi], then y minimising E(x, ·)
    (each a quadratic; kept where its leading coefficient is not positive)."""
    a = e20 + (e21 + e22 * y) * y
    b = e10 + (e11 + e12 * y) * y
    pos = a > 0
    x = _where(pos, _clip(-b / _where(pos, 2 * a, 1.0), xlo, xhi), x)
    f = e02 + (e12 + e22 * x) * x
    g = e01 + (e11 + e21 * x) * x
    pos = f > 0
    y = _where(pos, _clip(-g / _where(pos, 2 * f, 1.0), ylo, yhi), y)
    return x, y


def _newton(
    e01: F,
    e02: F,
    e10: F,
    e11: F,
    e12: F,
    e20: F,
    e21: F,
    e22: F,
    x: F,
    y: F,
    xlo: float,
    xhi: float,
    ylo: float,
    yhi: float,
) -> tuple[F, F]:
    """One Newton step on ∇E = 0, clipped to the box (none where the Hessian is not
    positive definite)."""
    a = e20 + (e21 + e22 * y) * y
    da = e21 + 2 * e22 * y
    b = e10 + (e11 + e12 * y) * y
    db = e11 + 2 * e12 * y
    f = e02 + (e12 + e22 * x) * x
    g = e01 + (e11 + e21 * x) * x
    gx = 2 * a * x + b
    gy = 2 * f * y + g
    hxx = 2 * a
    hyy = 2 * f
    hxy = db + 2 * x * da
    det = hxx * hyy - hxy * hxy
    pos = (hxx > 0) & (det > 0)
    safe = _where(pos, det, 1.0)
    x = _clip(x - _where(pos, (hyy * gx - hxy * gy) / safe, 0.0), xlo, xhi)
    y = _clip(y - _where(pos, (hxx * gy - hxy * gx) / safe, 0.0), ylo, yhi)
    return x, y


def _quartic_positive(p0: F, p1: F, p2: F, p3: F, p4: F, a: F, b: F, slack: F) -> F:
    """p0 + p1 t + ... + p4 t^4 > slack at every t in [a, b], by its Bernstein coefficients
    there (a sufficient test)."""
    # Taylor coefficients about a (Horner's shift), then scaled to t = a + h s, s in [0, 1]
    h = b - a
    c4 = p4
    c3 = p3 + a * c4
    c2 = p2 + a * (p3 + a * c4)
    c1 = p1 + a * (p2 + a * (p3 + a * c4))
    c0 = p0 + a * (p1 + a * (p2 + a * (p3 + a * c4)))
    # second and later rows of the shift
    c3 = c3 + a * c4
    c2 = c2 + a * c3
    c1 = c1 + a * c2
    c3 = c3 + a * c4
    c2 = c2 + a * c3
    c3 = c3 + a * c4
    d1 = c1 * h
    d2 = c2 * h * h
    d3 = c3 * h * h * h
    d4 = c4 * h * h * h * h
    b1 = c0 + d1 / 4
    b2 = c0 + d1 / 2 + d2 / 6
    b3 = c0 + 3 * d1 / 4 + d2 / 2 + d3 / 4
    b4 = c0 + d1 + d2 + d3 + d4
    low = np.minimum(np.minimum(np.minimum(c0, b1), np.minimum(b2, b3)), b4)
    return low > slack


def _quadratic_positive(q0: F, q1: F, q2: F, a: float, b: float, slack: F) -> F:
    """q0 + q1 t + q2 t² > slack on [a, b], by its Bernstein coefficients there."""
    at_a = q0 + a * (q1 + a * q2)
    at_b = q0 + b * (q1 + b * q2)
    middle = at_a + (b - a) * (q1 + 2 * a * q2) / 2
    return (at_a > slack) & (at_b > slack) & (middle > slack)


def _side_clear(
    a0: F,
    a1: F,
    a2: F,
    b0: F,
    b1: F,
    b2: F,
    c0: F,
    c1: F,
    c2: F,
    level: F,
    at: F,
    r: float,
    lo: float,
    hi: float,
    emax: F,
) -> F:
    """min over every real x of A(t) x² + B(t) x + C(t) exceeds `level` at every t of
    [lo, at − r] and [at + r, hi] (A, B, C quadratics in t, given low first)."""
    m = max(1.0, abs(lo), abs(hi)) + 1.0
    c0 = c0 - level
    p0 = 4 * a0 * c0 - b0 * b0
    p1 = 4 * (a0 * c1 + a1 * c0) - 2 * b0 * b1
    p2 = 4 * (a0 * c2 + a1 * c1 + a2 * c0) - (b1 * b1 + 2 * b0 * b2)
    p3 = 4 * (a1 * c2 + a2 * c1) - 2 * b1 * b2
    p4 = 4 * a2 * c2 - b2 * b2
    size = (
        np.abs(p0)
        + np.abs(p1) * m
        + np.abs(p2) * m * m
        + np.abs(p3) * m * m * m
        + np.abs(p4) * m * m * m * m
        + 16 * (emax * m * m) * (emax * m * m + np.abs(level))
    )
    slack = BERNSTEIN_SLACK * size
    a_slack = BERNSTEIN_SLACK * emax * m * m
    return (
        _quadratic_positive(a0, a1, a2, lo, hi, a_slack)
        & _quartic_positive(p0, p1, p2, p3, p4, lo, at - r, slack)
        & _quartic_positive(p0, p1, p2, p3, p4, at + r, hi, slack)
    )


def certified_minimum(
    e00: F,
    e01: F,
    e02: F,
    e10: F,
    e11: F,
    e12: F,
    e20: F,
    e21: F,
    e22: F,
    xlo: float,
    xhi: float,
    ylo: float,
    yhi: float,
    tol: float,
) -> tuple[F, F, F, F, F]:
    """(x, y, E(x, y), δ, certified) for E = Σ e_ab x^a y^b over [xlo, xhi] x [ylo, yhi]:
    where `certified`, the minimiser over the box is unique and within δ <= tol of (x, y)."""
    xm, ym = 0.5 * (xlo + xhi), 0.5 * (ylo + yhi)
    x = xm + 0.0 * e00  # the shape of the coefficients (an array for the numpy engine)
    y = ym + 0.0 * e00
    # written out rather than looped: the compiled engine vectorises its loop over nets only
    # when the body is straight-line code
    x, y = _sweep(e01, e02, e10, e11, e12, e20, e21, e22, x, y, xlo, xhi, ylo, yhi)
    x, y = _sweep(e01, e02, e10, e11, e12, e20, e21, e22, x, y, xlo, xhi, ylo, yhi)
    x, y = _sweep(e01, e02, e10, e11, e12, e20, e21, e22, x, y, xlo, xhi, ylo, yhi)
    x, y = _sweep(e01, e02, e10, e11, e12, e20, e21, e22, x, y, xlo, xhi, ylo, yhi)
    x, y = _newton(e01, e02, e10, e11, e12, e20, e21, e22, x, y, xlo, xhi, ylo, yhi)
    x, y = _newton(e01, e02, e10, e11, e12, e20, e21, e22, x, y, xlo, xhi, ylo, yhi)
    x, y = _newton(e01, e02, e10, e11, e12, e20, e21, e22, x, y, xlo, xhi, ylo, yhi)
    x, y = _newton(e01, e02, e10, e11, e12, e20, e21, e22, x, y, xlo, xhi, ylo, yhi)
    x, y = _newton(e01, e02, e10, e11, e12, e20, e21, e22, x, y, xlo, xhi, ylo, yhi)
    r = RADIUS * max(xhi - xlo, yhi - ylo)
    emax = np.maximum(
        np.maximum(np.maximum(np.abs(e00), np.abs(e01)), np.maximum(np.abs(e02), np.abs(e10))),
        np.maximum(
            np.maximum(np.abs(e11), np.abs(e12)),
            np.maximum(np.maximum(np.abs(e20), np.abs(e21)), np.abs(e22)),
        ),
    )
    ax, ay = np.abs(x) + r, np.abs(y) + r
    slack = ROUND * emax * (1 + ax + ax * ax) * (1 + ay + ay * ay)
    a = e20 + (e21 + e22 * y) * y  # E = a x² + b x + c along this y
    da = e21 + 2 * e22 * y
    b = e10 + (e11 + e12 * y) * y
    db = e11 + 2 * e12 * y
    f = e02 + (e12 + e22 * x) * x  # E = f y² + g y + k along this x
    df = e12 + 2 * e22 * x
    g = e01 + (e11 + e21 * x) * x
    c = e00 + (e01 + e02 * y) * y
    energy = (a * x + b) * x + c
    gx = 2 * a * x + b
    gy = 2 * f * y + g
    hxy = db + 2 * x * da
    # bounds over R of E_xx = 2 A(y'), E_yy = 2 F(x') and |E_xy|
    lo_xx = 2 * (a - np.abs(da) * r - np.abs(e22) * r * r) - slack
    lo_yy = 2 * (f - np.abs(df) * r - np.abs(e22) * r * r) - slack
    hi_xy = (
        np.abs(hxy)
        + (np.abs(2 * e21 + 4 * e22 * y) + np.abs(2 * e12 + 4 * e22 * x)) * r
        + 4 * np.abs(e22) * r * r
        + slack
    )
    half = 0.5 * (lo_xx - lo_yy)
    mu = 0.5 * (lo_xx + lo_yy) - np.sqrt(half * half + hi_xy * hi_xy)
    convex = (lo_xx > 0) & (lo_yy > 0) & (mu > 0)
    # the gradient's own rounding: at most GRADIENT_ROUND times the sum of its terms' sizes
    ux, uy = np.abs(x), np.abs(y)
    size_gx = 2 * (np.abs(e20) + (np.abs(e21) + np.abs(e22) * uy) * uy) * ux + (
        np.abs(e10) + (np.abs(e11) + np.abs(e12) * uy) * uy
    )
    size_gy = 2 * (np.abs(e02) + (np.abs(e12) + np.abs(e22) * ux) * ux) * uy + (
        np.abs(e01) + (np.abs(e11) + np.abs(e21) * ux) * ux
    )
    ex = np.abs(gx) + GRADIENT_ROUND * size_gx
    ey = np.abs(gy) + GRADIENT_ROUND * size_gy
    grad = np.sqrt(ex * ex + ey * ey)
    delta = grad / _where(convex, mu, 1.0)
    # 2δ < r: E on R's boundary exceeds E(x, y) (E >= E(x, y) − |∇E| r + μ r² / 2), so the
    # minimum over R is interior, the critical point
    local = convex & (delta <= tol) & (2 * delta < r)
    inside = (x - r > xlo) & (x + r < xhi) & (y - r > ylo) & (y + r < yhi)
    level = energy + slack
    clear_y = _side_clear(e20, e21, e22, e10, e11, e12, e00, e01, e02, level, y, r, ylo, yhi, emax)
    clear_x = _side_clear(e02, e12, e22, e01, e11, e21, e00, e10, e20, level, x, r, xlo, xhi, emax)
    ok = local & inside & clear_y & clear_x
    return x, y, energy, _where(convex, delta, np.inf), ok
