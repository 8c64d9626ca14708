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
   on [ylo, y − r] and on [y + r, yhi] when its Bernstein coefficients there are (and A's
   least value on the whole side is, below). The same in x with E = F(x) y² + G(x) y + H(x)
   covers |x' − x| >= r.

Every "this quadratic q(t) = q0 + q1 t + q2 t² exceeds `slack` on [a, b]" (A's positivity on
a side, an edge's E_s and values on a piece) is decided by q's least value on [a, b], not by
its three Bernstein coefficients there, which are lower bounds of it only and too loose where
A dips well below its end values inside the box (at_cubic's 10,000 benchmark nets: 1,533
declined with the Bernstein test, 372 with this one; no net the former certified is declined).

Why it is sound in floats, with the same margin as before: q's least value on [a, b] is at
an end or, when q2 > 0 and the vertex v = −q1/(2 q2) is in [a, b], m = q0 − q1²/(4 q2),
which is also q's least value over every real t, so using it whenever the float vertex lies
in a widened [a, b] only makes the test stricter. When the exact v is in [a, b], the float
vertex (one rounding: 2 q2 is exact) is within 2^-53 |v| <= 2^-53 max(|a|, |b|) of it,
inside the widening (VERTEX_WIDEN), so m is never skipped where it is the minimum; v
overflows only far outside [a, b], where the ends decide. m is computed as q0 + (q1/2) v,
not with q1², which underflows to 0 where q1 and q2 are both below 1e-154 (m would then be
q0: tests/test_surface_certify_quadratic.py found it). Its three roundings (v, the product,
the sum) err by at most 3·2^-53 (|q0| + q2 v²) <= 3·2^-53 (|q0| + |q2| max(a², b²)), the
size of q's value at a point of [a, b], which the ends (Horner) and the Bernstein
coefficients carried too; every caller's `slack` exceeds it several times over (about 2^-40
of that size in _side_clear, BERNSTEIN_SLACK; 64 units of 2^-53 of the coefficients' reach
in _edge, ROUND). As before, the margins are relative: coefficients so small that products
of them underflow (below about 1e-290) are not covered.

A net is certified when all of that holds with δ <= `tol` (and 2δ < r) and R inside the
open box; the minimiser is then unique and within δ of the returned point.

