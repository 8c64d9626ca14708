"""Issue #29, an independent audit (round 21) beside tests/test_acceptance_29*.py, which it does
not repeat: one rule on every curve class for three things the classes answered differently.

- `locate` at a self-crossing: the polynomial classes refused it ("several parameters"), the
  rational, trigonometric and C-Bézier classes returned one of the two t.
- A meeting at a curve's end where that curve stops (its first control points repeat): the
  polynomial classes called it "tangent" whatever the other curve's direction (the zero
  derivative counted as parallel to anything); the trigonometric one placed it 1.8e-9 from
  the end. The tangent line there is the one-sided tangent, the first derivative that does
  not vanish (the tangent cone, also at a cusp).
- A rational curve that is a single point: it met a line at one arbitrary s, where the
  polynomial classes refuse a point by name.

Every expected answer is exact by construction, from mpmath at 50 digits, or from the
curve's own points sampled next to the end (the direction the curve leaves in); none comes
from the code under test."""

from __future__ import annotations

from fractions import Fraction as F

import mpmath as mp
import numpy as np
import pytest
from conftest import family_file

import lambda_bezier as lb

LOOP = [(0, 0), (3, 3), (-2, 3), (1, 0)]  # symmetric about x = 1/2: C(1 − s) mirrors C(s)


def _classes(points: list[tuple[int, int]]) -> dict[str, object]:
    """One curve of each class on these control points (exact: ints)."""
    return {
        "bezier": lb.BezierCurve(points),
        "same_degree": lb.SameDegreeCurve(points, lam=F(1, 2)),
        "bernstein_like": lb.BernsteinLikeCurve(points, F(1, 3)),
        # a user's own polynomial family from its TOML file; mu = −lam: symmetric
        "two_end_toml": lb.load_family(family_file("two_end_bezier")).curve(
            points, lam=F(1, 2), mu=F(-1, 2)
        ),
        "rational": lb.RationalBezierCurve(points, [1, 2, 2, 1]),
        "rational_float": lb.RationalBezierCurve(
            [(float(x), float(y)) for x, y in points], [1.0, 2.0, 2.0, 1.0]
        ),
        "han_trig": lb.load_family(family_file("han_trig_cubic")).curve(
            points, lam=F(1, 2), mu=F(1, 2)
        ),
        "c_bezier": lb.load_family(family_file("c_bezier_cubic")).curve(points, alpha=1.0),
    }


LOOP_CURVES = _classes(LOOP)
POLYNOMIAL = {"bezier", "same_degree", "bernstein_like", "two_end_toml"}


# ------------------------------------------------------------- locate at a self-crossing
@pytest.mark.parametrize("name", sorted(LOOP_CURVES))
def test_locate_at_a_self_crossing_refuses_on_every_class(name):
    """Every class is symmetric under x -> 1 − x with the parameter reversed (the control
    points mirror and every family's basis is symmetric at these parameters), so the loop
    crosses itself on x = 1/2 at s* and lo + hi − s*, s* the root of x(s) = 1/2 below the
    middle, found by bisection on the sign of x − 1/2 from the curve's evaluation (not from
    locate or self_intersections). locate refuses the point there, naming both parameters;
    the rational, trigonometric and C-Bézier classes returned one of them."""
    curve = LOOP_CURVES[name]
    lo, hi = (float(v) for v in curve.domain)
    a, b = lo, lo + 0.25 * (hi - lo)  # x − 1/2 < 0 at lo, > 0 just past the loop's start
    assert float(curve.evaluate(a)[0]) < 0.5 < float(curve.evaluate(b)[0])
    while b - a > 4e-16 * (hi - lo):
        m = (a + b) / 2
        a, b = (m, b) if float(curve.evaluate(m)[0]) < 0.5 else (a, m)
    s_star = (a + b) / 2
    point = curve.evaluate(s_star)
    with pytest.raises(ValueError, match="several parameters") as err:
        curve.locate(point)
    got = [float(x) for x in str(err.value).split("[")[1].rstrip("]").split(",")]
    assert len(got) == 2
    assert abs(got[0] - s_star) <= 1e-9 * (hi - lo)
    assert abs(got[1] - (lo + hi - s_star)) <= 1e-9 * (hi - lo)
    # a point met once is located, on every class alike
    one = lo + 0.3 * (hi - lo)
    assert abs(curve.locate(curve.evaluate(one)) - one) <= 1e-12 * (hi - lo)


