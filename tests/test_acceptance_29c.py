"""Issue #29, an independent audit (round 19) beside tests/test_acceptance_29*.py, which it
does not repeat: crossings closer than those (1e-7 to 1e-9 apart on exact input, where the
issue asks for exact isolation), bad input to locate (booleans, ints past the float range),
and closest_point, bounding_box and arc_length at the ends of the float range (a query at
1e308, curves scaled by 2^±1000 or with Fraction coordinates near 1.8e308). Every expected
answer is exact by construction (Fractions) or computed by mpmath at 50 digits; none comes
from the code under test."""

from __future__ import annotations

import math
import warnings
from fractions import Fraction as F
from math import comb
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest
from conftest import family_file
from hypothesis import example, given, settings
from hypothesis import strategies as st
from test_acceptance_29 import _compose, _polymul, _power_to_bezier

import lambda_bezier as lb
from lambda_bezier import examples
from lambda_bezier.conversion import from_bezier

FAMILIES = Path(__file__).parent / "data" / "families"


# ------------------------------------------------- crossings 1e-7 .. 1e-9 apart, exact input
def _graph_with_roots(a: F, b: F, extra: list[F]) -> lb.BezierCurve:
    """(s, (s − a)(s − b) · extra(s)) on s in [0, 1], exactly: it crosses y = 0 at s = a and
    s = b (extra has no root in [0, 1]: its constant term outweighs the rest)."""
    y = _polymul([a * b, -(a + b), F(1)], extra)
    x = [F(0), F(1)] + [F(0)] * (len(y) - 2)
    return _power_to_bezier(list(zip(x, y, strict=True)))


@settings(max_examples=12, deadline=None)
@given(
    a_milli=st.integers(100, 890),
    gap_exponent=st.integers(7, 9),
    extra=st.lists(st.integers(-1, 1), min_size=0, max_size=3),
    family=st.sampled_from(["bezier", "same_degree"]),
)
@example(a_milli=462, gap_exponent=7, extra=[0], family="bezier")  # one crossing was dropped
@example(a_milli=439, gap_exponent=7, extra=[], family="same_degree")
def test_exact_crossings_1e7_apart_are_both_found(a_milli, gap_exponent, extra, family):
    """Exact input, two crossings 10^-7 .. 10^-9 apart: the curve is within 1e-14 of the line
    between them, inside the float merge gap (64 ε per degree), and the merged hit came back
    "transversal", so the exact isolation never ran and one crossing was dropped (in round
    19, at 1e-7; at 1e-8 and below the merged hit was "tangent" and was split exactly)."""
    a = F(a_milli, 1000)
    b = a + F(1, 10**gap_exponent)
    curve = _graph_with_roots(a, b, [F(3)] + [F(k, 2) for k in extra])
    if family == "same_degree":
        while curve.degree < 3:
            curve = curve.elevate()
        curve = from_bezier(lb.FAMILIES["same_degree"], curve, F(1, 2))
    lo, hi = F(-1, 10), F(11, 10)
    line = lb.BezierCurve([(lo, 0), (hi, 0)])
    got = curve.intersect(line)
    want = [(float(r), float((r - lo) / (hi - lo))) for r in (a, b)]
    assert len(got) == 2, got
    for hit, (s, t) in zip(got, want, strict=True):
        assert abs(hit.s - s) <= 1e-15 and abs(hit.t - t) <= 1e-15, (hit, s, t)
        assert hit.kind == "transversal"
    # the other way round, and through intersect_many, the same answer
    assert [(h.t, h.s) for h in line.intersect(curve)] == [(h.s, h.t) for h in got]
    assert lb.intersect_many([curve], [line]) == [got]