R's half-width r is RADIUS of the box, or, where the point is nearer a face than that,
NEAR_FACE of its distance to the nearest face (so R still lies inside the box). Any r > 0 is
sound: steps 2 and 3 bound E over R and outside R for whatever R they are given (the bounds of
E_xx, E_yy, |E_xy| over R, the rounding slack with |x| + r and |y| + r, the quartics on the
sides beyond r), and the argument (the box's minimum is in R, where E has one critical point,
within δ) uses no property of r but 2δ < r and R inside the box. A smaller R makes the local
part easier and the global clearing harder (min over x of E(x, y ± r) exceeds E(x, y) by
about μ r² / 2, which must clear the slack): on the 10,000 benchmark nets it certifies 26 of the
39 the fixed RADIUS declined (interior minima 0.002 to 0.045 from a face), and a minimum
closer than about 3e-4 (box 3 wide) to a face is still declined. Where the point is at least
RADIUS from every face, r and so the verdict are what they were. The certificate
is about the float coefficients e_ab; its rounding bounds are generous estimates (a few
hundred units in the last place of each quantity's size), not interval arithmetic. A net
whose minimum is on an edge or a corner, or near one, or whose energy is not convex enough
about its minimum, is declined; the caller solves it by the careful path (surface_optimum)
and counts it.

**The retries** (round 21), run only on what certified_minimum and edge_minimum both
decline, each a certificate on its own by the same argument:

- retry_minimum: the start searched (SEARCH values of x, y minimised exactly at each; from
  the box's middle, two sweeps and four Newton steps left 102 of at_cubic's 274 declined
  interior minima unconverged, some in another basin), RETRY_NEWTON Newton steps, the same
  local part, and each side beyond R cleared in CLEAR_PIECES pieces (_side_clear_pieces):
  a piece is clear when the quartic's Bernstein coefficients on it clear the slack (they
  bound p there, as the whole side's bound it on the side, only more tightly), or when E
  grows from a face of the box into it above the level along the whole piece (_grows_from:
  with A > 0, E(·, t) is convex, so its least value over the box's s is then at that face;
  the global clearing needs the box's minimum over s, not the real line's). On at_cubic's
  10,000 benchmark nets: 274 of 274 declined interior minima certified (at the careful
  path's points the whole-side test cleared both directions of 43, the pieces 273, the
  face the last);
- retry_edges (surface_fixed_cost; the compiled kernel tries the bands net by net):
  edge_band_minimum at bands RADIUS / 2, ..., / 2^EDGE_BANDS. The band must be narrow where
  E_s(edge, t) turns to point out of the box close to the answer; the pieces beyond it are
  cleared by their own tests, so any r > 0 is sound. At_cubic: 32 of 32 declined edge
  minima.
"""

from __future__ import annotations

from typing import Any

import numpy as np

# certified_minimum makes 2 alternating closed-form sweeps, then 4 Newton steps (quadratic
# convergence: from the sweeps' start, enough to reach the rounding level)
RADIUS = 1.0 / 64  # half-width of the square R of local strong convexity, times the box size
NEAR_FACE = 0.5  # R's half-width, times the point's distance to a face, where that is nearer
# a rounding bound: every value, gradient or Hessian entry below is a sum of at most nine
# terms, each at most 4 |e_ab| |x|^a |y|^b; a few dozen roundings of unit 2^-53 each
ROUND = 64 * 2.0**-53
# E_x and E_y: Horner on quadratics, then two more operations; at most 8 roundings, so
# γ_8 < 9 * 2^-53 of the sum of the terms' sizes (twice that, for safety)
GRADIENT_ROUND = 16 * 2.0**-53
BERNSTEIN_SLACK = 1e-12  # Bernstein coefficients must exceed this times the polynomial's size
# a quadratic's float vertex counts as inside [a, b] within this times |a| + |b| + (b − a):
# far above the vertex's own rounding (2^-53 |v|), far below any width the tests use
VERTEX_WIDEN = 2.0**-30
EDGE_PIECES = 32  # pieces of each side of an edge minimum's band, each cleared by one test
# the retry (retry_minimum, retry_edges; only on what both certificates above decline): a start
# from SEARCH values of x, y minimised exactly at each, then RETRY_NEWTON Newton steps; the
# sides beyond R cleared in CLEAR_PIECES pieces each; edge bands RADIUS / 2 ... / 2^EDGE_BANDS
SEARCH = 9
RETRY_NEWTON = 8
CLEAR_PIECES = 4
EDGE_BANDS = 5

F = Any  # a float, or an array of floats (the numpy engine)

# the one non-arithmetic selection: np.where for arrays; the compiled engine recompiles these
# functions with a scalar `c ? a : b` in its place (numba's np.where on scalars allocates a
# 0-d array per call)
_where = np.where


def _none(c: F) -> bool:
    """Whether no set is still undecided (`c` False everywhere): the compiled engine rebinds
    it to a scalar `not c`, so that `_edge` stops at its first failed test; the answers are
    the same either way (a False stays False under every later `&`)."""
    return not np.any(c)


def _every(c: F) -> bool:
    """Whether every set has `c` True: the compiled engine rebinds it to the scalar `c`, so
    that a test is skipped for a net another has passed (the answers are the same either
    way: the skipped test is only ever `|`-ed with True)."""
    return bool(np.all(c))


def _clip(t: F, lo: float, hi: float) -> F:
    return np.minimum(np.maximum(t, lo), hi)


def _at(c0: F, c1: F, c2: F, t: F) -> F:
    """c0 + c1 t + c2 t² by Horner: E's coefficients along one variable (A, B, C at the other's
    value, an edge's q_k, a quadratic's ends), the one shape every such step shares."""
    return c0 + (c1 + c2 * t) * t


def _slope(c1: F, c2: F, t: F) -> F:
    """d/dt (c0 + c1 t + c2 t²) = c1 + 2 c2 t."""
    return c1 + 2 * c2 * t


def _step(
    a0: F, a1: F, a2: F, b0: F, b1: F, b2: F, fixed: F, current: F, lo: float, hi: float
) -> F:
    """The minimiser over [lo, hi] of A(fixed) s² + B(fixed) s (A, B quadratics, low first):
    one direction's half of an alternating step (`current` where A(fixed) is not positive)."""
    a = _at(a0, a1, a2, fixed)
    b = _at(b0, b1, b2, fixed)
    pos = a > 0
    return _where(pos, _clip(-b / _where(pos, 2 * a, 1.0), lo, hi), current)


