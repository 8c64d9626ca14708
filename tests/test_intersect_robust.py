"""Intersection shapes that defeat plain subdivision + Newton (issue #29), each with its exact
answer: crossings closer together than the subdivision's pieces, tangencies built by
reflecting a curve in its own tangent line, and a curve against a non-affine
reparameterisation of itself. Hypothesis generates more of each shape, exactly (Fractions),
so the expected answers are known in closed form."""

from __future__ import annotations

import math
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
import sympy
from conftest import assert_same_isolated, on_both_subdivision_paths
from exact_curves import exact_point, point_and_tangent, reflect_line
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier.hazmat import intersect as _intersect

# every test here runs on both subdivision paths (numpy and numba; conftest.py)
pytestmark = pytest.mark.usefixtures("intersect_engine")

F = Fraction


# ---------------------------------------------------------------------------- exact helpers
def power_to_bernstein(coeffs: list[Fraction]) -> list[Fraction]:
    """Σ a_k t^k (k <= n) in the Bernstein basis of degree n = len - 1."""
    n = len(coeffs) - 1
    return [
        sum((F(math.comb(i, k), math.comb(n, k)) * coeffs[k] for k in range(i + 1)), F(0))
        for i in range(n + 1)
    ]


def bernstein_to_power(coeffs: list[Fraction]) -> list[Fraction]:
    n = len(coeffs) - 1
    out = [F(0)] * (n + 1)
    for i, b in enumerate(coeffs):
        for j in range(n - i + 1):
            out[i + j] += b * math.comb(n, i) * math.comb(n - i, j) * (-1) ** j
    return out


def compose(coeffs: list[Fraction], inner: list[Fraction]) -> list[Fraction]:
    """p(inner(t)) for power coefficients (Horner on polynomials)."""
    result = [F(0)]
    for c in reversed(coeffs):
        grown = [F(0)] * (len(result) + len(inner) - 1)
        for i, r in enumerate(result):
            for j, s in enumerate(inner):
                grown[i + j] += r * s
        grown[0] += c
        result = grown
    while len(result) > 1 and result[-1] == 0:
        result.pop()
    return result


def curve_from_power(xs: list[Fraction], ys: list[Fraction]) -> lb.BezierCurve:
    n = max(len(xs), len(ys)) - 1
    xs = xs + [F(0)] * (n + 1 - len(xs))
    ys = ys + [F(0)] * (n + 1 - len(ys))
    return lb.BezierCurve(list(zip(power_to_bernstein(xs), power_to_bernstein(ys), strict=True)))


def assert_on_both(a: lb.Curve, b: lb.Curve, hits) -> None:
    """Every reported pair is a root: exact evaluation of the Bézier forms at the floats."""
    ra, rb = a.to_bezier().control_points(), b.to_bezier().control_points()
    for h in hits:
        x, y = exact_point(ra, F(h.s)), exact_point(rb, F(h.t))
        assert max(abs(float(u - v)) for u, v in zip(x, y, strict=True)) < 1e-12, h


ROTATIONS = [(F(1), F(0)), (F(3, 5), F(4, 5)), (F(-5, 13), F(12, 13)), (F(8, 17), F(-15, 17))]


def rotate(curve: lb.BezierCurve, rotation: tuple[Fraction, Fraction]) -> lb.BezierCurve:
    c, s = rotation
    return lb.BezierCurve([(c * x - s * y, s * x + c * y) for x, y in curve.control_points()])


# ------------------------------------------------------------------------ near-double crossings
def parabola_and_line(vertex: Fraction, gap: Fraction, k: Fraction = Fraction(1)):
    """y = k (x - vertex)^2 over x = 2s - 1, and the line y = k gap^2 over x = 2t - 1: they
    cross at x = vertex ± gap, i.e. s = t = (1 + vertex ± gap) / 2."""
    x = [F(-1), F(2)]
    y = compose([k * vertex**2, -2 * k * vertex, k], x)
    parabola = curve_from_power(x + [F(0)], y)
    height = k * gap**2
    line = lb.BezierCurve([(-1, height), (1, height)])
    roots = sorted(r for r in ((1 + vertex - gap) / 2, (1 + vertex + gap) / 2) if 0 <= r <= 1)
    return parabola, line, roots


