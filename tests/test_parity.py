"""Parity with the `bezier` package, checked on its own fixture files (tests/data/bezier/,
see NOTE.md there), and the same algorithms for the λ families, checked by conversion and by
independent numerics."""

from __future__ import annotations

import json
import math
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from exact_curves import exact_point
from hypothesis import given, settings
from hypothesis import strategies as st

import lambda_bezier as lb

# every test here runs on both subdivision paths (numpy and numba; conftest.py)
pytestmark = pytest.mark.usefixtures("intersect_engine")

DATA = Path(__file__).parent / "data" / "bezier"
CURVES = json.loads((DATA / "curves.json").read_text())
CASES = json.loads((DATA / "curve_intersections.json").read_text())
# Parameters given as fractions ("2/3") are exact: a transversal intersection must give
# their nearest float. At a tangency the last bit depends on the rounding of the Newton step
# so there a few ulps; with equal curvature too (cases 42 and 45: a triple root, where the
# float Jacobian loses rank) only the 1e-12 of every case.
TANGENT_ULPS = 32
TRIPLE_CONTACT = {42, 45}


def number(v) -> Fraction:
    """A fixture number: int, "p/q" or a C99 hex float; every one is an exact rational."""
    if isinstance(v, int):
        return Fraction(v)
    if "x" in v:
        return Fraction(float.fromhex(v))
    return Fraction(v)


def control_rows(curve_id: str) -> tuple[tuple[Fraction, ...], ...]:
    """The fixtures store one row per coordinate; our curves take one row per point."""
    cols = CURVES[curve_id]["control_points"]
    return tuple(zip(*[[number(v) for v in row] for row in cols], strict=True))


def elevate_to(rows, degree: int):
    curve = lb.BezierCurve(rows)
    while curve.degree < degree:
        curve = curve.elevate()
    return curve.control_points()


def expected_pairs(case) -> list[tuple[Fraction, Fraction]]:
    s = [number(v) for v in case["curve1_params"]]
    t = [number(v) for v in case["curve2_params"]]
    return sorted(zip(s, t, strict=True))


def check_pairs(got, case) -> None:
    want = expected_pairs(case)
    assert len(got) == len(want), (got, want)
    for hit, (s, t) in zip(sorted(got, key=lambda h: (h.s, h.t)), want, strict=True):
        assert abs(hit.s - float(s)) <= 1e-12 and abs(hit.t - float(t)) <= 1e-12, (hit, s, t)
        for value, raw in ((hit.s, s), (hit.t, t)):
            if raw.denominator >= 2**20:  # a hex float: a rounded irrational
                continue
            if case["id"] in TRIPLE_CONTACT:
                continue
            if hit.kind == "tangent":
                assert abs(value - float(raw)) <= TANGENT_ULPS * np.spacing(float(raw)), hit
            else:
                assert value == float(raw), (hit, raw)


# ---------------------------------------------------------------------------- intersections
def fixture_curve(curve_id: str, case) -> lb.BezierCurve:
    """A fixture curve as the fixture means it: in a "tangent" case, a curve with a hex-float
    control point (a rounded irrational: case 46, "tangent only up to machine precision") is
    float input, answered at the precision of its floats; every other curve is exact. (Exact
    input with a tangency is decided exactly: case 46 taken exactly is two crossings, see
    test_case46_taken_exactly_is_two_crossings.)"""
    return lb.BezierCurve(fixture_rows(curve_id, case))


def fixture_rows(curve_id: str, case):
    """control_rows, as floats where fixture_curve takes the curve as float input."""
    rows = control_rows(curve_id)
    if case["type"] == "tangent" and any(v.denominator >= 2**20 for row in rows for v in row):
        return tuple(tuple(float(v) for v in row) for row in rows)
    return rows