def _sweep(e: tuple[F, ...], x: F, y: F, box: tuple[float, float, float, float]) -> tuple[F, F]:
    """One alternating step: x minimising E(·, y) on [xlo, xhi], then y minimising E(x, ·)
    (the same step with the coefficients transposed, e_ab -> e_ba). `e` is the start's
    eight coefficients (e01, e02, e10, e11, e12, e20, e21, e22: e00 moves no minimiser),
    `box` (xlo, xhi, ylo, yhi), as for _newton."""
    e01, e02, e10, e11, e12, e20, e21, e22 = e
    xlo, xhi, ylo, yhi = box
    x = _step(e20, e21, e22, e10, e11, e12, y, x, xlo, xhi)
    y = _step(e02, e12, e22, e01, e11, e21, x, y, ylo, yhi)
    return x, y


def _newton(e: tuple[F, ...], x: F, y: F, box: tuple[float, float, float, float]) -> tuple[F, F]:
    """One Newton step on ∇E = 0, clipped to the box (none where the Hessian is not
    positive definite); `e` and `box` as for _sweep."""
    e01, e02, e10, e11, e12, e20, e21, e22 = e
    xlo, xhi, ylo, yhi = box
    a, da = _at(e20, e21, e22, y), _slope(e21, e22, y)
    b, db = _at(e10, e11, e12, y), _slope(e11, e12, y)
    f = _at(e02, e12, e22, x)
    g = _at(e01, e11, e21, x)
    gx = _slope(b, a, x)
    gy = _slope(g, f, y)
    hxx = 2 * a
    hyy = 2 * f
    hxy = db + 2 * x * da
    det = hxx * hyy - hxy * hxy
    pos = (hxx > 0) & (det > 0)
    inv = 1.0 / _where(pos, det, 1.0)  # one division for both coordinates
    x = _clip(x - _where(pos, (hyy * gx - hxy * gy) * inv, 0.0), xlo, xhi)
    y = _clip(y - _where(pos, (hxx * gy - hxy * gx) * inv, 0.0), ylo, yhi)
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
    b2 = c0 + d1 / 2 + d2 * (1 / 6)  # a product, not a division (within the slack)
    b3 = c0 + 3 * d1 / 4 + d2 / 2 + d3 / 4
    b4 = c0 + d1 + d2 + d3 + d4
    low = np.minimum(np.minimum(np.minimum(c0, b1), np.minimum(b2, b3)), b4)
    return low > slack


def _quadratic_positive(q0: F, q1: F, q2: F, a: F, b: F, slack: F) -> F:
    """q0 + q1 t + q2 t² > slack on [a, b], by its least value there: its ends, and
    q0 − q1²/(4 q2) where q2 > 0 and the vertex −q1/(2 q2) is in [a, b] (widened by
    VERTEX_WIDEN: see the module's doc for why this is sound in floats)."""
    at_a = _at(q0, q1, q2, a)
    at_b = _at(q0, q1, q2, b)
    cup = q2 > 0
    safe = _where(cup, q2, 1.0)
    vertex = -q1 / (2 * safe)
    reach = VERTEX_WIDEN * (np.abs(a) + np.abs(b) + (b - a))
    inside = cup & (vertex >= a - reach) & (vertex <= b + reach)
    # q0 − q1²/(4 q2) as q0 + (q1/2) v: no q1² to underflow where q1 and q2 are both tiny
    least = _where(inside, q0 + (0.5 * q1) * vertex, at_a)
    return (at_a > slack) & (at_b > slack) & (least > slack)


