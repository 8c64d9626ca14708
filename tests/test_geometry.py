"""Arc length, its inverse, bounding boxes, closest points and torsion, each against an
independent computation: scipy's adaptive quadrature at high accuracy, dense sampling refined
by a bounded scalar minimiser, and the torsion formula on exact derivatives (Fractions)."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from conftest import curves, make_curve
from hypothesis import given, settings
from hypothesis import strategies as st
from reference import FAMILIES
from scipy.integrate import quad
from scipy.optimize import minimize_scalar

import lambda_bezier as lb
from lambda_bezier import examples

FAMS = list(FAMILIES.values())
FEW = settings(max_examples=12, deadline=None)


def speed_integral(curve, a, b, epsrel=2e-14, points=None):
    """scipy's QUADPACK on |p'|, far tighter than the 1e-12 we claim (split at `points`)."""
    value, _ = quad(
        lambda t: float(np.linalg.norm(curve.derivative(t))),
        a,
        b,
        epsabs=0,
        epsrel=epsrel,
        limit=500,
        points=points,
    )
    return value


def speed_kinks(curve):
    """Break points for QUADPACK where |p'| has a kink or nearly: at the real part x of
    each zero x + iy of |p'|² near the real axis (|p'|², of degree 2(N − 1), fitted through
    Chebyshev points from curve.derivative) and at x ± |y|·4^k, where such a bend of width
    |y| flattens out. QUADPACK's rules have no node near the ends of a subinterval, and
    little resolution for a bend much narrower than their nodes' spacing: hypothesis's
    random curves once had a kink at t = 0.0039 and once a bend of width 2e-6 where quad
    alone was off by 4e-10 and 6e-11 (mpmath agrees with ours to 1e-15)."""
    n = 2 * curve.polynomial_degree
    t = 0.5 + 0.5 * np.cos(np.pi * (np.arange(n + 1) + 0.5) / (n + 1))
    q = np.square(curve.derivative(t)).sum(axis=1)
    points = set()
    for z in np.polynomial.Chebyshev.fit(t, q, n, domain=[0, 1]).roots():
        if abs(z.imag) < 1e-3:
            width = max(abs(z.imag), 1e-12)
            steps = width * 4.0 ** np.arange(np.ceil(np.log(1 / width) / np.log(4)) + 1)
            points |= {float(z.real)} | set((z.real + steps).tolist() + (z.real - steps).tolist())
    # (a point at an end is no kink inside, and quad mishandles one 1e-16 from an end)
    return sorted(p for p in points if 1e-9 < p < 1 - 1e-9)


def refined_extreme(f, ts, values, sign):
    """Dense samples, then a bounded minimiser around the best sample."""
    i = int(np.argmin(sign * values))
    lo, hi = ts[max(i - 1, 0)], ts[min(i + 1, len(ts) - 1)]
    res = minimize_scalar(
        lambda t: sign * f(t), bounds=(lo, hi), method="bounded", options={"xatol": 1e-13}
    )
    return min(sign * values[i], res.fun) * sign


def sample_curves():
    """One fixed curve per family, 2D and 3D, exact and float."""
    out = []
    for fam in FAMS:
        n = max(fam.degrees[0], 4)
        rng = np.random.default_rng(n)
        for d in (2, 3):
            pts = rng.integers(-9, 10, size=(n + 1, d)).tolist()
            lam = None if fam.name == "bezier" else Fraction(1, 3)
            out.append(make_curve(fam, pts, lam))
            flam = None if lam is None else 0.3
            out.append(make_curve(fam, np.array(pts, float) + 0.25, flam))
    return out


CURVES = sample_curves()
IDS = [f"{c.family}-{c.dimension}d-{'exact' if c.is_exact else 'float'}" for c in CURVES]


# ---------------------------------------------------------------------- arc length
@pytest.mark.parametrize("curve", CURVES, ids=IDS)
def test_arc_length_matches_quadpack(curve):
    ref = speed_integral(curve, 0, 1)
    assert curve.arc_length() == pytest.approx(ref, rel=1e-12, abs=0)
    part = speed_integral(curve, 0.2, 0.7)
    assert curve.arc_length(0.2, 0.7) == pytest.approx(part, rel=1e-12, abs=0)


@pytest.mark.parametrize("fam", FAMS, ids=[f.name for f in FAMS])
@FEW
@given(data=st.data())
def test_arc_length_random_curves(fam, data):
    curve, _, _ = data.draw(curves(fam, max_degree=8))
    ref = speed_integral(curve, 0, 1, points=speed_kinks(curve) or None)
    assert curve.arc_length() == pytest.approx(ref, rel=1e-12, abs=1e-13)


def test_arc_length_of_a_cusp_and_of_a_line():
    # p'(1/2) = 0: the speed has a kink there, which the adaptive rule must resolve
    cusp = lb.BezierCurve([(0, 0), (2, 1), (0, 1), (2, 0)])
    half = speed_integral(cusp, 0, 0.5, epsrel=1e-13)  # symmetric about t = 1/2
    assert cusp.arc_length() == pytest.approx(2 * half, rel=1e-12)
    line = lb.BezierCurve([(0, 0), (1, 1), (3, 3)])
    assert line.arc_length() == pytest.approx(3 * math.sqrt(2), rel=1e-14)


@pytest.mark.parametrize("curve", CURVES, ids=IDS)
def test_parameter_at_length_inverts_arc_length(curve):
    total = curve.arc_length()
    s = np.linspace(0, total, 6)
    t = curve.parameter_at_length(s)
    assert t[0] == 0 and t[-1] == pytest.approx(1, abs=1e-12)
    assert np.all(np.diff(t) > 0)
    for si, ti in zip(s[1:-1], t[1:-1], strict=True):
        assert speed_integral(curve, 0, ti) == pytest.approx(si, rel=0, abs=1e-12 * total)
    assert curve.parameter_at_length(float(s[3])) == pytest.approx(t[3], abs=1e-15)
    with pytest.raises(ValueError, match="outside"):
        curve.parameter_at_length(total * 1.01)


def test_arc_length_input_errors():
    c = CURVES[0]
    with pytest.raises(ValueError, match="t0 <= t1"):
        c.arc_length(0.7, 0.2)
    with pytest.raises(ValueError, match="outside"):
        c.arc_length(0, 1.5)
    with pytest.raises(ValueError, match="must be a number"):
        c.arc_length("a")
    with pytest.raises(ValueError, match="NaN"):
        c.parameter_at_length([1.0, float("nan")])


def test_parameter_at_length_refuses_the_same_inputs_on_every_kind_of_curve(at_pi_family):
    """One validation of s (geometry.length_queries) for polynomial, rational and atom
    curves and composites of them: before it, a polynomial curve took True as 1, an atom
    curve returned a 2-D array for [[s]] and named t for a NaN s."""
    pts = [(0, 0), (1, 2), (3, 2), (4, 0)]
    kinds = [
        lb.BezierCurve(pts),
        lb.RationalBezierCurve(pts, [1, 2, 2, 1]),
        lb.load_family(examples.path("han_trig_cubic.toml")).curve(pts, lam=0, mu=0),  # rational
        at_pi_family.curve(pts, lam=0),  # numeric (_atom_geometry)
        lb.CompositeCurve(
            [lb.BezierCurve(pts), at_pi_family.curve([(4, 0), (5, 1), (6, 0), (7, 1)], lam=0)]
        ),
    ]
    for curve in kinds:
        for s, match in (
            (True, "s must be numbers, got booleans"),
            ([0.5, False], "s must be numbers, got booleans"),
            ("1", "s must be numbers, got the text"),
            ([[1.0]], "s must be a number or a 1-D array, got shape"),
            ([0.5, float("nan")], "s contains NaN or infinity"),
        ):
            with pytest.raises(ValueError, match=match):
                curve.parameter_at_length(s)
        assert np.shape(curve.parameter_at_length([0.5, 1.0])) == (2,)


# ---------------------------------------------------------------------- bounding box
@pytest.mark.parametrize("curve", CURVES, ids=IDS)
def test_bounding_box_matches_refined_sampling(curve):
    lo, hi = curve.bounding_box()
    ts = np.linspace(0, 1, 4001)
    pts = curve.evaluate(ts)
    scale = np.abs(pts).max()
    for axis in range(curve.dimension):
        f = lambda t, a=axis: float(curve.evaluate(t)[a])  # noqa: E731
        assert lo[axis] == pytest.approx(refined_extreme(f, ts, pts[:, axis], 1), abs=1e-12 * scale)
        assert hi[axis] == pytest.approx(
            refined_extreme(f, ts, pts[:, axis], -1), abs=1e-12 * scale
        )
    assert np.all(pts >= lo - 1e-12 * scale) and np.all(pts <= hi + 1e-12 * scale)


@pytest.mark.parametrize("fam", FAMS, ids=[f.name for f in FAMS])
@FEW
@given(data=st.data())
def test_bounding_box_random_curves(fam, data):
    curve, _, _ = data.draw(curves(fam))
    lo, hi = curve.bounding_box()
    pts = curve.evaluate(np.linspace(0, 1, 20001))
    scale = max(1.0, np.abs(pts).max())
    assert np.all(pts >= lo - 1e-12 * scale) and np.all(pts <= hi + 1e-12 * scale)
    # the box is tight: dense samples come within the sampling error of every face
    slack = 1e-5 * scale
    assert np.all(pts.min(axis=0) <= lo + slack) and np.all(pts.max(axis=0) >= hi - slack)


def test_bounding_box_of_a_constant_coordinate_and_a_flat_extremum():
    c = lb.BezierCurve([(0, 1), (1, 1), (2, 1)])
    lo, hi = c.bounding_box()
    assert lo.tolist() == [0, 1] and hi.tolist() == [2, 1]
    # y = 1 - (2t - 1)^4 has a quadruple-root derivative at t = 1/2: max y = 1
    flat = lb.BezierCurve([(0, 0), (1, 2), (2, 4 / 3), (3, 2), (4, 0)])
    _, hi = flat.bounding_box()
    ts = np.linspace(0, 1, 100001)
    assert hi[1] == pytest.approx(flat.evaluate(ts)[:, 1].max(), abs=1e-12)


# ---------------------------------------------------------------------- closest point
@pytest.mark.parametrize("curve", CURVES, ids=IDS)
def test_closest_point_matches_refined_sampling(curve):
    rng = np.random.default_rng(7)
    queries = rng.uniform(-12, 12, size=(6, curve.dimension))
    batch = curve.closest_point(queries)
    ts = np.linspace(0, 1, 4001)
    pts = curve.evaluate(ts)
    for j, q in enumerate(queries):
        f = lambda t, q=q: float(np.linalg.norm(curve.evaluate(t) - q))  # noqa: E731
        ref = refined_extreme(f, ts, np.linalg.norm(pts - q, axis=1), 1)
        assert batch.distance[j] <= ref + 1e-12
        assert batch.distance[j] == pytest.approx(ref, abs=1e-9)
        one = curve.closest_point(q)
        assert one.t == pytest.approx(batch.t[j], abs=1e-12)
        assert one.distance == pytest.approx(batch.distance[j], abs=1e-14)
        np.testing.assert_allclose(one.point, curve.evaluate(one.t), atol=1e-12)


@pytest.mark.parametrize("fam", FAMS, ids=[f.name for f in FAMS])
@FEW
@given(data=st.data())
def test_closest_point_random(fam, data):
    curve, _, _ = data.draw(curves(fam))
    q = np.array(
        data.draw(st.lists(st.floats(-15, 15), min_size=curve.dimension, max_size=curve.dimension))
    )
    res = curve.closest_point(q)
    pts = curve.evaluate(np.linspace(0, 1, 20001))
    sampled = np.linalg.norm(pts - q, axis=1).min()
    assert res.distance <= sampled + 1e-12 * max(1.0, sampled)


def test_degree_elevated_float_curve_keeps_its_geometry():
    """Elevated to degree 14 in floats, a cubic's top Taylor coefficients are rounding
    noise: the root finders must see through them to the cubic's answers."""
    cubic = lb.BezierCurve([(0.0, 0.0), (1.0, 3.0), (2.0, -1.0), (3.0, 3.0)])
    high = cubic
    while high.degree < 14:
        high = high.elevate()
    np.testing.assert_allclose(high.bounding_box(), cubic.bounding_box(), atol=1e-12)
    queries = np.random.default_rng(3).uniform(-2, 5, size=(20, 2))
    a, b = high.closest_point(queries), cubic.closest_point(queries)
    np.testing.assert_allclose(a.distance, b.distance, atol=1e-12)
    assert high.arc_length() == pytest.approx(cubic.arc_length(), rel=1e-12)