def test_case46_taken_exactly_is_two_crossings():
    """Case 46's curves as the exact rationals of their floats are not tangent: the line
    through #64's rounded control point crosses #63 twice, 1.4e-9 apart in s, near the
    fixture's tangency s = 0.1729. Reference: SymPy's own resultant of x and y of p(s) − q(t)
    and its real roots (CRootOf), to 30 digits."""
    import sympy as sp

    case = next(c for c in CASES if c["id"] == 46)
    rows1, rows2 = control_rows(case["curve1"]), control_rows(case["curve2"])
    hits = lb.BezierCurve(rows1).intersect(lb.BezierCurve(rows2))
    s, t = sp.symbols("s t")

    def bezier(rows, x):
        n = len(rows) - 1
        return [
            sum(
                sp.binomial(n, i) * x**i * (1 - x) ** (n - i) * sp.Rational(r[c])
                for i, r in enumerate(rows)
            )
            for c in range(2)
        ]

    p, q = bezier(rows1, s), bezier(rows2, t)
    res = sp.Poly(sp.resultant(p[0] - q[0], p[1] - q[1], t), s)
    roots = [r for r in res.real_roots() if 0 <= r <= 1]
    near = sorted(float(sp.N(r, 30)) for r in roots if abs(float(sp.N(r, 30)) - 0.1729) < 1e-3)
    assert len(near) == 2 and 0 < near[1] - near[0] < 1e-8
    close = sorted(h for h in hits if abs(h.s - 0.1729) < 1e-3)
    assert [h.kind for h in close] == ["transversal", "transversal"]
    assert all(abs(h.s - r) <= 1e-15 for h, r in zip(close, near, strict=True)), (close, near)
    assert len(hits) == len(case["curve1_params"]) + 1  # the other two fixture crossings stay


@pytest.mark.parametrize("case", CASES, ids=[f"case{c['id']}-{c['type']}" for c in CASES])
def test_curve_intersections(case):
    c1, c2 = fixture_curve(case["curve1"], case), fixture_curve(case["curve2"], case)
    hits = c1.intersect(c2)
    check_pairs(hits, case)
    # the same intersections with the curves swapped
    swapped = c2.intersect(c1)
    np.testing.assert_allclose(
        sorted((h.t, h.s) for h in swapped), sorted((h.s, h.t) for h in hits), rtol=0, atol=1e-14
    )
    kinds = [h.kind for h in hits]
    if case["type"] == "standard":
        assert set(kinds) == {"transversal"}
    elif case["type"] == "tangent":
        assert "tangent" in kinds
    elif case["type"] == "coincident" and case["id"] == 20:
        assert kinds == ["coincident", "coincident"]  # the two ends of the shared stretch
    elif case["type"] == "coincident":
        # the curves continue each other past an end: within [0, 1] they share one point,
        # where they touch tangentially
        assert "tangent" in kinds
    # every reported point is on both curves (independent exact evaluation)
    for h in hits:
        a = exact_point(c1.control_points(), Fraction(h.s))
        b = exact_point(c2.control_points(), Fraction(h.t))
        assert max(abs(float(x - y)) for x, y in zip(a, b, strict=True)) < 1e-12


@pytest.mark.parametrize("case", CASES, ids=[f"case{c['id']}" for c in CASES])
def test_locate_intersection_points(case):
    """The fixture's intersection points, located on each curve, give the parameters."""
    points = list(zip(*[[number(v) for v in row] for row in case["intersections"]], strict=True))
    c1 = lb.BezierCurve(control_rows(case["curve1"]))
    c2 = lb.BezierCurve(control_rows(case["curve2"]))
    for point, s, t in zip(points, case["curve1_params"], case["curve2_params"], strict=True):
        # exact points (Fractions) when the fixture's are; hex floats are rounded values
        assert abs(c1.locate(point) - float(number(s))) <= 1e-9
        assert abs(c2.locate(point) - float(number(t))) <= 1e-9


def test_locate_off_curve_and_ambiguous():
    c = lb.BezierCurve([(0, 0), (4, 2), (-1, 2), (3, 0)])  # a loop crossing itself
    assert c.locate((5, 5)) is None
    assert c.locate(c.evaluate(0.25)) == pytest.approx(0.25, abs=1e-14)
    crossing = c.self_intersections()[0]
    with pytest.raises(ValueError, match="several parameters"):
        c.locate(c.evaluate(crossing.s))
    with pytest.raises(ValueError, match="shape"):
        c.locate((1, 2, 3))