@pytest.mark.parametrize("gap_exponent", [5, 7, 9])
def test_exact_rational_crossings_close_together_to_the_last_bits(gap_exponent):
    """A rational quadratic (weights 1, 2, 1) whose height is (t − a)(t − b)/w(t), exactly,
    against y = 0: at 1e-5 apart the float search returned both, each 2e-13 off (its
    parameter is only as good as 1/sine); the exact isolation now answers such crossings."""
    a = F(437, 1000)
    b = a + F(1, 10**gap_exponent)
    heights = [a * b, a * b - (a + b) / 2, a * b - (a + b) + 1]  # Bernstein form of Y
    weights = [1, 2, 1]
    curve = lb.RationalBezierCurve(
        [(F(k, 2), h / w) for k, (h, w) in enumerate(zip(heights, weights, strict=True))],
        weights,
    )
    got = curve.intersect(lb.BezierCurve([(-1, 0), (2, 0)]))
    assert [h.kind for h in got] == ["transversal", "transversal"]
    assert [h.s for h in got] == [float(a), float(b)]


# ------------------------------------------------------------------- locate: bad points
def _classes() -> list[object]:
    arch = [(0, 0), (1, 2), (2, 0)]
    trig = lb.load_family(FAMILIES / "han_trig_cubic.toml")
    return [
        lb.BezierCurve(arch),
        lb.SameDegreeCurve([(0, 0), (1, 2), (2, 2), (3, 0)], lam=F(1, 2)),
        lb.RationalBezierCurve(arch, [1, 2, 1]),
        trig.curve([(0, 0), (1, 2), (2, 2), (3, 0)], lam=F(1, 2), mu=F(-1, 2)),
    ]


@pytest.mark.parametrize("curve", _classes(), ids=lambda c: type(c).__name__)
@pytest.mark.parametrize(
    ("point", "match"),
    [
        ((True, False), "point must be numbers, got booleans"),
        ((1, np.True_), "point must be numbers, got booleans"),
        ((10**400, 0), r"point at index \(0,\) = .* too large for a float"),
        ((F(10**400), 0), r"point at index \(0,\) = .* too large for a float"),
        ((1j, 0), "point must be real numbers"),
        ("ab", "point must be a sequence of 2 numbers"),
        ((None, 1), "point must be a sequence of 2 numbers"),
        ((1, 2, 3), r"point must have shape \(2,\)"),
    ],
)
def test_locate_refuses_booleans_and_ints_past_the_float_range(curve, point, match):
    """locate took (True, False) as (0, 0) -> t = 0 of the arch, and raised a bare
    OverflowError for an int past 1.8e308; closest_point and the constructors refuse both by
    name, as the README says bad input is refused."""
    with pytest.raises(ValueError, match=match):
        curve.locate(point)


def test_locate_still_takes_exact_and_mixed_points():
    arch = lb.BezierCurve([(0, 0), (1, 2), (2, 0)])
    assert arch.locate((F(1, 2), F(3, 4))) == 0.25  # exact: (2t, 4t(1 − t)) at t = 1/4
    assert arch.locate((F(1, 2), 0.75)) == 0.25
    assert arch.locate(np.array([1, 1], dtype=np.int64)) == 0.5
    assert arch.locate((0.5, 0.7)) is None


# ------------------------------------------------ closest point, box, length at the float limits
def _arch_length() -> float:
    """∫₀¹ |(2, 4 − 8t)| dt, the length of the arch (0,0), (1,2), (2,0), at 50 digits."""
    mp.mp.dps = 50
    return float(mp.quad(lambda t: mp.sqrt(4 + (4 - 8 * t) ** 2), [0, mp.mpf(1) / 2, 1]))


@pytest.mark.parametrize("exponent", [-1000, -500, 0, 500, 1000])
def test_box_length_and_closest_point_scale_with_the_curve(exponent):
    """The arch 2^k (0,0), (1,2), (2,0): box [0, 2] x [0, 1] times 2^k exactly (the box of a
    float curve scaled past 2^±500 came back with the unscaled inner extremum: 0.75 instead
    of 1e300), length 2^k times the mpmath integral, nearest point to 2^k (1, 3) the apex."""
    scale = math.ldexp(1.0, exponent)
    arch = lb.BezierCurve(np.array([(0, 0), (1, 2), (2, 0)], dtype=float) * scale)
    lo, hi = arch.bounding_box()
    assert lo.tolist() == [0.0, 0.0]
    assert hi.tolist() == [2 * scale, scale]
    assert arch.arc_length() == pytest.approx(_arch_length() * scale, rel=1e-12)
    near = arch.closest_point((scale, 3 * scale))
    assert near.t == pytest.approx(0.5, abs=1e-12)
    assert near.distance == pytest.approx(2 * scale, rel=1e-14)
    assert np.allclose(near.point, [scale, scale], rtol=1e-14, atol=0)