def test_locate_at_the_exact_self_crossing_of_the_polynomial_loop():
    """The Bézier loop crosses itself at (1/2, 9/16), s = (2 ∓ √3)/4, exactly: the rational
    curve with all weights 1 is the same curve and refuses the same point the same way."""
    mp.mp.dps = 50
    want = [float((2 - mp.sqrt(3)) / 4), float((2 + mp.sqrt(3)) / 4)]
    for curve in (lb.BezierCurve(LOOP), lb.RationalBezierCurve(LOOP, [1, 1, 1, 1])):
        with pytest.raises(ValueError, match="several parameters") as err:
            curve.locate((F(1, 2), F(9, 16)))
        got = [float(x) for x in str(err.value).split("[")[1].rstrip("]").split(",")]
        assert np.allclose(got, want, rtol=0, atol=1e-15), got


# --------------------------------------------------- meeting where a curve stops at its end
STOPS = [(0, 0), (0, 0), (1, 0), (1, 1)]  # the first control point repeated: zero speed at 0
LINES = {
    "vertical": [(0, -1), (0, 1)],
    "diagonal": [(-1, 1), (1, -1)],
    "horizontal": [(-1, 0), (1, 0)],
}


def _leaving_direction(curve: object) -> np.ndarray:
    """The direction the curve leaves its start in, from its own points 1e-6 of the domain
    in (p(ε) − p(0) over its norm; the one-sided tangent to within about ε)."""
    lo, hi = (float(v) for v in curve.domain)
    step = np.asarray(curve.evaluate(lo + 1e-6 * (hi - lo)), float) - np.asarray(
        curve.evaluate(lo), float
    )
    return step / np.linalg.norm(step)


@pytest.mark.parametrize("line", sorted(LINES))
@pytest.mark.parametrize("name", sorted(_classes(STOPS)))
def test_a_meeting_where_a_curve_stops_has_the_kind_of_its_one_sided_tangent(name, line):
    """The curve starts at the origin with zero speed; each line passes through the origin at
    its t = 1/2. The meeting is at s = lo exactly (the end point is on the line, exactly),
    "tangent" when the direction the curve leaves in is along the line (sine below 1e-3:
    the Bézier cubic leaves along (1, 0), the same-degree one along (1, 1/6)), "transversal"
    otherwise: on every class (the polynomial ones also the other way round and through
    intersect_many, on their own path)."""
    curve = _classes(STOPS)[name]
    other = lb.BezierCurve(LINES[line])
    lo = float(curve.domain[0])
    u = _leaving_direction(curve)
    v = np.subtract(*LINES[line][::-1], dtype=float)
    sine = abs(u[0] * v[1] - u[1] * v[0]) / np.linalg.norm(v)
    assert sine < 1e-3 or sine > 0.1  # a clear case either way
    kind = "tangent" if sine < 1e-3 else "transversal"
    got = curve.intersect(other)
    # t to 2e-16: the trigonometric and C-Bézier curves evaluate their start to 2e-16
    assert [(h.s, h.kind) for h in got] == [(lo, kind)], got
    assert abs(got[0].t - 0.5) <= 2e-16
    if name in POLYNOMIAL:  # the others answer both of these through the same intersect
        assert [(h.s, h.t, h.kind) for h in other.intersect(curve)] == [(got[0].t, lo, kind)]
        assert lb.intersect_many([curve], [other]) == [got]


OTHERS = [  # curves starting at the origin too, two of them with zero speed there as well
    [(0, 0), (0, 1), (1, 1)],
    [(0, 0), (2, 0), (2, -1)],
    [(0, 0), (0, 0), (0, 1), (-1, 1)],
    [(0, 0), (0, 0), (-1, 0), (-1, 1)],
]