def test_coincident_stretch_is_reported_by_its_ends():
    case = next(c for c in CASES if c["id"] == 20)
    c1 = lb.BezierCurve(control_rows(case["curve1"]))
    c2 = lb.BezierCurve(control_rows(case["curve2"]))
    assert [(h.s, h.t, h.kind) for h in c1.intersect(c2)] == [
        (0.25, 0.0, "coincident"),
        (1.0, 0.75, "coincident"),
    ]


def test_coincident_variants():
    """A curve with itself, reversed, with a piece of itself (in 3-D too), and with a reversed
    piece that runs past its end: each reported by the two ends of the shared stretch."""
    c = lb.BezierCurve([(0, 0), (1, 2), (3, 2), (4, 0)])

    def ends(a, b):
        hits = a.intersect(b)
        assert {h.kind for h in hits} == {"coincident"}
        return [(h.s, h.t) for h in hits]

    assert ends(c, c) == [(0.0, 0.0), (1.0, 1.0)]
    assert ends(c, lb.BezierCurve(c.control_points()[::-1])) == [(0.0, 1.0), (1.0, 0.0)]
    assert ends(c, c.segment(Fraction(1, 4), Fraction(1, 2))) == [(0.25, 0.0), (0.5, 1.0)]
    longer = c.segment(Fraction(1, 5), Fraction(3, 2), extrapolate=True)
    got = ends(c, lb.BezierCurve(longer.control_points()[::-1]))
    assert got[0] == (0.2, 1.0)
    assert got[1] == pytest.approx((1.0, 5 / 13), abs=1e-15)  # s = 1 is t = (3/2 - 1)/(13/10)
    c3 = lb.BezierCurve([(0, 0, 0), (1, 2, 1), (3, 2, -1), (4, 0, 2)])
    assert ends(c3, c3.segment(0.25, 0.5)) == [(0.25, 0.0), (0.5, 1.0)]


def test_to_bezier_keeps_the_parameter():
    """Parameters reported through to_bezier() are the family's own: both evaluate alike."""
    rng = np.random.default_rng(7)
    t = np.linspace(0, 1, 41)
    for curve in (
        lb.SameDegreeCurve(rng.integers(-9, 10, (6, 2)).tolist(), Fraction(-3, 4)),
        lb.BernsteinLikeCurve(rng.integers(-9, 10, (5, 3)).tolist(), Fraction(2, 3)),
    ):
        np.testing.assert_allclose(curve.evaluate(t), curve.to_bezier().evaluate(t), atol=1e-12)


def test_self_intersections_against_sympy():
    """A cubic loop: the parameters of its crossing solved exactly by SymPy."""
    import sympy

    rows = [(0, 0), (4, 2), (-1, 2), (3, 0)]
    s, t = sympy.symbols("s t")

    def point(u):
        return [
            sum(math.comb(3, i) * u**i * (1 - u) ** (3 - i) * r[c] for i, r in enumerate(rows))
            for c in (0, 1)
        ]

    ps, pt = point(s), point(t)
    # divide out the trivial solutions s = t
    eqs = [sympy.cancel((a - b) / (s - t)) for a, b in zip(ps, pt, strict=True)]
    sols = [
        (float(a), float(b))
        for a, b in sympy.solve(eqs, [s, t])
        if a.is_real and b.is_real and 0 <= a < b <= 1
    ]
    got = lb.BezierCurve(rows).self_intersections()
    assert len(got) == len(sols) == 1
    assert got[0].s == pytest.approx(sols[0][0], abs=1e-14)
    assert got[0].t == pytest.approx(sols[0][1], abs=1e-14)
    # on a line: none when it runs one way; when it turns back (x = 4s − 5s², out to 4/5 at
    # s = 2/5 = the root of x′ and back), the stretch s in [0, 2/5] = t in [2/5, 4/5], whose
    # end pairs are SymPy's (tests/test_folded_line.py has more)
    assert lb.BezierCurve([(0, 0), (1, 1), (1, 1), (3, 3)]).self_intersections() == []
    x = 4 * s - 5 * s**2
    (turn,) = sympy.solve(sympy.diff(x, s), s)
    back = max(sympy.solve(x, s))
    folded = lb.BezierCurve([(0, 0), (2, 0), (-1, 0)]).self_intersections()
    assert [(h.s, h.t, h.kind) for h in folded] == [
        (0.0, float(back), "coincident"),
        (float(turn), float(turn), "coincident"),
    ]
    # a cusp is not a self-intersection, a simple arc has none
    assert lb.BezierCurve([(0, 0), (2, 2), (0, 2), (2, 0)]).self_intersections() == []
    assert lb.BezierCurve([(0, 0), (1, 2), (3, 2), (4, 0)]).self_intersections() == []