def test_parabola_and_line_closer_than_the_pieces():
    """The issue's case: crossings 1e-3 apart at s = 0.5495 and 0.5505."""
    parabola = lb.BezierCurve([(-1, F(121, 100)), (0, F(-99, 100)), (1, F(81, 100))])
    line = lb.BezierCurve([(-1, F(1, 10**6)), (1, F(1, 10**6))])
    hits = parabola.intersect(line)
    assert [(h.s, h.t, h.kind) for h in hits] == [
        (0.5495, 0.5495, "transversal"),
        (0.5505, 0.5505, "transversal"),
    ]
    # the line at the float 1e-6 (its nearest double, still exact), as the issue has it
    float_line = lb.BezierCurve([(-1, F(1e-6)), (1, F(1e-6))])
    got = parabola.intersect(float_line)
    assert [h.s for h in got] == pytest.approx([0.5495, 0.5505], abs=1e-15)
    # and the same curves in floats
    float_hits = lb.BezierCurve([(-1, 1.21), (0, -0.99), (1, 0.81)]).intersect(
        lb.BezierCurve([(-1, 1e-6), (1, 1e-6)])
    )
    assert [h.s for h in float_hits] == pytest.approx([0.5495, 0.5505], abs=1e-12)


@settings(max_examples=40, deadline=None)
@given(
    vertex=st.fractions(F(-4, 5), F(4, 5), max_denominator=1000),
    gap_exponent=st.integers(2, 6),
    gap_digit=st.integers(1, 9),
    rotation=st.sampled_from(ROTATIONS),
    k=st.sampled_from([F(1), F(7, 2), F(1, 3)]),
)
@example(vertex=F(1, 5), gap_exponent=6, gap_digit=1, rotation=ROTATIONS[0], k=F(1, 3))
def test_near_double_crossings(vertex, gap_exponent, gap_digit, rotation, k):
    gap = F(gap_digit, 10**gap_exponent)
    parabola, line, roots = parabola_and_line(vertex, gap, k)
    a, b = rotate(parabola, rotation), rotate(line, rotation)
    hits = a.intersect(b)
    assert [h.kind for h in hits] == ["transversal"] * len(roots), (hits, roots)
    for h, r in zip(hits, roots, strict=True):
        assert h.s == pytest.approx(float(r), abs=1e-14) and h.t == pytest.approx(
            float(r), abs=1e-14
        )
    assert_on_both(a, b, hits)


def chebyshev_curve(n: int) -> lb.BezierCurve:
    """(t, T_n(2t - 1)) as an exact Bézier curve of degree n."""
    t0, t1 = [F(1)], [F(0), F(1)]
    for _ in range(n - 1):
        t2 = [F(0)] + [2 * c for c in t1]
        for i, c in enumerate(t0):
            t2[i] -= c
        t0, t1 = t1, t2
    return curve_from_power([F(0), F(1)], compose(t1, [F(-1), F(2)]))