@pytest.mark.parametrize("rows", OTHERS)
@pytest.mark.parametrize("name", ["bezier", "same_degree", "rational", "rational_float"])
def test_two_curves_leaving_one_point_meet_as_their_one_sided_tangents_say(name, rows):
    """Both curves start at the origin; the meeting there is "tangent" exactly when the
    directions they leave in (sampled, as above) lie on one line (also opposite ways). The
    trigonometric and C-Bézier classes answer the same, but take 2-10 s a pair where the
    curves touch (their search halves the contact), too slow for this file."""
    curve = _classes(STOPS)[name]
    other = lb.BezierCurve(rows)
    u, v = _leaving_direction(curve), _leaving_direction(other)
    sine = abs(u[0] * v[1] - u[1] * v[0])
    assert sine < 1e-3 or sine > 0.1
    got = [h for h in curve.intersect(other) if h.t == 0.0]
    assert [(h.s, h.kind) for h in got] == [
        (float(curve.domain[0]), "tangent" if sine < 1e-3 else "transversal")
    ]


@pytest.mark.parametrize(
    ("line", "kind"),
    [
        ([(F(1, 2), 0), (F(1, 2), 1)], "tangent"),  # along the cusp's tangent (its cone)
        ([(0, F(3, 4)), (1, F(3, 4))], "transversal"),  # across it, at the tip
    ],
)
@pytest.mark.parametrize("exact", [True, False])
def test_a_meeting_at_a_cusp_has_the_kind_of_the_cusp_tangent(line, kind, exact):
    """(0,0), (1,1), (0,1), (1,0) stops at s = 1/2, at (1/2, 3/4): x' = 3 (1 − 2s)² and
    y' = 3 (1 − 2s) vanish there, and p(1/2 + h) − p(1/2) = (4h³, −3h²): the cusp's tangent
    is vertical. The vertical line through it is tangent, the horizontal one transversal
    (the same rule as at an end: the first derivative that does not vanish)."""
    rows = [(0, 0), (1, 1), (0, 1), (1, 0)]
    curve = lb.BezierCurve(rows if exact else [(float(x), float(y)) for x, y in rows])
    got = curve.intersect(lb.BezierCurve(line))
    assert [(h.s, h.kind) for h in got] == [(0.5, kind)]


# --------------------------------------------------------------- a curve that is one point
@pytest.mark.parametrize(
    "point",
    [
        lb.RationalBezierCurve([(1, 2)], [3]),
        lb.RationalBezierCurve([(1, 2), (1, 2), (1, 2)], [1, 5, 2]),
        lb.RationalBezierCurve([(1.0, 2.0), (1.0, 2.0)], [1.0, 7.0]),
        lb.BezierCurve([(1, 2), (1, 2), (1, 2)]),
    ],
)
def test_a_curve_that_is_one_point_is_refused_alike_on_every_class(point):
    """A rational curve whose control points are one point is that point whatever its
    weights: it met the line through it at s = 0.5 (any s is as good), and an exact quadratic
    one refused self_intersections as a cusp. As the polynomial classes: intersect and
    locate refuse it by name (every s gives the point), self_intersections is []."""
    line = lb.BezierCurve([(0, 0), (2, 4)])
    with pytest.raises(ValueError, match="first curve is a single point"):
        point.intersect(line)
    with pytest.raises(ValueError, match="second curve is a single point"):  # named in order
        line.intersect(point)
    with pytest.raises(ValueError, match="single point"):
        lb.intersect_many([point], [line])
    with pytest.raises(ValueError, match="single point: every t gives it"):
        point.locate((1, 2))
    assert point.self_intersections() == []
    assert line.locate((1, 2)) == 0.5


@pytest.mark.parametrize(
    ("line", "kind"),
    [([(0, 0, -1), (0, 0, 1)], "transversal"), ([(-1, 0, 0), (1, 0, 0)], "tangent")],
)
@pytest.mark.parametrize("rational", [False, True])
def test_a_space_curve_stopping_on_a_line_meets_it_as_its_one_sided_tangent_says(
    line, kind, rational
):
    """(0,0,0), (0,0,0), (1,0,0), (1,1,1) leaves the origin along (1, 0, 0) (p(h) − p(0) =
    (3h² − 2h³, h³, h³)): it touches the x-axis there and crosses the z-axis (was "tangent"
    on both)."""
    rows = [(0, 0, 0), (0, 0, 0), (1, 0, 0), (1, 1, 1)]
    curve = lb.RationalBezierCurve(rows, [1, 2, 2, 1]) if rational else lb.BezierCurve(rows)
    assert [tuple(h) for h in curve.intersect(lb.BezierCurve(line))] == [(0.0, 0.5, kind)]