def integer_curve(degree_range=(1, 4)):
    return st.integers(*degree_range).flatmap(
        lambda n: st.lists(
            st.tuples(st.integers(-6, 6), st.integers(-6, 6)), min_size=n + 1, max_size=n + 1
        )
    )


@settings(max_examples=25)
@given(a=integer_curve(), b=integer_curve())
def test_intersect_properties(a, b):
    """Random exact curves: each pair is a root (exact evaluation), swapping the curves
    swaps the pairs, and every crossing of fine polylines away from the ends and from
    tangencies is among the pairs."""
    p, q = lb.BezierCurve(a), lb.BezierCurve(b)
    try:
        hits = p.intersect(q)
    except ValueError as exc:  # both on one line, overlapping: refused, and only then
        assert "one line" in str(exc) or "single point" in str(exc)
        return
    for h in hits:
        x = exact_point(p.control_points(), Fraction(h.s))
        y = exact_point(q.control_points(), Fraction(h.t))
        assert max(abs(float(u - v)) for u, v in zip(x, y, strict=True)) < 1e-12
    swapped = sorted((h.t, h.s) for h in q.intersect(p))
    np.testing.assert_allclose(swapped, sorted((h.s, h.t) for h in hits), atol=1e-12)
    if any(h.kind == "coincident" for h in hits):
        return  # a shared stretch: its points are not listed one by one
    u = np.linspace(0, 1, 1201)
    for s, t in polyline_crossing_params(p.evaluate(u), q.evaluate(u)):
        if min(s, t, 1 - s, 1 - t) < 1e-3:
            continue  # a crossing at an end may fall between the polylines' last segments
        assert any(abs(h.s - s) < 1e-3 and abs(h.t - t) < 1e-3 for h in hits), (s, t, hits)


def test_contact_of_order_four_at_a_shared_end_is_symmetric():
    """Hypothesis's case: a and b differ in the first control point only, so along the
    diagonal p(s) - q(s) = (0, (1 - s)^4): a contact of order 4 at the shared end (1, 1).
    Near it the exact residual is below rounding over a whole neighbourhood, and pairs of
    pieces there 2^-17 wide were "isolated" (rounding turned their hodograph cones apart),
    so each order of the curves reported a different spurious crossing near s = t = 0.99999.
    The answer is the five crossings intersect_exact certifies, in both orders."""
    a = [(0, 0), (0, 0), (0, 4), (1, 1), (0, 1)]
    b = [(0, 1), (0, 0), (0, 4), (1, 1), (0, 1)]
    p, q = lb.BezierCurve(a), lb.BezierCurve(b)
    hits = p.intersect(q)
    swapped = sorted((h.t, h.s, h.kind) for h in q.intersect(p))
    assert swapped == sorted((h.s, h.t, h.kind) for h in hits)
    boxes = lb.intersect_exact(p, q)
    assert all(c.certified for c in boxes) and len(hits) == len(boxes) == 5
    for h, c in zip(hits, sorted(boxes, key=lambda c: (c.s[0], c.t[0])), strict=True):
        # each hit is a point of its box rounded to the nearest float: within an ulp of it
        # (FLINT's isolating intervals can be narrower than an ulp)
        for got, (lo, hi) in ((h.s, c.s), (h.t, c.t)):
            ulp = Fraction(math.ulp(got))
            assert lo - ulp <= Fraction(got) <= hi + ulp, (got, lo, hi)
    assert hits[-1] == (1.0, 1.0, "tangent")  # the contact, at the end exactly, once
    assert [h for h in hits if min(h.s, h.t) > 1 - 1e-3] == [hits[-1]]


