"""Exact, certified isolation of the crossings of two planar curves with rational control points.

With F(s, t) = p(s) - q(t) in the power basis (exact Fractions), every crossing's s is a real
root of R_s = Res_t(F_x, F_y) and its t one of R_t = Res_s(F_x, F_y) (exact_poly.resultant).
Sturm sequences isolate those roots in [0, 1] into intervals with rational ends, each holding
exactly one distinct root (exact_poly.real_roots). A box I_s x I_t then holds at most one
crossing, and

- it holds none when interval evaluation of F_x or F_y over it excludes 0;
- it holds exactly one when the Krawczyk operator K(X) = m - Y F(m) + (I - Y J(X)) (X - m)
  (m the box's centre, Y = J(m)^-1, J(X) an enclosure of the Jacobian over the box, all in
  exact rational interval arithmetic) maps the box into its interior: a transversal crossing.

Boxes neither excluded nor proved are bisected (the isolating intervals refined). A box
Krawczyk fails on EARLY_DECISION times (a tangency, most likely: the Jacobian is singular
there, so Krawczyk cannot contract), and one still open after MAX_HALVINGS halvings, is
decided algebraically (`_Decider`, exact at any width): the box's s* is the one root
of R_s in I_s, and where the first subresultant S_1 = a1(s) t + a0(s) of F_x, F_y in t has
a1(s*) ≠ 0, the only t with F(s*, t) = 0 is t* = −a0(s*)/a1(s*); whether t* lies in I_t, and
whether the Jacobian's determinant vanishes at (s*, t*) (a tangency), are signs of
polynomials at s*, decided exactly by gcds over Q and Sturm sequences
(exact_poly.sign_at_root). So a touching point is proved (certified, tangent) and a box with
no common point is dropped: a near-tangency with no real contact is not reported. The same
the other way round (s* from t*) when a1 vanishes there; only when both vanish (two common
points over one s* and over one t*) is the box left uncertified. Nothing is rounded: the
ends of every interval are Fractions.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from fractions import Fraction
from math import comb
from typing import NamedTuple

from . import exact_flint
from . import exact_poly as xp

MAX_HALVINGS = 60  # per isolating interval: widths down to 2^-60 before a box is left undecided
# Krawczyk failing this often on one box (transversal crossings are proved within a few
# halvings), the box is decided algebraically at once (exact at any width: each interval
# isolates one root of its resultant) rather than after MAX_HALVINGS more tries, each an
# interval evaluation of large Fractions (reflected sextic pairs with FLINT: 0.72-0.92 s a pair
# before, 0.29-0.48 s after, load average 7-8).
EARLY_DECISION = 12

Interval = tuple[Fraction, Fraction]


class ExactCrossing(NamedTuple):
    """s in [s[0], s[1]] and t in [t[0], t[1]] (Fractions). certified: the box provably holds
    exactly one crossing (Krawczyk); False: it was neither excluded nor proved (a tangency,
    most likely), though it is the only box left for that s and t."""

    s: Interval
    t: Interval
    certified: bool
    tangent: bool = False  # certified and the tangents are parallel there (decided exactly)


class Algebra(NamedTuple):
    """The exact steps isolate takes, from one implementation: the standard library's
    (exact_poly, always there) or python-flint's (exact_flint, when installed)."""

    name: str
    resultant: Callable[[xp.Bivariate, xp.Bivariate, int], xp.Poly]
    squarefree: Callable[[xp.Poly], xp.Poly]
    real_roots: Callable[[xp.Poly, Fraction, Fraction], list[Fraction | Interval]]
    sign_at_root: Callable[[xp.Poly, xp.Poly, Interval], int]
    first_subresultant: Callable[[xp.Bivariate, xp.Bivariate, int], tuple[xp.Poly, xp.Poly] | None]
    multiply: Callable[[xp.Poly, xp.Poly], xp.Poly]
    decide_degree: int  # intersect decides tangencies exactly up to this product of the degrees
    decide_degree_rational: int  # the same for rational curves (the cross-multiplied system)


