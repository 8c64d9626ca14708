"""A curve on a line that turns back along it meets itself along stretches (issue #29): its
self_intersections are the end pairs of those stretches, "coincident", as two curves sharing
a stretch are reported (it was refused by name). References from SymPy: the turning points
are the roots of u′ (u the position along the line), the other ends the roots of u(t) = v."""

from __future__ import annotations

from fractions import Fraction as F

import numpy as np
import pytest
import sympy as sp

import lambda_bezier as lb

S = sp.Symbol("s")


def position(rows, direction) -> sp.Expr:
    """u(s) = (p(s) − P_0)·direction for the Bézier curve with control points rows (SymPy)."""
    n = len(rows) - 1
    u = [
        sum(sp.Rational(str(x - x0)) * d for x, x0, d in zip(r, rows[0], direction, strict=True))
        for r in rows
    ]
    return sp.expand(
        sum(sp.binomial(n, i) * S**i * (1 - S) ** (n - i) * u[i] for i in range(n + 1))
    )


def roots_in(poly: sp.Expr, lo, hi) -> list[sp.Expr]:
    return sorted({r for r in sp.Poly(poly, S).real_roots() if lo <= r <= hi}, key=float)


def near(got, want, tol=1e-15) -> None:
    assert len(got) == len(want), (got, want)
    for h, (s, t) in zip(got, want, strict=True):
        assert h.kind == "coincident"
        assert abs(h.s - float(sp.N(s, 30))) <= tol and abs(h.t - float(sp.N(t, 30))) <= tol, (
            got,
            want,
        )


def test_a_quadratic_folded_once():
    """x = 4s − 5s² on y = 0: out to x = 4/5 at s = 2/5 and back to −1. The stretch s in
    [0, 2/5] is t in [2/5, 4/5] run backwards: end pairs (0, 4/5) (x = 0) and (2/5, 2/5)
    (the fold)."""
    rows = [(0, 0), (2, 0), (-1, 0)]
    u = position(rows, (1, 0))
    (turn,) = roots_in(sp.diff(u, S), 0, 1)
    back = roots_in(u, turn, 1)
    assert turn == sp.Rational(2, 5) and back == [sp.Rational(4, 5)]
    want = [(0, back[0]), (turn, turn)]
    near(lb.BezierCurve(rows).self_intersections(), want)
    floats = lb.BezierCurve(np.array(rows, dtype=float))
    near(floats.self_intersections(), want)


@pytest.mark.parametrize("direction", [(1, 1, 1), (3, -1, 2)])
def test_a_cubic_folded_twice_in_3d(direction):
    """Control points 0, 2, −1, 1 along a line in 3-D: u rises to M at s1, falls to m at s2,
    rises to u(1) = 1 (SymPy: s1, s2 roots of u′, m > 0); the three monotone pieces share
    [m, M] pairwise, reported once per distinct end pair."""
    d = np.array(direction)
    rows = [tuple(int(k) * d) for k in (0, 2, -1, 1)]
    u = position([(k,) for k in (0, 2, -1, 1)], (1,))
    s1, s2 = roots_in(sp.diff(u, S), 0, 1)
    big, small = u.subs(S, s1), u.subs(S, s2)
    assert 0 < small < big < 1
    # u − m has the double root s2 and u − M the double root s1; the third root of each is
    # the roots' sum (Vieta: −u₂/u₃) less twice the double one
    total = -sp.Poly(u, S).nth(2) / sp.Poly(u, S).nth(3)
    a_small, c_big = sp.simplify(total - 2 * s2), sp.simplify(total - 2 * s1)
    assert sp.simplify(u.subs(S, a_small) - small) == 0 and 0 <= a_small <= s1
    assert sp.simplify(u.subs(S, c_big) - big) == 0 and s2 <= c_big <= 1
    want = [(a_small, s2), (s1, s1), (s1, c_big), (s2, s2)]
    near(lb.BezierCurve(rows).self_intersections(), want, tol=1e-14)


def test_a_line_run_one_way_does_not_meet_itself():
    """A stationary point of even order (u = 2 ((s − 1/2)³ + 1/8), u′ = 6 (s − 1/2)² ≥ 0)
    does not turn back."""
    rows = [(0, 0), (F(1, 4), F(1, 4)), (0, 0), (F(1, 4), F(1, 4))]
    u = position(rows, (1, 1))
    assert roots_in(sp.diff(u, S), 0, 1) == [sp.Rational(1, 2)]
    assert lb.BezierCurve(rows).self_intersections() == []