def test_intersect_bad_input():
    c = lb.BezierCurve([(0, 0), (1, 1)])
    with pytest.raises(TypeError, match="curve"):
        c.intersect([(0, 0), (1, 1)])
    with pytest.raises(ValueError, match="dimensions 2 and 3"):
        c.intersect(lb.BezierCurve([(0, 0, 0), (1, 1, 1)]))
    with pytest.raises(ValueError, match="dimension >= 2"):
        lb.BezierCurve([[0], [1]]).intersect(lb.BezierCurve([[0], [2]]))
    with pytest.raises(ValueError, match="single point"):
        c.intersect(lb.BezierCurve([(1, 1), (1, 1)]))
    # a cubic folding back along y = -7, against a segment of that line: a continuum
    folded = lb.BezierCurve([(-4, -7), (-4, -7), (1, -7), (-8, -7)])
    with pytest.raises(ValueError, match="not a set of points"):
        folded.intersect(lb.BezierCurve([(1, -7), (-13, -7)]))
    assert folded.intersect(lb.BezierCurve([(5, -7), (9, -7)])) == []  # same line, apart
    on_line = folded.intersect(lb.BezierCurve([(-3, -7), (-3, -6)]))  # across it: x = -3 twice
    assert [h.t for h in on_line] == [0.0, 0.0] and len({h.s for h in on_line}) == 2


# ---------------------------------------------------------------------------- λ families
def family_curve(family: str, rows):
    """The fixture curve as a λ curve at the family's Bernstein parameter: same_degree at
    λ = 1 is the classical curve of the same degree (n >= 3), bernstein_like at λ = 0 is
    the classical curve elevated twice (its to_bezier has degree n + 2, n >= 2)."""
    if family == "same_degree":
        return lb.SameDegreeCurve(elevate_to(rows, 3), 1)
    return lb.BernsteinLikeCurve(elevate_to(rows, 2), 0)


@pytest.mark.parametrize("family", ["same_degree", "bernstein_like"])
def test_families_at_bernstein_parameter_are_the_fixture_curves(family):
    for curve_id in CURVES:
        rows = control_rows(curve_id)
        curve = family_curve(family, rows)
        bez = curve.to_bezier()
        assert bez.degree == curve.polynomial_degree
        assert bez.control_points() == elevate_to(rows, bez.degree)


@pytest.mark.parametrize("case", CASES, ids=[f"case{c['id']}" for c in CASES])
def test_family_intersections(case):
    """The fixture cases through the λ families (one curve each), same parameters."""
    r1, r2 = fixture_rows(case["curve1"], case), fixture_rows(case["curve2"], case)
    hits = family_curve("same_degree", r1).intersect(family_curve("bernstein_like", r2))
    check_pairs(hits, case)


@pytest.mark.parametrize("case", CASES, ids=[f"case{c['id']}" for c in CASES])
def test_family_intersections_from_bezier(case):
    """The fixture curves written exactly in the same_degree family away from its Bernstein
    parameter (from_bezier, λ = -1/2 and 1/3): the same parameters."""
    c1 = lb.SameDegreeCurve.from_bezier(fixture_curve(case["curve1"], case), Fraction(-1, 2))
    c2 = lb.SameDegreeCurve.from_bezier(fixture_curve(case["curve2"], case), Fraction(1, 3))
    check_pairs(c1.intersect(c2), case)