# The budgets, measured on reflected tangencies (a random integer curve against its reflection
# in its own tangent line at t0 = 7/23 or 3/40, 12 pairs per degree), load average 7-8 on 2
# cores: exact_poly 0.06-0.19 s a pair for two cubics, 1.4-3.3 s for two quartics (110 s for
# two quintics in round 17); exact_flint 0.03-0.04 s, 0.07-0.13 s, 0.18-0.26 s for quintics,
# 0.29-0.48 s for sextics (products of the degrees 25 and 36).
PURE = Algebra(
    "exact_poly",
    xp.resultant,
    xp.squarefree,
    xp.real_roots,
    xp.sign_at_root,
    xp.first_subresultant,
    xp.multiply,
    9,
    4,  # two conics 0.04-0.06 s, two rational cubics 1.6-2.6 s (loaded, reflected tangencies)
)
DECIDE_DEGREE_FLINT = 36
FLINT = Algebra(
    "exact_flint",
    exact_flint.resultant,
    exact_flint.squarefree,
    exact_flint.real_roots,
    exact_flint.sign_at_root,
    exact_flint.first_subresultant,
    exact_flint.multiply,
    DECIDE_DEGREE_FLINT,
    16,  # rational cubics 0.14-0.18 s, quartics 0.37-0.49 s, quintics 1.0-1.5 s (loaded)
)


def algebra() -> Algebra:
    """FLINT when python-flint is installed, else the standard library's."""
    return FLINT if exact_flint.available() else PURE


def power_coefficients(rows: Sequence[Sequence[Fraction]], axis: int) -> list[Fraction]:
    """Coordinate `axis` of the Bézier curve with control points rows, in the power basis:
    the coefficient of s^k is sum_i P_i C(n, i) C(n - i, k - i) (-1)^(k - i)."""
    n = len(rows) - 1
    return [
        sum(
            (Fraction(rows[i][axis]) * comb(n, i) * comb(n - i, k - i) * (-1) ** (k - i))
            for i in range(k + 1)
        )
        or Fraction(0)
        for k in range(n + 1)
    ]


def _difference(p: list[Fraction], q: list[Fraction]) -> xp.Bivariate:
    """p(s) - q(t) as a bivariate polynomial {(i, j): coefficient of s^i t^j}."""
    out: xp.Bivariate = {}
    for i, c in enumerate(p):
        if c:
            out[(i, 0)] = out.get((i, 0), Fraction(0)) + c
    for j, c in enumerate(q):
        if c:
            out[(0, j)] = out.get((0, j), Fraction(0)) - c
    return {k: v for k, v in out.items() if v}


def rational_system(
    p_rows: Sequence[Sequence[Fraction]],
    p_weights: Sequence[Fraction],
    q_rows: Sequence[Sequence[Fraction]],
    q_weights: Sequence[Fraction],
) -> tuple[xp.Bivariate, xp.Bivariate]:
    """F_c(s, t) = X_c(s) W_q(t) − Y_c(t) W_p(s) for c = x, y: p(s) = q(t) cross-multiplied,
    X, W (Y, W) the homogeneous coordinates of p (of q) in the power basis. With positive
    weights W_p, W_q > 0 on [0, 1], so F's zeros in [0, 1]² are the crossings exactly, and at
    one DF = W_p W_q D(p − q) (the terms with p − q as a factor vanish there): det DF is
    0 exactly where the curves touch, as for polynomial curves."""
    w_p = power_coefficients([(Fraction(w),) for w in p_weights], 0)
    w_q = power_coefficients([(Fraction(w),) for w in q_weights], 0)
    out = []
    for axis in (0, 1):
        x_p = power_coefficients(
            [(Fraction(r[axis]) * w,) for r, w in zip(p_rows, p_weights, strict=True)], 0
        )
        x_q = power_coefficients(
            [(Fraction(r[axis]) * w,) for r, w in zip(q_rows, q_weights, strict=True)], 0
        )
        f: xp.Bivariate = {}
        for i, a in enumerate(x_p):
            for j, b in enumerate(w_q):
                f[(i, j)] = f.get((i, j), Fraction(0)) + a * b
        for i, a in enumerate(w_p):
            for j, b in enumerate(x_q):
                f[(i, j)] = f.get((i, j), Fraction(0)) - a * b
        out.append({k: v for k, v in f.items() if v})
    return out[0], out[1]