def test_closest_point_input_errors():
    c = CURVES[0]
    with pytest.raises(ValueError, match=r"shape \(2,\) or \(m, 2\)"):
        c.closest_point([1, 2, 3])
    with pytest.raises(ValueError, match="NaN"):
        c.closest_point([1, float("nan")])


# ---------------------------------------------------------------------- torsion
def exact_derivatives(curve, t: Fraction):
    """p', p'', p''' at t from the exact Bézier form: forward differences, then the
    Bernstein sum, all in Fractions."""
    rows = [list(r) for r in curve.to_bezier().control_points()]
    n = len(rows) - 1
    out = []
    for k in (1, 2, 3):
        diffs = rows
        for _ in range(k):
            diffs = [
                [b - a for a, b in zip(p, q, strict=True)]
                for p, q in zip(diffs[:-1], diffs[1:], strict=True)
            ]
        m = n - k
        factor = math.factorial(n) // math.factorial(m)
        value = [
            factor
            * sum(math.comb(m, i) * t**i * (1 - t) ** (m - i) * diffs[i][c] for i in range(m + 1))
            for c in range(3)
        ]
        out.append(value)
    return out


def exact_torsion(curve, t: Fraction) -> Fraction:
    d1, d2, d3 = exact_derivatives(curve, t)
    cross = [
        d1[1] * d2[2] - d1[2] * d2[1],
        d1[2] * d2[0] - d1[0] * d2[2],
        d1[0] * d2[1] - d1[1] * d2[0],
    ]
    return sum(c * e for c, e in zip(cross, d3, strict=True)) / sum(c * c for c in cross)


