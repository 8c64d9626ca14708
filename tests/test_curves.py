"""The curve classes against the definitions, finite differences and each other."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from conftest import curves, make_curve
from hypothesis import given
from hypothesis import strategies as st
from reference import FAMILIES

import lambda_bezier as lb

TS = np.linspace(0, 1, 17)


def _scale(pts) -> float:
    return 1.0 + float(np.abs(np.asarray(pts, float)).max())


@pytest.mark.parametrize("name", list(FAMILIES))
@given(data=st.data())
def test_evaluate_is_sum_of_definition_basis(name, data):
    fam = FAMILIES[name]
    curve, pts, lam = data.draw(curves(fam))
    want = fam.basis(curve.degree, TS, lam) @ np.asarray(pts, float)
    np.testing.assert_allclose(curve.evaluate(TS), want, atol=1e-9 * _scale(pts))


@pytest.mark.parametrize("name", list(FAMILIES))
@given(data=st.data())
def test_derivatives_against_finite_differences(name, data):
    fam = FAMILIES[name]
    curve, pts, lam = data.draw(curves(fam, max_degree=8))
    t = np.array(data.draw(st.lists(st.floats(0.05, 0.95), min_size=1, max_size=4)))
    h = 1e-4
    p = curve.evaluate
    fd1 = (p(t + h) - p(t - h)) / (2 * h)
    fd2 = (p(t + h) - 2 * p(t) + p(t - h)) / h**2
    d1, d2 = curve.derivative(t, 1), curve.derivative(t, 2)
    scale = _scale(pts) * (curve.polynomial_degree + 1) ** 3
    np.testing.assert_allclose(d1, fd1, atol=1e-6 * scale)
    np.testing.assert_allclose(d2, fd2, atol=2e-3 * scale)
    # higher orders: the derivative of the (k-1)-th by central differences
    for k in range(3, curve.polynomial_degree + 1):
        fdk = (curve.derivative(t + h, k - 1) - curve.derivative(t - h, k - 1)) / (2 * h)
        np.testing.assert_allclose(
            curve.derivative(t, k), fdk, atol=1e-6 * scale * (curve.polynomial_degree + 1) ** k
        )
    np.testing.assert_array_equal(curve.derivative(t, curve.polynomial_degree + 1), 0.0)


@pytest.mark.parametrize("name", list(FAMILIES))
@given(data=st.data())
def test_to_bezier_is_the_same_curve(name, data):
    curve, pts, _ = data.draw(curves(FAMILIES[name]))
    bez = curve.to_bezier()
    assert bez.degree == curve.polynomial_degree
    np.testing.assert_allclose(bez.evaluate(TS), curve.evaluate(TS), atol=1e-9 * _scale(pts))
    np.testing.assert_allclose(bez.de_casteljau(TS), curve.evaluate(TS), atol=1e-9 * _scale(pts))


@pytest.mark.parametrize("name", ["same_degree", "bernstein_like"])
@given(data=st.data())
def test_to_bezier_exact(name, data):
    """Exact points and λ give exact Bézier points, equal to the definition at rational t."""
    fam = FAMILIES[name]
    n = data.draw(st.integers(fam.degrees[0], 7))
    pts = data.draw(
        st.lists(st.tuples(st.integers(-9, 9), st.integers(-9, 9)), min_size=n + 1, max_size=n + 1)
    )
    lam = Fraction(data.draw(st.integers(-4, 4)), 4)
    if name == "same_degree" and lam == -2:
        lam = Fraction(-7, 4)
    curve = lb.FAMILIES[name](pts, lam)
    bez = curve.to_bezier()
    ctrl = bez.control_points()
    assert all(isinstance(v, Fraction) for row in ctrl for v in row)
    # exact comparison with the float path to rounding
    np.testing.assert_allclose(
        np.array(ctrl, float), curve.basis_bernstein_matrix().T @ pts, atol=1e-9
    )
    # exact evaluation at t = 1/3 by exact de Casteljau equals float evaluation
    left, _ = bez.split(Fraction(1, 3))
    exact_point = left.control_points()[-1]
    np.testing.assert_allclose(np.array(exact_point, float), curve.evaluate(1 / 3), atol=1e-9)


@given(data=st.data())
def test_geometric_algorithm_matches_basis(data):
    curve, pts, _ = data.draw(curves(FAMILIES["same_degree"]))
    t = np.array(data.draw(st.lists(st.floats(0, 1), min_size=1, max_size=6)))
    np.testing.assert_allclose(
        curve.evaluate_geometric(t), curve.evaluate(t), atol=1e-9 * _scale(pts)
    )


def test_geometric_algorithm_paper_setting():
    """Fig. 1 of 000: n = 5, t = 2/3, λ = 1/2 (control points of our choosing)."""
    pts = [(0, 0), (1, 3), (3, 4), (5, 3), (6, 1), (8, 2)]
    c = lb.SameDegreeCurve(pts, Fraction(1, 2))
    np.testing.assert_allclose(c.evaluate_geometric(2 / 3), c.evaluate(2 / 3), atol=1e-12)
    assert c.evaluate_geometric([0.1, 2 / 3]).shape == (2, 2)


@pytest.mark.parametrize("name", list(FAMILIES))
@given(data=st.data())
def test_curvature(name, data):
    curve, pts, _ = data.draw(curves(FAMILIES[name], max_degree=8))
    t = np.array(data.draw(st.lists(st.floats(0, 1), min_size=1, max_size=5)))
    d1, d2 = curve.derivative(t), curve.derivative(t, 2)
    d1_3 = np.pad(d1, ((0, 0), (0, 3 - curve.dimension)))
    d2_3 = np.pad(d2, ((0, 0), (0, 3 - curve.dimension)))
    cross = np.cross(d1_3, d2_3)
    speed = np.linalg.norm(d1, axis=1)
    ok = speed > 1e-6
    want = (cross[:, 2] if curve.dimension == 2 else np.linalg.norm(cross, axis=1))[ok] / speed[
        ok
    ] ** 3
    kappa = curve._curvature(t)  # NaN where p'(t) = 0 exactly
    np.testing.assert_allclose(kappa[ok], want, rtol=1e-9, atol=1e-12)
    if np.isnan(kappa).any():  # the public method names such a t instead of returning NaN
        with pytest.raises(ValueError, match="undefined at t"):
            curve.curvature(t)
    else:
        np.testing.assert_array_equal(curve.curvature(t), kappa)


def test_curvature_of_circle_like_and_line():
    line = lb.BezierCurve([(0, 0), (1, 1), (2, 2)])
    np.testing.assert_allclose(line.curvature(TS), 0.0, atol=1e-12)
    # quarter circle approximated: sign is positive for counter-clockwise turning
    arc = lb.BezierCurve([(1, 0), (1, 1), (0, 1)])
    assert (arc.curvature(TS) > 0).all()
    assert (lb.BezierCurve([(0, 1), (1, 1), (1, 0)]).curvature(TS) < 0).all()
    still = lb.BezierCurve([(0, 0), (0, 0), (0, 0)])
    with pytest.raises(ValueError, match=r"undefined at t = 0\.5"):
        still.curvature(0.5)
    # a cusp at t = 1/2 only: the error names that t, the other values are finite
    cusp = lb.BezierCurve([(0, 0), (1, 1), (0, 0)])
    with pytest.raises(ValueError, match=r"undefined at t = 0\.5"):
        cusp.curvature([0.25, 0.5, 0.75])
    assert np.isfinite(cusp.curvature([0.25, 0.75])).all()


def test_shapes(family):
    n = family.degrees[0] + 1
    for d in (2, 3):
        pts = np.arange((n + 1) * d, dtype=float).reshape(n + 1, d) % 5
        c = make_curve(family, pts, None if family.name == "bezier" else 0.5)
        assert c.evaluate(0.3).shape == (d,)
        assert c.evaluate([0.3]).shape == (1, d)
        assert c.evaluate(np.linspace(0, 1, 7)).shape == (7, d)
        assert c.derivative(0.3, 2).shape == (d,)
        assert c.basis(0.3).shape == (n + 1,)
        assert c.basis([0.1, 0.2]).shape == (2, n + 1)
        assert np.ndim(c.curvature(0.3)) == 0
        assert c.curvature([0.3, 0.4]).shape == (2,)
        np.testing.assert_allclose(c.evaluate(0.0), pts[0], atol=1e-12)
        np.testing.assert_allclose(c.evaluate(1.0), pts[-1], atol=1e-12)


# ---------------------------------------------------------------------------- bad input

GOOD = [(0, 0), (1, 2), (3, 2), (4, 0)]


@pytest.mark.parametrize(
    ("cls", "args", "kwargs", "message"),
    [
        (lb.SameDegreeCurve, ([[(0, 0)]] * 4, 0.5), {}, "shape"),
        (lb.SameDegreeCurve, ([0, 1, 2, 3], 0.5), {}, "shape"),
        (lb.SameDegreeCurve, ([(0, 0)] * 3, 0.5), {}, "at least 4 control points"),
        (lb.BernsteinLikeCurve, ([(0, 0)] * 2, 0.5), {}, "at least 3 control points"),
        (lb.BezierCurve, (np.zeros((0, 2)),), {}, "at least 1 control points"),
        (lb.SameDegreeCurve, ([(0, 0)] * 14, 0.5), {}, "degree 13 is not supported"),
        (lb.SameDegreeCurve, ([(0, 0), (1, float("nan")), (2, 0), (3, 0)], 0.5), {}, "non-finite"),
        (lb.SameDegreeCurve, ([(0, 0), (1, float("inf")), (2, 0), (3, 0)], 0.5), {}, "non-finite"),
        (lb.SameDegreeCurve, (GOOD, -2), {}, r"outside the same_degree range \(-2, 1\]"),
        (lb.SameDegreeCurve, (GOOD, 1.5), {}, r"\(-2, 1\]"),
        (lb.BernsteinLikeCurve, (GOOD, -1.01), {}, r"outside the bernstein_like range \[-1, 1\]"),
        (lb.SameDegreeCurve, (GOOD, float("nan")), {}, "finite"),
        (lb.SameDegreeCurve, (GOOD, "0.5"), {}, "real number"),
        (lb.SameDegreeCurve, (GOOD, None), {}, "needs a shape parameter"),
        (lb.SameDegreeCurve, ([("a", 0), (1, 2), (3, 2), (4, 0)], 0.5), {}, "numbers"),
    ],
)
def test_bad_construction(cls, args, kwargs, message):
    with pytest.raises(ValueError, match=message):
        cls(*args, **kwargs)


def test_check_range_false_allows_outside():
    c = lb.SameDegreeCurve(GOOD, -2.5, check_range=False)
    assert c.lam == -2.5
    assert lb.BernsteinLikeCurve(GOOD, 3, check_range=False).lam == 3


@pytest.mark.parametrize("t", [1.5, -0.1, [0.5, 1.01], float("nan"), [[0.1]], "x"])
def test_bad_parameters(t):
    c = lb.SameDegreeCurve(GOOD, 0.5)
    with pytest.raises(ValueError, match="t "):
        c.evaluate(t)


def test_extrapolate():
    c = lb.SameDegreeCurve(GOOD, 0.5)
    np.testing.assert_allclose(
        c.evaluate(1.5, extrapolate=True), c.to_bezier().de_casteljau(1.5, extrapolate=True)
    )


@pytest.mark.parametrize("k", [-1, 1.5, "2", True])
def test_bad_order(k):
    with pytest.raises(ValueError, match="order"):
        lb.SameDegreeCurve(GOOD, 0.5).derivative(0.5, k)


@given(data=st.data())
def test_geometric_levels(data):
    n = data.draw(st.integers(3, 8))
    pts = data.draw(
        st.lists(st.tuples(st.integers(-9, 9), st.integers(-9, 9)), min_size=n + 1, max_size=n + 1)
    )
    lam = Fraction(data.draw(st.integers(-7, 4)), 4)
    t = Fraction(data.draw(st.integers(0, 12)), 12)
    curve = lb.SameDegreeCurve(pts, lam)
    levels = curve.geometric_levels(t)
    assert [len(level) for level in levels] == [*range(n + 1, 3, -1), 4, 3, 2, 1]
    assert all(isinstance(v, Fraction) for v in levels[-1][0])
    np.testing.assert_allclose(np.array(levels[-1][0], float), curve.evaluate(float(t)), atol=1e-9)
    floats = lb.SameDegreeCurve(np.array(pts, float), float(lam)).geometric_levels(float(t))
    np.testing.assert_allclose(np.array(floats[-1][0]), curve.evaluate(float(t)), atol=1e-9)


def test_evaluation_across_cache_blocks():
    """More parameters than one evaluation block: every block agrees with de Casteljau."""
    from lambda_bezier.hazmat.kernels import BLOCK

    curve = lb.BezierCurve(np.random.default_rng(9).normal(size=(7, 3)))
    t = np.random.default_rng(10).random(2 * BLOCK + 17)
    np.testing.assert_allclose(curve.evaluate(t), curve.de_casteljau(t), atol=1e-12)
    np.testing.assert_allclose(curve.derivative(t, 2)[-5:], curve.derivative(t[-5:], 2))


def test_basis_power_matrix_is_the_power_form_of_the_basis(family):
    n = family.degrees[0] + 2
    curve = make_curve(
        family,
        np.arange(2 * (n + 1), dtype=float).reshape(n + 1, 2),
        None if family.name == "bezier" else 0.375,
    )
    t = np.linspace(0, 1, 9)
    power = curve.basis_power_matrix()
    assert power.shape == (n + 1, curve.polynomial_degree + 1)
    values = np.polynomial.polynomial.polyval(t, power.T).T
    np.testing.assert_allclose(values, curve.basis(t), atol=1e-10)