def polyline_crossing_params(a: np.ndarray, b: np.ndarray) -> list[tuple[float, float]]:
    """Independent numerics: the (s, t) of the proper crossings of two fine polylines
    (sampled at equal parameter steps)."""
    p, r = a[:-1, None], (a[1:] - a[:-1])[:, None]
    q, s = b[None, :-1], (b[1:] - b[:-1])[None]
    denom = r[..., 0] * s[..., 1] - r[..., 1] * s[..., 0]
    qp = q - p
    with np.errstate(divide="ignore", invalid="ignore"):
        u = (qp[..., 0] * s[..., 1] - qp[..., 1] * s[..., 0]) / denom
        v = (qp[..., 0] * r[..., 1] - qp[..., 1] * r[..., 0]) / denom
    i, j = np.nonzero((u >= 0) & (u < 1) & (v >= 0) & (v < 1))
    na, nb = len(a) - 1, len(b) - 1
    return [((k + u[k, m]) / na, (m + v[k, m]) / nb) for k, m in zip(i, j, strict=True)]


def polyline_crossings(a: np.ndarray, b: np.ndarray) -> int:
    """Independent count: proper crossings of two fine polylines."""
    return len(polyline_crossing_params(a, b))


@pytest.mark.parametrize("seed", range(6))
def test_family_intersections_against_polylines(seed):
    """Random λ curves away from the Bernstein parameter: the count agrees with fine
    polylines and each pair is a root of the families' own evaluators."""
    rng = np.random.default_rng(seed)
    a = lb.SameDegreeCurve(rng.integers(-9, 10, (5, 2)).tolist(), Fraction(-1, 2))
    b = lb.BernsteinLikeCurve(rng.integers(-9, 10, (4, 2)).tolist(), Fraction(1, 2))
    hits = a.intersect(b)
    u = np.linspace(0, 1, 1201)
    assert len(hits) == polyline_crossings(a.evaluate(u), b.evaluate(u))
    for h in hits:
        assert np.linalg.norm(a.evaluate(h.s) - b.evaluate(h.t)) < 1e-12
    # float control points take the same route
    fa = lb.SameDegreeCurve(a.points, -0.5)
    np.testing.assert_allclose(
        [(h.s, h.t) for h in fa.intersect(b)], [(h.s, h.t) for h in hits], atol=1e-12
    )


def test_family_locate_and_self_intersections():
    c = lb.SameDegreeCurve([(0, 0), (6, 3), (-4, 4), (-1, 0), (3, 2)], Fraction(1, 3))
    assert c.locate(c.evaluate(0.7)) == pytest.approx(0.7, abs=1e-13)
    for h in c.self_intersections():
        assert np.linalg.norm(c.evaluate(h.s) - c.evaluate(h.t)) < 1e-12
    pts = c.evaluate(np.linspace(0, 1, 2001))
    # a crossing of the polyline with itself shows up as the pairs (i, j) and (j, i)
    crossings = polyline_crossings(pts, pts)
    assert crossings % 2 == 0
    assert len(c.self_intersections()) == crossings // 2 >= 1


# ---------------------------------------------------------------------------- implicitization
IMPLICIT = [k for k, v in CURVES.items() if "implicitized" in v]


@pytest.mark.parametrize("curve_id", IMPLICIT)
def test_implicitize(curve_id):
    poly = lb.BezierCurve(control_rows(curve_id)).implicitize()
    got = sorted([int(c), m[0], m[1]] for m, c in poly.terms())
    assert got == sorted(CURVES[curve_id]["implicitized"])


def test_implicitize_families_and_bad_input():
    rows = control_rows("4")
    same = family_curve("same_degree", rows).implicitize()
    assert same == lb.BezierCurve(rows).implicitize()
    # floats are binary rationals, taken exactly (issue #28)
    assert (
        lb.BezierCurve([(0.5, 0.0), (1.0, 1.0)]).implicitize()
        == lb.BezierCurve([(Fraction(1, 2), 0), (1, 1)]).implicitize()
    )
    with pytest.raises(ValueError, match="planar"):
        lb.BezierCurve([(0, 0, 0), (1, 1, 1)]).implicitize()