@pytest.mark.parametrize(
    "curve", [c for c in CURVES if c.dimension == 3 and c.is_exact], ids=lambda c: c.family
)
def test_torsion_against_the_exact_formula(curve):
    ts = [Fraction(k, 7) for k in range(8)]
    got = curve.torsion(np.array([float(t) for t in ts]))
    want = [float(exact_torsion(curve, t)) for t in ts]
    np.testing.assert_allclose(got, want, rtol=1e-9, atol=1e-12)
    assert curve.torsion(0.5) == pytest.approx(
        float(exact_torsion(curve, Fraction(1, 2))), rel=1e-9
    )


def test_torsion_of_the_twisted_cubic():
    # (t, t², t³) has torsion 3 / (9t⁴ + 9t² + 1)
    cubic = lb.BezierCurve(
        [(0, 0, 0), (Fraction(1, 3), 0, 0), (Fraction(2, 3), Fraction(1, 3), 0), (1, 1, 1)]
    )
    t = np.linspace(0, 1, 11)
    np.testing.assert_allclose(cubic.torsion(t), 3 / (9 * t**4 + 9 * t**2 + 1), rtol=1e-13)
    mirrored = lb.BezierCurve(np.array(cubic.points) * [1, 1, -1])
    np.testing.assert_allclose(mirrored.torsion(t), -3 / (9 * t**4 + 9 * t**2 + 1), rtol=1e-13)