def _discriminant(
    a0: F, a1: F, a2: F, b0: F, b1: F, b2: F, c0: F, c1: F, c2: F, level: F, m: float, emax: F
) -> tuple[F, F, F, F, F, F]:
    """(p0, …, p4, slack): p(t) = 4 A (C − level) − B², positive (with A > 0) exactly where
    min over every real s of A(t) s² + B(t) s + C(t) exceeds `level`; slack, the margin its
    Bernstein coefficients must clear on |t| <= m − 1."""
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
    return p0, p1, p2, p3, p4, BERNSTEIN_SLACK * size


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
    r: F,
    lo: float,
    hi: float,
    emax: F,
) -> F:
    """min over every real x of A(t) x² + B(t) x + C(t) exceeds `level` at every t of
    [lo, at − r] and [at + r, hi] (A, B, C quadratics in t, given low first)."""
    m = max(1.0, abs(lo), abs(hi)) + 1.0
    p0, p1, p2, p3, p4, slack = _discriminant(a0, a1, a2, b0, b1, b2, c0, c1, c2, level, m, emax)
    return (
        _quadratic_positive(a0, a1, a2, lo, hi, BERNSTEIN_SLACK * emax * m * m)
        & _quartic_positive(p0, p1, p2, p3, p4, lo, at - r, slack)
        & _quartic_positive(p0, p1, p2, p3, p4, at + r, hi, slack)
    )


def _largest(e00: F, e01: F, e02: F, e10: F, e11: F, e12: F, e20: F, e21: F, e22: F) -> F:
    """max |e_ab|: the size the rounding bounds are measured against."""
    return np.maximum(
        np.maximum(np.maximum(np.abs(e00), np.abs(e01)), np.maximum(np.abs(e02), np.abs(e10))),
        np.maximum(
            np.maximum(np.abs(e11), np.abs(e12)),
            np.maximum(np.maximum(np.abs(e20), np.abs(e21)), np.abs(e22)),
        ),
    )


def _direction(
    a0: F,
    a1: F,
    a2: F,
    b0: F,
    b1: F,
    b2: F,
    c0: F,
    c1: F,
    c2: F,
    at: F,
    other: F,
    r: F,
    lo: float,
    hi: float,
    level: F,
    emax: F,
    slack: F,
) -> tuple[F, F, F]:
    """One direction's share of the certificate, for E = A(t) s² + B(t) s + C(t) with s the
    direction's variable (at `at`) and t the other one (at `other`, over [lo, hi]); the other
    direction is the same call with the coefficients transposed (e_ab -> e_ba):

    - a lower bound of E_ss = 2 A(t') over |t' − other| <= r;
    - |E_s| at the point plus its rounding (at most GRADIENT_ROUND times the sum of its
      terms' sizes);
    - whether every t of [lo, hi] at least r from `other` has min over s of E above `level`
      (the global exclusion: no point there can be the minimum)."""
    a = _at(a0, a1, a2, other)
    da = _slope(a1, a2, other)
    b = _at(b0, b1, b2, other)
    lower = 2 * (a - np.abs(da) * r - np.abs(a2) * r * r) - slack
    s, t = np.abs(at), np.abs(other)
    size = 2 * (np.abs(a0) + (np.abs(a1) + np.abs(a2) * t) * t) * s + (
        np.abs(b0) + (np.abs(b1) + np.abs(b2) * t) * t
    )
    gradient = np.abs(_slope(b, a, at)) + GRADIENT_ROUND * size
    clear = _side_clear(a0, a1, a2, b0, b1, b2, c0, c1, c2, level, other, r, lo, hi, emax)
    return lower, gradient, clear