# ---------------------------------------------------------------------------- reduction
@pytest.mark.parametrize(("elevated", "original"), [("52", "50"), ("53", "51")])
def test_full_reduce_fixture_elevations(elevated, original):
    """The fixture notes: curve #52 is a degree elevation of #50, #53 of #51."""
    curve, error = lb.BezierCurve(control_rows(elevated)).full_reduce()
    assert error == 0
    assert curve.control_points() == control_rows(original)


def test_full_reduce_line_and_reduce_error():
    """#32 is a degree-elevated line segment (its note)."""
    curve, error = lb.BezierCurve(control_rows("32")).full_reduce()
    assert curve.degree == 1 and error == 0
    c = lb.BezierCurve([(0, 0), (1, 3), (3, -1), (4, 2)])
    red, err = c.reduce()
    assert red.degree == 2 and err > 0
    u = np.linspace(0, 1, 501)
    assert np.abs(c.evaluate(u) - red.evaluate(u)).max() <= err * (1 + 1e-12)
    up = c.elevate().elevate()
    assert up.full_reduce()[0].control_points() == c.control_points()
    fl, ferr = lb.BezierCurve(up.points).full_reduce()
    assert fl.degree == 3 and ferr < 1e-12
    np.testing.assert_allclose(fl.points, c.points, atol=1e-12)
    with pytest.raises(ValueError, match="degree-0"):
        lb.BezierCurve([(1, 2)]).reduce()


def test_elevation_and_hodograph_formulas_match_tables():
    from lambda_bezier._generated import bernstein

    from lambda_bezier.hazmat import forms

    for n in bernstein.DEGREES:
        assert forms.hodograph_matrix(n) == bernstein.HODOGRAPH[n]
    for n in bernstein.ELEVATION:
        assert forms.elevation_matrix(n) == bernstein.ELEVATION[n]
    # past the tables: elevation keeps every point of the curve (exactly), and the hodograph
    # is the derivative SymPy takes of the Bernstein form
    import sympy

    n = bernstein.DEGREES[-1] + 2
    rows = tuple((Fraction(i * i % 7), Fraction(i % 3, 5)) for i in range(n + 1))
    up = lb.BezierCurve(rows).elevate()
    for t in (Fraction(1, 3), Fraction(5, 7)):
        assert exact_point(up.control_points(), t) == exact_point(rows, t)
    u = sympy.Symbol("u")
    x = sum(
        math.comb(n, i) * u**i * (1 - u) ** (n - i) * sympy.Rational(r[0])
        for i, r in enumerate(rows)
    )
    hod = lb.BezierCurve(rows).hodograph().control_points()
    for t in (Fraction(1, 3), Fraction(5, 7)):
        want = sympy.diff(x, u).subs(u, sympy.Rational(t.numerator, t.denominator))
        assert exact_point(hod, t)[0] == Fraction(int(want.p), int(want.q))


# ---------------------------------------------------------------------------- degrees, dimensions
@pytest.mark.parametrize("degree", [15, 30, 55])
def test_high_degree_evaluation(degree):
    rng = np.random.default_rng(degree)
    rows = [
        tuple(Fraction(int(v), 7) for v in row) for row in rng.integers(-20, 21, (degree + 1, 2))
    ]
    c = lb.BezierCurve(rows)
    for t in (Fraction(0), Fraction(1, 10), Fraction(1, 2), Fraction(7, 9), Fraction(1)):
        want = np.array([float(v) for v in exact_point(rows, t)])
        np.testing.assert_allclose(c.evaluate(float(t)), want, rtol=0, atol=1e-12)
    # derivative: the hodograph's exact value
    hod = c.hodograph()
    t = Fraction(3, 10)
    want = np.array([float(v) for v in exact_point(hod.control_points(), t)])
    np.testing.assert_allclose(c.derivative(0.3), want, rtol=1e-12, atol=1e-9)
    assert c.basis(0.3).sum() == pytest.approx(1.0)
    left, right = c.split(Fraction(1, 3))
    assert left.control_points()[-1] == exact_point(rows, Fraction(1, 3))
    assert c.elevate().degree == degree + 1
    # past the tables the same tables are computed (issue #28; tests/test_every_degree.py)
    assert c.basis_power_matrix().shape == (degree + 1, degree + 1)
    assert c.arc_length() > 0
    hod = c.hodograph().control_points()  # E_1 = ∫|p'|² from the exact p'² product
    square = [
        sum(a * b for a, b in zip(hod[i], hod[j], strict=True))
        for i in range(degree)
        for j in range(degree)
    ]
    m = degree - 1
    want = sum(
        square[i * degree + j]
        * Fraction(math.comb(m, i) * math.comb(m, j), math.comb(2 * m, i + j) * (2 * m + 1))
        for i in range(degree)
        for j in range(degree)
    )
    assert c.energy(1) == want


