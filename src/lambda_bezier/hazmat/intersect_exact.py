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

Boxes neither excluded nor proved are bisected (the isolating intervals refined) up to
MAX_HALVINGS times. What is still undecided then is reported uncertified: a tangency (the
Jacobian is singular there, so Krawczyk cannot contract) or crossings closer than the width.
Nothing is rounded: the ends of every interval are Fractions.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from math import comb
from typing import NamedTuple

from . import exact_poly as xp

MAX_HALVINGS = 60  # per isolating interval: widths down to 2^-60 before a box is left undecided

Interval = tuple[Fraction, Fraction]


class ExactCrossing(NamedTuple):
    """s in [s[0], s[1]] and t in [t[0], t[1]] (Fractions). certified: the box provably holds
    exactly one crossing (Krawczyk); False: it was neither excluded nor proved (a tangency,
    most likely), though it is the only box left for that s and t."""

    s: Interval
    t: Interval
    certified: bool


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


def _roots(poly: list[Fraction]) -> list[Interval]:
    return [
        (r, r) if isinstance(r, Fraction) else r
        for r in xp.real_roots(poly, Fraction(0), Fraction(1))
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
    p_rows: Sequence[Sequence[Fraction]], q_rows: Sequence[Sequence[Fraction]]
) -> list[ExactCrossing]:
    """The crossings of two planar Bézier curves with exact control points, as boxes of
    Fractions sorted by s (see the module's docstring). ValueError when the curves share a
    component (the resultant vanishes identically)."""
    fx = _difference(power_coefficients(p_rows, 0), power_coefficients(q_rows, 0))
    fy = _difference(power_coefficients(p_rows, 1), power_coefficients(q_rows, 1))
    if not fx or not fy:
        raise ValueError("a coordinate of p - q vanishes identically: no finite set of crossings")
    r_s = xp.resultant(fx, fy, 1)  # t eliminated: a polynomial in s
    r_t = xp.resultant(fx, fy, 0)
    if not r_s or not r_t:
        raise ValueError(
            "the curves share a component (their resultant vanishes identically): their "
            "intersection is not a finite set of points"
        )
    f = [fx, fy]
    jac = [[xp.partial(g, 0), xp.partial(g, 1)] for g in f]
    boxes = (_roots(r_s), _roots(r_t))  # isolating intervals of s, of t
    halvings = ([0] * len(boxes[0]), [0] * len(boxes[1]))
    squares = (xp.squarefree(xp.trim(r_s)), xp.squarefree(xp.trim(r_t)))
    pending = [(i, j) for i in range(len(boxes[0])) for j in range(len(boxes[1]))]
    found: list[ExactCrossing] = []
    while pending:
        i, j = pending.pop()
        s_box, t_box = boxes[0][i], boxes[1][j]
        if not all(_contains_zero(xp.interval_evaluate2(g, s_box, t_box)) for g in f):
            continue
        if s_box[0] == s_box[1] and t_box[0] == t_box[1]:
            if all(xp.evaluate2(g, s_box[0], t_box[0]) == 0 for g in f):
                found.append(ExactCrossing(s_box, t_box, True))
            continue
        if _krawczyk(f, jac, [_widen(s_box), _widen(t_box)]):
            found.append(ExactCrossing(s_box, t_box, True))
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
        else:  # as narrow as allowed, neither excluded nor proved
            found.append(ExactCrossing(s_box, t_box, False))
    return sorted(found, key=lambda c: (c.s[0], c.t[0]))


def _widen(box: Interval) -> Interval:
    """A degenerate interval (an exact rational root) as a small box around it, so that
    Krawczyk's interior test has an interior (uniqueness then holds in the wider box)."""
    lo, hi = box
    if lo != hi:
        return box
    eps = Fraction(1, 2**80)
    return lo - eps, hi + eps