def _roots(poly: list[Fraction], alg: Algebra) -> list[Interval]:
    return [
        (r, r) if isinstance(r, Fraction) else r
        for r in alg.real_roots(poly, Fraction(0), Fraction(1))
    ]


def _contains_zero(box: Interval) -> bool:
    return box[0] <= 0 <= box[1]


def _add(a: Interval, b: Interval) -> Interval:
    return a[0] + b[0], a[1] + b[1]


def _scale(c: Fraction, a: Interval) -> Interval:
    return (c * a[0], c * a[1]) if c >= 0 else (c * a[1], c * a[0])


def _mul(a: Interval, b: Interval) -> Interval:
    prods = (a[0] * b[0], a[0] * b[1], a[1] * b[0], a[1] * b[1])
    return min(prods), max(prods)


def _krawczyk(f: list[xp.Bivariate], jac: list[list[xp.Bivariate]], box: list[Interval]) -> bool:
    """True when K(box) lies in the interior of box: exactly one root of f in it."""
    mid = [(a + b) / 2 for a, b in box]
    jm = [[xp.evaluate2(jac[r][c], mid[0], mid[1]) for c in range(2)] for r in range(2)]
    det = jm[0][0] * jm[1][1] - jm[0][1] * jm[1][0]
    if det == 0:
        return False
    inv = [[jm[1][1] / det, -jm[0][1] / det], [-jm[1][0] / det, jm[0][0] / det]]
    fm = [xp.evaluate2(g, mid[0], mid[1]) for g in f]
    enclosure = [
        [xp.interval_evaluate2(jac[r][c], box[0], box[1]) for c in range(2)] for r in range(2)
    ]
    offset = [(box[k][0] - mid[k], box[k][1] - mid[k]) for k in range(2)]
    for r in range(2):
        centre = mid[r] - inv[r][0] * fm[0] - inv[r][1] * fm[1]
        total: Interval = (centre, centre)
        for c in range(2):
            # (I - Y J(X))[r][c], an interval
            one = Fraction(1 if r == c else 0)
            entry: Interval = (one, one)
            for k in range(2):
                term = _scale(-inv[r][k], enclosure[k][c])
                entry = _add(entry, term)
            total = _add(total, _mul(entry, offset[c]))
        if not (box[r][0] < total[0] and total[1] < box[r][1]):
            return False
    return True


def isolate(
    p_rows: Sequence[Sequence[Fraction]],
    q_rows: Sequence[Sequence[Fraction]],
    narrow: Fraction | None = None,
    alg: Algebra | None = None,
    weights: tuple[Sequence[Fraction], Sequence[Fraction]] | None = None,
) -> list[ExactCrossing]:
    """The crossings of two planar Bézier curves with exact control points, as boxes of
    Fractions sorted by s (see the module's docstring); with `narrow`, each box's intervals
    refined to that width at the end; the algebra `alg` (default: `algebra()`); with
    `weights` (p's, q's: positive Fractions), of the two rational Bézier curves, on the
    cross-multiplied system (`rational_system`). ValueError when the curves share a
    component (the resultant vanishes identically)."""
    if weights is None:
        fx = _difference(power_coefficients(p_rows, 0), power_coefficients(q_rows, 0))
        fy = _difference(power_coefficients(p_rows, 1), power_coefficients(q_rows, 1))
    else:
        fx, fy = rational_system(p_rows, weights[0], q_rows, weights[1])
    return isolate_system(fx, fy, narrow, alg)