def _local_bounds(
    e00: F,
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
) -> tuple[F, F, F, F, F, F, F, F]:
    """The local part of certified_minimum's argument at the point (x, y), one source for it
    and retry_minimum: (r, emax, E(x, y), level, clear_x, clear_y, convex, δ), r the half-width
    of the square R, emax the coefficients' size, level E(x, y) + the rounding slack, the sides
    beyond R cleared in one piece each, and whether E is convex over R with δ = |∇E| / μ."""
    # R's half-width: RADIUS of the box, or NEAR_FACE of the point's distance to the nearest
    # face where that is less (a minimum near a face; module doc: any r > 0 is sound)
    r0 = RADIUS * max(xhi - xlo, yhi - ylo)
    room = np.minimum(np.minimum(x - xlo, xhi - x), np.minimum(y - ylo, yhi - y))
    r = _where(room > r0, r0, NEAR_FACE * room)
    emax = _largest(e00, e01, e02, e10, e11, e12, e20, e21, e22)
    ax, ay = np.abs(x) + r, np.abs(y) + r
    slack = ROUND * emax * (1 + ax + ax * ax) * (1 + ay + ay * ay)
    a = _at(e20, e21, e22, y)  # E = a x² + b x + c along this y
    b = _at(e10, e11, e12, y)
    c = _at(e00, e01, e02, y)
    energy = _at(c, b, a, x)
    level = energy + slack
    lo_xx, ex, clear_y = _direction(
        e20, e21, e22, e10, e11, e12, e00, e01, e02, x, y, r, ylo, yhi, level, emax, slack
    )
    lo_yy, ey, clear_x = _direction(
        e02, e12, e22, e01, e11, e21, e00, e10, e20, y, x, r, xlo, xhi, level, emax, slack
    )
    # |E_xy| over R, E_xy = B'(y) + 2 x A'(y)
    hxy = e11 + 2 * e12 * y + 2 * x * (e21 + 2 * e22 * y)
    hi_xy = (
        np.abs(hxy)
        + (np.abs(2 * e21 + 4 * e22 * y) + np.abs(2 * e12 + 4 * e22 * x)) * r
        + 4 * np.abs(e22) * r * r
        + slack
    )
    half = 0.5 * (lo_xx - lo_yy)
    mu = 0.5 * (lo_xx + lo_yy) - np.sqrt(half * half + hi_xy * hi_xy)
    convex = (lo_xx > 0) & (lo_yy > 0) & (mu > 0)
    grad = np.sqrt(ex * ex + ey * ey)
    delta = grad / _where(convex, mu, 1.0)
    return r, emax, energy, level, clear_x, clear_y, convex, delta


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
    # when the body is straight-line code. Two sweeps and four Newton steps: on the 10,000
    # benchmark nets three more sweeps and steps certify 3 more nets (161 declined, not 164),
    # at a fifth of the certificate's cost
    e, box = (e01, e02, e10, e11, e12, e20, e21, e22), (xlo, xhi, ylo, yhi)
    x, y = _sweep(e, x, y, box)
    x, y = _sweep(e, x, y, box)
    x, y = _newton(e, x, y, box)
    x, y = _newton(e, x, y, box)
    x, y = _newton(e, x, y, box)
    x, y = _newton(e, x, y, box)
    r, emax, energy, level, clear_x, clear_y, convex, delta = _local_bounds(
        e00, e01, e02, e10, e11, e12, e20, e21, e22, x, y, xlo, xhi, ylo, yhi
    )
    # 2δ < r: E on R's boundary exceeds E(x, y) (E >= E(x, y) − |∇E| r + μ r² / 2), so the
    # minimum over R is interior, the critical point
    local = convex & (delta <= tol) & (2 * delta < r)
    inside = (x - r > xlo) & (x + r < xhi) & (y - r > ylo) & (y + r < yhi)
    ok = local & inside & clear_y & clear_x
    return x, y, energy, _where(convex, delta, np.inf), ok


def _grows_from(
    a0: F,
    a1: F,
    a2: F,
    b0: F,
    b1: F,
    b2: F,
    c0: F,
    c1: F,
    c2: F,
    s0: float,
    inward: float,
    level: F,
    u0: F,
    u1: F,
    m: float,
    emax: F,
) -> F:
    """Whether, at every t of [u0, u1], E(·, t) = A(t) s² + B(t) s + C(t) grows from the
    box's face s = s0 into the box (inward · E_s(s0, t) > 0; with A > 0 its least value over
    the box's s is then at s0) and E(s0, t) exceeds `level`: _edge's test of a piece, with
    its slack (m bounds |t|)."""
    reach = emax * (1 + abs(s0) + s0 * s0)
    slack = ROUND * reach * (1 + m + m * m)
    q0 = _at(c0, b0, a0, s0) - level
    q1 = _at(c1, b1, a1, s0)
    q2 = _at(c2, b2, a2, s0)
    g0 = inward * _slope(b0, a0, s0)
    g1 = inward * _slope(b1, a1, s0)
    g2 = inward * _slope(b2, a2, s0)
    return _quadratic_positive(g0, g1, g2, u0, u1, slack) & _quadratic_positive(
        q0, q1, q2, u0, u1, slack
    )