def test_peer_examples_from_the_issue():
    c = lb.BezierCurve(np.eye(31)[:, :2])
    assert c.degree == 30
    # B_{0,30}(t) and B_{1,30}(t)
    t = 0.3
    np.testing.assert_allclose(c.evaluate(t), [0.7**30, 30 * 0.3 * 0.7**29], rtol=1e-13)
    flat = lb.BezierCurve([[1.0]] * 8)
    assert flat.dimension == 1
    np.testing.assert_allclose(flat.evaluate([0.0, 0.4, 1.0]), [[1.0]] * 3)


def test_dimensions_one_and_four():
    line = lb.BezierCurve([[0], [1], [3], [1]])
    assert line.locate([0.5]) == pytest.approx(line.locate(line.evaluate(line.locate([0.5]))))
    assert line.locate([5]) is None
    p = lb.BezierCurve([(0, 0, 0, 0), (1, 2, 0, 1), (2, 0, 1, 3)])
    point = p.evaluate(0.4)
    q = lb.BezierCurve([tuple(point - [1, 1, 1, 1]), tuple(point + [1, 1, 1, 1])])
    hits = p.intersect(q)
    assert len(hits) == 1
    assert hits[0].s == pytest.approx(0.4, abs=1e-14) and hits[0].t == pytest.approx(0.5, abs=1e-14)
    assert p.locate(point) == pytest.approx(0.4, abs=1e-14)
    with pytest.raises(ValueError, match="dimension 2 or 3"):
        p.curvature(0.5)
    same = lb.SameDegreeCurve(
        [(0, 0, 0, 0, 1), (1, 2, 0, 1, 1), (2, 0, 1, 3, 0), (1, 1, 1, 1, 1)], 0.5
    )
    np.testing.assert_allclose(same.evaluate(0.3), same.to_bezier().de_casteljau(0.3), atol=1e-14)


def test_segment_extrapolate():
    c = lb.BezierCurve([(0, 0), (1, 2), (3, 2), (4, 0)])
    seg = c.segment(-1, 2, extrapolate=True)
    for u in (Fraction(0), Fraction(1, 3), Fraction(1)):
        assert exact_point(seg.control_points(), u) == exact_point(c.control_points(), -1 + 3 * u)
    fl = c.segment(-0.5, 1.5, extrapolate=True)
    np.testing.assert_allclose(fl.evaluate(0.25), c.evaluate(0.0, extrapolate=True), atol=1e-14)
    # inside [0, 1] it agrees with the default path
    assert (
        c.segment(Fraction(1, 4), Fraction(3, 4), extrapolate=True).control_points()
        == c.segment(Fraction(1, 4), Fraction(3, 4)).control_points()
    )
    with pytest.raises(ValueError, match="extrapolate=True"):
        c.segment(-1, 2)
    with pytest.raises(ValueError, match="t1 < t2"):
        c.segment(2, -1, extrapolate=True)


def test_hodograph_of_a_line_is_a_constant():
    c = lb.BezierCurve([(1, 2), (4, 6)])
    hod = c.hodograph()
    assert hod.degree == 0 and hod.control_points() == ((3, 4),)
    np.testing.assert_allclose(hod.evaluate([0.0, 0.7]), [[3, 4], [3, 4]])
    np.testing.assert_allclose(hod.derivative(0.5), [0, 0])
    with pytest.raises(ValueError, match="degree-0"):
        hod.hodograph()