def isolate_system(
    fx: xp.Bivariate,
    fy: xp.Bivariate,
    narrow: Fraction | None = None,
    alg: Algebra | None = None,
    symmetric: bool = False,
) -> list[ExactCrossing]:
    """The common zeros of fx, fy in [0, 1]², isolated and certified as `isolate` describes.
    symmetric: fx and fy are symmetric in s and t (a curve's divided differences,
    intersect_self_exact), so the two resultants are one polynomial and its isolating
    intervals serve both variables; only the zeros with s < t are sought (the boxes pairing
    the i-th root with the j-th, i < j: a box pairing a root with itself holds a zero on the
    diagonal s = t, if any, which is not sought)."""
    alg = alg or algebra()
    if not fx or not fy:
        raise ValueError("a coordinate of p - q vanishes identically: no finite set of crossings")
    r_s = alg.resultant(fx, fy, 1)  # t eliminated: a polynomial in s
    r_t = r_s if symmetric else alg.resultant(fx, fy, 0)
    if not r_s or not r_t:
        raise ValueError(
            "the curves share a component (their resultant vanishes identically): their "
            "intersection is not a finite set of points"
        )
    f = [fx, fy]
    jac = [[xp.partial(g, 0), xp.partial(g, 1)] for g in f]
    roots_s = _roots(r_s, alg)
    boxes = (roots_s, list(roots_s) if symmetric else _roots(r_t, alg))  # of s, of t
    halvings = ([0] * len(boxes[0]), [0] * len(boxes[1]))
    square_s = alg.squarefree(xp.trim(r_s))
    squares = (square_s, square_s if symmetric else alg.squarefree(xp.trim(r_t)))
    decider = _Decider(f, jac, squares, alg)
    pending = [
        (i, j) for i in range(len(boxes[0])) for j in range(len(boxes[1])) if not symmetric or i < j
    ]
    failures: dict[tuple[int, int], int] = {}  # Krawczyk's failures on each box
    found: list[ExactCrossing] = []
    while pending:
        i, j = pending.pop()
        s_box, t_box = boxes[0][i], boxes[1][j]
        if not all(_contains_zero(xp.interval_evaluate2(g, s_box, t_box)) for g in f):
            continue
        if s_box[0] == s_box[1] and t_box[0] == t_box[1]:
            if all(xp.evaluate2(g, s_box[0], t_box[0]) == 0 for g in f):
                singular = _jacobian(jac, s_box[0], t_box[0]) == 0
                found.append(ExactCrossing(s_box, t_box, True, singular))
            continue
        if _krawczyk(f, jac, [_widen(s_box), _widen(t_box)]):
            found.append(ExactCrossing(s_box, t_box, True))
            continue
        failures[(i, j)] = failures.get((i, j), 0) + 1
        if failures[(i, j)] == EARLY_DECISION:  # most likely a tangency: decided now
            decided = decider.decide(s_box, t_box)
            if decided is not None:
                if decided[0]:
                    found.append(ExactCrossing(s_box, t_box, True, decided[1]))
                continue
        refined_any = False
        for axis, k in ((0, i), (1, j)):
            lo, hi = boxes[axis][k]
            if lo != hi and halvings[axis][k] < MAX_HALVINGS:
                refined = xp.refine(squares[axis], (lo, hi), (hi - lo) / 2)
                boxes[axis][k] = (refined, refined) if isinstance(refined, Fraction) else refined
                halvings[axis][k] += 1
                refined_any = True
        if refined_any:
            pending.append((i, j))
        else:  # as narrow as allowed, neither excluded nor proved: decided algebraically
            decided = decider.decide(s_box, t_box)
            if decided is None:
                found.append(ExactCrossing(s_box, t_box, False))
            elif decided[0]:
                found.append(ExactCrossing(s_box, t_box, True, decided[1]))
    if narrow is not None:
        found = [_narrowed(c, squares, narrow) for c in found]
    return sorted(found, key=lambda c: (c.s[0], c.t[0]))


def _narrowed(c: ExactCrossing, squares: tuple[xp.Poly, xp.Poly], width: Fraction) -> ExactCrossing:
    """c with its isolating intervals refined to `width` (each holds the same root)."""
    boxes = []
    for axis, box in ((0, c.s), (1, c.t)):
        if box[1] - box[0] > width:
            got = xp.refine(squares[axis], box, width)
            box = (got, got) if isinstance(got, Fraction) else got
        boxes.append(box)
    return c._replace(s=boxes[0], t=boxes[1])


def _jacobian(jac: list[list[xp.Bivariate]], s: Fraction, t: Fraction) -> Fraction:
    m = [[xp.evaluate2(jac[r][c], s, t) for c in range(2)] for r in range(2)]
    return m[0][0] * m[1][1] - m[0][1] * m[1][0]