def _side_clear_pieces(
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
    r: F,
    lo: float,
    hi: float,
    slo: float,
    shi: float,
    emax: F,
) -> F:
    """_side_clear with each side [lo, at − r] and [at + r, hi] cut into CLEAR_PIECES pieces,
    each cleared on its own: by the quartic's Bernstein test there (the same test and slack;
    a piece's coefficients bound p on it more tightly than the whole side's, a lower bound
    over a wide interval), or, where the minimiser over every real s lies outside the box's
    [slo, shi], by E growing from that face into the box above `level` (_grows_from; A > 0
    on the whole side, tested here, makes E(·, t) convex, so its least value over the box
    is then on the face). The module's doc says what each part certified on at_cubic."""
    m = max(1.0, abs(lo), abs(hi)) + 1.0
    p0, p1, p2, p3, p4, slack = _discriminant(a0, a1, a2, b0, b1, b2, c0, c1, c2, level, m, emax)
    ok = _quadratic_positive(a0, a1, a2, lo, hi, BERNSTEIN_SLACK * emax * m * m)
    mt = m - 1.0  # bounds |t| on the side, as _edge's m
    for side in range(2):
        start = _where(side == 0, lo + 0.0 * at, at + r)
        end = _where(side == 0, at - r, hi + 0.0 * at)
        step = (end - start) / CLEAR_PIECES
        for i in range(CLEAR_PIECES):
            u0 = start + i * step
            u1 = _where(i == CLEAR_PIECES - 1, end, start + (i + 1) * step)
            clear = _quartic_positive(p0, p1, p2, p3, p4, u0, u1, slack)
            if not _every(clear):  # the faces, only where the quartic does not clear it
                low = _grows_from(
                    a0, a1, a2, b0, b1, b2, c0, c1, c2, slo, 1.0, level, u0, u1, mt, emax
                )
                high = _grows_from(
                    a0, a1, a2, b0, b1, b2, c0, c1, c2, shi, -1.0, level, u0, u1, mt, emax
                )
                clear = clear | low | high
            ok = ok & clear
            if _none(ok):  # declined already
                return ok
    return ok


def _search_start(
    e: tuple[F, ...], xlo: float, xhi: float, ylo: float, yhi: float, zero: F
) -> tuple[F, F]:
    """The best of SEARCH points (x_i, y_i), x_i evenly spaced over [xlo, xhi] with both ends
    and y_i the exact minimiser of E(x_i, ·) over [ylo, yhi] (the middle where E(x_i, ·) is
    not convex); `e` as for _sweep, `zero` 0 in the coefficients' shape. Only a start: the
    certificate below is of whatever point the steps from here reach."""
    e01, e02, e10, e11, e12, e20, e21, e22 = e
    ym = 0.5 * (ylo + yhi)
    best = np.inf + zero
    bx = xlo + zero
    by = ym + zero
    for i in range(SEARCH):
        xi = xlo + (xhi - xlo) * (i / (SEARCH - 1)) + zero
        yi = _step(e02, e12, e22, e01, e11, e21, xi, ym + zero, ylo, yhi)
        # E(x_i, y_i) less e00 (the same for every point): (A x + B) x + G y + F y²
        a = _at(e20, e21, e22, yi)
        b = _at(e10, e11, e12, yi)
        v = (a * xi + b) * xi + (e01 + e02 * yi) * yi
        better = v < best
        best = _where(better, v, best)
        bx = _where(better, xi, bx)
        by = _where(better, yi, by)
    return bx, by