def test_an_exact_curve_near_the_float_limit_is_measured_not_overflowed():
    """Fraction control points at 1e308: the Taylor coefficients of the exact Bézier form pass
    the float range (closest_point, bounding_box and arc_length raised a bare OverflowError
    from Fraction.__float__)."""
    s = F(5 * 10**307)
    arch = lb.BezierCurve([(0, 0), (s, 2 * s), (2 * s, 0)])
    near = arch.closest_point((s, F(3, 2) * s))  # the apex (s, s) at t = 1/2, distance s/2
    assert near.t == pytest.approx(0.5, abs=1e-12)
    assert near.distance == pytest.approx(float(s / 2), rel=1e-14)
    lo, hi = arch.bounding_box()
    assert lo.tolist() == [0.0, 0.0] and hi.tolist() == [float(2 * s), float(s)]
    assert arch.arc_length() == pytest.approx(_arch_length() * float(s), rel=1e-12)
    # curves of every size: a tiny exact one keeps its digits (no subnormal coefficients)
    tiny = F(1, 10**320)
    small = lb.BezierCurve([(0, 0), (tiny, 2 * tiny), (2 * tiny, 0)])
    assert small.bounding_box()[1].tolist() == [float(2 * tiny), float(tiny)]


def _far_reference(curve: lb.BezierCurve, q: tuple[float, float]) -> float:
    """min over 2001 samples of the exact distance |p(t) − q| (mpmath, 50 digits): an upper
    bound on the true minimum, within the curve's size of it."""
    mp.mp.dps = 50
    best = None
    for t in np.linspace(0, 1, 2001):
        x, y = (mp.mpf(float(v)) for v in curve.evaluate(t))
        d = mp.sqrt((x - q[0]) ** 2 + (y - q[1]) ** 2)
        best = d if best is None or d < best else best
    return float(best)


@pytest.mark.parametrize("q", [(1e308, 1e308), (-1.7e308, 3e307), (1e200, -1e200)])
def test_closest_point_to_a_query_near_the_float_limit(q):
    """A query at 1e308: the squared distance is past the float range; closest_point raised a
    bare OverflowError (math.ldexp(1, 1024)), now the distance, to the last bits."""
    arch = lb.BezierCurve([(0, 0), (1, 2), (2, 0)])
    near = arch.closest_point(q)
    assert math.isfinite(near.distance)
    assert near.distance == pytest.approx(_far_reference(arch, q), rel=1e-15)
    batch = arch.closest_point([q, (1, 3)])
    assert batch.distance[0] == near.distance and batch.distance[1] == pytest.approx(2)


def test_closest_point_on_a_curve_scaled_to_the_float_limit():
    """A float curve with coordinates at 1e308 (scaled by 2^1023 inside): its nearest point
    came back as inf (a factor 2^1023 x 2 made inf), now the point itself."""
    curve = lb.BezierCurve([(0, 0), (1e308, 2), (2, 1e308)])
    near = curve.closest_point((1e308, 1e307))
    assert np.isfinite(near.point).all()
    assert np.allclose(near.point, curve.evaluate(near.t), rtol=1e-15, atol=0)
    assert near.distance == pytest.approx(_far_reference(curve, (1e308, 1e307)), rel=1e-6)


