"""Issue #29: exact self-crossings of exact rational Bézier curves (hazmat/intersect_self_exact.py
on X(s) W(t) − X(t) W(s) divided by s − t). The curves are the polynomial cases of
test_self_crossings_exact.py under the Möbius change of parameter u = t / (c (1 − t) + t),
which makes a rational Bézier curve of the same control points with weights c^(n − i): its
self-crossings are the polynomial curve's at t = c u / (1 − u + c u), exactly."""

from __future__ import annotations

from fractions import Fraction as F

import pytest
from test_self_crossings_exact import algebra, assert_exactly, crossing, folded, loop

import lambda_bezier as lb
from lambda_bezier.hazmat import intersect_self_exact as se

__all__ = ["algebra"]  # the fixture, imported for the tests below


def reparameterised(curve: lb.BezierCurve, c: F) -> lb.RationalBezierCurve:
    rows = curve.control_points()
    n = len(rows) - 1
    return lb.RationalBezierCurve(rows, [c ** (n - i) for i in range(n + 1)])


def moved(u: F, c: F) -> F:
    return c * u / (1 - u + c * u)


@pytest.mark.parametrize(
    ("r", "c", "algebra"),
    [(F(1, 10**7), F(1), "flint"), (F(1, 10**9), F(2), "fractions")],
    indirect=["algebra"],
)
def test_small_loops_of_rational_curves(algebra, r, c):
    """Main refused the first as a cusp (ValueError) and gave the second as one "tangent" hit
    with s and t 7e-9 apart; the float search takes 1-3 s on these (most of the tests' time)."""
    s, t = crossing(r)
    curve = reparameterised(loop(r, (F(3, 5), F(4, 5))), c)
    assert_exactly(curve.self_intersections(), [(moved(s, c), moved(t, c), "transversal")])


@pytest.mark.parametrize(
    ("c", "algebra"), [(F(1), "fractions"), (F(3, 2), "flint")], indirect=["algebra"]
)
def test_a_rational_cusp_is_no_crossing(algebra, c):
    """Main refused it at c = 1 (C' vanishes: "such curves are not supported") and gave none at
    c = 3/2; decided exactly: none."""
    assert reparameterised(loop(F(0)), c).self_intersections() == []


def test_near_double_self_crossings_of_a_rational_quintic(algebra):
    """Two crossings 1e-9 apart (main: one "tangent"), within FLINT's rational budget (degree
    6); past the standard library's (4) the float answer stands."""
    c, g = F(2), F(1, 10**9)
    curve = reparameterised(folded(F(1, 2), F(1, 2) + g, (F(-5, 13), F(12, 13))), c)
    hits = curve.self_intersections()
    if curve.degree > se.SELF_DEGREE_RATIONAL[algebra.name]:
        assert [h.kind for h in hits] == ["tangent"]  # the documented float limit
        return
    want = [crossing(F(1, 2) + g), crossing(F(1, 2))]
    assert_exactly(hits, [(moved(s, c), moved(t, c), "transversal") for s, t in want])