def retry_minimum(
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
    """certified_minimum again, for the nets it and edge_minimum decline, with more work: a
    start searched along x (_search_start), two sweeps and RETRY_NEWTON Newton steps (from
    the middle, four steps left 102 of at_cubic's 274 declined interior minima unconverged,
    some in another basin), and the sides beyond R cleared piece by piece
    (_side_clear_pieces). The local part and the argument are certified_minimum's, for
    whatever point it is given (its doc); only the clearing's test is finer, each piece's
    Bernstein coefficients a lower bound of p there as the whole side's are of p on it."""
    zero = 0.0 * e00
    e, box = (e01, e02, e10, e11, e12, e20, e21, e22), (xlo, xhi, ylo, yhi)
    x, y = _search_start(e, xlo, xhi, ylo, yhi, zero)
    x, y = _sweep(e, x, y, box)
    x, y = _sweep(e, x, y, box)
    for _ in range(RETRY_NEWTON):
        x, y = _newton(e, x, y, box)
    # its local bounds (_local_bounds' one-piece clearing of the sides is not used here)
    r, emax, energy, level, _, _, convex, delta = _local_bounds(
        e00, e01, e02, e10, e11, e12, e20, e21, e22, x, y, xlo, xhi, ylo, yhi
    )
    local = convex & (delta <= tol) & (2 * delta < r)
    inside = (x - r > xlo) & (x + r < xhi) & (y - r > ylo) & (y + r < yhi)
    ok = local & inside
    if _none(ok):  # the clearing could only keep it declined
        return x, y, energy, _where(convex, delta, np.inf), ok
    clear_y = _side_clear_pieces(
        e20, e21, e22, e10, e11, e12, e00, e01, e02, level, y, r, ylo, yhi, xlo, xhi, emax
    )
    clear_x = _side_clear_pieces(
        e02, e12, e22, e01, e11, e21, e00, e10, e20, level, x, r, xlo, xhi, ylo, yhi, emax
    )
    return x, y, energy, _where(convex, delta, np.inf), ok & clear_y & clear_x


def _edge(
    a0: F,
    a1: F,
    a2: F,
    b0: F,
    b1: F,
    b2: F,
    c0: F,
    c1: F,
    c2: F,
    s0: float,
    inward: float,
    lo: float,
    hi: float,
    r: F,
    emax: F,
    tol: float,
) -> tuple[F, F, F, F]:
    """(t, E(s0, t), δ, certified): the minimum over the box when it lies on the edge s = s0
    of one direction, E = A(t) s² + B(t) s + C(t) with t over [lo, hi] (the other direction
    is the same call with the coefficients transposed), inward = 1 at the low end of s and
    −1 at the high end. The edge's quadratic q(t) = E(s0, t), strictly convex, has its
    minimum over [lo, hi] at its vertex clipped there (clipping moves no error further),
    within δ of t. Certified when δ <= tol, A > 0 on [lo, hi], and
    - on the band of t within r of it, inward · E_s(s0, t) > 0: each E(·, t) grows from the
      edge into the box, so there the box's minimum is the edge's, q(t) >= q(t*);
    - each of EDGE_PIECES pieces of the rest of [lo, hi] on either side of the band is
      cleared: there E(·, t) grows from the edge and q > q(t*), or min over every real s of
      E(s, t) exceeds q(t*) (the unconstrained minimiser may lie outside the box on one
      part of a side and inside it on another: the pieces let each part take its test)."""
    m = max(1.0, abs(lo), abs(hi))
    reach = emax * (1 + abs(s0) + s0 * s0)  # the size of every q_k and of E_s's coefficients
    slack = ROUND * reach * (1 + m + m * m)
    q0 = _at(c0, b0, a0, s0)
    q1 = _at(c1, b1, a1, s0)
    q2 = _at(c2, b2, a2, s0)
    # q_k = (a_k s0 + b_k) s0 + c_k: four roundings, each of at most reach (4x that, for safety)
    err = GRADIENT_ROUND * reach
    cup = q2 > err
    vertex = -q1 / _where(cup, 2 * q2, 1.0)
    t = _clip(vertex, lo, hi)
    # the vertex moves by at most (|Δq1| + 2 |v| |Δq2|) / (2 (q2 − |Δq2|)) under the
    # coefficients' rounding, plus its own few roundings
    delta = err * (1 + 2 * np.abs(vertex)) / _where(
        cup, 2 * (q2 - err), 1.0
    ) + GRADIENT_ROUND * np.abs(vertex)
    energy = _at(q0, q1, q2, t)
    level = energy + slack
    g0, g1, g2 = (
        inward * _slope(b0, a0, s0),
        inward * _slope(b1, a1, s0),
        inward * _slope(b2, a2, s0),
    )
    ok = cup & (delta <= tol) & _quadratic_positive(a0, a1, a2, lo, hi, slack)
    ok = ok & _quadratic_positive(g0, g1, g2, np.maximum(t - r, lo), np.minimum(t + r, hi), slack)
    if _none(ok):  # declined already: the pieces below could only keep it so
        return t, energy, delta, ok
    p0, p1, p2, p3, p4, p_slack = _discriminant(
        a0, a1, a2, b0, b1, b2, c0, c1, c2, level, m + 1.0, emax
    )
    for side in range(2):
        start = _where(side == 0, lo + 0.0 * t, t + r)
        end = _where(side == 0, t - r, hi + 0.0 * t)
        step = (end - start) / EDGE_PIECES
        for i in range(EDGE_PIECES):
            u0 = start + i * step
            u1 = _where(i == EDGE_PIECES - 1, end, start + (i + 1) * step)
            grows = _quadratic_positive(g0, g1, g2, u0, u1, slack) & _quadratic_positive(
                q0 - level, q1, q2, u0, u1, slack
            )
            clear = grows | _quartic_positive(p0, p1, p2, p3, p4, u0, u1, p_slack)
            ok = ok & ((end <= start) | clear)  # an empty side (t within r of an end)
            if _none(ok):  # the compiled engine's nets one at a time: most stop early
                return t, energy, delta, ok
    return t, energy, delta, ok


def edge_minimum(
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
    """(x, y, E(x, y), δ, certified) as certified_minimum's, for the nets it declines whose
    minimum lies on an edge or a corner of the box: the first of the four edges x = xlo,
    x = xhi, y = ylo, y = yhi that `_edge` certifies (any certified one is the box's unique
    minimiser, so they agree within their δ)."""
    return edge_band_minimum(
        e00, e01, e02, e10, e11, e12, e20, e21, e22,
        xlo, xhi, ylo, yhi, tol, RADIUS * max(xhi - xlo, yhi - ylo),
    )  # fmt: skip


def edge_band_minimum(
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
    r: F,
) -> tuple[F, F, F, F, F]:
    """edge_minimum with the band's half-width `r` given (any r > 0 is sound: the band is
    where each E(·, t) must grow from the edge, the pieces beyond it are cleared by their
    own tests, _edge's doc)."""
    emax = _largest(e00, e01, e02, e10, e11, e12, e20, e21, e22)
    # x = xlo, xhi: E = A(y) x² + B(y) x + C(y); y = ylo, yhi: E = F(x) y² + G(x) y + H(x)
    t1, v1, d1, ok1 = _edge(
        e20, e21, e22, e10, e11, e12, e00, e01, e02, xlo, 1.0, ylo, yhi, r, emax, tol
    )
    t2, v2, d2, ok2 = _edge(
        e20, e21, e22, e10, e11, e12, e00, e01, e02, xhi, -1.0, ylo, yhi, r, emax, tol
    )
    t3, v3, d3, ok3 = _edge(
        e02, e12, e22, e01, e11, e21, e00, e10, e20, ylo, 1.0, xlo, xhi, r, emax, tol
    )
    t4, v4, d4, ok4 = _edge(
        e02, e12, e22, e01, e11, e21, e00, e10, e20, yhi, -1.0, xlo, xhi, r, emax, tol
    )
    zero = 0.0 * e00
    x = _where(ok1, xlo + zero, _where(ok2, xhi + zero, _where(ok3, t3, t4)))
    y = _where(ok1, t1, _where(ok2, t2, _where(ok3, ylo + zero, yhi + zero)))
    energy = _where(ok1, v1, _where(ok2, v2, _where(ok3, v3, v4)))
    delta = _where(ok1, d1, _where(ok2, d2, _where(ok3, d3, d4)))
    return x, y, energy, delta, ok1 | ok2 | ok3 | ok4