class _Decider:
    """Decides exactly whether a box I_s × I_t (each isolating one root of the square-free
    resultants) holds a common zero of F, and whether the Jacobian is singular there (see the
    module's docstring). The subresultants are computed once, on first use."""

    def __init__(
        self,
        f: list[xp.Bivariate],
        jac: list[list[xp.Bivariate]],
        squares: tuple[xp.Poly, xp.Poly],
        alg: Algebra,
    ) -> None:
        self.f, self.jac, self.squares, self.alg = f, jac, squares, alg
        self._forms: dict[int, tuple[xp.Poly, xp.Poly] | None] = {}

    def _form(self, var: int) -> tuple[xp.Poly, xp.Poly] | None:
        if var not in self._forms:
            self._forms[var] = self.alg.first_subresultant(self.f[0], self.f[1], var)
        return self._forms[var]

    def decide(self, s_box: Interval, t_box: Interval) -> tuple[bool, bool] | None:
        """(a common zero in the box, the Jacobian singular there), or None: undecided."""
        for var in (1, 0):  # t from s*, then s from t*
            got = self._decide_along(var, (s_box, t_box))
            if got is not None:
                return got
        return None

    def _decide_along(self, var: int, boxes: tuple[Interval, Interval]) -> tuple[bool, bool] | None:
        form = self._form(var)
        if form is None:
            return None
        a1, a0 = form
        known = 1 - var  # the root x* known by its isolating interval; var = -a0/a1 at x*
        square, box = self.squares[known], boxes[known]
        lead = self.alg.sign_at_root(a1, square, box)
        if lead == 0:
            return None
        # S_1(x*, ·) is the gcd of F_x(x*, ·), F_y(x*, ·) only where a leading coefficient
        # in var does not vanish at x* (always, for polynomial curves: constants)
        leads = [xp.substitute_row(g, var, max(k[var] for k in g)) for g in self.f]
        if all(len(c) > 1 and self.alg.sign_at_root(c, square, box) == 0 for c in leads):
            return None
        lo, hi = boxes[var]
        # var* >= lo  <=>  lead * (a0 + lo a1) <= 0 at x*; var* <= hi <=> lead * (a0 + hi a1) >= 0
        if lead * self.alg.sign_at_root(_plus(a0, a1, lo), square, box) > 0:
            return (False, False)
        if lead * self.alg.sign_at_root(_plus(a0, a1, hi), square, box) < 0:
            return (False, False)
        return True, self.alg.sign_at_root(self._determinant_along(var, a1, a0), square, box) == 0

    def _determinant_along(self, var: int, a1: xp.Poly, a0: xp.Poly) -> xp.Poly:
        """a1^d · det J(x, −a0/a1) as a polynomial in the known variable x, d the Jacobian's
        degree in var (a1 ≠ 0 at x*, so it vanishes at x* exactly when det J does there)."""
        det = _bivariate_det(self.jac)
        degree = max((k[var] for k in det), default=0)
        mul = self.alg.multiply
        by_power = [xp.substitute_row(det, var, j) for j in range(degree + 1)]  # det = Σ c_j var^j
        minus_a0: list[xp.Poly] = [[Fraction(1)]]
        a1_powers: list[xp.Poly] = [[Fraction(1)]]
        for _ in range(degree):
            minus_a0.append(mul(minus_a0[-1], [-x for x in a0]))
            a1_powers.append(mul(a1_powers[-1], a1))
        out: xp.Poly = []
        for j, c in enumerate(by_power):
            if c:
                out = _add_poly(out, mul(c, mul(minus_a0[j], a1_powers[degree - j])))
        return xp.trim(out)


def _plus(a0: xp.Poly, a1: xp.Poly, c: Fraction) -> xp.Poly:
    return _add_poly(a0, [c * x for x in a1])


def _add_poly(a: xp.Poly, b: xp.Poly) -> xp.Poly:
    size = max(len(a), len(b))
    return xp.trim(
        [
            (a[k] if k < len(a) else Fraction(0)) + (b[k] if k < len(b) else Fraction(0))
            for k in range(size)
        ]
    )


def _bivariate_det(jac: list[list[xp.Bivariate]]) -> xp.Bivariate:
    out: xp.Bivariate = {}
    for c, sign in ((0, 1), (1, -1)):  # J00 J11 − J01 J10
        for k1, c1 in jac[0][c].items():
            for k2, c2 in jac[1][1 - c].items():
                key = (k1[0] + k2[0], k1[1] + k2[1])
                out[key] = out.get(key, Fraction(0)) + sign * c1 * c2
    return {k: v for k, v in out.items() if v}