@pytest.mark.parametrize("depth", [F(1, 10**4), F(1, 10**7)])
def test_chebyshev_against_a_line_under_its_peaks(depth):
    """T_12 reaches 1 seven times on [-1, 1] (five interior peaks and both ends): the line
    y = 1 - depth crosses it twice at each interior peak and once near each end, at
    x = cos((2 pi k ± acos(1 - depth)) / 12)."""
    n = 12
    curve = chebyshev_curve(n)
    line = lb.BezierCurve([(0, 1 - depth), (1, 1 - depth)])
    theta = math.acos(1 - float(depth))
    want = sorted(
        (math.cos(a) + 1) / 2
        for k in range(n // 2 + 1)
        for a in ((2 * math.pi * k - theta) / n, (2 * math.pi * k + theta) / n)
        if 0 <= a <= math.pi
    )
    assert len(want) == 12
    hits = curve.intersect(line)
    assert len(hits) == 12
    # the roots are ill-conditioned in t only through theta (sqrt(depth)): 1e-13 is ample
    np.testing.assert_allclose([h.s for h in hits], want, rtol=0, atol=1e-13)
    np.testing.assert_allclose([h.t for h in hits], [h.s for h in hits], rtol=0, atol=1e-15)
    assert {h.kind for h in hits} == {"transversal"}


def folded_curve(r1: Fraction, r2: Fraction) -> lb.BezierCurve:
    """x = w^2, y = w (w^2 - r1^2)(w^2 - r2^2) for w = 2t - 1: symmetric about the x axis,
    it crosses itself on the axis at w = ±r1 and w = ±r2, i.e. at (s, t) = ((1 - r)/2,
    (1 + r)/2)."""
    a, b = r1 * r1, r2 * r2
    w = [F(-1), F(2)]
    x = compose([F(0), F(0), F(1)], w)
    y = compose([F(0), a * b, F(0), -(a + b), F(0), F(1)], w)
    return curve_from_power(x, y)


def test_self_crossings_0005_apart():
    curve = folded_curve(F(1, 2), F(51, 100))
    hits = curve.self_intersections()
    assert [(h.s, h.t, h.kind) for h in hits] == [
        (0.245, 0.755, "transversal"),
        (0.25, 0.75, "transversal"),
    ]


@settings(max_examples=30, deadline=None)
@given(
    r1=st.fractions(F(1, 10), F(9, 10), max_denominator=1000),
    gap=st.sampled_from([F(1, 100), F(1, 200), F(1, 1000), F(1, 10**4)]),
    rotation=st.sampled_from(ROTATIONS),
)
def test_close_self_crossings(r1, gap, rotation):
    r2 = r1 + gap
    curve = rotate(folded_curve(r1, r2), rotation)
    hits = curve.self_intersections()
    want = sorted(((1 - r) / 2, (1 + r) / 2) for r in (r1, r2))
    assert len(hits) == 2, hits
    for h, (s, t) in zip(hits, want, strict=True):
        assert h.s == pytest.approx(float(s), abs=1e-14) and h.t == pytest.approx(
            float(t), abs=1e-14
        )
        assert h.kind == "transversal"


# ------------------------------------------------------------------------ reflected tangencies
def reflect_in_tangent(rows, t0: Fraction):
    """The control points reflected in the tangent line of the curve (rows, a Bézier form)
    at t0: the reflected curve touches the original at t0 (same point, same tangent line)."""
    point, d = point_and_tangent(rows, [Fraction(1)] * len(rows), t0)
    dd = sum(x * x for x in d)
    return point, d, dd, reflect_line(point, d)


def diagonal_roots(rows, point, d) -> list[sympy.Rational]:
    """The t in [0, 1] with curve(t) on the tangent line (the diagonal hits s = t), exactly."""
    t = sympy.symbols("t")
    n = len(rows) - 1
    cx, cy = (
        sum(
            math.comb(n, i) * t**i * (1 - t) ** (n - i) * sympy.Rational(r[k])
            for i, r in enumerate(rows)
        )
        for k in (0, 1)
    )
    cross = sympy.Poly(
        sympy.expand(
            (cx - sympy.Rational(point[0])) * sympy.Rational(d[1])
            - (cy - sympy.Rational(point[1])) * sympy.Rational(d[0])
        ),
        t,
    )
    return [r for r in sympy.Poly(cross, t).real_roots() if 0 <= r <= 1]


small_ints = st.integers(-9, 9)


@settings(max_examples=40, deadline=None)
@given(
    points=st.integers(2, 5).flatmap(
        lambda n: st.lists(st.tuples(small_ints, small_ints), min_size=n + 1, max_size=n + 1)
    ),
    t0=st.fractions(F(1, 20), F(19, 20), max_denominator=40),
)
def test_reflected_tangency(points, t0):
    """A curve against its reflection in its own tangent line at t0: the tangency (t0, t0)
    is reported once, as tangent, and every point of the curve on that line is a hit."""
    curve = lb.BezierCurve(points)
    rows = curve.control_points()
    point, d, dd, reflect = reflect_in_tangent(rows, t0)
    assume(dd != 0)
    mirror = lb.BezierCurve([reflect(v) for v in rows])
    assume(mirror.control_points() != rows)  # a curve symmetric about the line: coincident
    try:
        hits = curve.intersect(mirror)
    except ValueError as exc:  # both on one line (the curve is that line)
        assert "one line" in str(exc)
        return
    assume(not any(h.kind == "coincident" for h in hits))
    assert_on_both(curve, mirror, hits)
    near = [h for h in hits if abs(h.s - float(t0)) < 1e-6 and abs(h.t - float(t0)) < 1e-6]
    assert len(near) == 1, hits
    assert near[0].kind == "tangent"
    assert near[0].s == pytest.approx(float(t0), abs=1e-7)  # a double root: sqrt(eps) at worst
    for r in diagonal_roots(rows, point, d):
        assert any(abs(h.s - float(r)) < 1e-7 and abs(h.t - float(r)) < 1e-7 for h in hits), (
            r,
            hits,
        )


@settings(max_examples=25, deadline=None)
@given(
    points=st.lists(st.tuples(small_ints, small_ints), min_size=5, max_size=5),
    lam=st.sampled_from([F(-1, 2), F(1, 3), F(-3, 2)]),
    t0=st.fractions(F(1, 10), F(9, 10), max_denominator=20),
)
def test_reflected_tangency_lambda_curves(points, lam, t0):
    """The same on a λ curve: the reflection is affine, so it acts on the control points."""
    curve = lb.SameDegreeCurve(points, lam)
    rows = curve.to_bezier().control_points()
    point, d, dd, reflect = reflect_in_tangent(rows, t0)
    assume(dd != 0)
    mirror = lb.SameDegreeCurve([reflect(v) for v in curve.control_points()], lam)
    assume(mirror.control_points() != curve.control_points())
    try:
        hits = curve.intersect(mirror)
    except ValueError as exc:
        assert "one line" in str(exc)
        return
    assume(not any(h.kind == "coincident" for h in hits))
    assert_on_both(curve, mirror, hits)
    near = [h for h in hits if abs(h.s - float(t0)) < 1e-6 and abs(h.t - float(t0)) < 1e-6]
    assert len(near) == 1 and near[0].kind == "tangent", hits
    for r in diagonal_roots(rows, point, d):
        assert any(abs(h.s - float(r)) < 1e-7 and abs(h.t - float(r)) < 1e-7 for h in hits), (
            r,
            hits,
        )


def test_tangency_at_the_corner_of_narrow_pieces_is_not_isolated():
    """Hypothesis's case (numpy engine): the tangency at t0 = 9/16, a dyadic, lies at the
    corner of a pair of pieces 2^-20 wide, whose hodograph cones touch along the tangent
    line. Rounding of the pieces' control points turns their directions by ~1e-8 there, so
    without the cones widened by that blur they looked apart and the pair was "isolated":
    the tangency came back as a transversal crossing."""
    lam, t0 = F(1, 3), F(9, 16)
    curve = lb.SameDegreeCurve([(-5, 7), (1, -4), (-8, -1), (1, 4), (-2, -9)], lam)
    rows = curve.to_bezier().control_points()
    point, d, _, reflect = reflect_in_tangent(rows, t0)
    mirror = lb.SameDegreeCurve([reflect(v) for v in curve.control_points()], lam)
    hits = curve.intersect(mirror)
    assert_on_both(curve, mirror, hits)
    roots = sorted(set(diagonal_roots(rows, point, d)))  # 9/16 (double) and one crossing
    assert [float(r) for r in roots][0] == 0.5625 and len(roots) == 2
    assert [h.kind for h in hits] == ["tangent", "transversal"]
    assert hits[0].s == hits[0].t == 0.5625
    assert hits[1].s == pytest.approx(float(roots[1]), abs=1e-15)
    assert hits[1].t == pytest.approx(float(roots[1]), abs=1e-15)


def test_newton_thrown_out_of_the_domain_still_finds_the_tangency():
    """A start near the tangency of a cubic and its reflection from which float Newton leaves
    the domain (the Jacobian is nearly singular there): the tangent refinement takes over."""
    curve = lb.BezierCurve([(0, 0), (1, 3), (3, -1), (4, 2)])
    rows = curve.control_points()
    _, d, _, reflect = reflect_in_tangent(rows, F(2, 5))
    mirror = lb.BezierCurve([reflect(v) for v in rows])
    p, q = curve._prepared, mirror._prepared
    start = (0.4 - 0.0275, 0.4 + 0.0425)
    assert _intersect._newton(p, q, *start)[2] == "out"  # the case this test is about
    hit = _intersect._solve_from(p, q, *start, [])
    assert hit is not None and hit.kind == "tangent"
    assert hit.s == pytest.approx(0.4, abs=1e-9) and hit.t == pytest.approx(0.4, abs=1e-9)
    assert [(h.kind, round(h.s, 9)) for h in curve.intersect(mirror)] == [
        ("tangent", 0.4),
        ("transversal", 0.7),
    ]


# ------------------------------------------------------------------------ reparameterised copies
def reparameterised(curve: lb.BezierCurve, inner: list[Fraction]) -> lb.BezierCurve:
    """curve(inner(s)) exactly, inner a polynomial (power coefficients)."""
    rows = curve.control_points()
    columns = [bernstein_to_power([r[k] for r in rows]) for k in range(len(rows[0]))]
    composed = [compose(c, inner) for c in columns]
    degree = max(len(c) for c in composed) - 1
    padded = [power_to_bernstein(c + [F(0)] * (degree + 1 - len(c))) for c in composed]
    return lb.BezierCurve(list(zip(*padded, strict=True)))


def test_reparameterised_copy_is_coincident():
    """P(s) = Q(s^2): the same image under a non-affine parameter change."""
    q = lb.BezierCurve([(0, 0), (1, 3), (3, 2), (4, 0)])
    p = reparameterised(q, [F(0), F(0), F(1)])
    assert p.degree == 6
    want = [(0.0, 0.0, "coincident"), (1.0, 1.0, "coincident")]
    assert [(h.s, h.t, h.kind) for h in p.intersect(q)] == want
    assert [(h.s, h.t, h.kind) for h in q.intersect(p)] == want
    # the straight-line version, which used to be refused
    segment = lb.BezierCurve([(0, 0), (1, 2)])
    assert [
        (h.s, h.t, h.kind) for h in lb.BezierCurve([(0, 0), (0, 0), (1, 2)]).intersect(segment)
    ] == want


def test_stretch_on_a_line_that_folds_back():
    """q runs along the x axis (x(t) = 1 - 3t^2 + 3t^3) from 1 down to its turning point and
    back to 1; p = q(3/5 s^2) covers q's first stretch [0, 3/5], and so also the stretch
    [t*, 1] of q's way back with the same image: x(t*) = x(3/5), t* = (1 + sqrt 7) / 5. Two
    coincident stretches. The stretch [0, t*] of q, which reaches past the turning point, is
    not one (it used to be reported, with a spurious tangent at (0, 0))."""
    q = lb.BezierCurve([(1, 0), (1, 0), (0, 0), (1, 0)])
    p = reparameterised(q, [F(0), F(0), F(3, 5)])
    t_star = (1 + math.sqrt(7)) / 5
    got = p.intersect(q)
    assert [h.kind for h in got] == ["coincident"] * 4, got
    assert [(h.s, h.t) for h in got] == [
        (0.0, 0.0),
        (0.0, 1.0),
        (1.0, pytest.approx(0.6, abs=1e-15)),
        (1.0, pytest.approx(t_star, abs=1e-15)),
    ]


def test_locate_on_a_piece_that_curves_round():
    """p = q(4/5 (2s - s^2)); the point q(t), t = 54/95, is p(s) at s = 1 - sqrt(1 - 5t/4).
    The subdivision used to take a one-to-one piece's foot point (a local minimum of the
    distance at s = 0.1456, half a unit away) for the point, and lose it; with it the
    stretch [0, 4/5] of q was not recognised as p's image (seven "tangent" points)."""
    q = lb.BezierCurve([(0, 0), (3, 6), (0, 2), (4, -2)])
    p = reparameterised(q, [F(0), F(8, 5), F(-4, 5)])
    t = F(54, 95)
    point = [float(v) for v in q.evaluate(float(t))]
    assert p.locate(point) == pytest.approx(1 - math.sqrt(1 - 5 * float(t) / 4), abs=1e-12)
    hits = [(h.s, h.t, h.kind) for h in p.intersect(q)]
    assert hits == [(0.0, 0.0, "coincident"), (1.0, pytest.approx(0.8, abs=1e-15), "coincident")]


@settings(max_examples=25, deadline=None)
@given(
    points=st.lists(st.tuples(small_ints, small_ints), min_size=4, max_size=4),
    a=st.fractions(F(0), F(2, 5), max_denominator=10),
    b=st.fractions(F(3, 5), F(1), max_denominator=10),
    shape=st.sampled_from(["square", "sqrt-like"]),
)
def test_reparameterised_stretch_is_coincident(points, a, b, shape):
    """p(s) = q(phi(s)) with phi a monotone quadratic from [0, 1] onto [a, b]: the stretch
    is reported by its two ends, coincident, and nothing inside it is reported."""
    q = lb.BezierCurve(points)
    inner = [a, F(0), b - a] if shape == "square" else [a, 2 * (b - a), -(b - a)]
    p = reparameterised(q, inner)
    try:
        hits = p.intersect(q)
    except ValueError as exc:  # a curve on a line that folds back: refused, and only then
        assert "one line" in str(exc) or "single point" in str(exc)
        return
    ends = [(h.s, h.t) for h in hits if h.kind == "coincident"]
    assert (0.0, pytest.approx(float(a), abs=1e-15)) in ends and (
        1.0,
        pytest.approx(float(b), abs=1e-15),
    ) in ends, hits
    inside = [
        h for h in hits if 0 < h.s < 1 and float(a) < h.t < float(b) and h.kind != "coincident"
    ]
    for h in inside:  # only a genuine self-crossing of q can add a point inside
        assert (
            abs(h.t - float(a + (b - a) * F(h.s) ** 2 if shape == "square" else 0)) > 1e-6
            or shape != "square"
        )


# ---------------------------------------------------------------------------- the merge tolerance
def test_merge_tolerance_is_documented_and_applied():
    """Hits closer than MERGE_RADIUS in both parameters are one only when the curves stay
    within MERGE_GAP (64 eps per degree, relative) of each other between them (a contact of
    high order), as docs/guide/geometry.md says; two transversal crossings 1e-5 apart, whose
    curves separate by 1e-10 between them, stay two."""
    assert _intersect.MERGE_RADIUS == 1e-3
    assert 64 * np.finfo(float).eps == _intersect.MERGE_GAP
    guide = (Path(__file__).parents[1] / "docs" / "guide" / "geometry.md").read_text()
    assert "merged into one only when the curves stay within 64 ε per degree" in guide
    parabola, line, roots = parabola_and_line(F(0), F(1, 10**5))
    got = [h.s for h in parabola.intersect(line)]
    assert got == pytest.approx([float(r) for r in roots], abs=1e-15)


# ---------------------------------------------------------------------------- intersect_many
@settings(max_examples=10, deadline=None)
@given(
    a=st.lists(
        st.integers(1, 4).flatmap(
            lambda n: st.lists(st.tuples(small_ints, small_ints), min_size=n + 1, max_size=n + 1)
        ),
        min_size=1,
        max_size=4,
    ),
    b=st.lists(
        st.integers(1, 4).flatmap(
            lambda n: st.lists(st.tuples(small_ints, small_ints), min_size=n + 1, max_size=n + 1)
        ),
        min_size=1,
        max_size=4,
    ),
)
def test_intersect_many_is_intersect_pair_by_pair(a, b):
    """Batched subdivision (pairs of equal degrees share arrays) gives what each pair gives
    alone, in both modes; a pair the single form refuses makes the batch raise the same."""
    curves_a = [lb.BezierCurve(p) for p in a]
    curves_b = [lb.BezierCurve(p) for p in b]

    def single(p, q):
        try:
            return p.intersect(q)
        except ValueError as exc:
            return str(exc)

    want = [[single(p, q) for q in curves_b] for p in curves_a]
    refused = [w for row in want for w in row if isinstance(w, str)]
    if refused:
        with pytest.raises(ValueError):
            lb.intersect_many(curves_a, curves_b, mode="all")
        return
    assert lb.intersect_many(curves_a, curves_b, mode="all") == want
    k = min(len(curves_a), len(curves_b))
    assert lb.intersect_many(curves_a[:k], curves_b[:k]) == [want[i][i] for i in range(k)]


def test_intersect_many_bad_input():
    c = lb.BezierCurve([(0, 0), (1, 1)])
    with pytest.raises(TypeError, match="curves_a must be a sequence of curves"):
        lb.intersect_many(c, [c])
    with pytest.raises(TypeError, match=r"curves_b\[1\] must be a curve"):
        lb.intersect_many([c, c], [c, (0, 0)])
    with pytest.raises(ValueError, match="equal length"):
        lb.intersect_many([c, c], [c])
    with pytest.raises(ValueError, match="mode must be"):
        lb.intersect_many([c], [c], mode="some")
    assert lb.intersect_many([], []) == []


# ---------------------------------------------------------------------------- the two paths
def test_compiled_subdivision_matches_numpy():
    """intersect_subdivide's numpy loop and its numba-compiled twin give the same isolated
    roots (to rounding: sums run in another order) and the same unresolved pieces, for
    pairs of curves, a curve against itself, and curves against points."""
    from lambda_bezier.hazmat import intersect_subdivide as sub

    if not sub.importlib.util.find_spec("numba"):
        pytest.skip("numba is not installed (pip install '.[fast]'): nothing to compare")
    rng = np.random.default_rng(29)

    compared = 0
    for n, m, d in [(2, 3, 2), (3, 3, 2), (5, 4, 2), (3, 2, 3), (7, 7, 2)]:
        a = rng.normal(size=(40, n + 1, d))
        b = rng.normal(size=(40, m + 1, d))
        slack = np.full(40, 1e-13)
        calls = [lambda a=a, b=b, s=slack: sub.isolate(a, b, s)]
        if n == m:
            calls.append(lambda a=a, s=slack: sub.isolate(a, None, s))
        calls.append(lambda a=a, b=b, s=slack: sub.isolate_points(a, b[:, 0], s))
        for call in calls:
            slow, fast = on_both_subdivision_paths(call)
            assert_same_isolated(slow, fast)
            compared += slow.root_pair.size
    assert compared > 100  # the random pairs do cross