def test_torsion_is_undefined_in_2d_and_on_straight_pieces():
    with pytest.raises(ValueError, match="3D curves; this curve is 2D"):
        CURVES[0].torsion(0.5)
    line = lb.BezierCurve([(0, 0, 0), (1, 1, 1), (3, 3, 3)])
    with pytest.raises(ValueError, match="undefined at 0.5"):
        line.torsion(0.5)
    kinked = lb.BezierCurve([(0, 0, 0), (1, 0, 0), (2, 0, 0), (2, 1, 1)])
    with pytest.raises(ValueError, match="undefined at 0.0"):
        kinked.torsion([0.5, 0.0])  # p''(0) = 0: an inflection at the start
    planar = lb.SameDegreeCurve([(0, 0, 1), (1, 2, 1), (3, 2, 1), (4, 0, 1)], lam=0)
    np.testing.assert_allclose(planar.torsion([0.1, 0.6]), 0, atol=1e-14)


# ---------------------------------------------------------------------- composites
def composite(dim: int) -> lb.CompositeCurve:
    pts = [(0, 0), (1, 2), (3, 2), (4, 0)]
    if dim == 3:
        pts = [(0, 0, 0), (1, 2, 1), (3, 2, -1), (4, 0, 2)]
    first = lb.BernsteinLikeCurve(pts, lam=Fraction(1, 2))
    rest1 = [(9, -1), (10, 1)] if dim == 2 else [(9, -1, 1), (10, 1, 0)]
    rest2 = [(14, 3)] if dim == 2 else [(14, 3, 2)]
    return (
        lb.CompositeCurve([first])
        .join("C2", 4, 0, rest=rest1)
        .join("G2", 3, Fraction(-1, 2), alpha=2, d=1, rest=rest2, family="same_degree")
    )