def _widen(box: Interval) -> Interval:
    """A degenerate interval (an exact rational root) as a small box around it, so that
    Krawczyk's interior test has an interior (uniqueness then holds in the wider box)."""
    lo, hi = box
    if lo != hi:
        return box
    eps = Fraction(1, 2**80)
    return lo - eps, hi + eps


NARROW = Fraction(1, 2**64)  # the width exact boxes are refined to when they replace float hits


def exact_answer(
    p_rows: Sequence[Sequence[Fraction]],
    q_rows: Sequence[Sequence[Fraction]],
    alg: Algebra | None = None,
    weights: tuple[Sequence[Fraction], Sequence[Fraction]] | None = None,
) -> list[tuple[float, float, bool]] | None:
    """Every crossing of two exact planar curves as (s, t, tangent): each box of `isolate`,
    refined to NARROW and rounded at its middle; None when a box is left undecided or the
    curves share a component (the float answer stands then)."""
    try:
        boxes = isolate(p_rows, q_rows, NARROW, alg, weights)
    except ValueError:
        return None
    if not all(c.certified for c in boxes):
        return None
    # sorted as the floats (boxes with one rounded s in the order of their t), as intersect's
    return sorted(
        (float((c.s[0] + c.s[1]) / 2), float((c.t[0] + c.t[1]) / 2), c.tangent) for c in boxes
    )


def decided(
    p_rows: Sequence[Sequence[Fraction]] | None,
    q_rows: Sequence[Sequence[Fraction]] | None,
    p_dim: int,
    q_dim: int,
    kinds: Sequence[str],
    alg: Algebra | None = None,
    weights: tuple[Sequence[Fraction], Sequence[Fraction]] | None = None,
) -> list[tuple[float, float, bool]] | None:
    """intersect's answer decided exactly (exact_answer) for exact (int, Fraction) planar
    input whose float answer (its hits' `kinds`) has a "tangent" hit: touching points proved,
    near-tangencies without contact dropped, near-double crossings split. None (the float
    answer stands) for float input, the curves sharing a stretch, a box left undecided, or
    a product of the degrees past the algebra's decide_degree (decide_degree_rational with
    `weights`: the exact isolation's cost, see PURE and FLINT)."""
    alg = alg or algebra()
    if (
        p_rows is not None
        and q_rows is not None
        and p_dim == q_dim == 3
        and weights is None
        and "tangent" in kinds
    ):
        planar = _in_one_plane(p_rows, q_rows)  # issue #29: crossings in 3-D, in one plane
        if planar is not None:
            (p_rows, q_rows), p_dim, q_dim = planar, 2, 2
    if (
        p_rows is None
        or q_rows is None
        or p_dim != 2
        or q_dim != 2
        or (len(p_rows) - 1) * (len(q_rows) - 1)
        > (alg.decide_degree if weights is None else alg.decide_degree_rational)
        or "tangent" not in kinds
        or "coincident" in kinds
    ):
        return None
    return exact_answer(p_rows, q_rows, alg, weights)


def _in_one_plane(
    p_rows: Sequence[Sequence[Fraction]], q_rows: Sequence[Sequence[Fraction]]
) -> tuple[list[list[Fraction]], list[list[Fraction]]] | None:
    """Two exact space curves whose control points all lie in one plane, as planar curves
    with the same parameters: projected along the axis the plane's normal is largest on
    (exactly; a bijection of the plane, so crossings and tangencies are kept). None when the
    points span space, or lie on one line."""
    rows = [[Fraction(x) for x in row] for row in (*p_rows, *q_rows)]
    base = rows[0]
    diffs = [[a - b for a, b in zip(row, base, strict=True)] for row in rows[1:]]
    normal = None
    for i, u in enumerate(diffs):
        for v in diffs[i + 1 :]:
            n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            if any(n):
                normal = n
                break
        if normal is not None:
            break
    if normal is None or any(sum(a * b for a, b in zip(normal, d, strict=True)) for d in diffs):
        return None
    drop = max(range(3), key=lambda k: abs(normal[k]))
    keep = [k for k in range(3) if k != drop]
    return (
        [[Fraction(row[k]) for k in keep] for row in p_rows],
        [[Fraction(row[k]) for k in keep] for row in q_rows],
    )