def test_a_c_bezier_curve_measures_a_far_query_without_overflow():
    """C-Bézier (atom) curves: a query past 1e154 overflowed the squared distances (inf, and a
    RuntimeWarning under -W error); the search and the distance now run at a power-of-two
    scale."""
    fam = lb.load_family(examples.path("c_bezier_cubic.toml"))
    curve = fam.curve([(0, 0), (1, 2), (2, 2), (3, 0)], alpha=1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for q in [(1e308, 1e308), (1e200, -3e199), (1e154, 1e154)]:
            near = curve.closest_point(q)
            want = math.dist(curve.evaluate(near.t) / 2**600, np.array(q) / 2**600) * 2**600
            assert math.isfinite(near.distance)
            assert near.distance == pytest.approx(want, rel=1e-15)
        near = curve.closest_point((1.5, 3))  # the symmetric apex: t = 1/2 of [0, 1]
        assert near.t == pytest.approx(0.5, abs=1e-9)


# --------------------------------------------- a curve turning back along itself, off a line
def _composed(points: list[tuple[F, ...]], inner: list[F]) -> lb.BezierCurve:
    """Q(g(s)) exactly, for the Bézier curve Q of `points` and g = Σ inner[k] s^k."""
    n, dim = len(points) - 1, len(points[0])
    power = [
        [
            sum(comb(n, k) * comb(k, i) * (-1) ** (k - i) * points[i][c] for i in range(k + 1))
            for k in range(n + 1)
        ]
        for c in range(dim)
    ]
    cols = [_compose(col, inner) for col in power]
    width = max(map(len, cols))
    cols = [col + [F(0)] * (width - len(col)) for col in cols]
    m = width - 1
    return lb.BezierCurve(
        [
            tuple(sum(F(comb(j, k), comb(m, k)) * col[k] for k in range(j + 1)) for col in cols)
            for j in range(m + 1)
        ]
    )


CUBIC = [(F(0), F(0)), (F(1), F(3)), (F(3), F(-1)), (F(4), F(2))]
SPACE_CUBIC = [(F(0), F(0), F(0)), (F(1), F(3), F(1)), (F(3), F(-1), F(2)), (F(4), F(2), F(-1))]


@pytest.mark.parametrize(
    ("points", "inner", "want", "exact"),
    [
        # g = 4s(1 − s): out along Q and back along all of it
        (CUBIC, [F(0), F(4), F(-4)], [(0, 1), (F(1, 2), F(1, 2))], True),
        (SPACE_CUBIC, [F(0), F(4), F(-4)], [(0, 1), (F(1, 2), F(1, 2))], False),
        # g = 3s − 9s²/2: to Q(1/2) at s = 1/3, back past Q(0) at s = 2/3
        (CUBIC, [F(0), F(3), F(-9, 2)], [(0, F(2, 3)), (F(1, 3), F(1, 3))], True),
    ],
    ids=["planar-exact", "space-float", "partial-exact"],
)
def test_a_curve_retracing_itself_reports_its_shared_stretch(points, inner, want, exact):
    """P(s) = Q(g(s)) with g turning at s = m retraces Q: p(s) = p(t) along a whole stretch,
    to be reported as coincident end pairs, as intersect reports two curves sharing a stretch
    and self_intersections a curve on a line turning back; it gave 6-9 arbitrary "tangent"
    points. The float case is the same curve scaled to integer control points (exact
    floats), so that it turns back exactly too."""
    curve = _composed(points, inner)
    if not exact:
        den = math.lcm(*(x.denominator for row in curve.control_points() for x in row))
        curve = lb.BezierCurve(
            np.array([[float(x * den) for x in row] for row in curve.control_points()])
        )
    got = curve.self_intersections()
    assert [(h.s, h.t, h.kind) for h in got] == [
        (float(s), float(t), "coincident") for s, t in want
    ]


def test_a_curve_turning_twice_shares_three_stretches():
    """g = 10s³ − 27s²/2 + 9s/2: turning at m = (9 ∓ √21)/20, with g(0) = g(3/5) = g(3/4) = 0
    and g(m₁) = g(9/20 + √21/10): three stretches (pieces 1-2, 1-3, 2-3), their end pairs."""
    curve = _composed(CUBIC, [F(0), F(9, 2), F(-27, 2), F(10)])
    mp.mp.dps = 50
    m1, m2 = (9 - mp.sqrt(21)) / 20, (9 + mp.sqrt(21)) / 20
    far = mp.mpf(9) / 20 + mp.sqrt(21) / 10
    want = [
        (0, 0.6),
        (0, 0.75),
        (float(m1), float(m1)),
        (float(m1), float(far)),
        (float(m2), float(m2)),
    ]
    got = curve.self_intersections()
    assert [h.kind for h in got] == ["coincident"] * 5
    for h, (s, t) in zip(got, want, strict=True):
        assert abs(h.s - s) <= 1e-15 and abs(h.t - t) <= 1e-15, (got, want)


@pytest.mark.parametrize("exact", [True, False], ids=["exact", "float"])
def test_a_curve_retracing_another_shares_two_stretches_listed_once(exact):
    """Q against P = Q(4s(1 − s)): P[0, 1/2] is Q run forwards and P[1/2, 1] Q run back. The
    end pair at P's turning point (s = 1/2, t = 1) ends both stretches: it came twice, and at
    s = 0.5000000082 (a double root of locating Q(1) on P, found to about 1e-8); now once,
    exactly at the turning point."""
    q = lb.BezierCurve(CUBIC)
    p = _composed(CUBIC, [F(0), F(4), F(-4)])
    if not exact:
        den = math.lcm(*(x.denominator for row in p.control_points() for x in row))
        p = lb.BezierCurve(np.array([[float(x * den) for x in row] for row in p.control_points()]))
        q = lb.BezierCurve(np.array([[float(x * den) for x in row] for row in CUBIC]))
    want = [(0.0, 0.0), (0.5, 1.0), (1.0, 0.0)]
    got = p.intersect(q)
    assert [(h.s, h.t) for h in got] == want and {h.kind for h in got} == {"coincident"}
    assert sorted((h.t, h.s) for h in q.intersect(p)) == want


# ------------------------------------------------ intersect, locate at any size of the curves
@pytest.mark.parametrize("exponent", [-1060, -700, -332, 0, 332, 700, 1020])
def test_intersections_do_not_depend_on_the_size_of_the_curves(exponent):
    """Curves multiplied by 2^k are the same curves in the same parameters. Lines crossing at
    their middles came back "tangent" at 2^-332 (1e-100: a product of four coordinates
    underflows), 1e-10 off at 2^-700 and not at all at 2^1020; a point on the arch at 2^1020
    was not located. Expected answers: exact (1/2, and 1/2 ∓ √2/4 for the arch at half its
    height, 1/2 ∓ √3/6 for the loop)."""
    k = exponent

    def curve(points):
        return lb.BezierCurve(np.ldexp(np.array(points, dtype=float), k))

    lines = curve([(0, 0), (2, 2)]), curve([(0, 2), (2, 0)])
    assert [tuple(h) for h in lines[0].intersect(lines[1])] == [(0.5, 0.5, "transversal")]
    assert lb.intersect_many([lines[0]], [lines[1]]) == [lines[0].intersect(lines[1])]
    arch = curve([(0, 0), (1, 2), (2, 0)])
    assert [tuple(h) for h in arch.intersect(curve([(0, 1), (2, 1)]))] == [(0.5, 0.5, "tangent")]
    r = math.sqrt(2) / 4
    got = arch.intersect(curve([(0, 0.5), (2, 0.5)]))
    assert [h.kind for h in got] == ["transversal"] * 2
    assert [h.s for h in got] == pytest.approx([0.5 - r, 0.5 + r], abs=1e-15)
    loop = curve([(0, 0), (4, 2), (-1, 2), (3, 0)])
    (hit,) = loop.self_intersections()
    assert (hit.s, hit.t) == pytest.approx(
        (0.5 - math.sqrt(3) / 6, 0.5 + math.sqrt(3) / 6), abs=1e-15
    )
    assert arch.locate(np.ldexp([1.0, 1.0], k)) == 0.5
    assert arch.locate(np.ldexp([0.5, 0.75], k)) == 0.25
    assert arch.locate(np.ldexp([1.0, 0.9], k)) is None


@pytest.mark.parametrize("exponent", [-1000, -700, 0, 332, 1000])
def test_rational_intersections_do_not_depend_on_the_size_of_the_curves(exponent):
    """The rational arch (0,0), (1,2), (2,0) with weights 1, 2, 1 has height
    8u / (1 + 2u), u = t(1 − t): it meets y = 1 where u = 1/6, t = (1 ∓ 1/√3)/2. Scaled by
    2^k: at 2^-700 one crossing was lost and the other called "tangent", at 2^1000 the search
    overflowed (RuntimeWarning)."""
    k = exponent
    arch = lb.RationalBezierCurve(np.ldexp([(0.0, 0.0), (1.0, 2.0), (2.0, 0.0)], k), [1, 2, 1])
    line = lb.BezierCurve(np.ldexp([(-1.0, 1.0), (3.0, 1.0)], k))
    want = [(1 - 1 / math.sqrt(3)) / 2, (1 + 1 / math.sqrt(3)) / 2]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for got in (arch.intersect(line), [h._replace(s=h.t) for h in line.intersect(arch)]):
            assert [h.kind for h in got] == ["transversal", "transversal"]
            assert [h.s for h in got] == pytest.approx(want, abs=1e-15)
        loop = lb.RationalBezierCurve(
            np.ldexp([(0.0, 0.0), (4.0, 2.0), (-1.0, 2.0), (3.0, 0.0)], k), [1, 2, 2, 1]
        )
        (hit,) = loop.self_intersections()
        assert hit.t == pytest.approx(1 - hit.s, abs=1e-15)  # symmetric under t -> 1 - t


def _bisect_roots(f, lo: float, hi: float, n: int = 400) -> list[float]:
    """The sign changes of f on n intervals of [lo, hi], bisected to the last bit."""
    xs = np.linspace(lo, hi, n + 1)
    out = []
    for a, b in zip(xs[:-1], xs[1:], strict=True):
        fa = f(a)
        if fa * f(b) > 0:
            continue
        while True:
            m = (a + b) / 2
            if m in (a, b):
                break
            if f(m) * fa > 0:
                a, fa = m, f(m)
            else:
                b = m
        out.append(a)
    return out


@pytest.mark.parametrize("exponent", [-1000, -700, 0, 700, 1000])
@pytest.mark.parametrize(
    ("name", "params"),
    [("han_trig_cubic", {"lam": 0.5, "mu": -0.5}), ("c_bezier_cubic", {"alpha": 1.0})],
)
def test_atom_intersections_do_not_depend_on_the_size_of_the_curves(name, params, exponent):
    """A trigonometric and a C-Bézier curve scaled by 2^k against y = 2^k: the crossings are
    where the unscaled curve's height is 1 (bisection on its evaluate, independent of the
    intersection engine). At 2^-700 one was lost and the other called "tangent", at 2^1000 the
    search overflowed; a point on the C-Bézier curve at 2^-700 was not located."""
    fam = lb.load_family(family_file(name))
    pts = [(0.0, 0.0), (1.0, 2.0), (2.0, 2.0), (3.0, 0.0)]
    unit = fam.curve(pts, **params)
    lo, hi = unit.domain
    want = _bisect_roots(lambda t: float(unit.evaluate(t)[1]) - 1.0, lo, hi)
    assert len(want) == 2
    k = exponent
    curve = fam.curve(np.ldexp(pts, k), **params)
    line = lb.BezierCurve(np.ldexp([(0.0, 1.0), (3.0, 1.0)], k))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = curve.intersect(line)
        assert [h.kind for h in got] == ["transversal", "transversal"]
        assert [h.s for h in got] == pytest.approx(want, abs=1e-12)
        assert [h.t for h in line.intersect(curve)] == [h.s for h in got]
        t = lo + 0.3 * (hi - lo)
        assert curve.locate(curve.evaluate(t)) == pytest.approx(t, abs=1e-12)