@pytest.mark.parametrize("dim", [2, 3])
def test_composite_geometry(dim):
    comp = composite(dim)
    segs = comp.segments
    total = comp.arc_length()
    ref = sum(speed_integral(s, 0, 1) for s in segs)
    assert total == pytest.approx(ref, rel=1e-12)
    part = comp.arc_length(0.5, 2.25)
    ref_part = (
        speed_integral(segs[0], 0.5, 1)
        + speed_integral(segs[1], 0, 1)
        + speed_integral(segs[2], 0, 0.25)
    )
    assert part == pytest.approx(ref_part, rel=1e-12)
    u = comp.parameter_at_length([0, ref_part, total])
    assert u[0] == 0 and u[-1] == pytest.approx(3, abs=1e-12)
    assert comp.arc_length(0, u[1]) == pytest.approx(ref_part, rel=1e-12)
    lo, hi = comp.bounding_box()
    pts = comp.evaluate(np.linspace(0, 3, 30001))
    assert np.all(pts >= lo - 1e-12) and np.all(pts <= hi + 1e-12)
    np.testing.assert_allclose(pts.min(0), lo, atol=1e-6)
    np.testing.assert_allclose(pts.max(0), hi, atol=1e-6)
    q = np.full(dim, 7.0)
    res = comp.closest_point(q)
    assert res.distance <= np.linalg.norm(pts - q, axis=1).min() + 1e-12
    np.testing.assert_allclose(res.point, comp.evaluate(res.t), atol=1e-12)
    batch = comp.closest_point(np.stack([q, q + 1]))
    assert batch.t[0] == pytest.approx(res.t) and batch.t.shape == (2,)
    if dim == 3:
        tau = comp.torsion([0.25, 1.5, 2.75])
        want = [segs[0].torsion(0.25), segs[1].torsion(0.5), segs[2].torsion(0.75)]
        np.testing.assert_allclose(tau, want, rtol=1e-14)
    else:
        with pytest.raises(ValueError, match="2D"):
            comp.torsion(1.0)
